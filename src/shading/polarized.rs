//! Polarization at surfaces, for camera paths and photons alike: the normalized Mueller
//! matrix N = M / M₀₀ a BSDF gives the light it scatters (the BSDF's scalar value already
//! carries M₀₀), in the s/p bases of the surface or of the microfacet that scattered
//! ([`mueller`], [`s_basis`]); the smooth crystal surfaces polarized transport handles apart
//! ([`smooth_crystal`]); a crystal segment's absorption by mode ([`segment_transmittance`]).
//!
//! Which BSDFs polarize (module table in docs/gem-optics.md): smooth and rough dielectrics
//! (Fresnel at the surface or at the microfacet normal, [`crate::polar::fresnel`]),
//! measured conductors (complex index at the hero wavelength), thin-walled dielectrics
//! (one interface in reflection, two in transmission). A Schlick conductor (glTF metal) is
//! a perfect mirror for polarization. The glTF PBR mix (diffuse + specular, its layers) and
//! Lambert depolarize: their light is treated as unpolarized (the ideal depolarizer).
//!
//! Frames: `wo`, `wi` local to the shading frame (z = outward normal), as the BSDF has
//! them; the light arrives along −wi and leaves along wo.

use super::Arrival;
use crate::bsdf::{dielectric::half_vector, Bsdf, SMOOTH_ALPHA};
use crate::material::CrystalDesc;
use crate::medium_stack::MediumStack;
use crate::polar::fresnel::{self, MIRROR};
use crate::polar::stokes::{mat_mul, transverse, Mueller, IDENTITY};
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::Vec3;

/// The normalized Mueller matrix of `b` for light from −`wi` to `wo` and the local normal
/// (surface or microfacet) its s/p bases refer to; `None` for a depolarizing BSDF.
pub fn mueller<C: Carrier>(b: &Bsdf<C>, wo: Vec3, wi: Vec3) -> Option<(Mueller, Vec3)> {
    let m = match *b {
        // The BSDFs of [`depolarizes`].
        Bsdf::Lambert { .. } | Bsdf::GltfPbr { .. } => return None,
        Bsdf::Conductor { .. } => return Some((MIRROR, Vec3::Z)),
        Bsdf::ComplexConductor { eta, k, alpha, .. } => {
            let m = if alpha < SMOOTH_ALPHA {
                Vec3::Z
            } else {
                (wo + wi).try_normalize()?
            };
            let (n, k) = (eta.to_lanes()[0], k.to_lanes()[0]);
            (fresnel::conductor(wi.dot(m).abs(), n, k), m)
        }
        Bsdf::Dielectric { eta, alpha, .. } => {
            if eta == 1.0 {
                return Some((IDENTITY, Vec3::Z));
            }
            let reflect = wo.z * wi.z > 0.0;
            let m = if alpha < SMOOTH_ALPHA {
                Vec3::Z
            } else {
                half_vector(eta, wo, wi)?.0
            };
            let (r, t) = fresnel::dielectric(wi.dot(m).abs(), light_eta(eta, wi));
            (if reflect { r } else { t }, m)
        }
        Bsdf::ThinDielectric { eta, .. } => {
            let (r, t) = fresnel::dielectric(wi.z.abs(), eta);
            let through = mat_mul(&t, &t);
            (if wo.z * wi.z > 0.0 { r } else { through }, Vec3::Z)
        }
    };
    normalized(m.0).map(|n| (n, m.1))
}

/// Whether `b` depolarizes whatever the directions (Lambert, the glTF PBR mix): the light
/// it scatters is read as unpolarized, [`mueller`] is `None`.
pub fn depolarizes<C: Carrier>(b: &Bsdf<C>) -> bool {
    matches!(b, Bsdf::Lambert { .. } | Bsdf::GltfPbr { .. })
}

/// Whether `b`'s polarization depends on the wavelength beyond what the shared step
/// already reduces to the hero (dispersive interfaces): a measured conductor, whose complex
/// index is taken at the hero ([`mueller`]). One Stokes vector or analyzer serves all the
/// lanes of a path until a crystal or such a surface; then the hero alone.
pub fn hero_polarizes<C: Carrier>(b: &Bsdf<C>) -> bool {
    matches!(b, Bsdf::ComplexConductor { .. })
}

/// η = n_t/n_i for light arriving from `wi`'s side of an interface with η = n_inside /
/// n_outside (outside = +z).
fn light_eta(eta: f32, wi: Vec3) -> f32 {
    if wi.z > 0.0 {
        eta
    } else {
        1.0 / eta
    }
}

/// M / M₀₀, `None` when M₀₀ is not positive.
fn normalized(m: Mueller) -> Option<Mueller> {
    let d = m[0][0];
    (d > 0.0 && d.is_finite()).then(|| m.map(|row| row.map(|v| v / d)))
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_glass_reflection_at_brewster_is_a_polarizer() {
        let eta = 1.5f32;
        let th = eta.atan();
        let wi = Vec3::new(th.sin(), 0.0, th.cos());
        let wo = Vec3::new(-th.sin(), 0.0, th.cos());
        let b: Bsdf<Vec3> = Bsdf::Dielectric {
            eta,
            alpha: 0.0,
            tint: Vec3::ONE,
        };
        let (n, m) = mueller(&b, wo, wi).unwrap();
        assert_eq!(m, Vec3::Z);
        // Normalized: unpolarized in, fully s-polarized out.
        assert!(
            (n[0][0] - 1.0).abs() < 1e-6 && (n[1][0] - 1.0).abs() < 1e-4,
            "{n:?}"
        );
    }

    #[test]
    fn diffuse_surfaces_depolarize() {
        let b: Bsdf<Vec3> = Bsdf::Lambert { albedo: Vec3::ONE };
        assert!(mueller(&b, Vec3::Z, Vec3::Z).is_none());
    }
}
