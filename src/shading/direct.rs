//! Direct lighting of an opaque hit with shadow rays, the Whitted tracer's light step: every
//! punctual light, one sample of the emissive triangles and one of the environment, each
//! through the material's opaque BSDF ([`crate::material::Material::opaque_bsdf`]) seen
//! from the viewer's side. The path tracer and VCM sample one light with MIS instead
//! ([`super::next_event::one`]).
//!
//! Directions are unit vectors pointing away from the surface (world space, the BSDF's in
//! the local frame of the shading normal); radiance in the units of the lights (cd and lux
//! give nits). The light choice, samples and shadow rays are the shared next-event
//! estimator's ([`super::next_event::every`]).

use super::next_event::{self, Chosen, Eval, Receiver};
use super::step::Arrival;
use crate::bsdf::{Bsdf, TransportMode};
use crate::interaction::SurfaceHit;
use crate::math::Frame;
use crate::sampler::Bounce;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::Vec3;

/// An opaque hit seen from the viewer's side, ready to receive light: the Whitted tracer's
/// side of the shared estimator ([`next_event::every`]), weight 1.
struct Opaque<'a, C: Carrier> {
    hit: &'a SurfaceHit,
    bsdf: Bsdf<C>,
    /// Local frame of the outward shading normal (the BSDF's frame).
    frame: Frame,
    /// `hit.wo` in that frame.
    wo: Vec3,
    /// Shading normal on the viewer's side.
    n: Vec3,
    /// Geometric normal on the viewer's side.
    ng: Vec3,
}

impl<C: Carrier> Receiver<C> for Opaque<'_, C> {
    fn hit(&self) -> &SurfaceHit {
        self.hit
    }

    /// f and cos toward `wi`; `None` from behind the shading or the geometric normal.
    fn eval(&self, wi: Vec3, _: &C::Lambda) -> Option<Eval<C>> {
        let cos = self.n.dot(wi);
        if cos <= 0.0 || self.ng.dot(wi) <= 0.0 {
            return None;
        }
        let f = self
            .bsdf
            .eval(self.wo, self.frame.to_local(wi), TransportMode::Radiance);
        Some(Eval { f, cos, pdf: 0.0 })
    }

    fn weight(&self, _: &Chosen<'_>, _: &Eval<C>) -> Option<f32> {
        Some(1.0)
    }
}

/// Direct light at an opaque hit, with shadow rays: every light of the scene's light sampler
/// with weight 1 ([`next_event::every`]) — each punctual light, one sample of the emissive
/// triangles (the vertex's light member and position numbers) and one of the environment
/// (its BSDF-direction numbers, which a Whitted vertex never uses otherwise).
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
    let r = Opaque {
        hit,
        bsdf: mat.opaque_bsdf(&at.sp, lambda),
        frame,
        wo: frame.to_local(hit.wo),
        n,
        ng,
    };
    next_event::every(scene, &r, lambda, u, rays)
}
