//! Polarization at surfaces, for camera paths and photons alike: the s/p bases of the
//! surface or of the microfacet that scattered ([`s_basis`]) for the normalized Mueller
//! matrix each BSDF lobe gives the light it scatters ([`crate::bsdf::Bsdf::mueller`]; which
//! lobes polarize and how is each lobe's own, in [`crate::bsdf`], module table in
//! docs/gem-optics.md); the smooth crystal surfaces polarized transport handles apart
//! ([`smooth_crystal`]); a crystal segment's absorption by mode ([`segment_transmittance`]).
//!
//! Frames: `wo`, `wi` local to the shading frame (z = outward normal), as the BSDF has
//! them; the light arrives along −wi and leaves along wo.

use super::Arrival;
use crate::bsdf::SMOOTH_ALPHA;
use crate::material::CrystalDesc;
use crate::medium_stack::MediumStack;
use crate::polar::stokes::transverse;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::Vec3;

/// The s vector of an interaction with normal `m` for light arriving along `k_in` (unit
/// normal to the plane of incidence, ⊥ both beams): k_in × m normalized, or at normal
/// incidence `fallback` made ⊥ `k_in` (the light's current basis: no rotation then).
pub fn s_basis(k_in: Vec3, m: Vec3, fallback: Vec3) -> Vec3 {
    let s = k_in.cross(m);
    if s.length_squared() > 1e-12 {
        s.normalize()
    } else {
        transverse(fallback, k_in)
    }
}

/// The crystal at an arrival if its material is one and smooth there (a rough crystal
/// scatters as an isotropic dielectric with its mean index).
pub fn smooth_crystal<'a, C: Carrier>(at: &Arrival<'a, C>) -> Option<&'a CrystalDesc> {
    let c = at.mat.desc.crystal.as_ref()?;
    let smooth = at.sp.roughness * at.sp.roughness < SMOOTH_ALPHA;
    (smooth && at.mat.is_volume() && at.sp.transmission > 0.0).then_some(c)
}

/// The transmission axis (world) of an ideal polarizer sheet at an arrival
/// (`extras.iris_polarizer` on a transmissive thin material), `None` elsewhere.
pub fn polarizer_sheet<C: Carrier>(at: &Arrival<'_, C>) -> Option<Vec3> {
    at.mat.desc.polarizer.filter(|_| at.sp.transmission > 0.0)
}

/// The transmittance of the segment just travelled to `at` inside `media`: in a crystal
/// with an absorption table, with the light in the mode whose D field is `mode_d`,
/// e^(−σ_m t) ([`CrystalDesc::mode_transmittance`]) at the hero of `lambda`; elsewhere the
/// arrival's (Beer–Lambert). A path in no medium leaving a volume (it started inside)
/// travelled in that volume ([`crate::medium_stack::segment_medium`]).
pub fn segment_transmittance<C: Carrier>(
    scene: &Scene,
    media: &MediumStack,
    mode_d: Option<Vec3>,
    at: &Arrival<'_, C>,
    lambda: &C::Lambda,
) -> C {
    let crystal = crate::medium_stack::segment_medium(scene, media, &at.hit)
        .and_then(|m| scene.materials()[m as usize].desc.crystal.as_ref());
    match (crystal, mode_d, C::hero(lambda)) {
        (Some(c), Some(d), Some(nm)) => c
            .mode_transmittance(nm, d, at.hit.t)
            .map_or(at.transmittance, C::splat),
        _ => at.transmittance,
    }
}
