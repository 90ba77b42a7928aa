//! Scattering media: homogeneous media inside closed meshes and the scene-wide fog, with
//! their phase functions, coefficients and free-flight sampling. The nested-media stack the
//! paths carry is [`crate::medium_stack`]; the path tracer's use of media is
//! [`crate::shading::media`].
//!
//! - [`phase`]: isotropic, Henyey–Greenstein and Rayleigh phase functions, evaluated and
//!   sampled exactly.
//! - [`coefficients`]: σ_a, σ_s per wavelength from KHR_materials_volume,
//!   KHR_materials_scatter and Rayleigh's law.
//! - [`medium`]: a medium's description and its coefficients at a path's wavelengths.
//! - [`track`]: distance sampling with spectral MIS and exact transmittance.
//! - [`fog`]: the scene-wide medium (`--fog`, scene `extras.iris_fog`) and its bounds.
//! - [`coarse`]: the coarse-graining of long random walks in dense media.

pub mod coarse;
pub mod coefficients;
pub mod fog;
pub mod medium;
pub mod phase;
pub mod track;

pub use medium::{Coeffs, Medium, Scattering, VolumeScatter};
pub use phase::Phase;
