//! The sample loop of the per-sample methods (path, Whitted, photon): rounds of camera
//! samples to checkpoints 1, 2, 4, … samples per pixel, accumulated per pixel in two halves
//! (sample k in half k mod 2). The invariants (stream per (seed, x, y, k), golden-ratio hero
//! wavelength, additions in sample order) are the parent module's; they make the image after
//! N samples independent of the round split and the thread count. Units: linear RGB
//! radiance; pixel (x, y) has its centre at (x + ½, y + ½) in raster space.

use super::{progress_bar, Control, Observer, Progress, RenderSettings, RenderStats, Setup, TILE};
use crate::camera::Camera;
use crate::error::Result;
use crate::integrator::Context;
use crate::math::{Ray, Rng};
use crate::output::ImageRgb;
use glam::{DVec3, Vec2, Vec3};
use rayon::prelude::*;
use std::time::Instant;

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
    observer: Option<Observer>,
    estimate: impl Fn(&Ray, f32, &mut Context) -> Vec3 + Sync,
) -> Result<(ImageRgb, RenderStats)> {
    sample_rounds(camera, settings, setup, observer, u64::MAX, estimate)
}

/// [`render_samples`] with rounds of at most `max_round` samples per pixel (tests split
/// the rounds with it; the image must not change).
fn sample_rounds(
    camera: &Camera,
    settings: &RenderSettings,
    setup: Setup,
    mut observer: Option<Observer>,
    max_round: u64,
    estimate: impl Fn(&Ray, f32, &mut Context) -> Vec3 + Sync,
) -> Result<(ImageRgb, RenderStats)> {
    let (w, h) = (settings.width, settings.height);
    let target = settings.spp.max(1) as u64;
    let mut acc = Accum::new(w, h);
    let tiles_x = acc.tiles_x;
    let n_tiles = acc.sums.len() / TILE_PIXELS;
    let bar = progress_bar(settings.quiet, target * n_tiles as u64, "rendering");
    let mut last_estimate: Option<f64> = None;
    let sampling_start = Instant::now();
    let (mut done, mut rays, mut next_checkpoint) = (0u64, setup.rays, 1u64);
    loop {
        // Samples to the next checkpoint, fewer if the time limit would be crossed.
        let mut n = (next_checkpoint.min(target) - done).min(max_round.max(1));
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
        bar.set_message(format!(
            "{done} spp, {rays} rays{}",
            super::estimate_note(last_estimate)
        ));
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
        if !settings.quiet && observer.is_none() && done >= 2 {
            let (a, b) = acc.halves(done);
            last_estimate = super::relative_error_estimate(&a, &b);
            bar.set_message(format!(
                "{done} spp, {rays} rays{}",
                super::estimate_note(last_estimate)
            ));
        }
        if let Some(obs) = observer.as_mut() {
            let image = acc.mean(done);
            let (a, b) = acc.halves(done);
            if done >= 2 {
                last_estimate = super::relative_error_estimate(&a, &b);
                bar.set_message(format!(
                    "{done} spp, {rays} rays{}",
                    super::estimate_note(last_estimate)
                ));
            }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::look_at;
    use crate::scene::desc::{CameraDesc, Projection};

    /// A synthetic estimate that uses every input: the sample's random stream, the hero
    /// variate and the ray; any dependence on the round split changes it.
    fn render_split(max_round: u64, threads: usize) -> (ImageRgb, Vec<u64>) {
        let settings = RenderSettings {
            width: 19,
            height: 13,
            spp: 23,
            seed: 4,
            threads,
            quiet: true,
            spectral: true,
            time_limit: None,
        };
        let desc = CameraDesc {
            name: "c".into(),
            projection: Projection::Perspective {
                yfov: 0.7,
                aspect: None,
            },
            world_from_camera: look_at(Vec3::Z, Vec3::ZERO, Vec3::Y),
        };
        let camera = Camera::new(&desc, settings.width, settings.height);
        let mut seen = Vec::new();
        let mut obs = |p: &Progress| -> Result<Control> {
            seen.push(p.samples);
            Ok(Control::Continue)
        };
        let pool = super::super::thread_pool(&settings).unwrap();
        let (img, _) = pool
            .install(|| {
                sample_rounds(
                    &camera,
                    &settings,
                    Setup::now(),
                    Some(&mut obs),
                    max_round,
                    |ray, u, ctx| Vec3::new(ctx.rng.next_f32(), u, ray.dir.x),
                )
            })
            .unwrap();
        (img, seen)
    }

    #[test]
    fn image_does_not_depend_on_round_split_or_threads() {
        let (whole, seen) = render_split(u64::MAX, 1);
        assert_eq!(seen, [1, 2, 4, 8, 16, 23]);
        for (max_round, threads) in [(1, 2), (3, 1), (5, 2)] {
            let (img, seen) = render_split(max_round, threads);
            assert_eq!(
                img.data, whole.data,
                "rounds of {max_round}, {threads} threads"
            );
            assert_eq!(seen, [1, 2, 4, 8, 16, 23]);
        }
    }
}
