//! The thin-walled dielectric lobe ([`ThinDielectric`], KHR_materials_transmission without
//! volume): a slab whose two parallel interfaces reflect or let light straight through, no
//! bending (pbrt-v4 `ThinDielectricBxDF`, §9.5.3). Always a delta.
//!
//! Frame: local shading frame, z = outward normal; `eta` = the slab's index relative to its
//! surroundings (the same medium on both sides).

use super::dielectric::specular_reflection;
use super::lobe::{normal_reflectance, Lobe, RouletteLobes};
use super::{Bsdf, BsdfSample, TransportMode};
use crate::optics::fresnel_either_side as fresnel;
use crate::polar::fresnel::dielectric as fresnel_mueller;
use crate::polar::stokes::{mat_mul, Mueller};
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

/// Thin-walled slab: the geometric series of inter-reflections between the two parallel
/// interfaces gives R' = R + T²R/(1 − R²), T' = 1 − R'; transmission goes straight through
/// (`wi = −wo`, no bending, no η² factor since both sides are the same medium), tinted by
/// `tint`.
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
        Some(specular_reflection(wo, r))
    } else {
        let wi = -wo;
        Some(BsdfSample::delta(wi, tint * (t / wi.z.abs()), t, true))
    }
}

/// [`Bsdf::ThinDielectric`]: the slab's index `eta`, transmission `tint`.
///
/// Polarization: one interface's Fresnel reflection matrix, or two interfaces' transmission
/// matrices in turn (the inter-reflections' scalar is the BSDF's; [`super::Bsdf::mueller`]
/// normalizes). Photons under lobe roulette reflect with the normal-incidence reflectance
/// and pass straight through with the rest, tinted. The denoiser's albedo is the tint.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ThinDielectric<C> {
    pub eta: f32,
    pub tint: C,
}

impl<C: Carrier> Lobe<C> for ThinDielectric<C> {
    fn is_delta(&self) -> bool {
        true
    }
    /// Reflection or transmission is chosen with `uc` alone.
    fn samples_direction(&self) -> bool {
        false
    }
    fn eval(&self, _wo: Vec3, _wi: Vec3, _mode: TransportMode) -> C {
        C::ZERO
    }
    fn pdf(&self, _wo: Vec3, _wi: Vec3) -> f32 {
        0.0
    }
    fn sample(&self, wo: Vec3, uc: f32, _u: Vec2, _mode: TransportMode) -> Option<BsdfSample<C>> {
        thin_sample(self.eta, self.tint, wo, uc)
    }
    fn mueller(&self, wo: Vec3, wi: Vec3) -> Option<(Mueller, Vec3)> {
        let (r, t) = fresnel_mueller(wi.z.abs(), self.eta);
        let through = mat_mul(&t, &t);
        Some((if wo.z * wi.z > 0.0 { r } else { through }, Vec3::Z))
    }
    fn depolarizes(&self) -> bool {
        false
    }
    fn hero_polarizes(&self) -> bool {
        false
    }
    fn is_diffuse_like(&self) -> bool {
        false
    }
    fn roulette_lobes(&self) -> RouletteLobes<C> {
        let r = normal_reflectance(self.eta);
        RouletteLobes {
            diffuse: C::ZERO,
            specular: C::splat(r),
            transmission: self.tint * (1.0 - r),
        }
    }
    fn roulette_transmission(&self, wo: Vec3) -> Vec3 {
        -wo
    }
    fn albedo(&self) -> C {
        self.tint
    }
    /// The slab does not bend light; its index is n_d whatever the wavelength.
    fn interface_eta(&self) -> Option<f32> {
        None
    }
    fn with_lane(&self, _eta: f32, _k: usize) -> Option<Bsdf<C>> {
        None
    }
}
