//! The renderer: splits the image into tiles rendered in parallel with rayon, with one
//! deterministic random stream per (seed, pixel, sample), so the same scene, seed and
//! backend give the same image whatever the thread count or scheduling. Shows progress on
//! stderr and returns the linear image with statistics.

use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::integrator::{Context, Integrator};
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
}

/// Figures from one render.
#[derive(Debug, Clone, Copy)]
pub struct RenderStats {
    /// Wall time of the rendering loop.
    pub time: Duration,
    /// Rays traced (closest-hit + shadow).
    pub rays: u64,
    /// Pixel samples taken.
    pub samples: u64,
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

/// Renders `scene` through `camera`.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    settings: &RenderSettings,
) -> Result<(ImageRgb, RenderStats)> {
    let (w, h) = (settings.width, settings.height);
    let tiles_x = w.div_ceil(TILE);
    let tiles_y = h.div_ceil(TILE);
    let tiles: Vec<(u32, u32)> = (0..tiles_y)
        .flat_map(|ty| (0..tiles_x).map(move |tx| (tx, ty)))
        .collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .start_handler(|_| {
            #[cfg(feature = "embree")]
            crate::accel::embree::enable_flush_to_zero();
        })
        .build()
        .map_err(|e| Error::Usage(format!("cannot start {} threads: {e}", settings.threads)))?;
    let bar = if settings.quiet {
        ProgressBar::hidden()
    } else {
        let b = ProgressBar::new(tiles.len() as u64);
        b.set_style(
            ProgressStyle::with_template(
                "{spinner} rendering [{elapsed_precise}] {bar:40} {percent:>3}% tiles {pos}/{len} eta {eta}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b
    };
    let start = Instant::now();
    let spp = settings.spp.max(1);
    let results: Vec<(Vec<(u32, Vec3)>, u64)> = pool.install(|| {
        tiles
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
                            let l = if settings.spectral {
                                sample::<SampledSpectrum>(
                                    scene,
                                    integrator,
                                    &ray,
                                    (k, spp),
                                    &mut ctx,
                                )
                            } else {
                                sample::<Vec3>(scene, integrator, &ray, (k, spp), &mut ctx)
                            };
                            sum += l.as_dvec3();
                        }
                        rays += ctx.rays;
                        out.push((y * w + x, (sum / spp as f64).as_vec3()));
                    }
                }
                bar.inc(1);
                (out, rays)
            })
            .collect()
    });
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
    Ok((
        ImageRgb {
            width: w,
            height: h,
            data,
        },
        RenderStats {
            time,
            rays,
            samples: w as u64 * h as u64 * spp as u64,
        },
    ))
}
