//! The photon methods: emission and aiming, photon maps, SPPM, the hybrid, light tracing,
//! VCM and bidirectional path tracing, polarized photons, and `--method auto`.

#[path = "../common/mod.rs"]
mod common;

mod auto_method;
mod blend_gather;
mod hybrid;
mod light_trace;
mod light_trace_pixels;
mod photon_agreement;
mod photon_aim;
mod photon_determinism;
mod photon_emit;
mod photon_focus;
mod photon_furnace;
mod photon_mirror;
mod polarized_photons;
mod rainbow_caustic;
mod sppm_spectral_mis;
mod vcm;
