//! Geometric optics at a smooth interface: mirror reflection, Snell refraction, the exact
//! unpolarised Fresnel equations and the critical angle. Pure functions on unit vectors;
//! `eta` is always the **relative** index n_transmitted / n_incident.
//!
//! Sign convention: `n` is the unit normal on the side the incident direction comes from,
//! i.e. `dot(wi, n) > 0` where `wi` points *away* from the surface toward the viewer/light.

use crate::spectrum::Carrier;
use glam::Vec3;

/// Mirror reflection of `wi` (pointing away from the surface) about `n`.
#[inline]
pub fn reflect(wi: Vec3, n: Vec3) -> Vec3 {
    2.0 * wi.dot(n) * n - wi
}

/// Refracts `wi` (pointing away from the surface, on the side of `n`) into the other medium
/// with relative index `eta` = n_t/n_i. Returns `None` on total internal reflection.
/// Snell's law n_i sin θ_i = n_t sin θ_t in vector form (pbrt-v4 §9.3, `Refract`).
/// The result is unit length when `wi` and `n` are.
#[inline]
pub fn refract(wi: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = wi.dot(n).clamp(0.0, 1.0);
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let wt = -wi / eta + (cos_i / eta - cos_t) * n;
    Some(wt.normalize())
}

/// Exact unpolarised Fresnel reflectance of a smooth dielectric interface
/// (Born & Wolf; pbrt-v4 `FrDielectric`): the mean of the s- and p-polarised reflectances,
/// `cos_i` = cosine of the incident angle (≥ 0), `eta` = n_t/n_i. Returns 1 under total
/// internal reflection. `eta` = +∞ (the glTF `ior: 0` mode) gives 1.
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    if eta.is_infinite() {
        return 1.0;
    }
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).max(0.0).sqrt();
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    (0.5 * (r_parl * r_parl + r_perp * r_perp)).clamp(0.0, 1.0)
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
