//! The dielectric interface lobe ([`Dielectric`]): smooth (delta) and rough GGX (Walter et
//! al. 2007) reflection + transmission. The thin-walled slab is [`super::thin`].
//!
//! Frame: local shading frame, z = OUTWARD normal; `wo.z < 0` means the path is inside the
//! object. `eta` = n_inside / n_outside (may be < 1, may be +∞ for a perfect mirror).
//! Follows pbrt-v4 `DielectricBxDF` / `ThinDielectricBxDF` (§9.5, §9.7): reflection vs
//! transmission is chosen with probability R/(R+T) of the Fresnel term, and in
//! [`TransportMode::Radiance`] transmission is divided by η'² (η' = n_t/n_i along the path
//! from `wo` to `wi`, pbrt-v4 §9.5.2). `tint` multiplies transmission only.
//! The rough interface's `eval`/`sample` include the multiple-scattering compensation of
//! [`super::energy`] (a factor 1/E_ss(wo) in Radiance mode, 1/E_ss(wi) in Importance mode,
//! its adjoint; pdf unchanged); [`Rough::eval_ss`] is the single-scatter, reciprocal part.

use super::energy;
use super::lobe::{normal_reflectance, Lobe, RouletteLobes, GLOSSY_ALPHA};
use super::microfacet::{Distribution, Ggx};
use super::{reflect_z, same_hemisphere, Bsdf, BsdfSample, TransportMode, SMOOTH_ALPHA};
use crate::optics::{fresnel_either_side as fresnel, reflect, refract};
use crate::polar::fresnel::dielectric as fresnel_mueller;
use crate::polar::stokes::{Mueller, IDENTITY};
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

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
        return Some(specular_reflection(wo, r));
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
    Some(BsdfSample::delta(wi, ft, t, true))
}

/// The delta reflection of a smooth interface chosen with probability `r`, its Fresnel
/// reflectance: f = r/|cos θi|.
#[inline]
pub(super) fn specular_reflection<C: Carrier>(wo: Vec3, r: f32) -> BsdfSample<C> {
    let wi = reflect_z(wo);
    BsdfSample::delta(wi, C::splat(r / wi.z.abs()), r, false)
}

/// Generalised half vector of a rough pair (Walter 2007, eq. 16; pbrt-v4 §9.7.5), faced to
/// +z, with η' and whether it is a reflection; `None` for degenerate or back-facing
/// configurations (microfacet on the wrong side of either direction).
#[inline]
pub(crate) fn half_vector(eta: f32, wo: Vec3, wi: Vec3) -> Option<(Vec3, f32, bool)> {
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

/// A rough interface: index ratio `eta`, GGX `alpha`, transmission `tint`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rough<C: Carrier> {
    pub eta: f32,
    pub alpha: f32,
    pub tint: C,
}

impl<C: Carrier> Rough<C> {
    /// f(wo, wi) with multiple-scattering compensation (Turquin 2019, see
    /// [`super::energy`]): the single-scatter [`Rough::eval_ss`] divided by its directional
    /// albedo, in Radiance mode E_ss(wo), so that a camera path's expected throughput at the
    /// vertex is 1 (white furnace); in Importance mode E_ss(wi), so that the mode is the
    /// exact adjoint, f_Importance(wo, wi) = f_Radiance(wi, wo), and photons and light
    /// subpaths estimate what camera paths do. Not reciprocal: f(wo, wi)·E(wo) =
    /// f(wi, wo)·E(wi).
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> C {
        let f = self.eval_ss(wo, wi, mode);
        if f == C::ZERO {
            return f;
        }
        let seen_from = match mode {
            TransportMode::Radiance => wo,
            TransportMode::Importance => wi,
        };
        f * energy::compensation(self.eta, self.alpha, seen_from)
    }

    /// Single-scatter f_ss(wo, wi): Walter 2007 eq. 20 (reflection) and eq. 21
    /// (transmission), with the height-correlated G2 instead of the separable one. Loses the
    /// energy of light scattered more than once between microfacets.
    pub fn eval_ss(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> C {
        let Some((wm, etap, refl)) = half_vector(self.eta, wo, wi) else {
            return C::ZERO;
        };
        let ggx = Ggx { alpha: self.alpha };
        let f = fresnel(wo.dot(wm), self.eta);
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
        self.tint * ft
    }

    /// Solid-angle pdf of [`Rough::sample`]: VNDF density times the Jacobian of the
    /// half-vector map, 1/(4|wo·wm|) for reflection (Walter 2007, eq. 14) and
    /// |wi·wm|/(wi·wm + wo·wm/η')² for transmission (eq. 17), times the R/T choice
    /// probability.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some((wm, etap, refl)) = half_vector(self.eta, wo, wi) else {
            return 0.0;
        };
        let ggx = Ggx { alpha: self.alpha };
        let r = fresnel(wo.dot(wm), self.eta);
        let t = 1.0 - r;
        if refl {
            ggx.pdf_visible(wo, wm) / (4.0 * wo.dot(wm).abs()) * r
        } else {
            let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2);
            ggx.pdf_visible(wo, wm) * wi.dot(wm).abs() / denom * t
        }
    }

    /// A visible microfacet normal (Heitz 2018), then reflection with probability
    /// F(wo·wm), else refraction through that microfacet (TIR ⇒ F = 1). `None` when the
    /// scattered direction ends on the wrong side of the macro-surface.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<C>> {
        if wo.z == 0.0 {
            return None;
        }
        let wm = Ggx { alpha: self.alpha }.sample_visible(wo, u);
        let r = fresnel(wo.dot(wm), self.eta);
        let (wi, transmission) = if uc < r {
            let wi = reflect(wo, wm);
            if !same_hemisphere(wo, wi) {
                return None;
            }
            (wi, false)
        } else {
            let (wi, _) = refract_either(wo, wm, self.eta)?;
            if same_hemisphere(wo, wi) || wi.z == 0.0 {
                return None;
            }
            (wi, true)
        };
        BsdfSample::lobe(wi, self.pdf(wo, wi), transmission, || {
            self.eval(wo, wi, mode)
        })
    }
}

/// [`Bsdf::Dielectric`]: index ratio `eta` (n_inside / n_outside), GGX `alpha`, transmission
/// `tint`; smooth (delta) when α < [`SMOOTH_ALPHA`] or η = 1.
///
/// Polarization: the Fresnel reflection or transmission matrix at the surface (smooth) or
/// at the generalised half vector (rough), for the light's own η (from `wi`'s side); η = 1
/// changes nothing. Photons under lobe roulette reflect with the normal-incidence
/// reflectance and refract (about the surface normal) with the rest, tinted. The
/// denoiser's albedo is the tint.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Dielectric<C> {
    pub eta: f32,
    pub alpha: f32,
    pub tint: C,
}

impl<C: Carrier> Dielectric<C> {
    fn rough(&self) -> Rough<C> {
        Rough {
            eta: self.eta,
            alpha: self.alpha,
            tint: self.tint,
        }
    }
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

impl<C: Carrier> Lobe<C> for Dielectric<C> {
    fn is_delta(&self) -> bool {
        self.alpha < SMOOTH_ALPHA || self.eta == 1.0
    }
    fn samples_direction(&self) -> bool {
        !self.is_delta()
    }
    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> C {
        self.rough().eval(wo, wi, mode)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.rough().pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<C>> {
        if self.is_delta() {
            smooth_sample(self.eta, self.tint, wo, uc, mode)
        } else {
            self.rough().sample(wo, uc, u, mode)
        }
    }
    fn mueller(&self, wo: Vec3, wi: Vec3) -> Option<(Mueller, Vec3)> {
        if self.eta == 1.0 {
            return Some((IDENTITY, Vec3::Z));
        }
        let reflect = wo.z * wi.z > 0.0;
        let m = if self.alpha < SMOOTH_ALPHA {
            Vec3::Z
        } else {
            half_vector(self.eta, wo, wi)?.0
        };
        let (r, t) = fresnel_mueller(wi.dot(m).abs(), light_eta(self.eta, wi));
        Some((if reflect { r } else { t }, m))
    }
    fn depolarizes(&self) -> bool {
        false
    }
    fn hero_polarizes(&self) -> bool {
        false
    }
    fn is_diffuse_like(&self) -> bool {
        !self.is_delta() && self.alpha >= GLOSSY_ALPHA
    }
    fn roulette_lobes(&self) -> RouletteLobes<C> {
        let r = normal_reflectance(self.eta);
        RouletteLobes {
            diffuse: C::ZERO,
            specular: C::splat(r),
            transmission: self.tint * (1.0 - r),
        }
    }
    /// Refraction about the surface normal, the mirror direction under total internal
    /// reflection.
    fn roulette_transmission(&self, wo: Vec3) -> Vec3 {
        let side = if wo.z >= 0.0 { 1.0 } else { -1.0 };
        let etap = if wo.z >= 0.0 {
            self.eta
        } else {
            1.0 / self.eta
        };
        refract(wo, Vec3::new(0.0, 0.0, side), etap).unwrap_or(Vec3::new(-wo.x, -wo.y, wo.z))
    }
    fn albedo(&self) -> C {
        self.tint
    }
    fn interface_eta(&self) -> Option<f32> {
        Some(self.eta)
    }
    fn with_lane(&self, eta: f32, k: usize) -> Option<Bsdf<C>> {
        Some(Bsdf::Dielectric {
            eta,
            alpha: self.alpha,
            tint: self.tint.rotated(k),
        })
    }
}
