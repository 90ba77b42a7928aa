//! Spectral foundation: the only code that knows about nanometres.
//!
//! - [`wavelengths`]: hero-wavelength sampling, 4 λ per camera path over 360–830 nm, and
//!   `terminate_secondary` for dispersive interfaces (pbrt-v4 `SampledWavelengths`).
//! - [`sampled`]: [`SampledSpectrum`], values at those 4 λ, and its unbiased XYZ estimator.
//! - [`cie`]: CIE 1931 2° colour-matching functions and D65 (tables in `cie_data.rs`, with
//!   their sources), Planck's law, XYZ ↔ linear sRGB (IEC 61966-2-1).
//! - [`upsample`]: RGB → reflectance / illuminant spectra (Smits 1999, basis fitted here).
//! - [`spectra`]: [`Spectrum`], what a material or light names (constant, RGB reflectance,
//!   RGB illuminant, blackbody, D65), with emission normalised to a requested luminance.
//! - [`ior`]: index-of-refraction models (constant, KHR_materials_dispersion, Cauchy,
//!   Sellmeier) and named materials.
//! - [`metals`]: complex indices n(λ) + ik(λ) of jewellery metals (measured tables in
//!   `metals_data.rs`, with their sources) and their RGB stand-ins.
//! - [`crystals`]: gemstones' crystal optics: principal indices n(λ) along three axes,
//!   optical character, birefringence, 2V and polarised absorption (table in
//!   `crystals_data.rs`, sources in the module doc).
//!
//! Units everywhere: wavelength λ in nm (vacuum); the IOR formulas that are defined in µm
//! convert internally. Spectral values are f32; table sums accumulate in f64.
//! Colour flows one way: RGB inputs → spectra (upsample) → per-path `SampledSpectrum`
//! → XYZ (`SampledSpectrum::to_xyz`, in the film) → linear sRGB (`cie::xyz_to_linear_srgb`).

pub mod carrier;
pub mod cie;
mod cie_data;
pub mod crystals;
pub mod emission;
mod fit;
pub mod ior;
pub mod metals;
mod metals_data;
pub mod sampled;
pub mod spectra;
pub mod upsample;
pub mod wavelengths;

pub use carrier::{Carrier, EmitterShape, Lambdas};
pub use emission::{effective_color, EmissionSpectrum, BLACKBODY_KELVIN, SUN_KELVIN};
pub use ior::{IorModel, UnknownIorName};
pub use metals::Metal;
pub use sampled::SampledSpectrum;
pub use spectra::Spectrum;
pub use upsample::{RgbIlluminant, RgbReflectance};
pub use wavelengths::{hero_number, rotate_lanes, SampledWavelengths};

/// Shortest wavelength sampled, nm (pbrt-v4 `Lambda_min`).
pub const LAMBDA_MIN: f32 = 360.0;
/// Longest wavelength sampled, nm (pbrt-v4 `Lambda_max`).
pub const LAMBDA_MAX: f32 = 830.0;
/// Wavelengths carried per path (hero + 3 companions).
pub const N_LAMBDA: usize = 4;
