//! Opaque reflection lobes: Lambert, the GGX conductor (Schlick from a colour, or the exact
//! complex Fresnel term of a measured metal), and the glTF metallic-roughness
//! mix (glTF 2.0 spec Appendix B + KHR_materials_specular).
//!
//! Frame: local shading frame, z = normal. All lobes here are two-sided reflection: they are
//! non-zero only when `wo` and `wi` lie in the same hemisphere and use |cos θ|. Densities
//! are per unit solid angle.

use super::anisotropic::Microfacet;
use super::iridescence::{ior_from_f0, LobeExtensions};
use super::microfacet::Distribution;
use super::{reflect_z, same_hemisphere, Bsdf, BsdfSample};
use crate::optics::{fresnel_conductor_c, fresnel_schlick, reflect};
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Smallest GGX α of the glTF lobe (the same floor as `crate::shading`): the glTF
/// material has no delta lobe.
pub const GLTF_MIN_ALPHA: f32 = 1e-2;

/// Cosine-weighted hemisphere direction on `wo`'s side (Malley's method, pbrt-v4 §A.5.3,
/// with the concentric map replaced by the polar one), pdf |cos θ|/π.
#[inline]
pub(super) fn cosine_hemisphere(wo: Vec3, u: Vec2) -> Vec3 {
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let z = (1.0 - u.x).max(0.0).sqrt();
    let z = if wo.z < 0.0 { -z } else { z };
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Lambert f = albedo/π.
pub(crate) fn lambert_eval<C: Carrier>(albedo: C, wo: Vec3, wi: Vec3) -> C {
    if same_hemisphere(wo, wi) {
        albedo * FRAC_1_PI
    } else {
        C::ZERO
    }
}

/// Cosine-weighted pdf |cos θi|/π.
pub(crate) fn lambert_pdf(wo: Vec3, wi: Vec3) -> f32 {
    if same_hemisphere(wo, wi) {
        wi.z.abs() * FRAC_1_PI
    } else {
        0.0
    }
}

/// Cosine-weighted sample of the Lambert lobe.
pub(crate) fn lambert_sample<C: Carrier>(albedo: C, wo: Vec3, u: Vec2) -> Option<BsdfSample<C>> {
    let wi = cosine_hemisphere(wo, u);
    BsdfSample::lobe(wi, lambert_pdf(wo, wi), false, || albedo * FRAC_1_PI)
}

/// Half vector of a reflection pair, faced to +z (`None` when degenerate or not a
/// reflection).
#[inline]
pub(super) fn half_reflect(wo: Vec3, wi: Vec3) -> Option<Vec3> {
    if !same_hemisphere(wo, wi) {
        return None;
    }
    let wm = (wo + wi).normalize_or_zero();
    if wm == Vec3::ZERO {
        return None;
    }
    Some(if wm.z < 0.0 { -wm } else { wm })
}

/// Cook–Torrance specular term D·G2/(4|cos θo||cos θi|) without Fresnel (Walter 2007,
/// eq. 20), and |wo·wm| for the Fresnel term.
#[inline]
pub(super) fn ggx_spec(ggx: impl Into<Microfacet>, wo: Vec3, wi: Vec3) -> Option<(f32, f32)> {
    let ggx: Microfacet = ggx.into();
    let wm = half_reflect(wo, wi)?;
    let s = ggx.d(wm) * ggx.g(wo, wi) / (4.0 * wo.z.abs() * wi.z.abs());
    Some((s, wo.dot(wm).abs()))
}

/// pdf of reflecting a visible normal: D_wo(wm)/(4|wo·wm|) (Walter 2007, eq. 14;
/// Heitz 2018, eq. 17).
#[inline]
pub(super) fn ggx_reflect_pdf(ggx: impl Into<Microfacet>, wo: Vec3, wi: Vec3) -> f32 {
    let ggx: Microfacet = ggx.into();
    match half_reflect(wo, wi) {
        Some(wm) => ggx.pdf_visible(wo, wm) / (4.0 * wo.dot(wm).abs()),
        None => 0.0,
    }
}

/// Reflects `wo` about a visible normal; `None` when it lands under the surface.
#[inline]
pub(super) fn ggx_reflect_sample(ggx: impl Into<Microfacet>, wo: Vec3, u: Vec2) -> Option<Vec3> {
    let ggx: Microfacet = ggx.into();
    if wo.z == 0.0 {
        return None;
    }
    let wi = reflect(wo, ggx.sample_visible(wo, u));
    same_hemisphere(wo, wi).then_some(wi)
}

/// The Fresnel reflectance of a conductor lobe.
#[derive(Debug, Clone, Copy)]
pub(crate) enum ConductorFresnel<C: Carrier> {
    /// Schlick from the normal-incidence reflectance (a glTF metal's base colour).
    Schlick(C),
    /// The exact reflectance of the complex index η + ik of a measured metal, mixed with a
    /// thin film's on that metal when the material is iridescent.
    Complex {
        eta: C,
        k: C,
        extensions: LobeExtensions,
    },
}

impl<C: Carrier> ConductorFresnel<C> {
    /// The reflectance at the cosine `cos` of the angle of incidence.
    #[inline]
    fn at(&self, cos: f32) -> C {
        match *self {
            ConductorFresnel::Schlick(f0) => fresnel_schlick(f0, cos),
            ConductorFresnel::Complex { eta, k, extensions } => {
                let plain = fresnel_conductor_c(cos, eta, k);
                match extensions.iridescence {
                    Some(ir) => ir.mix(plain, cos, eta, k),
                    None => plain,
                }
            }
        }
    }
}

/// A GGX conductor: reflection only, f = D·G2·F(|wo·wm|)/(4|cos θo||cos θi|), sampled by
/// reflecting a visible normal; `smooth` (α below the delta threshold) makes it a delta
/// mirror.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Conductor<C: Carrier> {
    pub fresnel: ConductorFresnel<C>,
    pub ggx: Microfacet,
    pub smooth: bool,
}

impl<C: Carrier> Conductor<C> {
    /// f(wo, wi) of the rough lobe.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> C {
        match ggx_spec(self.ggx, wo, wi) {
            Some((s, cos_h)) => self.fresnel.at(cos_h) * s,
            None => C::ZERO,
        }
    }

    /// Solid-angle pdf of the rough lobe (VNDF reflection).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        ggx_reflect_pdf(self.ggx, wo, wi)
    }

    /// A VNDF reflection; when smooth, the mirror direction with f = F/|cos θi|, pdf 1.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample<C>> {
        if wo.z == 0.0 {
            return None;
        }
        if self.smooth {
            let wi = reflect_z(wo);
            let f = self.fresnel.at(wo.z.abs()) / wi.z.abs();
            return Some(BsdfSample::delta(wi, f, 1.0, false));
        }
        let wi = ggx_reflect_sample(self.ggx, wo, u)?;
        BsdfSample::lobe(wi, self.pdf(wo, wi), false, || self.eval(wo, wi))
    }
}

/// The glTF metallic-roughness BRDF with KHR_materials_specular, already resolved.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Gltf<C: Carrier> {
    pub base: C,
    pub metallic: f32,
    pub ggx: Microfacet,
    /// Dielectric F0 = min(((ior−1)/(ior+1))²·specular_color, 1)·specular.
    pub f0: C,
    /// Dielectric F90 = specular.
    pub f90: f32,
    /// Iridescence and anisotropy ([`super::iridescence`]).
    pub extensions: LobeExtensions,
}

impl<C: Carrier> Gltf<C> {
    /// The BRDF of a [`Bsdf::GltfPbr`] (`None` for another BSDF).
    pub fn of(bsdf: &Bsdf<C>) -> Option<Self> {
        let Bsdf::GltfPbr {
            base,
            metallic,
            alpha,
            ior,
            specular,
            specular_color,
            extensions,
            ..
        } = *bsdf
        else {
            return None;
        };
        let f0_ior = if ior.is_finite() {
            ((ior - 1.0) / (ior + 1.0)).powi(2)
        } else {
            1.0
        };
        Some(Gltf {
            base,
            metallic: metallic.clamp(0.0, 1.0),
            ggx: Microfacet::khr(alpha.max(GLTF_MIN_ALPHA), extensions.anisotropy),
            f0: (specular_color * f0_ior).min(C::ONE) * specular,
            f90: specular,
            extensions,
        })
    }

    /// Schlick with f90 (KHR_materials_specular): F0 + (F90 − F0)(1 − cos)^5.
    #[inline]
    /// With KHR_materials_iridescence: mixed with the film's reflectance on a substrate of
    /// index from F0/specular, times `specular` ([`super::iridescence`]).
    pub(super) fn fresnel_d(&self, cos: f32) -> C {
        let plain = self.f0 + (C::splat(self.f90) - self.f0) * (1.0 - cos.clamp(0.0, 1.0)).powi(5);
        match self.extensions.iridescence {
            Some(layer) if self.f90 > 0.0 => {
                let eta = ior_from_f0(self.f0 / self.f90);
                let r = layer.reflectance(cos, eta, C::ZERO) * self.f90;
                plain.lerp(r, layer.factor)
            }
            _ => plain,
        }
    }

    /// The metal lobe's Fresnel: Schlick with F0 = base colour, mixed with the film's
    /// reflectance on a substrate of index from the base colour (KHR_materials_iridescence).
    fn fresnel_m(&self, cos: f32) -> C {
        let plain = fresnel_schlick(self.base, cos);
        match self.extensions.iridescence {
            Some(layer) if self.metallic > 0.0 => {
                layer.mix(plain, cos, ior_from_f0(self.base), C::ZERO)
            }
            _ => plain,
        }
    }

    /// f = mix((1 − max F_d)·base/π + F_d·spec, F_schlick(base)·spec, metallic)
    /// (glTF 2.0 Appendix B.3.5).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> C {
        let Some((s, cos_h)) = ggx_spec(self.ggx, wo, wi) else {
            return C::ZERO;
        };
        let fd = self.fresnel_d(cos_h);
        let dielectric = self.base * FRAC_1_PI * (1.0 - fd.max_element()) + fd * s;
        let metal = self.fresnel_m(cos_h) * s;
        dielectric.lerp(metal, self.metallic)
    }

    /// Probability of sampling the specular lobe: its estimated weight (Fresnel at |cos θo|)
    /// over the total, kept in [0.1, 0.9] unless a lobe is exactly absent.
    fn p_spec(&self, wo: Vec3) -> f32 {
        let c = wo.z.abs();
        let fd = self.fresnel_d(c);
        let m = self.metallic;
        let w_spec = (1.0 - m) * fd.average() + m * fresnel_schlick(self.base, c).average();
        let w_diff = (1.0 - m) * self.base.average() * (1.0 - fd.max_element());
        if w_diff <= 0.0 {
            1.0
        } else if w_spec <= 0.0 {
            0.0
        } else {
            (w_spec / (w_spec + w_diff)).clamp(0.1, 0.9)
        }
    }

    /// Mixture pdf p_spec·pdf_GGX + (1 − p_spec)·pdf_cos.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z == 0.0 {
            return 0.0;
        }
        let p = self.p_spec(wo);
        p * ggx_reflect_pdf(self.ggx, wo, wi) + (1.0 - p) * lambert_pdf(wo, wi)
    }

    /// One-sample lobe selection by `uc`; returns the full f and mixture pdf.
    pub fn sample(&self, wo: Vec3, uc: f32, u: Vec2) -> Option<BsdfSample<C>> {
        if wo.z == 0.0 {
            return None;
        }
        let wi = if uc < self.p_spec(wo) {
            ggx_reflect_sample(self.ggx, wo, u)?
        } else {
            cosine_hemisphere(wo, u)
        };
        BsdfSample::lobe(wi, self.pdf(wo, wi), false, || self.eval(wo, wi))
    }
}
