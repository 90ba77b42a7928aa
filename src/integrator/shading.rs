//! The per-hit step shared by the integrators: which BSDF ([`crate::bsdf`]) a hit has —
//! glTF metallic-roughness (Appendix B of the glTF 2.0 spec, with KHR_materials_specular),
//! smooth/rough dielectric with η from the path's media, thin-walled transmission — and
//! direct lighting of opaque hits from punctual lights, emissive triangles and the
//! environment with shadow rays (Whitted's light step; the path tracer adds MIS on top).
//!
//! Directions are unit vectors pointing away from the surface; radiance in the units of the
//! lights (cd and lux give nits).

use super::lights::{self, LightSample};
use super::Context;
use crate::bsdf::{Bsdf, TransportMode};
use crate::interaction::{CoincidentSet, SurfaceHit};
use crate::material::{Material, ShadingPoint};
use crate::math::Frame;
use crate::medium::{self, MediumStack};
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

/// The surface BSDF of an opaque (non-transmitting) shading point: glTF metallic-roughness
/// with KHR_materials_specular.
pub fn surface_bsdf<C: Carrier>(mat: &Material, sp: &ShadingPoint, l: &C::Lambda) -> Bsdf<C> {
    let d = &mat.desc;
    Bsdf::GltfPbr {
        base: C::reflectance(sp.base_color, l),
        metallic: sp.metallic,
        alpha: sp.roughness * sp.roughness,
        ior: mat.ior(),
        specular: d.specular,
        specular_color: C::reflectance(d.specular_color, l),
    }
}

/// The surface a path really meets at `hit`, for touching objects (the intersection layer's
/// [`Scene::coincident`], probed only at volume boundaries): a non-volumetric face lying
/// on the boundary wins — water filling an opaque mug meets the mug's wall, still in the
/// water — and otherwise the coincident volume faces are returned to be crossed as one
/// interface. Either way rays leave from the returned hit, which clears all of them.
pub fn meet(scene: &Scene, hit: SurfaceHit) -> (SurfaceHit, CoincidentSet) {
    if !scene.materials[hit.material as usize].is_volume() {
        return (hit, CoincidentSet::default());
    }
    let (merged, set) = scene.coincident(&hit);
    let solid = set
        .iter()
        .find(|c| !scene.materials[c.material as usize].is_volume());
    match solid {
        Some(solid) => (solid, CoincidentSet::default()),
        None => (merged, set),
    }
}

/// Arriving at a surface, the first part of the per-hit step every path (camera, photon,
/// final gather) takes: the surface really met ([`meet`]), its material and the shading
/// point (textures evaluated at the hit).
pub fn arrive(
    scene: &Scene,
    hit: SurfaceHit,
) -> (SurfaceHit, CoincidentSet, &Material, ShadingPoint) {
    let (hit, coincident) = meet(scene, hit);
    let mat = &scene.materials[hit.material as usize];
    let sp = mat.shade(hit.uv, &scene.images);
    (hit, coincident, mat, sp)
}

/// The BSDF at a hit (one lobe chosen by the transmission weight with `u`) and the media on
/// the far side of a refraction. At a volume boundary η is the ratio of the indices on the
/// two sides from the path's medium stack, with the `coincident` volume faces (from
/// [`meet`]) crossed in the same step ([`medium::crossing`]).
///
/// Spectral transport: when a medium on either side may be dispersive (a dispersive
/// material among the surfaces crossed or the media the path is in), the indices are taken
/// at the hero wavelength and the third value is `true`: the caller must then keep only the
/// hero ([`Carrier::keep_hero`]) — the refracted direction is the hero's alone. Thin walls
/// do not bend light and use n_d.
pub fn bsdf_at<C: Carrier>(
    scene: &Scene,
    hit: &SurfaceHit,
    coincident: &CoincidentSet,
    sp: &ShadingPoint,
    media: MediumStack,
    u: f32,
    l: &C::Lambda,
) -> (Bsdf<C>, MediumStack, bool) {
    let mat = &scene.materials[hit.material as usize];
    if sp.transmission > 0.0 && u < sp.transmission {
        let tint = C::reflectance(sp.base_color, l);
        if !mat.is_volume() {
            return (
                Bsdf::ThinDielectric {
                    eta: mat.ior(),
                    tint,
                },
                media,
                false,
            );
        }
        let (n_i, n_t, after, dispersive) = interface::<C>(scene, hit, coincident, media, l);
        // Bsdf's η is n_inside / n_outside, the outside being the normal's side.
        let eta = if n_i == n_t {
            1.0
        } else if hit.front_face {
            n_t / n_i
        } else {
            n_i / n_t
        };
        return (
            Bsdf::Dielectric {
                eta,
                alpha: sp.roughness * sp.roughness,
                tint,
            },
            after,
            dispersive,
        );
    }
    (surface_bsdf(mat, sp, l), media, false)
}

/// The indices on both sides of the volume boundary at `hit` (coincident volume faces
/// merged, [`medium::crossing`]), the media beyond, and whether the path must keep only its
/// hero wavelength: in spectral transport, when a dispersive material is among the surfaces
/// crossed or the media the path is in, the indices are those at the hero wavelength.
pub fn interface<C: Carrier>(
    scene: &Scene,
    hit: &SurfaceHit,
    coincident: &CoincidentSet,
    media: MediumStack,
    l: &C::Lambda,
) -> (f32, f32, MediumStack, bool) {
    let hero = C::hero(l);
    let disp = |m: u32| scene.materials[m as usize].is_dispersive();
    let dispersive = hero.is_some()
        && (disp(hit.material)
            || coincident.iter().any(|c| disp(c.material))
            || media.iter().any(disp));
    let (n_i, n_t, after) = medium::crossing(scene, hit, coincident, media, |m| {
        scene.materials[m as usize].ior_at(hero, dispersive)
    });
    (n_i, n_t, after, dispersive)
}

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
    fn connect(&self, ls: Option<LightSample>, ctx: &mut Context) -> C {
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
        ctx.rays += 1;
        if self.scene.occluded(&ls.shadow) {
            return C::ZERO;
        }
        f * C::emitted(ls.incident, ls.shape, &self.lambda) * cos
    }
}

/// Direct light at an opaque hit, with shadow rays: every punctual light, one sample of the
/// emissive triangles and one of the environment.
pub fn direct_light<C: Carrier>(
    scene: &Scene,
    hit: &SurfaceHit,
    mat: &Material,
    sp: &ShadingPoint,
    lambda: &C::Lambda,
    ctx: &mut Context,
) -> C {
    // Shade the side the viewer is on.
    let (n, ng) = if hit.front_face || mat.desc.double_sided || !mat.is_volume() {
        let s = if hit.ng.dot(hit.wo) >= 0.0 { 1.0 } else { -1.0 };
        (hit.ns * s, hit.ng * s)
    } else {
        (-hit.ns, -hit.ng)
    };
    let frame = Frame::from_normal(hit.ns);
    let r = Receiver {
        scene,
        bsdf: surface_bsdf(mat, sp, lambda),
        lambda: *lambda,
        frame,
        wo: frame.to_local(hit.wo),
        n,
        ng,
    };
    let mut sum = C::ZERO;
    for k in 0..scene.lights.len() {
        sum += r.connect(lights::punctual(scene, hit, k), ctx);
    }
    // One emissive-triangle sample, then one environment sample.
    let uc = ctx.rng.next_f32();
    let u = Vec2::new(ctx.rng.next_f32(), ctx.rng.next_f32());
    sum += r.connect(lights::area(scene, hit, uc, u), ctx);
    if scene.environment.is_some() {
        let u = Vec2::new(ctx.rng.next_f32(), ctx.rng.next_f32());
        sum += r.connect(lights::environment(scene, hit, u), ctx);
    }
    sum
}
