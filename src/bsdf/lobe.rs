//! What every lobe answers ([`Lobe`]): the questions any integrator asks of a BSDF, each
//! answered by the lobe's own module (pbrt-v4's `BxDF`: `f`, `Sample_f`, `PDF`, `Flags`;
//! Mitsuba 3's polarized BSDFs return their own Mueller matrix). [`super::Bsdf`] forwards
//! every question to its lobe through one exhaustive match ([`super::Bsdf`]'s `with_lobe!`),
//! and the trait has no default methods: a new lobe must answer each question (its
//! polarization, its photon behaviour, its denoiser albedo) or the crate does not compile.
//!
//! Frames and units as in [`super`]: directions in the local shading frame (z = outward
//! normal), away from the surface; `f` per steradian, pdfs per unit solid angle; colours
//! dimensionless in the carrier's channels or lanes.

use super::{Bsdf, BsdfSample, TransportMode};
use crate::polar::stokes::Mueller;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

/// GGX α from which a glossy lobe is treated like a diffuse one (a visible point,
/// [`Lobe::is_diffuse_like`]); below it camera paths continue by BSDF sampling.
pub const GLOSSY_ALPHA: f32 = 0.25;

/// The colours a photon chooses among under lobe roulette (`--photon-rr lobe`, Cropp &
/// Zhang's rule, [`crate::photon::trace`]): by their magnitudes, a diffuse bounce (a cosine
/// direction), a mirror reflection, a transmission ([`Lobe::roulette_transmission`]), or
/// absorption with the remaining probability. Fresnel's angle dependence and roughness are
/// ignored: the normal-incidence values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RouletteLobes<C> {
    /// Diffuse reflection colour.
    pub diffuse: C,
    /// Specular reflection colour.
    pub specular: C,
    /// Transmission colour.
    pub transmission: C,
}

/// One lobe of [`Bsdf`]: its scattering (sample, eval, pdf), its polarized response, what a
/// photon does at it, the denoiser's albedo, and the predicates the integrators branch on.
pub(crate) trait Lobe<C: Carrier>: Copy {
    /// Whether every lobe is a delta (eval and pdf are then always 0): where photons are
    /// not stored and camera paths do not connect to lights.
    fn is_delta(&self) -> bool;

    /// Whether [`Lobe::sample`] reads its 2D number `u` (the path tracer skips it if not).
    fn samples_direction(&self) -> bool;

    /// f(wo, wi) of a lobe that is not a delta ([`Bsdf::eval`] answers 0 for deltas).
    fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> C;

    /// Solid-angle pdf of [`Lobe::sample`] producing `wi`, for a lobe that is not a delta.
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32;

    /// Samples wi given wo; `uc` picks a sub-lobe, `u` the direction.
    fn sample(&self, wo: Vec3, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<C>>;

    /// The Mueller matrix of the light scattered from −`wi` to `wo` (not normalized: M₀₀ is
    /// the interface's own reflectance or transmittance where the lobe has one) and the
    /// local normal (surface or microfacet) its s/p bases refer to; `None` when the lobe
    /// depolarizes ([`Lobe::depolarizes`]) or the pair is degenerate.
    fn mueller(&self, wo: Vec3, wi: Vec3) -> Option<(Mueller, Vec3)>;

    /// Whether the lobe depolarizes whatever the directions: its light is read as
    /// unpolarized (the ideal depolarizer).
    fn depolarizes(&self) -> bool;

    /// Whether the lobe's polarization depends on the wavelength beyond the hero's (a
    /// complex index taken at the hero): the path keeps its hero alone from there.
    fn hero_polarizes(&self) -> bool;

    /// Whether photons are gathered at the lobe rather than continuing a camera path (and a
    /// photon's caustic path ends there): a diffuse lobe, or a glossy one at least
    /// [`GLOSSY_ALPHA`] rough.
    fn is_diffuse_like(&self) -> bool;

    /// The colours of [`RouletteLobes`] (what a photon does at the lobe under lobe roulette).
    fn roulette_lobes(&self) -> RouletteLobes<C>;

    /// The direction a photon takes when lobe roulette chooses transmission from `wo`.
    fn roulette_transmission(&self, wo: Vec3) -> Vec3;

    /// The reflectance the denoiser's albedo feature uses (OIDN's docs: the diffuse colour,
    /// a metal's normal-incidence reflectance, the transmission tint of glass), in [0, 1]
    /// per channel for physical inputs.
    fn albedo(&self) -> C;

    /// The η (n_inside / n_outside) of an interface that bends light and whose index the
    /// path's wavelengths may change (the η² radiance scale on refraction, spectral MIS's
    /// lanes); `None` for a lobe without one.
    fn interface_eta(&self) -> Option<f32>;

    /// The lobe as lane `k` of a spectral path sees it: its interface η replaced by `eta`
    /// and its colours' lanes rotated by `k` ([`Carrier::rotated`]); `None` for a lobe
    /// without an interface η ([`Lobe::interface_eta`]).
    fn with_lane(&self, eta: f32, k: usize) -> Option<Bsdf<C>>;
}

/// The normal-incidence reflectance ((η−1)/(η+1))² of an interface of index ratio `eta`,
/// 1 for η = ∞ (the `ior: 0` mirror): lobe roulette's specular weight.
pub(super) fn normal_reflectance(eta: f32) -> f32 {
    if eta.is_infinite() {
        1.0
    } else {
        ((eta - 1.0) / (eta + 1.0)).powi(2)
    }
}
