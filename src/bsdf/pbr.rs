//! The glTF metallic-roughness lobe ([`GltfPbr`]): the BRDF of [`super::gltf_brdf`] (glTF
//! 2.0 spec Appendix B + KHR_materials_specular), with the KHR layers ([`super::layers`])
//! when present.
//!
//! Frame: local shading frame, z = normal. The lobe is two-sided reflection: non-zero only
//! when `wo` and `wi` lie in the same hemisphere, with |cos θ| (the diffuse transmission
//! layer excepted). Densities are per unit solid angle.

use super::anisotropic::Microfacet;
use super::gltf_brdf::{Gltf, GLTF_MIN_ALPHA};
use super::iridescence::LobeExtensions;
use super::layers::{Layered, Layers};
use super::lobe::{normal_reflectance, Lobe, RouletteLobes, GLOSSY_ALPHA};
use super::{Bsdf, BsdfSample, TransportMode};
use crate::polar::stokes::Mueller;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

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
    /// The BRDF of this lobe, its layers aside.
    pub(super) fn brdf(&self) -> Gltf<C> {
        let GltfPbr {
            base,
            metallic,
            alpha,
            ior,
            specular,
            specular_color,
            extensions,
            ..
        } = *self;
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

    /// The layered BSDF when any KHR layer is present (`None` otherwise: the plain glTF
    /// BRDF, unchanged).
    pub(super) fn layered(&self) -> Option<Layered<C>> {
        (!self.layers.is_none()).then(|| Layered::new(self.brdf(), &self.layers))
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
            None => self.brdf().eval(wo, wi),
        }
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self.layered() {
            Some(l) => l.pdf(wo, wi),
            None => self.brdf().pdf(wo, wi),
        }
    }
    fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<C>> {
        match self.layered() {
            Some(l) => l.sample(wo, uc, u, mode),
            None => self.brdf().sample(wo, uc, u),
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
