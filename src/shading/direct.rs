//! Direct lighting of an opaque hit with shadow rays, the Whitted tracer's light step: every
//! punctual light, one sample of the emissive triangles and one of the environment, each
//! through the material's opaque BSDF ([`crate::material::Material::opaque_bsdf`]) seen
//! from the viewer's side. The path tracer uses its own next-event estimation with MIS
//! instead.
//!
//! Directions are unit vectors pointing away from the surface (world space, the BSDF's in
//! the local frame of the shading normal); radiance in the units of the lights (cd and lux
//! give nits).

use super::lights::{self, LightSample};
use super::step::Arrival;
use crate::bsdf::{Bsdf, TransportMode};
use crate::light::LightId;
use crate::math::Frame;
use crate::sampler::Bounce;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::Vec3;

/// An opaque hit seen from the viewer's side, ready to receive light.
struct Receiver<'a, C: Carrier> {
    scene: &'a Scene,
    bsdf: Bsdf<C>,
    lambda: C::Lambda,
    /// Local frame of the outward shading normal (the BSDF's frame).
    frame: Frame,
    /// `hit.wo` in that frame.
    wo: Vec3,
    /// Shading normal on the viewer's side.
    n: Vec3,
    /// Geometric normal on the viewer's side.
    ng: Vec3,
}

impl<C: Carrier> Receiver<'_, C> {
    /// Light from `ls` if its shadow ray is unblocked: f · incident · cos.
    fn connect(&self, ls: Option<LightSample>, rays: &mut u64) -> C {
        let Some(ls) = ls else {
            return C::ZERO;
        };
        let cos = self.n.dot(ls.wi);
        if cos <= 0.0 || self.ng.dot(ls.wi) <= 0.0 {
            return C::ZERO;
        }
        let f = self
            .bsdf
            .eval(self.wo, self.frame.to_local(ls.wi), TransportMode::Radiance);
        if f == C::ZERO {
            return C::ZERO;
        }
        *rays += 1;
        if self.scene.occluded(&ls.shadow) {
            return C::ZERO;
        }
        f * C::emitted(ls.incident, ls.shape, &self.lambda) * cos
    }
}

/// Direct light at an opaque hit, with shadow rays: every light of the scene's light sampler
/// with weight 1 — each punctual light, one sample of the emissive triangles (the vertex's
/// light member and position numbers) and one of the environment (its BSDF-direction
/// numbers, which a Whitted vertex never uses otherwise).
pub fn direct_light<C: Carrier>(
    scene: &Scene,
    at: &Arrival<'_, C>,
    lambda: &C::Lambda,
    u: &mut Bounce<'_>,
    rays: &mut u64,
) -> C {
    let (hit, mat) = (&at.hit, at.mat);
    // Shade the side the viewer is on.
    let (n, ng) = if hit.front_face || mat.desc.double_sided || !mat.is_volume() {
        let s = if hit.ng.dot(hit.wo) >= 0.0 { 1.0 } else { -1.0 };
        (hit.ns * s, hit.ng * s)
    } else {
        (-hit.ns, -hit.ng)
    };
    let frame = super::frame::shading_frame(scene, hit, &at.sp.anisotropy);
    let r = Receiver {
        scene,
        bsdf: mat.opaque_bsdf(&at.sp, lambda),
        lambda: *lambda,
        frame,
        wo: frame.to_local(hit.wo),
        n,
        ng,
    };
    // The numbers of the emissive-triangle sample are drawn at every vertex, those of the
    // environment sample only where there is one.
    let uc = u.light_member();
    let up = u.light_position();
    let mut sum = C::ZERO;
    for &id in scene.light_sampler().lights() {
        let ls = match id {
            LightId::Punctual(_) | LightId::Area => lights::sample(scene, hit, id, uc, up),
            LightId::Environment => lights::environment(scene, hit, u.bsdf_direction()),
        };
        sum += r.connect(ls, rays);
    }
    sum
}
