//! The BSDF a material has at a hit ([`crate::bsdf`]): the material's opaque BSDF
//! ([`crate::material::Material::opaque_bsdf`]), or its transmission
//! ([`crate::material::Material::transmission_bsdf`]) with η from the path's media; and a
//! sample of a BSDF that a path can use ([`sample_bsdf`]).
//!
//! Directions are unit vectors in the local frame of the outward shading normal; η is the
//! ratio n_inside / n_outside, the outside being the normal's side.

use crate::bsdf::{Bsdf, BsdfSample, TransportMode};
use crate::interaction::{CoincidentFaces, SurfaceHit};
use crate::material::ShadingPoint;
use crate::medium_stack::{self, MediumStack};
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

/// The BSDF at a hit (one lobe chosen by the transmission weight with `u`) and the media on
/// the far side of a refraction. At a volume boundary η is the ratio of the indices on the
/// two sides from the path's medium stack, with the `coincident` volume faces (from
/// [`super::meet`]) crossed in the same step ([`medium_stack::crossing`]).
///
/// Spectral transport: when a medium on either side may be dispersive (a dispersive
/// material among the surfaces crossed or the media the path is in), the indices are taken
/// at the hero wavelength and the third value is `true`: the caller must then keep only the
/// hero ([`Carrier::keep_hero`]) — the refracted direction is the hero's alone. Thin walls
/// do not bend light and use n_d.
pub fn bsdf_at<C: Carrier>(
    scene: &Scene,
    hit: &SurfaceHit,
    coincident: &CoincidentFaces,
    sp: &ShadingPoint,
    media: MediumStack,
    u: f32,
    l: &C::Lambda,
) -> (Bsdf<C>, MediumStack, bool) {
    let mat = &scene.materials()[hit.material as usize];
    if sp.transmission > 0.0 && u < sp.transmission {
        if !mat.is_volume() {
            return (mat.transmission_bsdf(sp, None, l), media, false);
        }
        let (n_i, n_t, after, dispersive) = interface::<C>(scene, hit, coincident, media, l);
        let eta = bsdf_eta(n_i, n_t, hit.front_face);
        return (mat.transmission_bsdf(sp, Some(eta), l), after, dispersive);
    }
    (mat.opaque_bsdf(sp, l), media, false)
}

/// The indices on both sides of the volume boundary at `hit` (coincident volume faces
/// merged, [`medium_stack::crossing`]), the media beyond, and whether the path must keep only its
/// hero wavelength: in spectral transport, when a dispersive material is among the surfaces
/// crossed or the media the path is in, the indices are those at the hero wavelength.
pub fn interface<C: Carrier>(
    scene: &Scene,
    hit: &SurfaceHit,
    coincident: &CoincidentFaces,
    media: MediumStack,
    l: &C::Lambda,
) -> (f32, f32, MediumStack, bool) {
    let hero = C::hero(l);
    let disp = |m: u32| scene.materials()[m as usize].is_dispersive();
    let dispersive = hero.is_some()
        && (disp(hit.material)
            || coincident.iter().any(|c| disp(c.material))
            || media.iter().any(disp));
    let (n_i, n_t, after) = medium_stack::crossing(scene, hit, coincident, media, |m| {
        scene.materials()[m as usize].ior_at(hero, dispersive)
    });
    (n_i, n_t, after, dispersive)
}

/// The BSDF's η (n_inside / n_outside, the outside being the normal's side) from the
/// indices on the incident (`n_i`) and far (`n_t`) sides.
fn bsdf_eta(n_i: f32, n_t: f32, front_face: bool) -> f32 {
    if n_i == n_t {
        1.0
    } else if front_face {
        n_t / n_i
    } else {
        n_i / n_t
    }
}

/// The BSDF's η at each of the 4 wavelengths `lanes` (nm) at a dispersive volume boundary
/// (what [`bsdf_at`] takes at the hero alone), for spectral MIS at rough interfaces
/// ([`super::spectral_mis`]). Lane 0 is the hero: equal to the η [`bsdf_at`] gives.
pub fn lane_etas(
    scene: &Scene,
    hit: &SurfaceHit,
    coincident: &CoincidentFaces,
    media: MediumStack,
    lanes: [f32; 4],
) -> [f32; 4] {
    lanes.map(|nm| {
        let (n_i, n_t, _) = medium_stack::crossing(scene, hit, coincident, media, |m| {
            scene.materials()[m as usize].ior_at(Some(nm), true)
        });
        bsdf_eta(n_i, n_t, hit.front_face)
    })
}

/// Samples `bsdf` at the local `wo`; `None` when there is no sample or it cannot be used
/// (a pdf that is not positive, a non-finite value): the path ends there.
pub fn sample_bsdf<C: Carrier>(
    bsdf: &Bsdf<C>,
    wo: Vec3,
    uc: f32,
    u: Vec2,
    mode: TransportMode,
) -> Option<BsdfSample<C>> {
    let bs = bsdf.sample(wo, uc, u, mode)?;
    if bs.pdf.is_nan() || bs.pdf <= 0.0 || !bs.f.is_finite() {
        return None;
    }
    Some(bs)
}
