//! The Lambertian lobe: f = albedo/π, two-sided (non-zero when `wo` and `wi` share a
//! hemisphere), sampled by a cosine-weighted direction on `wo`'s side; it depolarizes, a
//! photon under lobe roulette bounces diffusely with its albedo, the denoiser's albedo is
//! its albedo.
//!
//! Frame: local shading frame, z = normal; densities per unit solid angle.

use super::lobe::{Lobe, RouletteLobes};
use super::{same_hemisphere, Bsdf, BsdfSample, TransportMode};
use crate::polar::stokes::Mueller;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

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

/// The direction [`lambert_sample`] draws from `wo` with `u` (a photon's diffuse bounce
/// under lobe roulette), `None` when its density is not positive and finite.
pub fn cosine_direction(wo: Vec3, u: Vec2) -> Option<Vec3> {
    let wi = cosine_hemisphere(wo, u);
    let pdf = lambert_pdf(wo, wi);
    (pdf > 0.0 && pdf.is_finite()).then_some(wi)
}

/// [`Bsdf::Lambert`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lambert<C> {
    pub albedo: C,
}

impl<C: Carrier> Lobe<C> for Lambert<C> {
    fn is_delta(&self) -> bool {
        false
    }
    fn samples_direction(&self) -> bool {
        true
    }
    fn eval(&self, wo: Vec3, wi: Vec3, _mode: TransportMode) -> C {
        lambert_eval(self.albedo, wo, wi)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        lambert_pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3, _uc: f32, u: Vec2, _mode: TransportMode) -> Option<BsdfSample<C>> {
        lambert_sample(self.albedo, wo, u)
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
    fn is_diffuse_like(&self) -> bool {
        true
    }
    fn roulette_lobes(&self) -> RouletteLobes<C> {
        RouletteLobes {
            diffuse: self.albedo,
            specular: C::ZERO,
            transmission: C::ZERO,
        }
    }
    fn roulette_transmission(&self, wo: Vec3) -> Vec3 {
        -wo
    }
    fn albedo(&self) -> C {
        self.albedo
    }
    fn interface_eta(&self) -> Option<f32> {
        None
    }
    fn with_lane(&self, _eta: f32, _k: usize) -> Option<Bsdf<C>> {
        None
    }
}
