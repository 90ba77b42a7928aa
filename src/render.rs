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
use crate::math::Rng;
use crate::output::ImageRgb;
use crate::scene::Scene;
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::{DVec3, Vec2, Vec3};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use std::time::{Duration, Instant};

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
    /// Worker threads (0 = all cores).
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

/// The worker pool for `settings.threads` (FTZ/DAZ on for Embree on every worker).
pub fn thread_pool(settings: &RenderSettings) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .start_handler(|_| {
            #[cfg(feature = "embree")]
            crate::accel::embree::enable_flush_to_zero();
        })
        .build()
        .map_err(|e| Error::Usage(format!("cannot start {} threads: {e}", settings.threads)))
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

/// Per-pixel sums of the samples of each half (sample k in half k mod 2), stored tile by
/// tile (`TILE²` slots per tile; slots outside the image stay zero) so each parallel tile
/// owns one contiguous chunk.
struct Accum {
    width: u32,
    height: u32,
    tiles_x: u32,
    sums: Vec<[DVec3; 2]>,
}

impl Accum {
    fn new(width: u32, height: u32) -> Self {
        let tiles_x = width.div_ceil(TILE);
        let tiles = tiles_x as usize * height.div_ceil(TILE) as usize;
        Accum {
            width,
            height,
            tiles_x,
            sums: vec![[DVec3::ZERO; 2]; tiles * (TILE * TILE) as usize],
        }
    }

    /// The image `f(sums)` in row-major order.
    fn image(&self, f: impl Fn(&[DVec3; 2]) -> DVec3) -> ImageRgb {
        let (w, h) = (self.width, self.height);
        let mut data = vec![Vec3::ZERO; w as usize * h as usize];
        for (t, tile) in self.sums.chunks(TILE_PIXELS).enumerate() {
            let (tx, ty) = (t as u32 % self.tiles_x, t as u32 / self.tiles_x);
            for (i, s) in tile.iter().enumerate() {
                let (x, y) = (tx * TILE + i as u32 % TILE, ty * TILE + i as u32 / TILE);
                if x < w && y < h {
                    data[(y * w + x) as usize] = f(s).as_vec3();
                }
            }
        }
        ImageRgb {
            width: w,
            height: h,
            data,
        }
    }

    /// The mean after `n` samples per pixel.
    fn mean(&self, n: u64) -> ImageRgb {
        let inv = 1.0 / n.max(1) as f64;
        self.image(|s| (s[0] + s[1]) * inv)
    }

    /// The two halves' means after `n` samples (half 0 has ⌈n/2⌉, half 1 ⌊n/2⌋; an empty
    /// half 1 is a copy of half 0).
    fn halves(&self, n: u64) -> (ImageRgb, ImageRgb) {
        let (n0, n1) = (n.div_ceil(2).max(1) as f64, (n / 2) as f64);
        let a = self.image(|s| s[0] / n0);
        let b = if n1 > 0.0 {
            self.image(|s| s[1] / n1)
        } else {
            a.clone()
        };
        (a, b)
    }
}

/// Pixels per tile.
const TILE_PIXELS: usize = (TILE * TILE) as usize;
/// Stream key of the per-pixel offset of the hero-wavelength sequence.
const LAMBDA_KEY: u64 = 0x1A4B_DA00;
/// 1/φ, the golden ratio's fractional part: the rank-1 lattice generator.
const INV_PHI: f64 = 0.618_033_988_749_894_9;

/// The sample loop of the per-sample methods: samples k = 0, 1, … per pixel, each a jittered
/// camera ray (the pixel centre when `spp` = 1) estimated by `estimate(ray, u_lambda, ctx)`
/// (linear RGB), in rounds to checkpoints 1, 2, 4, … (see the module docs). `setup` is the
/// work done before (photon maps): its start time, rays and photons count in the progress
/// and the stats. Runs on the current rayon pool.
pub fn render_samples(
    camera: &Camera,
    settings: &RenderSettings,
    setup: Setup,
    mut observer: Option<Observer>,
    estimate: impl Fn(&Ray, f32, &mut Context) -> Vec3 + Sync,
) -> Result<(ImageRgb, RenderStats)> {
    let (w, h) = (settings.width, settings.height);
    let target = settings.spp.max(1) as u64;
    let mut acc = Accum::new(w, h);
    let tiles_x = acc.tiles_x;
    let n_tiles = acc.sums.len() / TILE_PIXELS;
    let bar = progress_bar(settings.quiet, target * n_tiles as u64, "rendering");
    let sampling_start = Instant::now();
    let (mut done, mut rays, mut next_checkpoint) = (0u64, setup.rays, 1u64);
    loop {
        // Samples to the next checkpoint, fewer if the time limit would be crossed.
        let mut n = next_checkpoint.min(target) - done;
        if let (Some(limit), true) = (settings.time_limit, done > 0) {
            let per_sample = sampling_start.elapsed().as_secs_f64() / done as f64;
            let left = limit.saturating_sub(setup.start.elapsed()).as_secs_f64();
            n = n.min(((left / per_sample.max(1e-12)) as u64).max(1));
        }
        let (k0, k1) = (done, done + n);
        rays += acc
            .sums
            .par_chunks_mut(TILE_PIXELS)
            .enumerate()
            .map(|(t, tile)| {
                let (tx, ty) = (t as u32 % tiles_x, t as u32 / tiles_x);
                let mut rays = 0;
                for (i, sums) in tile.iter_mut().enumerate() {
                    let (x, y) = (tx * TILE + i as u32 % TILE, ty * TILE + i as u32 / TILE);
                    if x >= w || y >= h {
                        continue;
                    }
                    let (xk, yk) = (x as u64, y as u64);
                    let offset = Rng::new(&[settings.seed, xk, yk, LAMBDA_KEY]).next_f32() as f64;
                    for k in k0..k1 {
                        let mut ctx = Context {
                            rng: Rng::new(&[settings.seed, xk, yk, k]),
                            rays: 0,
                        };
                        let jitter = if target == 1 {
                            Vec2::splat(0.5)
                        } else {
                            Vec2::new(ctx.rng.next_f32(), ctx.rng.next_f32())
                        };
                        let ray = camera.generate_ray(Vec2::new(x as f32, y as f32) + jitter);
                        let u_lambda =
                            ((offset + k as f64 * INV_PHI).fract() as f32).min(1.0 - f32::EPSILON);
                        sums[(k % 2) as usize] += estimate(&ray, u_lambda, &mut ctx).as_dvec3();
                        rays += ctx.rays;
                    }
                }
                bar.inc(n);
                rays
            })
            .sum::<u64>();
        done = k1;
        bar.set_message(format!("{done} spp, {rays} rays"));
        let out_of_time = settings
            .time_limit
            .is_some_and(|t| setup.start.elapsed() >= t);
        let finished = done >= target || out_of_time;
        if done < next_checkpoint && !finished {
            continue;
        }
        while next_checkpoint <= done {
            next_checkpoint *= 2;
        }
        if let Some(obs) = observer.as_mut() {
            let image = acc.mean(done);
            let (a, b) = acc.halves(done);
            let progress = Progress {
                image: &image,
                halves: (&a, &b),
                elapsed: setup.start.elapsed(),
                samples: done,
                passes: 1,
                rays,
                photons: setup.photons,
                done: finished,
            };
            if obs(&progress)? == Control::Stop {
                break;
            }
        }
        if finished {
            break;
        }
    }
    bar.finish_and_clear();
    Ok((
        acc.mean(done),
        RenderStats {
            time: setup.start.elapsed(),
            rays,
            samples: w as u64 * h as u64 * done,
            photons: setup.photons,
            passes: 1,
        },
    ))
}
