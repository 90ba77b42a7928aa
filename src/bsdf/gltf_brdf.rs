//! The glTF metallic-roughness BRDF with KHR_materials_specular ([`Gltf`]), resolved from a
//! [`super::pbr::GltfPbr`] lobe's parameters: Lambert diffuse + GGX specular mixed with a
//! metal lobe (glTF 2.0 spec Appendix B), with iridescence's Fresnel where present. The
//! base of [`super::layers`] and the lobe itself when it has no layer.
//!
//! Frame: local shading frame, z = normal; two-sided reflection (|cos θ|). Densities are per
//! unit solid angle.

use super::anisotropic::Microfacet;
use super::ggx_reflect::{ggx_reflect_pdf, ggx_reflect_sample, ggx_spec};
use super::iridescence::{ior_from_f0, LobeExtensions};
use super::lambert::{cosine_hemisphere, lambert_pdf};
use super::BsdfSample;
use crate::optics::fresnel_schlick;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// Smallest GGX α of the glTF lobe (the same floor as `crate::shading`): the glTF
/// material has no delta lobe.
pub const GLTF_MIN_ALPHA: f32 = 1e-2;

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
