//! Conductor lobes: GGX reflection with Schlick's Fresnel from a colour (a glTF metal,
//! [`Conductor`]) or the exact reflectance of a measured metal's complex index η + ik
//! ([`ComplexConductor`], [`crate::optics::fresnel_conductor`]); α below
//! [`SMOOTH_ALPHA`] makes either a delta mirror.
//!
//! Polarization: the complex-index lobe reflects with the conductor Fresnel matrices at the
//! surface (smooth) or at the half vector (rough), at the hero wavelength
//! ([`crate::polar::fresnel::conductor`]); the Schlick lobe is a perfect mirror for
//! polarization (its colour has no phase). Neither transmits, both are opaque to photons
//! except by specular reflection under lobe roulette, and the denoiser's albedo is the
//! normal-incidence reflectance.
//!
//! Frame: local shading frame, z = normal; reflection only, two-sided (|cos θ|).

use super::anisotropic::Microfacet;
use super::ggx_reflect::{ggx_reflect_pdf, ggx_reflect_sample, ggx_spec};
use super::iridescence::LobeExtensions;
use super::lobe::{Lobe, RouletteLobes, GLOSSY_ALPHA};
use super::{reflect_z, Bsdf, BsdfSample, TransportMode, SMOOTH_ALPHA};
use crate::optics::{fresnel_conductor_c, fresnel_schlick};
use crate::polar::fresnel::{self, MIRROR};
use crate::polar::stokes::Mueller;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

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
pub(crate) struct GgxConductor<C: Carrier> {
    pub fresnel: ConductorFresnel<C>,
    pub ggx: Microfacet,
    pub smooth: bool,
}

impl<C: Carrier> GgxConductor<C> {
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

/// [`Bsdf::Conductor`]: Schlick from `f0`, GGX `alpha`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Conductor<C> {
    pub f0: C,
    pub alpha: f32,
}

impl<C: Carrier> Conductor<C> {
    fn ggx(&self) -> GgxConductor<C> {
        GgxConductor {
            fresnel: ConductorFresnel::Schlick(self.f0),
            ggx: Microfacet::khr(self.alpha, 0.0),
            smooth: self.is_delta(),
        }
    }
}

impl<C: Carrier> Lobe<C> for Conductor<C> {
    fn is_delta(&self) -> bool {
        self.alpha < SMOOTH_ALPHA
    }
    fn samples_direction(&self) -> bool {
        true
    }
    fn eval(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> C {
        self.ggx().eval(wo, wi)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.ggx().pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3, _uc: f32, u: Vec2, _mode: TransportMode) -> Option<BsdfSample<C>> {
        self.ggx().sample(wo, u)
    }
    fn mueller(&self, _wo: Vec3, _wi: Vec3) -> Option<(Mueller, Vec3)> {
        Some((MIRROR, Vec3::Z))
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
        RouletteLobes {
            diffuse: C::ZERO,
            specular: self.f0,
            transmission: C::ZERO,
        }
    }
    fn roulette_transmission(&self, wo: Vec3) -> Vec3 {
        -wo
    }
    fn albedo(&self) -> C {
        self.f0
    }
    fn interface_eta(&self) -> Option<f32> {
        None
    }
    fn with_lane(&self, _eta: f32, _k: usize) -> Option<Bsdf<C>> {
        None
    }
}

/// [`Bsdf::ComplexConductor`]: the complex index `eta` + i`k`, GGX `alpha`, the film and
/// anisotropy `extensions`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ComplexConductor<C> {
    pub eta: C,
    pub k: C,
    pub alpha: f32,
    pub extensions: LobeExtensions,
}

impl<C: Carrier> ComplexConductor<C> {
    fn ggx(&self) -> GgxConductor<C> {
        GgxConductor {
            fresnel: ConductorFresnel::Complex {
                eta: self.eta,
                k: self.k,
                extensions: self.extensions,
            },
            ggx: Microfacet::khr(self.alpha, self.extensions.anisotropy),
            smooth: self.is_delta(),
        }
    }
}

impl<C: Carrier> Lobe<C> for ComplexConductor<C> {
    fn is_delta(&self) -> bool {
        // Anisotropy widens the lobe along x (α_x = mix(α, 1, s²)): never a delta.
        self.alpha < SMOOTH_ALPHA && self.extensions.anisotropy <= 0.0
    }
    fn samples_direction(&self) -> bool {
        true
    }
    fn eval(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> C {
        self.ggx().eval(wo, wi)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.ggx().pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3, _uc: f32, u: Vec2, _mode: TransportMode) -> Option<BsdfSample<C>> {
        self.ggx().sample(wo, u)
    }
    /// The conductor Fresnel matrix at the hero's index, at the surface normal (smooth) or
    /// the half vector of the reflection (rough).
    fn mueller(&self, wo: Vec3, wi: Vec3) -> Option<(Mueller, Vec3)> {
        let m = if self.alpha < SMOOTH_ALPHA {
            Vec3::Z
        } else {
            (wo + wi).try_normalize()?
        };
        let (n, k) = (self.eta.to_lanes()[0], self.k.to_lanes()[0]);
        Some((fresnel::conductor(wi.dot(m).abs(), n, k), m))
    }
    fn depolarizes(&self) -> bool {
        false
    }
    fn hero_polarizes(&self) -> bool {
        true
    }
    fn is_diffuse_like(&self) -> bool {
        !self.is_delta() && self.alpha >= GLOSSY_ALPHA
    }
    fn roulette_lobes(&self) -> RouletteLobes<C> {
        RouletteLobes {
            diffuse: C::ZERO,
            specular: fresnel_conductor_c(1.0, self.eta, self.k),
            transmission: C::ZERO,
        }
    }
    fn roulette_transmission(&self, wo: Vec3) -> Vec3 {
        -wo
    }
    /// Normal incidence of the exact conductor Fresnel, per channel:
    /// ((n−1)² + k²)/((n+1)² + k²) (Born & Wolf §14.2; [`crate::optics::fresnel_conductor`]
    /// at cos θ = 1).
    fn albedo(&self) -> C {
        let (n, k) = (self.eta.to_lanes(), self.k.to_lanes());
        C::from_lanes(std::array::from_fn(|i| {
            let k2 = k[i] * k[i];
            ((n[i] - 1.0) * (n[i] - 1.0) + k2) / ((n[i] + 1.0) * (n[i] + 1.0) + k2)
        }))
    }
    fn interface_eta(&self) -> Option<f32> {
        None
    }
    fn with_lane(&self, _eta: f32, _k: usize) -> Option<Bsdf<C>> {
        None
    }
}
