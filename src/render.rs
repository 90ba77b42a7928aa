//! The renderer: splits the image into tiles rendered in parallel with rayon, with one
//! deterministic random stream per (seed, pixel, sample), so the same scene, seed and
//! backend give the same image whatever the thread count or scheduling. Shows progress on
//! stderr and returns the linear image with statistics.

use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::integrator::{photon_map, sppm, Context, Integrator, Method};
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
    /// Stop progressive methods (SPPM passes) after this long; at least one pass runs.
    pub time_limit: Option<Duration>,
}

/// Called every K passes of a progressive method with the image so far and the number of
/// passes done (`--checkpoint K`).
pub type Checkpoint<'a> = (
    u32,
    &'a mut (dyn FnMut(&ImageRgb, u32) -> Result<()> + Send),
);

/// Figures from one render.
#[derive(Debug, Clone, Copy)]
pub struct RenderStats {
    /// Wall time of the rendering loop.
    pub time: Duration,
    /// Rays traced (closest-hit + shadow).
    pub rays: u64,
    /// Pixel samples taken.
    pub samples: u64,
    /// Photons emitted (photon methods).
    pub photons: u64,
    /// Passes done (SPPM; 1 otherwise).
    pub passes: u32,
}

/// One camera sample's radiance as linear RGB: wavelengths drawn for spectral transport,
/// and the film's conversion ([`Carrier::to_rgb`], spectrum → XYZ → sRGB) — the only place
/// colour is converted.
///
/// `stratum` = (k, n): this is the k-th of the pixel's n samples; the hero wavelength's
/// uniform variate is stratified over them ((k + ξ)/n), which cuts colour noise.
fn sample<C: Carrier>(
    scene: &Scene,
    integrator: &Integrator,
    ray: &crate::math::Ray,
    stratum: (u32, u32),
    ctx: &mut Context,
) -> Vec3 {
    let lambda = if C::SPECTRAL {
        let (k, n) = stratum;
        C::sample_lambda(((k as f32 + ctx.rng.next_f32()) / n as f32).min(1.0 - f32::EPSILON))
    } else {
        C::sample_lambda(0.0)
    };
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

/// A progress bar on stderr (hidden with `quiet`).
pub fn progress_bar(quiet: bool, len: u64, what: &str) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let b = ProgressBar::new(len);
    b.set_style(
        ProgressStyle::with_template(&format!(
            "{{spinner}} {what} [{{elapsed_precise}}] {{bar:40}} {{pos}}/{{len}} {{msg}} eta {{eta}}"
        ))
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    b
}

/// Renders `scene` through `camera`.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    settings: &RenderSettings,
) -> Result<(ImageRgb, RenderStats)> {
    render_with_checkpoints(scene, camera, integrator, settings, None)
}

/// [`render`], calling `checkpoint` every K passes of a progressive method.
pub fn render_with_checkpoints(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    settings: &RenderSettings,
    checkpoint: Option<Checkpoint>,
) -> Result<(ImageRgb, RenderStats)> {
    let pool = thread_pool(settings)?;
    match integrator.method {
        Method::Whitted | Method::Path | Method::Auto => {
            let (image, mut stats) = pool.install(|| {
                render_samples(camera, settings, |ray, stratum, ctx| {
                    if settings.spectral {
                        sample::<SampledSpectrum>(scene, integrator, ray, stratum, ctx)
                    } else {
                        sample::<Vec3>(scene, integrator, ray, stratum, ctx)
                    }
                })
            });
            stats.passes = 1;
            Ok((image, stats))
        }
        Method::Photon => pool.install(|| photon_map::render(scene, camera, integrator, settings)),
        Method::Sppm => {
            pool.install(|| sppm::render(scene, camera, integrator, settings, checkpoint))
        }
    }
}

/// The tile loop of the per-sample methods: `spp` jittered camera samples per pixel, each
/// estimated by `estimate(ray, (k, spp), ctx)` (linear RGB), averaged. Runs on the current
/// rayon pool.
pub fn render_samples(
    camera: &Camera,
    settings: &RenderSettings,
    estimate: impl Fn(&crate::math::Ray, (u32, u32), &mut Context) -> Vec3 + Sync,
) -> (ImageRgb, RenderStats) {
    let (w, h) = (settings.width, settings.height);
    let tiles_x = w.div_ceil(TILE);
    let tiles_y = h.div_ceil(TILE);
    let tiles: Vec<(u32, u32)> = (0..tiles_y)
        .flat_map(|ty| (0..tiles_x).map(move |tx| (tx, ty)))
        .collect();
    let bar = progress_bar(settings.quiet, tiles.len() as u64, "rendering tiles");
    let start = Instant::now();
    let spp = settings.spp.max(1);
    let results: Vec<(Vec<(u32, Vec3)>, u64)> = tiles
        .par_iter()
        .map(|&(tx, ty)| {
            let mut out = Vec::with_capacity((TILE * TILE) as usize);
            let mut rays = 0u64;
            for y in ty * TILE..((ty + 1) * TILE).min(h) {
                for x in tx * TILE..((tx + 1) * TILE).min(w) {
                    let mut ctx = Context {
                        rng: Rng::new(&[settings.seed, x as u64, y as u64]),
                        rays: 0,
                    };
                    let mut sum = DVec3::ZERO;
                    for k in 0..spp {
                        let jitter = if spp == 1 {
                            Vec2::splat(0.5)
                        } else {
                            Vec2::new(ctx.rng.next_f32(), ctx.rng.next_f32())
                        };
                        let ray = camera.generate_ray(Vec2::new(x as f32, y as f32) + jitter);
                        sum += estimate(&ray, (k, spp), &mut ctx).as_dvec3();
                    }
                    rays += ctx.rays;
                    out.push((y * w + x, (sum / spp as f64).as_vec3()));
                }
            }
            bar.inc(1);
            (out, rays)
        })
        .collect();
    bar.finish_and_clear();
    let time = start.elapsed();
    let mut data = vec![Vec3::ZERO; (w * h) as usize];
    let mut rays = 0;
    for (px, r) in results {
        rays += r;
        for (i, v) in px {
            data[i as usize] = v;
        }
    }
    (
        ImageRgb {
            width: w,
            height: h,
            data,
        },
        RenderStats {
            time,
            rays,
            samples: w as u64 * h as u64 * spp as u64,
            photons: 0,
            passes: 1,
        },
    )
}

// STAND-IN until Y1 lands (drop this whole block at merge): progressive rendering as
// rounds of independent renders, two per round (one per half), doubling each round.

/// The state of a progressive render at a checkpoint.
pub struct Progress<'a> {
    /// Mean so far.
    pub image: &'a ImageRgb,
    /// Means of two independent halves of the samples/passes.
    pub halves: (&'a ImageRgb, &'a ImageRgb),
    /// Wall time since rendering started.
    pub elapsed: Duration,
    /// Samples per pixel so far.
    pub samples: u64,
    /// Passes so far.
    pub passes: u32,
    /// Rays so far.
    pub rays: u64,
    /// Photons so far.
    pub photons: u64,
    /// Last call.
    pub done: bool,
}

/// What the observer wants.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// Keep rendering.
    Continue,
    /// Stop now.
    Stop,
}

/// Called at checkpoints.
pub type Observer<'a> = &'a mut (dyn FnMut(&Progress) -> Result<Control> + Send);

/// Renders progressively (stand-in: rounds of independent renders).
pub fn render_progressive(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    settings: &RenderSettings,
    mut observer: Option<Observer>,
) -> Result<(ImageRgb, RenderStats)> {
    let sppm = integrator.method == Method::Sppm;
    let bound = if sppm {
        integrator.photon.passes.max(1)
    } else {
        settings.spp.max(1)
    };
    let start = Instant::now();
    let n = (settings.width * settings.height) as usize;
    let (mut sum_a, mut sum_b) = (vec![DVec3::ZERO; n], vec![DVec3::ZERO; n]);
    let (mut done_units, mut round, mut stats) = (0u32, 0u64, None::<RenderStats>);
    loop {
        let per_half = (done_units / 2)
            .max(1)
            .min((bound - done_units).div_ceil(2).max(1));
        let mut halves = Vec::new();
        for half in 0..2u64 {
            let mut s = settings.clone();
            let mut it = *integrator;
            s.seed = settings.seed ^ (round * 2 + half + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
            s.time_limit = None;
            s.quiet = true;
            if sppm {
                it.photon.passes = per_half;
            } else {
                s.spp = per_half;
            }
            halves.push(render_with_checkpoints(scene, camera, &it, &s, None)?);
        }
        for (sum, (img, _)) in [&mut sum_a, &mut sum_b].into_iter().zip(&halves) {
            for (acc, p) in sum.iter_mut().zip(&img.data) {
                *acc += p.as_dvec3() * f64::from(per_half);
            }
        }
        done_units += 2 * per_half;
        round += 1;
        let st = stats.get_or_insert(RenderStats {
            time: Duration::ZERO,
            rays: 0,
            samples: 0,
            photons: 0,
            passes: 0,
        });
        for (_, h) in &halves {
            st.rays += h.rays;
            st.samples += h.samples;
            st.photons += h.photons;
        }
        st.passes = if sppm { done_units } else { 1 };
        st.time = start.elapsed();
        let to_img = |v: &[DVec3], k: f64| ImageRgb {
            width: settings.width,
            height: settings.height,
            data: v.iter().map(|p| (*p / k).as_vec3()).collect(),
        };
        let half_units = f64::from(done_units / 2);
        let a = to_img(&sum_a, half_units);
        let b = to_img(&sum_b, half_units);
        let mean = ImageRgb {
            width: settings.width,
            height: settings.height,
            data: a
                .data
                .iter()
                .zip(&b.data)
                .map(|(p, q)| (*p + *q) * 0.5)
                .collect(),
        };
        let timed_out = settings.time_limit.is_some_and(|t| start.elapsed() >= t);
        let mut done = done_units >= bound || timed_out;
        let mut ask = |done: bool| -> Result<Control> {
            match observer.as_mut() {
                Some(o) => o(&Progress {
                    image: &mean,
                    halves: (&a, &b),
                    elapsed: start.elapsed(),
                    samples: u64::from(done_units),
                    passes: st.passes,
                    rays: st.rays,
                    photons: st.photons,
                    done,
                }),
                None => Ok(Control::Continue),
            }
        };
        if ask(done)? == Control::Stop && !done {
            done = true;
            ask(true)?;
        }
        if done {
            return Ok((mean, *st));
        }
    }
}
