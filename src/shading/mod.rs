//! Shading at a hit, below the integrators ([`crate::integrator`]) and photon tracing
//! ([`crate::photon`]), which both call it and which it never imports:
//! - [`step`]: the per-hit step every loop takes (arrive at a surface, BLEND coverage, the
//!   BSDF, the hero wavelength, the shading frame);
//! - [`material_bsdf`]: the BSDF a material has at a hit, and which BSDFs count as diffuse;
//! - [`spectral_mis`]: spectral MIS over the 4 wavelengths at rough dispersive interfaces;
//! - [`frame`]: the shading frame at a hit (the tangent frame anisotropy uses);
//! - [`direct`]: direct light with shadow rays (the Whitted tracer's light step);
//! - [`lights`]: one light sample toward a hit (punctual, emissive triangles, environment);
//! - [`next_event`]: next-event estimation written once (light choice, sample, weight,
//!   shadow ray), each tracer's differences in its [`next_event::Receiver`];
//! - [`media`]: scattering media along a path's rays (free flight, medium-only boundaries,
//!   shadow-ray transmittance);
//! - [`termination`]: how every path ends (Russian roulette, the delta-bounce cap).
//!
//! Units and frames are stated in each module: directions are unit vectors, world space
//! unless said to be in the local frame of the outward shading normal.

pub mod direct;
pub mod frame;
pub mod lights;
pub mod material_bsdf;
pub mod media;
pub mod next_event;
pub mod polarized;
pub mod spectral_mis;
pub mod step;
pub mod termination;

pub use crate::bsdf::GLOSSY_ALPHA;
pub use direct::direct_light;
pub use material_bsdf::{bsdf_at, interface, lane_etas, sample_bsdf};
pub use step::{arrival, arrive, meet, Arrival, Event, Surface};
pub use termination::MAX_DELTA_BOUNCES;
