//! The render driver and the path tracer: end-to-end renders of the project's and the
//! shared scenes, progressive and adaptive rendering, lanes, samplers, the denoiser, the
//! light choice, the plan, dispersion and spectral MIS.

#[path = "../common/mod.rs"]
mod common;

mod adaptive;
mod denoise;
mod dispersion;
mod display_error;
mod light_choice;
mod path_lanes;
mod plan;
mod progressive;
mod render_assets;
mod render_e2e;
mod sampler;
mod spectral_mis;
mod wavelength_split;
