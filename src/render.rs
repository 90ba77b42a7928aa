//! The renderer: progressive rendering in rounds, tiles rendered in parallel with rayon.
//!
//! Per-sample methods (path, Whitted, photon) take their samples in rounds that double the
//! samples per pixel (1, 1, 2, 4, … capped by `spp`; a time limit may split a round); SPPM
//! renders in passes. After 1, 2, 4, 8, … samples (passes) and at the end an optional
//! [`Observer`] sees the image so far ([`Progress`]) and may stop the render.
//!
//! Invariants:
//! - Sample k of pixel (x, y) draws only from the stream `Rng::new(&[seed, x, y, k])` and is
//!   added to the pixel's running sums in the order k = 0, 1, 2, …, so the image after N
//!   samples is bit-identical however the rounds were split and whatever the thread count.
//! - The spectral hero wavelength of sample k uses the rank-1 lattice (golden-ratio)
//!   sequence u_k = frac(o + k·φ⁻¹) with a per-pixel random offset o (a Cranley–Patterson
//!   rotation; Owen, "Monte Carlo theory, methods and examples", §15.4): every prefix of
//!   samples is well stratified, so stopping early (time limit, observer) keeps colour noise
//!   low and unbiased.
//! - Sample k goes to half k mod 2: the two half images are independent estimates used to
//!   estimate the error without a reference.
//!
//! Images are linear RGB (radiance, W·sr⁻¹·m⁻² per channel); times are wall-clock.

use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::integrator::{photon_map, sppm, Context, Integrator, Method};
use crate::math::Ray;
use crate::output::ImageRgb;
use crate::scene::Scene;
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::Vec3;
use indicatif::{ProgressBar, ProgressStyle};
use std::time::{Duration, Instant};

pub mod coverage;
pub mod guard;
mod samples;
pub use samples::render_samples;

/// Tile edge in pixels.
const TILE: u32 = 16;

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
    /// Photons emitted (photon methods).
    pub photons: u64,
    /// Passes done (SPPM; 1 otherwise).
    pub passes: u32,
    /// Samples (SPPM: per-pixel pass contributions) dropped because they were NaN or
    /// infinite ([`guard::admit`]); 0 in a healthy render.
    pub bad_samples: u64,
    /// The render ended early on a stop request ([`guard::request_stop`], SIGINT); the image
    /// is the mean of the samples taken so far (tiles of the last round may have one round
    /// more than others).
    pub interrupted: bool,
}

/// The state of a render at a checkpoint, shown to an [`Observer`].
#[derive(Debug, Clone, Copy)]
pub struct Progress<'a> {
    /// The mean of all samples (passes) so far.
    pub image: &'a ImageRgb,
    /// The means of two independent halves of the samples (even and odd sample indices;
    /// SPPM: even and odd passes). With a single sample (pass) the second half is empty and
    /// both are that sample's image, so error estimates from them are 0 then.
    pub halves: (&'a ImageRgb, &'a ImageRgb),
    /// Wall time since the render started (photon map building included).
    pub elapsed: Duration,
    /// Samples per pixel so far (SPPM: passes).
    pub samples: u64,
    /// Passes done (SPPM; 1 for the other methods).
    pub passes: u32,
    /// Rays traced so far.
    pub rays: u64,
    /// Photons emitted so far.
    pub photons: u64,
    /// True on the last call of a render that ended by itself (sample, pass or time limit).
    /// After an observer returns [`Control::Stop`] it is not called again.
    pub done: bool,
}

/// An observer's answer: render on, or end the render with the image just shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// Keep rendering.
    Continue,
    /// Stop now; the render returns the image the observer just saw.
    Stop,
}

/// Called at checkpoints 1, 2, 4, 8, … samples per pixel (SPPM: passes) and at the end.
/// An error aborts the render and is returned.
pub type Observer<'a> = &'a mut (dyn FnMut(&Progress) -> Result<Control> + Send);

/// Work done before the first camera sample (photon maps): its start time and counts.
#[derive(Debug, Clone, Copy)]
pub struct Setup {
    /// When the render started.
    pub start: Instant,
    /// Rays traced building (photon maps).
    pub rays: u64,
    /// Photons emitted.
    pub photons: u64,
}

impl Setup {
    /// Nothing done yet: starts the clock now.
    pub fn now() -> Self {
        Setup {
            start: Instant::now(),
            rays: 0,
            photons: 0,
        }
    }
}

/// One camera sample's radiance as linear RGB: wavelengths drawn for spectral transport
/// from the hero variate `u_lambda` ∈ [0, 1), and the film's conversion
/// ([`Carrier::to_rgb`], spectrum → XYZ → sRGB) — the only place colour is converted.
fn sample<C: Carrier>(
    scene: &Scene,
    integrator: &Integrator,
    ray: &Ray,
    u_lambda: f32,
    ctx: &mut Context,
) -> Vec3 {
    let lambda = C::sample_lambda(if C::SPECTRAL { u_lambda } else { 0.0 });
    integrator
        .radiance::<C>(scene, ray, lambda, ctx)
        .to_rgb(&lambda)
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

/// Memory the per-pixel buffers of a render may take: 8 GiB. [`check_memory`] compares
/// it with the image's pixels times [`bytes_per_pixel`] before anything is allocated.
pub const PIXEL_MEMORY_BUDGET: u64 = 8 << 30;

/// Bytes each pixel costs `method` (the accumulation buffers, the images handed to
/// observers and writers, coverage and the output's encoding; SPPM adds its per-pixel
/// direct and photon sums and visible point).
pub fn bytes_per_pixel(method: Method) -> u64 {
    use std::mem::size_of;
    let common = size_of::<[glam::DVec3; 2]>() + 3 * size_of::<Vec3>() + 16 + 8;
    let extra = match method {
        Method::Sppm => {
            2 * size_of::<[glam::DVec3; 2]>()
                + size_of::<Option<crate::integrator::path::VisiblePoint<SampledSpectrum>>>()
        }
        _ => 0,
    };
    (common + extra) as u64
}

/// Rejects a `width × height` image whose per-pixel buffers for `method` would exceed
/// [`PIXEL_MEMORY_BUDGET`] (SPPM needs several times what the other methods need).
pub fn check_memory(width: u32, height: u32, method: Method) -> Result<()> {
    let per = bytes_per_pixel(method);
    let pixels = u64::from(width) * u64::from(height);
    if pixels.saturating_mul(per) > PIXEL_MEMORY_BUDGET {
        return Err(Error::Usage(format!(
            "--size {width}x{height}: --method {} needs {per} bytes per pixel, {:.1} GiB for \
             this image, over the {} GiB budget (at most {} pixels)",
            crate::converge::method_name(method),
            (pixels * per) as f64 / (1u64 << 30) as f64,
            PIXEL_MEMORY_BUDGET >> 30,
            PIXEL_MEMORY_BUDGET / per
        )));
    }
    Ok(())
}

/// Stack of each render worker: 8 MiB. The Whitted tracer recurses once per bounce, about
/// 1–2 KiB a level in release: `--max-depth` 1024 ([`crate::integrator::MAX_DEPTH`]) fits
/// the default 2 MiB with no margin, and 2048 overflowed it (measured in a closed mirror box,
/// `tests/stiff_renders.rs`). 8 MiB gives 4× headroom; it is address space, committed only
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

/// The relative error of the full image estimated from its two halves
/// ([`crate::measure::metrics::half_buffer_estimate`], √ of the relative MSE), for the progress bar.
pub fn relative_error_estimate(a: &ImageRgb, b: &ImageRgb) -> Option<f64> {
    crate::measure::metrics::half_buffer_estimate(a, b)
        .ok()
        .map(|e| e.rel_mse.sqrt())
}

/// ", est. rel. error 0.123" for the progress bar, or nothing before the first estimate.
pub fn estimate_note(e: Option<f64>) -> String {
    e.map_or(String::new(), |e| format!(", est. rel. error {e:.3}"))
}

/// A progress bar on stderr (hidden with `quiet`): elapsed time, the bar, and a message
/// (samples or passes done, rays).
pub fn progress_bar(quiet: bool, len: u64, what: &str) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let b = ProgressBar::new(len);
    b.set_style(
        ProgressStyle::with_template(&format!(
            "{{spinner}} {what} [{{elapsed_precise}}] {{bar:40}} {{percent}}% {{msg}} eta {{eta}}"
        ))
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    b
}

/// Renders `scene` through `camera` to the end (no observer).
pub fn render(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    settings: &RenderSettings,
) -> Result<(ImageRgb, RenderStats)> {
    render_progressive(scene, camera, integrator, settings, None)
}

/// Renders progressively, stopping at `settings.spp` samples per pixel (path, Whitted,
/// photon), `integrator.photon.passes` (SPPM), `settings.time_limit`, or when the observer
/// says [`Control::Stop`] — whichever first. The observer is called at checkpoints 1, 2, 4,
/// 8, … samples (or passes) and at the end (`done`).
pub fn render_progressive(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    settings: &RenderSettings,
    observer: Option<Observer>,
) -> Result<(ImageRgb, RenderStats)> {
    integrator.check()?;
    check_memory(settings.width, settings.height, integrator.method)?;
    let pool = thread_pool(settings)?;
    match integrator.method {
        Method::Whitted | Method::Path | Method::Auto => pool.install(|| {
            render_samples(
                camera,
                settings,
                Setup::now(),
                observer,
                |ray, u_lambda, ctx| {
                    if settings.spectral {
                        sample::<SampledSpectrum>(scene, integrator, ray, u_lambda, ctx)
                    } else {
                        sample::<Vec3>(scene, integrator, ray, u_lambda, ctx)
                    }
                },
            )
        }),
        Method::Photon => {
            pool.install(|| photon_map::render(scene, camera, integrator, settings, observer))
        }
        Method::Sppm => {
            pool.install(|| sppm::render(scene, camera, integrator, settings, observer))
        }
    }
}
