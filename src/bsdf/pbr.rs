//! The glTF metallic-roughness lobe ([`GltfPbr`]): Lambert diffuse + GGX specular mixed with
//! a metal lobe (glTF 2.0 spec Appendix B + KHR_materials_specular), with the KHR layers
//! ([`super::layers`]) when present; and the GGX reflection helpers the conductor and the
//! layers share.
//!
//! Frame: local shading frame, z = normal. The lobes here are two-sided reflection: they are
//! non-zero only when `wo` and `wi` lie in the same hemisphere and use |cos θ| (the diffuse
//! transmission layer excepted). Densities are per unit solid angle.

use super::anisotropic::Microfacet;
use super::iridescence::{ior_from_f0, LobeExtensions};
use super::lambert::{cosine_hemisphere, lambert_pdf};
use super::layers::{Layered, Layers};
use super::lobe::{normal_reflectance, Lobe, RouletteLobes, GLOSSY_ALPHA};
use super::microfacet::Distribution;
use super::{same_hemisphere, Bsdf, BsdfSample, TransportMode};
use crate::optics::{fresnel_schlick, reflect};
use crate::polar::stokes::Mueller;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// Smallest GGX α of the glTF lobe (the same floor as `crate::shading`): the glTF
/// material has no delta lobe.
pub const GLTF_MIN_ALPHA: f32 = 1e-2;

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
    /// The BRDF of a [`GltfPbr`] lobe, its layers aside.
    pub fn of(lobe: &GltfPbr<C>) -> Self {
        let GltfPbr {
            base,
            metallic,
            alpha,
            ior,
            specular,
            specular_color,
            extensions,
            ..
        } = *lobe;
        let f0_ior = if ior.is_finite() {
            ((ior - 1.0) / (ior + 1.0)).powi(2)
        } else {
            1.0
        };
        Gltf {
            base,
            metallic: metallic.clamp(0.0, 1.0),
            ggx: Microfacet::khr(alpha.max(GLTF_MIN_ALPHA), extensions.anisotropy),
            f0: (specular_color * f0_ior).min(C::ONE) * specular,
            f90: specular,
            extensions,
        }
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

/// [`Bsdf::GltfPbr`]: the glTF metallic-roughness parameters, its KHR layers and extensions.
///
/// Polarization: it depolarizes (the diffuse, specular and layer lobes mixed are treated as
/// the ideal depolarizer). Photons under lobe roulette: diffuse with (1 − metallic)·base,
/// specular with metallic·base + (1 − metallic)·the dielectric F0. The denoiser's albedo
/// is the base colour (the specular layer is a non-absorbing coat; for a metal the base
/// colour is the normal-incidence reflectance).
#[derive(Debug, Clone, Copy)]
pub(crate) struct GltfPbr<C: Carrier> {
    pub base: C,
    pub metallic: f32,
    pub alpha: f32,
    pub ior: f32,
    pub specular: f32,
    pub specular_color: C,
    pub layers: Layers<C>,
    pub extensions: LobeExtensions,
}

impl<C: Carrier> GltfPbr<C> {
    /// The layered BSDF when any KHR layer is present (`None` otherwise: the plain glTF
    /// BRDF, unchanged).
    pub(super) fn layered(&self) -> Option<Layered<C>> {
        (!self.layers.is_none()).then(|| Layered::new(Gltf::of(self), &self.layers))
    }
}

impl<C: Carrier> Lobe<C> for GltfPbr<C> {
    fn is_delta(&self) -> bool {
        false
    }
    fn samples_direction(&self) -> bool {
        true
    }
    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> C {
        match self.layered() {
            Some(l) => l.eval(wo, wi, mode),
            None => Gltf::of(self).eval(wo, wi),
        }
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self.layered() {
            Some(l) => l.pdf(wo, wi),
            None => Gltf::of(self).pdf(wo, wi),
        }
    }
    fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<C>> {
        match self.layered() {
            Some(l) => l.sample(wo, uc, u, mode),
            None => Gltf::of(self).sample(wo, uc, u),
        }
    }
    fn mueller(&self, _wo: Vec3, _wi: Vec3) -> Option<(Mueller, Vec3)> {
        None
    }
    fn depolarizes(&self) -> bool {
        true
    }
    fn hero_polarizes(&self) -> bool {
        false
    }
    /// A coat over a diffuse base is still gathered on; a sheen is a diffuse-like lobe.
    fn is_diffuse_like(&self) -> bool {
        self.metallic < 1.0
            || self.alpha >= GLOSSY_ALPHA
            || self.layers.sheen_color.max_element() > 0.0
    }
    fn roulette_lobes(&self) -> RouletteLobes<C> {
        let dielectric_f0 =
            (self.specular_color * (normal_reflectance(self.ior) * self.specular)).min(C::ONE);
        RouletteLobes {
            diffuse: self.base * (1.0 - self.metallic),
            specular: self.base * self.metallic + dielectric_f0 * (1.0 - self.metallic),
            transmission: C::ZERO,
        }
    }
    fn roulette_transmission(&self, wo: Vec3) -> Vec3 {
        -wo
    }
    fn albedo(&self) -> C {
        self.base
    }
    fn interface_eta(&self) -> Option<f32> {
        None
    }
    fn with_lane(&self, _eta: f32, _k: usize) -> Option<Bsdf<C>> {
        None
    }
}
