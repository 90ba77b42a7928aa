//! Dielectric interfaces: smooth (delta) and rough GGX (Walter et al. 2007) reflection +
//! transmission, and the thin-walled slab (straight-through transmission).
//!
//! Frame: local shading frame, z = OUTWARD normal; `wo.z < 0` means the path is inside the
//! object. `eta` = n_inside / n_outside (may be < 1, may be +∞ for a perfect mirror).
//! Follows pbrt-v4 `DielectricBxDF` / `ThinDielectricBxDF` (§9.5, §9.7): reflection vs
//! transmission is chosen with probability R/(R+T) of the Fresnel term, and in
//! [`TransportMode::Radiance`] transmission is divided by η'² (η' = n_t/n_i along the path
//! from `wo` to `wi`, pbrt-v4 §9.5.2). `tint` multiplies transmission only.
//! The rough interface's `eval`/`sample` include the multiple-scattering compensation of
//! [`super::energy`] (a factor 1/E_ss(wo); pdf unchanged); `rough_eval_ss` is the
//! single-scatter, reciprocal part.

use super::{same_hemisphere, BsdfSample, TransportMode};
use crate::optics::{fresnel_either_side as fresnel, reflect, refract};
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

use super::energy;
use super::microfacet::Ggx;

/// Refraction of `w` through a (micro)surface with normal `n` on either side, reusing
/// [`crate::optics::refract`] after orienting the interface (pbrt-v4 `Refract`). Returns the
/// refracted direction and η' = n_t/n_i, or `None` under total internal reflection.
#[inline]
fn refract_either(w: Vec3, n: Vec3, eta: f32) -> Option<(Vec3, f32)> {
    let (n, etap) = if w.dot(n) < 0.0 {
        (-n, 1.0 / eta)
    } else {
        (n, eta)
    };
    if !etap.is_finite() || etap <= 0.0 {
        return None;
    }
    refract(w, n, etap).map(|wt| (wt, etap))
}

/// Sample of the smooth interface (delta lobes). For η = 1 the interface vanishes: all
/// energy goes straight through, `wi = −wo`, f = tint/|cos θi|.
pub(crate) fn smooth_sample<C: Carrier>(
    eta: f32,
    tint: C,
    wo: Vec3,
    uc: f32,
    mode: TransportMode,
) -> Option<BsdfSample<C>> {
    if wo.z == 0.0 {
        return None;
    }
    let r = fresnel(wo.z, eta);
    let t = 1.0 - r;
    if uc < r {
        let wi = Vec3::new(-wo.x, -wo.y, wo.z);
        return Some(BsdfSample {
            wi,
            f: C::splat(r / wi.z.abs()),
            pdf: r,
            delta: true,
            transmission: false,
        });
    }
    let (wi, etap) = if eta == 1.0 {
        (-wo, 1.0)
    } else {
        refract_either(wo, Vec3::Z, eta)?
    };
    if wi.z == 0.0 || t <= 0.0 {
        return None;
    }
    let mut ft = tint * (t / wi.z.abs());
    if mode == TransportMode::Radiance {
        ft /= etap * etap;
    }
    Some(BsdfSample {
        wi,
        f: ft,
        pdf: t,
        delta: true,
        transmission: true,
    })
}

/// Generalised half vector of a rough pair (Walter 2007, eq. 16; pbrt-v4 §9.7.5), faced to
/// +z, with η' and whether it is a reflection; `None` for degenerate or back-facing
/// configurations (microfacet on the wrong side of either direction).
#[inline]
fn half_vector(eta: f32, wo: Vec3, wi: Vec3) -> Option<(Vec3, f32, bool)> {
    let (co, ci) = (wo.z, wi.z);
    if co == 0.0 || ci == 0.0 {
        return None;
    }
    let reflect = co * ci > 0.0;
    let etap = if reflect {
        1.0
    } else if co > 0.0 {
        eta
    } else {
        1.0 / eta
    };
    if !reflect && (!etap.is_finite() || etap <= 0.0) {
        return None;
    }
    // wi·η' + wo, scaled by 1/η' when η' > 1 so that neither form overflows for extreme
    // indices (η' = 1e30 made |wm|² = +∞ and wm NaN); the direction is the same.
    let wm = if etap > 1.0 {
        wi + wo / etap
    } else {
        wi * etap + wo
    };
    if wm.length_squared() == 0.0 || !wm.is_finite() {
        return None;
    }
    let mut wm = wm.normalize();
    if wm.z < 0.0 {
        wm = -wm;
    }
    if wm.dot(wi) * ci < 0.0 || wm.dot(wo) * co < 0.0 {
        return None;
    }
    Some((wm, etap, reflect))
}

/// Rough dielectric with multiple-scattering compensation (Turquin 2019, see
/// [`super::energy`]): the single-scatter [`rough_eval_ss`] divided by its directional
/// albedo E_ss(wo), so that ∫ f |cos θi| dωi = 1 (Importance mode, tint 1) for every wo.
/// Not reciprocal: f(wo, wi)·E(wo) = f(wi, wo)·E(wi).
pub(crate) fn rough_eval<C: Carrier>(
    eta: f32,
    alpha: f32,
    tint: C,
    wo: Vec3,
    wi: Vec3,
    mode: TransportMode,
) -> C {
    let f = rough_eval_ss(eta, alpha, tint, wo, wi, mode);
    if f == C::ZERO {
        return f;
    }
    f * energy::compensation(eta, alpha, wo)
}

/// Single-scatter rough dielectric f_ss(wo, wi): Walter 2007 eq. 20 (reflection) and eq. 21
/// (transmission), with the height-correlated G2 instead of the separable one. Loses the
/// energy of light scattered more than once between microfacets.
pub(crate) fn rough_eval_ss<C: Carrier>(
    eta: f32,
    alpha: f32,
    tint: C,
    wo: Vec3,
    wi: Vec3,
    mode: TransportMode,
) -> C {
    let Some((wm, etap, refl)) = half_vector(eta, wo, wi) else {
        return C::ZERO;
    };
    let ggx = Ggx { alpha };
    let f = fresnel(wo.dot(wm), eta);
    let (co, ci) = (wo.z, wi.z);
    if refl {
        return C::splat(ggx.d(wm) * ggx.g(wo, wi) * f / (4.0 * ci * co).abs());
    }
    // Radiance mode divides by η'²; folding it into the denominator,
    // (wi·wm + wo·wm/η')²·η'² = (η' wi·wm + wo·wm)², keeps 0/0 and ∞/∞ out of extreme
    // indices (η' = 1e-30 made the denominator +∞ and η'² zero).
    let (iw, ow) = (wi.dot(wm), wo.dot(wm));
    let denom = match mode {
        TransportMode::Radiance => (etap * iw + ow).powi(2),
        TransportMode::Importance => (iw + ow / etap).powi(2),
    };
    let ft = ggx.d(wm) * (1.0 - f) * ggx.g(wo, wi) * (iw * ow / (denom * ci * co)).abs();
    if !ft.is_finite() {
        return C::ZERO;
    }
    tint * ft
}

/// Solid-angle pdf of [`rough_sample`]: VNDF density times the Jacobian of the half-vector
/// map, 1/(4|wo·wm|) for reflection (Walter 2007, eq. 14) and |wi·wm|/(wi·wm + wo·wm/η')²
/// for transmission (eq. 17), times the R/T choice probability.
pub(crate) fn rough_pdf(eta: f32, alpha: f32, wo: Vec3, wi: Vec3) -> f32 {
    let Some((wm, etap, refl)) = half_vector(eta, wo, wi) else {
        return 0.0;
    };
    let ggx = Ggx { alpha };
    let r = fresnel(wo.dot(wm), eta);
    let t = 1.0 - r;
    if refl {
        ggx.pdf_visible(wo, wm) / (4.0 * wo.dot(wm).abs()) * r
    } else {
        let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2);
        ggx.pdf_visible(wo, wm) * wi.dot(wm).abs() / denom * t
    }
}

/// Samples the rough dielectric: a visible microfacet normal (Heitz 2018), then reflection
/// with probability F(wo·wm), else refraction through that microfacet (TIR ⇒ F = 1).
/// `None` when the scattered direction ends on the wrong side of the macro-surface.
pub(crate) fn rough_sample<C: Carrier>(
    eta: f32,
    alpha: f32,
    tint: C,
    wo: Vec3,
    uc: f32,
    u: Vec2,
    mode: TransportMode,
) -> Option<BsdfSample<C>> {
    if wo.z == 0.0 {
        return None;
    }
    let ggx = Ggx { alpha };
    let wm = ggx.sample_visible(wo, u);
    let r = fresnel(wo.dot(wm), eta);
    let (wi, transmission) = if uc < r {
        let wi = reflect(wo, wm);
        if !same_hemisphere(wo, wi) {
            return None;
        }
        (wi, false)
    } else {
        let (wi, _) = refract_either(wo, wm, eta)?;
        if same_hemisphere(wo, wi) || wi.z == 0.0 {
            return None;
        }
        (wi, true)
    };
    let pdf = rough_pdf(eta, alpha, wo, wi);
    if pdf <= 0.0 || !pdf.is_finite() {
        return None;
    }
    Some(BsdfSample {
        wi,
        f: rough_eval(eta, alpha, tint, wo, wi, mode),
        pdf,
        delta: false,
        transmission,
    })
}

/// Thin-walled slab (pbrt-v4 `ThinDielectricBxDF`, §9.5.3): the geometric series of
/// inter-reflections between the two parallel interfaces gives R' = R + T²R/(1 − R²),
/// T' = 1 − R'; transmission goes straight through (`wi = −wo`, no bending, no η² factor
/// since both sides are the same medium), tinted by `tint`.
pub(crate) fn thin_sample<C: Carrier>(
    eta: f32,
    tint: C,
    wo: Vec3,
    uc: f32,
) -> Option<BsdfSample<C>> {
    if wo.z == 0.0 {
        return None;
    }
    let mut r = fresnel(wo.z.abs(), eta);
    let mut t = 1.0 - r;
    if r < 1.0 {
        r += t * t * r / (1.0 - r * r);
        t = 1.0 - r;
    }
    if uc < r {
        let wi = Vec3::new(-wo.x, -wo.y, wo.z);
        Some(BsdfSample {
            wi,
            f: C::splat(r / wi.z.abs()),
            pdf: r,
            delta: true,
            transmission: false,
        })
    } else {
        let wi = -wo;
        Some(BsdfSample {
            wi,
            f: tint * (t / wi.z.abs()),
            pdf: t,
            delta: true,
            transmission: true,
        })
    }
}
