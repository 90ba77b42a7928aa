//! Scattering media (issue 32, in progress): phase functions and optical coefficients.
//! Not yet used by the renderers; [`crate::medium`] holds the nested-media stack that
//! absorbing volumes use today.
//!
//! - [`phase`]: isotropic, Henyey–Greenstein and Rayleigh phase functions, evaluated and
//!   sampled exactly.
//! - [`coefficients`]: σ_a, σ_s per wavelength from KHR_materials_volume,
//!   KHR_materials_scatter and Rayleigh's law.

pub mod coefficients;
pub mod phase;
