//! The Mueller matrices of a smooth interface: Fresnel's complex amplitudes for the s and
//! p components (dielectric, with the phase retardation of total internal reflection, and
//! conductor with a complex index n + ik) turned into 4×4 matrices.
//!
//! Bases: s = the unit normal to the plane of incidence, the same vector for the incident,
//! reflected and transmitted light; each beam's p = k × s for its own direction k (so at
//! normal incidence the reflected p is minus the incident p, and r_p = −r_s there). With
//! that convention the amplitudes are Born & Wolf's (*Principles of Optics*, 7th ed.,
//! §1.5.2, eqs. 20–21) written with the relative index η = n_t/n_i:
//! r_s = (cos θ_i − η cos θ_t)/(cos θ_i + η cos θ_t), r_p = (η cos θ_i − cos θ_t)/(η cos θ_i + cos θ_t),
//! t_s = 2 cos θ_i/(cos θ_i + η cos θ_t), t_p = 2 cos θ_i/(η cos θ_i + cos θ_t),
//! with cos θ_t = √(1 − sin²θ_i/η²), the principal root, imaginary beyond the critical
//! angle (|r_s| = |r_p| = 1 and a phase difference: TIR retardation) and complex for a
//! conductor. The Mueller matrix of a pair of amplitudes (Chipman, Lam & Young 2018,
//! eq. 6.107): ½·[[|r_s|²+|r_p|², |r_s|²−|r_p|², 0, 0], [|r_s|²−|r_p|², |r_s|²+|r_p|², 0, 0],
//! [0, 0, 2 Re(r_s r_p*), 2 Im(r_s r_p*)], [0, 0, −2 Im(r_s r_p*), 2 Re(r_s r_p*)]], with
//! the transmitted power scaled by η cos θ_t / cos θ_i. Its (0, 0) entry is the
//! unpolarized reflectance or transmittance of [`crate::optics`].

use super::stokes::Mueller;
use crate::math::Complex;

/// The Mueller matrix of an interface with complex amplitudes `s` and `p`, times `scale`.
fn from_amplitudes(s: Complex, p: Complex, scale: f64) -> Mueller {
    let (ss, pp) = (s.norm_sqr(), p.norm_sqr());
    // s·p̄
    let sp = Complex::new(s.re * p.re + s.im * p.im, s.im * p.re - s.re * p.im);
    let h = 0.5 * scale;
    let m = [
        [h * (ss + pp), h * (ss - pp), 0.0, 0.0],
        [h * (ss - pp), h * (ss + pp), 0.0, 0.0],
        [0.0, 0.0, 2.0 * h * sp.re, 2.0 * h * sp.im],
        [0.0, 0.0, -2.0 * h * sp.im, 2.0 * h * sp.re],
    ];
    m.map(|row| row.map(|v| v as f32))
}

/// cos θ_t for the complex relative index `eta` (principal root).
fn cos_t(cos_i: f64, eta: Complex) -> Complex {
    let sin2_t = Complex::real((1.0 - cos_i) * (1.0 + cos_i)) / (eta * eta);
    (Complex::real(1.0) - sin2_t).sqrt()
}

/// Reflection and transmission Mueller matrices of a smooth dielectric interface for light
/// arriving at `cos_i` ∈ [0, 1] with relative index `eta` = n_t/n_i (finite, > 0). Under
/// total internal reflection the transmission is zero and the reflection a pure retarder.
/// `eta` = 1 gives no reflection and the identity in transmission.
pub fn dielectric(cos_i: f32, eta: f32) -> (Mueller, Mueller) {
    let c = f64::from(cos_i.clamp(0.0, 1.0));
    let e = f64::from(eta);
    let ct = cos_t(c, Complex::real(e));
    let ci = Complex::real(c);
    let et = ct * e;
    let rs = (ci - et) / (ci + et);
    let rp = (ci * e - ct) / (ci * e + ct);
    let r = from_amplitudes(rs, rp, 1.0);
    if ct.im != 0.0 || ct.re <= 0.0 || c <= 0.0 {
        return (r, [[0.0; 4]; 4]);
    }
    let ts = Complex::real(2.0 * c) / (ci + et);
    let tp = Complex::real(2.0 * c) / (ci * e + ct);
    let t = from_amplitudes(ts, tp, e * ct.re / c);
    (r, t)
}

/// Reflection Mueller matrix of a smooth conductor with relative complex index
/// `n` + i`k` (k ≥ 0) for light arriving at `cos_i`.
pub fn conductor(cos_i: f32, n: f32, k: f32) -> Mueller {
    let c = f64::from(cos_i.clamp(0.0, 1.0));
    let eta = Complex::new(f64::from(n), f64::from(k.max(0.0)));
    let ct = cos_t(c, eta);
    let ci = Complex::real(c);
    let et = eta * ct;
    let rs = (ci - et) / (ci + et);
    let rp = (eta * ci - ct) / (eta * ci + ct);
    from_amplitudes(rs, rp, 1.0)
}

/// A perfect mirror (|r_s| = |r_p| = 1, r_p = −r_s): diag(1, 1, −1, −1).
pub const MIRROR: Mueller = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, -1.0, 0.0],
    [0.0, 0.0, 0.0, -1.0],
];

/// The retardance δ (radians, in [0, π]) of a Mueller matrix of the form of
/// [`dielectric`]'s reflection: the phase difference between s and p,
/// cos δ = M22 / √(M00² − M01²).
pub fn retardance(m: &Mueller) -> f32 {
    let d = (m[0][0] * m[0][0] - m[0][1] * m[0][1]).max(0.0).sqrt();
    if d <= 0.0 {
        return 0.0;
    }
    (m[2][2] / d).clamp(-1.0, 1.0).acos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::{fresnel_conductor, fresnel_dielectric};
    use crate::polar::stokes::{mul, Stokes};

    #[test]
    fn the_intensity_row_is_the_unpolarized_fresnel_term() {
        for eta in [1.33f32, 1.5, 2.417, 1.0 / 1.5, 1.0 / 2.417] {
            for i in 0..=20 {
                let c = i as f32 / 20.0;
                let (r, t) = dielectric(c, eta);
                let f = fresnel_dielectric(c, eta);
                assert!(
                    (r[0][0] - f).abs() < 1e-5,
                    "R {eta} {c}: {} vs {f}",
                    r[0][0]
                );
                if f < 1.0 && c > 0.0 {
                    assert!((t[0][0] - (1.0 - f)).abs() < 1e-5, "T {eta} {c}");
                }
            }
        }
        let m = conductor(0.6, 0.2, 3.9);
        assert!((m[0][0] - fresnel_conductor(0.6, 0.2, 3.9)).abs() < 1e-5);
    }

    #[test]
    fn brewster_reflection_has_no_p_component() {
        // tan θ_B = η: the reflected light is purely s-polarized (S1 = S0 for x = s).
        let eta = 1.5f32;
        let cos_b = (1.0 / (1.0 + eta * eta)).sqrt();
        let (r, _) = dielectric(cos_b, eta);
        let s: Stokes = mul(&r, &[1.0, 0.0, 0.0, 0.0]);
        assert!(s[0] > 0.03, "{s:?}");
        assert!((s[1] - s[0]).abs() < 1e-6 * s[0].max(1e-6) + 1e-7, "{s:?}");
        // p-polarized light (S1 = −1) is not reflected at all there.
        let p = mul(&r, &[1.0, -1.0, 0.0, 0.0]);
        assert!(p[0].abs() < 1e-7, "{p:?}");
    }

    #[test]
    fn total_internal_reflection_retards_by_the_fresnel_rhomb_phase() {
        // tan(δ/2) = cos θ √(sin²θ − 1/n²) / sin²θ (Born & Wolf §1.5.4, eq. 60) for light
        // inside glass of index n; at θ = 54.6° in n = 1.51 one reflection gives ≈ 45°, so
        // the Fresnel rhomb's two turn 45° linear light circular.
        let n = 1.51f32;
        let th = 54.6f32.to_radians();
        let (r, t) = dielectric(th.cos(), 1.0 / n);
        assert_eq!(t[0][0], 0.0);
        assert!((r[0][0] - 1.0).abs() < 1e-6 && r[0][1].abs() < 1e-6);
        let s2 = th.sin().powi(2);
        let expect = 2.0 * (th.cos() * (s2 - 1.0 / (n * n)).sqrt() / s2).atan();
        assert!(
            (retardance(&r) - expect).abs() < 1e-4,
            "{} vs {expect}",
            retardance(&r)
        );
        assert!((expect.to_degrees() - 45.0).abs() < 0.5);
        let linear45: Stokes = [1.0, 0.0, 1.0, 0.0];
        let out = mul(&r, &mul(&r, &linear45));
        assert!(
            out[3].abs() > 0.999,
            "circular after two reflections: {out:?}"
        );
    }

    #[test]
    fn energy_is_conserved_for_every_polarization() {
        // R + T keeps S0 for s, p, ±45° and circular light below the critical angle.
        for s in [
            [1.0f32, 1.0, 0.0, 0.0],
            [1.0, -1.0, 0.0, 0.0],
            [1.0, 0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0, 1.0],
        ] {
            for c in [0.05f32, 0.4, 0.9, 1.0] {
                let (r, t) = dielectric(c, 1.7);
                let total = mul(&r, &s)[0] + mul(&t, &s)[0];
                assert!((total - 1.0).abs() < 1e-5, "{s:?} {c}: {total}");
            }
        }
    }

    #[test]
    fn a_metal_reflects_s_more_than_p_and_retards() {
        // Gold-like index at 600 nm: R_s > R_p away from normal incidence, and a phase
        // difference (S2 → S3 leakage).
        let m = conductor(0.5, 0.25, 3.0);
        assert!(m[0][1] > 0.0, "{m:?}");
        assert!(m[2][3].abs() > 0.01, "{m:?}");
        // A perfect conductor is the mirror.
        let big = conductor(0.5, 1e4, 1e4);
        for i in 0..4 {
            assert!((big[i][i] - MIRROR[i][i]).abs() < 1e-2, "{big:?}");
        }
    }
}
