//! Geometric optics at a smooth interface: mirror reflection, Snell refraction, the exact
//! unpolarised Fresnel equations (dielectric, and conductor with a complex index) and the
//! critical angle. Pure functions on unit vectors; `eta` is always the **relative** index
//! n_transmitted / n_incident.
//!
//! Sign convention: `n` is the unit normal on the side the incident direction comes from,
//! i.e. `dot(wi, n) > 0` where `wi` points *away* from the surface toward the viewer/light.

use crate::math::Complex;
use crate::spectrum::Carrier;
use glam::Vec3;

/// Mirror reflection of `wi` (pointing away from the surface) about `n`.
#[inline]
pub fn reflect(wi: Vec3, n: Vec3) -> Vec3 {
    2.0 * wi.dot(n) * n - wi
}

/// Refracts `wi` (pointing away from the surface, on the side of `n`) into the other medium
/// with relative index `eta` = n_t/n_i. Returns `None` on total internal reflection.
/// Snell's law n_i sin θ_i = n_t sin θ_t in vector form (pbrt-v4 §9.3, `Refract`):
/// w_t = −(w_i − cos θ_i n)/η − cos θ_t n. The result is unit length when `wi` and `n` are.
///
/// Stiff cases: computed in f64 with cos θ_t from [`cos_transmitted`]'s cancellation-free
/// form, so grazing rays keep their digits; η = 1 returns `-wi` exactly at every angle,
/// η = 1 + 1e-7 bends a grazing ray by the right 5e-4 rad, and η from 1e-38 to 3e38 gives
/// a unit vector or `None`. η = +∞ gives `-n`; η ≤ 0 or NaN gives `None`.
#[inline]
pub fn refract(wi: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    if eta.is_nan() || eta <= 0.0 {
        return None;
    }
    if eta == 1.0 {
        return Some(-wi);
    }
    if eta.is_infinite() {
        return Some(-n);
    }
    let (wi, n) = (wi.as_dvec3(), n.as_dvec3());
    let cos_i = wi.dot(n).clamp(0.0, 1.0);
    let cos_t = cos_transmitted(cos_i, f64::from(eta))?;
    let wt = -(wi - cos_i * n) / f64::from(eta) - cos_t * n;
    Some(wt.normalize().as_vec3())
}

/// cos θ_t for cos θ_i ∈ [0, 1] and a finite η > 0, or `None` under total internal
/// reflection: cos²θ_t = 1 − sin²θ_i/η² = (η² − (1 − cos θ_i)(1 + cos θ_i))/η² (Snell), in
/// f64 and in that form so that neither η² nor sin²θ_i loses its small part (η ≈ 1 at
/// grazing incidence; η → 0 at normal incidence). At the critical angle it is 0.
#[inline]
fn cos_transmitted(cos_i: f64, eta: f64) -> Option<f64> {
    let k = eta * eta - (1.0 - cos_i) * (1.0 + cos_i);
    (k >= 0.0).then(|| k.sqrt() / eta)
}

/// [`fresnel_dielectric`] for a cosine on either side (pbrt-v4 `FrDielectric`): a negative
/// `cos` means the incident direction is inside, so the relative index `eta` inverts;
/// `eta` = +∞ gives 1. Shared by the dielectric BSDFs and their energy tables.
#[inline]
pub fn fresnel_either_side(cos: f32, eta: f32) -> f32 {
    if eta.is_infinite() {
        return 1.0;
    }
    if cos < 0.0 {
        fresnel_dielectric(-cos, 1.0 / eta)
    } else {
        fresnel_dielectric(cos, eta)
    }
}

/// Exact unpolarised Fresnel reflectance of a smooth dielectric interface
/// (Born & Wolf; pbrt-v4 `FrDielectric`): the mean of the s- and p-polarised reflectances,
/// `cos_i` = cosine of the incident angle (≥ 0), `eta` = n_t/n_i. Returns 1 under total
/// internal reflection. `eta` = +∞ (the glTF `ior: 0` mode) gives 1; `eta` = 1 (no
/// interface) gives 0 at every angle. Evaluated in f64 with cos θ_t as in [`refract`], so
/// 1 − R keeps its digits at grazing incidence (→ 2 cos θ_i (η²+1)/√(η²−1), see
/// `tests/optics/stiff_optics.rs`) and no η in (0, ∞) yields NaN.
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    if eta.is_infinite() || eta.is_nan() || eta <= 0.0 {
        return 1.0;
    }
    if eta == 1.0 {
        return 0.0;
    }
    let cos_i = f64::from(cos_i.clamp(0.0, 1.0));
    let eta = f64::from(eta);
    // cos θ_t = 0 only at the critical angle (then R = 1 below), never with cos θ_i = 0
    // (that needs η = 1), so no 0/0.
    let Some(cos_t) = cos_transmitted(cos_i, eta) else {
        return 1.0;
    };
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    (0.5 * (r_parl * r_parl + r_perp * r_perp)).clamp(0.0, 1.0) as f32
}

/// Exact unpolarised Fresnel reflectance of a smooth conductor with complex relative index
/// η = n + ik (k ≥ 0), light arriving from the side of the normal: the mean of |r_∥|² and
/// |r_⊥|² with Snell's law in complex form, sin²θ_t = sin²θ_i/η², cos θ_t = √(1 − sin²θ_t)
/// (principal root), r_∥ = (η cos θ_i − cos θ_t)/(η cos θ_i + cos θ_t),
/// r_⊥ = (cos θ_i − η cos θ_t)/(cos θ_i + η cos θ_t) (Born & Wolf, Principles of Optics,
/// 7th ed., §14.2; pbrt-v4 `FrComplex`). In f64. At normal incidence it is
/// ((n − 1)² + k²)/((n + 1)² + k²); with k = 0 it is [`fresnel_dielectric`] (below the
/// critical angle). `cos_i` is clamped to [0, 1]; a NaN index gives 1 (a mirror).
#[inline]
pub fn fresnel_conductor(cos_i: f32, n: f32, k: f32) -> f32 {
    if n.is_nan() || k.is_nan() {
        return 1.0;
    }
    let c = f64::from(cos_i.clamp(0.0, 1.0));
    let eta = Complex::new(f64::from(n), f64::from(k.max(0.0)));
    let sin2_t = Complex::real((1.0 - c) * (1.0 + c)) / (eta * eta);
    let cos_t = (Complex::real(1.0) - sin2_t).sqrt();
    let ci = Complex::real(c);
    let r_parl = (eta * ci - cos_t) / (eta * ci + cos_t);
    let r_perp = (ci - eta * cos_t) / (ci + eta * cos_t);
    let r = 0.5 * (r_parl.norm_sqr() + r_perp.norm_sqr());
    if r.is_nan() {
        // 0/0 only when both denominators vanish: η = 0 at grazing incidence.
        return 1.0;
    }
    r.clamp(0.0, 1.0) as f32
}

/// [`fresnel_conductor`] channel by channel (RGB) or lane by lane (4 wavelengths).
#[inline]
pub fn fresnel_conductor_c<C: Carrier>(cos_i: f32, eta: C, k: C) -> C {
    let (n, k) = (eta.to_lanes(), k.to_lanes());
    C::from_lanes(std::array::from_fn(|i| {
        fresnel_conductor(cos_i, n[i], k[i])
    }))
}

/// Critical angle θ_c = asin(n_t/n_i) for light going from the denser medium; `None` when
/// `eta = n_t/n_i ≥ 1` (no total internal reflection possible).
pub fn critical_angle(eta: f32) -> Option<f32> {
    (eta < 1.0).then(|| eta.asin())
}

/// Schlick's approximation F0 + (1−F0)(1−cos)^5 (Schlick 1994), used for metals with a
/// base-colour F0 as the glTF spec prescribes.
#[inline]
pub fn fresnel_schlick<C: Carrier>(f0: C, cos_i: f32) -> C {
    let m = (1.0 - cos_i.clamp(0.0, 1.0)).powi(5);
    f0 + (C::ONE - f0) * m
}

/// Orients an interface for a ray arriving at a surface with outward normal `n_out` and
/// inside index `ior` (outside: air). Returns the normal on the incident side and the
/// relative index η = n_t/n_i: `(n_out, ior)` when entering (`front_face`), and
/// `(−n_out, 1/ior)` when exiting.
#[inline]
pub fn orient_interface(front_face: bool, n_out: Vec3, ior: f32) -> (Vec3, f32) {
    if front_face {
        (n_out, ior)
    } else {
        (-n_out, 1.0 / ior)
    }
}
