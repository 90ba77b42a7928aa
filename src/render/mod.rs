//! Rendering machinery shared by every integrator, below them: the [`Film`] (two half
//! buffers), the progressive [`drive`]r (rounds to checkpoints 1, 2, 4, …, time limit, stop
//! request, progress bar, observer), the per-sample loop ([`render_samples`], one
//! [`primary_ray`]), the worker pool and the coverage pass. It knows nothing of how
//! radiance is estimated: integrators ([`crate::integrator::Integrator::render`]) own their
//! render and call into this module.
//!
//! Per-sample methods (path, Whitted, photon) take their samples in rounds that double the
//! samples per pixel (1, 1, 2, 4, … capped by `spp`; a time limit may split a round); SPPM
//! renders in passes, one per round. After 1, 2, 4, 8, … samples (passes) and at the end an
//! optional [`Observer`] sees the image so far ([`Progress`]) and may stop the render.
//!
//! Invariants:
//! - Sample k of pixel (x, y) draws only from its [`crate::sampler::SampleStream`] (a pure
//!   function of seed, x, y, k, the resolution and `spp`; low-discrepancy Sobol' by default,
//!   [`crate::sampler`]) and is added to the pixel's running sums in the order k = 0, 1, 2,
//!   …, so the image after N samples is bit-identical however the rounds were split and
//!   whatever the thread count.
//! - The spectral hero wavelength of sample k is the stream's wavelength number: stratified
//!   over the pixel's samples, so stopping early (time limit, observer) keeps colour noise
//!   low and unbiased.
//! - Sample k goes to half k mod 2: the two half images are independent estimates used to
//!   estimate the error without a reference.
//! - The film's sums are exact ([`crate::image::fixed`]), so a render may take any
//!   contiguous range of its units (a shard: [`Schedule::first`]), and the shards' sums add
//!   up to the sums of one render of them all ([`crate::image::ExactImage::add`]).
//!
//! Images are linear RGB (radiance, W·sr⁻¹·m⁻² per channel); times are wall-clock.

use crate::error::{Error, Result};
use crate::sampler::{SampleStream, SamplerKind};
use std::time::Duration;

pub mod adaptive;
pub mod coverage;
pub mod driver;
pub mod film;
pub mod guard;
pub mod progress;
mod samples;
pub use adaptive::Adaptive;
pub use driver::{drive, drive_passes, Round, RoundEnv, Schedule};
pub use film::{Film, FilmTile, TileState, TILE, TILE_PIXELS};
pub use progress::{
    estimate_note, judged_note, progress_bar, relative_error_estimate, time_to_target, Control,
    Judged, Observer, Prepass, Progress,
};
pub use samples::{pixel_sampler, primary_ray, render_batches, render_samples, Job, Starts};

/// What to render.
#[derive(Debug, Clone)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// Base seed.
    pub seed: u64,
    /// Worker threads (0 = all cores), at most [`MAX_THREADS`].
    pub threads: usize,
    /// Hide the progress bar.
    pub quiet: bool,
    /// Spectral transport (4 wavelengths per sample) instead of RGB.
    pub spectral: bool,
    /// Stop after the round (SPPM: pass) that crosses this wall time, counted from the start
    /// of the render (photon map building included); at least one sample (pass) is taken.
    pub time_limit: Option<Duration>,
    /// The numbers driving camera paths (`--sampler`).
    pub sampler: SamplerKind,
    /// Adaptive sampling ([`adaptive`]), for the methods whose schedule allows it
    /// ([`Schedule::adaptive`]); `None` gives every tile every unit.
    pub adaptive: Option<Adaptive>,
    /// This render's own stop request ([`guard::Cancel`]; the default is never set).
    pub cancel: guard::Cancel,
    /// Which code renders the path tracer's camera paths ([`Kernel`]).
    pub kernel: Kernel,
}

/// Which code renders the path tracer's camera paths: the structure-of-arrays kernel
/// where the scene is in its class ([`crate::integrator::path::kernel`]), else the scalar
/// path vertex; or the scalar vertex always. The two give the same image up to float
/// rounding, each deterministic on its own; a render's shards all use one (it is part of
/// their identity).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Kernel {
    /// As the environment variable `IRIS_KERNEL` says: `soa` (or unset) or `scalar`
    /// ([`Kernel::resolve`]).
    #[default]
    FromEnv,
    /// The structure-of-arrays kernel where the scene qualifies.
    Soa,
    /// The scalar path vertex.
    Scalar,
}

impl Kernel {
    /// [`Kernel::Soa`] or [`Kernel::Scalar`]: `FromEnv` read from `IRIS_KERNEL` (`soa`,
    /// the default when unset or empty, or `scalar`; anything else is an error naming it).
    pub fn resolve(self) -> crate::error::Result<Kernel> {
        if self != Kernel::FromEnv {
            return Ok(self);
        }
        match std::env::var("IRIS_KERNEL")
            .ok()
            .filter(|v| !v.is_empty())
            .as_deref()
        {
            None | Some("soa") => Ok(Kernel::Soa),
            Some("scalar") => Ok(Kernel::Scalar),
            Some(v) => Err(crate::error::Error::Usage(format!(
                "environment variable IRIS_KERNEL={v}: expected soa or scalar"
            ))),
        }
    }
}

impl RenderSettings {
    /// Quiet RGB settings of `width`×`height` at `spp` with `seed` on `threads` (0 = all
    /// cores), the default sampler, no time limit, no adaptive sampling: what tests and
    /// benchmarks render with.
    pub fn quiet_rgb((width, height): (u32, u32), spp: u32, seed: u64, threads: usize) -> Self {
        RenderSettings {
            width,
            height,
            spp,
            seed,
            threads,
            quiet: true,
            spectral: false,
            time_limit: None,
            sampler: Default::default(),
            adaptive: None,
            cancel: Default::default(),
            kernel: Kernel::FromEnv,
        }
    }
}

/// Per-thread state an integrator carries along one camera sample (or photon).
pub struct Context {
    /// Random numbers for this pixel sample: the scheduled low-discrepancy decisions and
    /// the independent stream ([`SampleStream::rng`]).
    pub sample: SampleStream,
    /// Rays traced so far (closest-hit and shadow).
    pub rays: u64,
}

/// Figures from one render.
#[derive(Debug, Clone, Copy)]
pub struct RenderStats {
    /// Wall time of the rendering loop.
    pub time: Duration,
    /// Rays traced (closest-hit + shadow).
    pub rays: u64,
    /// Pixel samples taken (all pixels; SPPM: one per pixel and pass).
    pub samples: u64,
    /// The fewest and the most units (samples or passes) a pixel took: equal unless
    /// adaptive sampling rested tiles or a stop request cut a round short.
    pub unit_span: (u64, u64),
    /// Photons emitted (photon methods).
    pub photons: u64,
    /// Photons emitted in the last pass (the hybrid's caustic photons: without `--photons`
    /// the count grows with the pass, [`crate::integrator::photon_budget`]; 0 for other
    /// methods).
    pub photons_per_pass: u64,
    /// Passes done (SPPM; 1 otherwise).
    pub passes: u32,
    /// Samples (SPPM: per-pixel pass contributions) dropped because they were NaN or
    /// infinite ([`guard::admit`]); 0 in a healthy render.
    pub bad_samples: u64,
    /// What ended the render ([`EndReason`]).
    pub end: EndReason,
}

impl RenderStats {
    /// Whether the render ended early on a stop request ([`guard::request_stop`], SIGINT);
    /// the image is then the mean of the samples taken so far (tiles of the last round may
    /// have one round more than others).
    pub fn interrupted(&self) -> bool {
        self.end == EndReason::Interrupted
    }
}

/// What ended a progressive render ([`drive`]). When several hold at the last round, the
/// first in this order is reported: an interruption, the observer's stop, the unit count,
/// the time limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndReason {
    /// Every unit asked for was taken (`--spp`, or `--passes` for SPPM).
    Samples,
    /// The observer answered [`Control::Stop`]: in `iris render` it does so only when the
    /// estimated error reached the target (`--target-error` or the default target,
    /// [`crate::app::budget`]).
    Target,
    /// The time limit (`--time`, or the default limit) was crossed.
    TimeLimit,
    /// A stop request ([`guard::request_stop`]: Ctrl-C, SIGTERM) ended it early.
    Interrupted,
}

/// A unit count from which [`drive`] treats the count as open-ended: the progress bar
/// shows elapsed time and the image's state instead of a fraction of the units (the time
/// limit or the error target will end the render first). `iris render` without `--spp` or
/// `--passes` asks for this many ([`crate::app::budget::OPEN_UNITS`]).
pub const OPEN_UNITS: u64 = 1 << 20;

/// The schedule of a render of `total` units (samples per pixel, or passes) that takes
/// `range` of them (absolute indices; `None` = all), in rounds of at most `max_round`.
/// Open-ended when `total` is [`OPEN_UNITS`] or more.
pub fn schedule(
    total: u64,
    range: Option<std::ops::Range<u64>>,
    max_round: u64,
    passes: bool,
    label: &'static str,
) -> Schedule {
    // Adaptive sampling takes every unit from a pixel's own count: a shard's range would
    // not merge as one render's.
    let adaptive = range.is_none();
    let total = total.max(1);
    let range = range.unwrap_or(0..total);
    Schedule {
        first: range.start,
        target: range.end.saturating_sub(range.start).max(1),
        open: total >= OPEN_UNITS,
        max_round,
        passes,
        label,
        adaptive,
    }
}

/// Most worker threads (`--threads`); 0 asks for one per core. Far more threads than
/// cores only add memory (a stack each) and scheduling, and a pool of 10⁵ threads would
/// exhaust the process before the render began.
pub const MAX_THREADS: usize = 1024;

/// Rejects a thread count above [`MAX_THREADS`] (0 = all cores is fine) before any thread
/// is spawned.
pub fn check_threads(threads: usize) -> Result<()> {
    if threads > MAX_THREADS {
        return Err(Error::Usage(format!(
            "--threads {threads}: at most {MAX_THREADS} worker threads (0 = one per core)"
        )));
    }
    Ok(())
}

/// Memory the per-pixel buffers of a render may take: 8 GiB; the integrator compares it
/// with the image's pixels times its bytes per pixel before anything is allocated
/// ([`crate::integrator::check_memory`]).
pub const PIXEL_MEMORY_BUDGET: u64 = 8 << 30;

/// Stack of each render worker: 8 MiB. The Whitted tracer recurses once per bounce, about
/// 1–2 KiB a level in release: `--max-depth` 1024 ([`crate::integrator::MAX_DEPTH`]) fits
/// the default 2 MiB with no margin, and 2048 overflowed it (measured in a closed mirror box,
/// `tests/optics/stiff_renders.rs`). 8 MiB gives 4× headroom; it is address space, committed only
/// as it is touched.
pub const WORKER_STACK: usize = 8 << 20;

/// The worker pool for `settings.threads` (FTZ/DAZ on for Embree on every worker, stacks of
/// [`WORKER_STACK`]); an error, not a panic, when the count is above [`MAX_THREADS`] or the
/// threads cannot start.
pub fn thread_pool(settings: &RenderSettings) -> Result<rayon::ThreadPool> {
    check_threads(settings.threads)?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .stack_size(WORKER_STACK)
        .start_handler(|_| {
            #[cfg(feature = "embree")]
            crate::accel::embree::enable_flush_to_zero();
        })
        .build()
        .map_err(|e| Error::Usage(format!("cannot start {} threads: {e}", settings.threads)))
}
