//! Low-discrepancy samplers: the camera paths' numbers ([`stream`]) and the sequences behind
//! them.
//!
//! - [`sobol`]: the Sobol' sequence (Joe & Kuo 2008 matrices, [`sobol_table`]) with
//!   pbrt-v4's randomisations: none, XOR (random digit), fast Owen (Burley 2020).
//! - [`zsobol`]: per-pixel Owen-scrambled Sobol' in Morton order (pbrt-v4 `ZSobolSampler`),
//!   for camera-side methods.
//! - [`halton`]: the Owen-scrambled Halton sequence over a global index (photon emission,
//!   as pbrt-v4 SPPM).
//!
//! All samples are in `[0, 1)`, and each is a pure function of its indices and the seed,
//! which keeps the determinism rule: an N-sample image is bit-identical however its samples
//! are split into rounds, threads or shards. [`schedule`] fixes which dimension each
//! random decision of a camera path draws.

pub mod halton;
pub mod schedule;
pub mod sobol;
pub mod sobol_table;
pub mod stream;
pub mod zsobol;

pub use sobol::{sobol_sample, Scramble};
pub use stream::{Bounce, PixelSampler, SampleStream, SamplerKind};
pub use zsobol::{Randomize, ZSobol};
