//! The polarization a surface's BSDF gives the light it scatters: the normalized Mueller
//! matrix N = M / M₀₀ of the interaction (the BSDF's scalar value already carries M₀₀) in
//! the s/p bases of the surface or of the microfacet that scattered, applied to the
//! analyzer of a camera path.
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

use crate::bsdf::{dielectric::half_vector, Bsdf, SMOOTH_ALPHA};
use crate::math::Frame;
use crate::polar::fresnel::{self, MIRROR};
use crate::polar::stokes::{mat_mul, transverse, Analyzer, Mueller, DEPOLARIZER, IDENTITY};
use crate::spectrum::Carrier;
use glam::Vec3;

/// The normalized Mueller matrix of `b` for light from −`wi` to `wo` and the local normal
/// (surface or microfacet) its s/p bases refer to; `None` for a depolarizing BSDF.
pub(super) fn mueller<C: Carrier>(b: &Bsdf<C>, wo: Vec3, wi: Vec3) -> Option<(Mueller, Vec3)> {
    let m = match *b {
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

/// The analyzer before a scattering at a surface with shading `frame` and BSDF `b`, the
/// path's analyzer after it being `after` (light leaving along the world `wo`), the light
/// arriving along −`wi` (world): N applied in the s/p bases of its normal.
pub(super) fn through<C: Carrier>(
    after: &Analyzer,
    b: &Bsdf<C>,
    frame: &Frame,
    (wo, wi): (Vec3, Vec3),
) -> Analyzer {
    let k_in = -wi;
    let (n, m) = match mueller(b, frame.to_local(wo), frame.to_local(wi)) {
        Some(x) => x,
        None => (DEPOLARIZER, Vec3::Z),
    };
    let s = s_basis(k_in, frame.to_world(m), after);
    after.through(&n, s, s, k_in, 1.0)
}

/// The s vector of an interaction with normal `m` for light arriving along `k_in` (unit
/// normal to the plane of incidence, ⊥ both beams): k_in × m normalized, or at normal
/// incidence the analyzer's x made ⊥ `k_in` (no rotation then).
pub(super) fn s_basis(k_in: Vec3, m: Vec3, after: &Analyzer) -> Vec3 {
    let s = k_in.cross(m);
    if s.length_squared() > 1e-12 {
        s.normalize()
    } else {
        transverse(after.x, k_in)
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
