//! The sample loop of the per-sample methods (path, Whitted, photon): rounds of camera
//! samples to checkpoints 1, 2, 4, … samples per pixel, accumulated per pixel in two halves
//! (sample k in half k mod 2). The invariants (stream per (seed, x, y, k), golden-ratio hero
//! wavelength, additions in sample order) are the parent module's; they make the image after
//! N samples independent of the round split and the thread count. Units: linear RGB
//! radiance; pixel (x, y) has its centre at (x + ½, y + ½) in raster space.

use super::{
    guard, progress_bar, Control, Observer, Progress, RenderSettings, RenderStats, Setup, TILE,
};
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
/// owns one contiguous chunk, and the samples per pixel each tile has taken (equal for all
/// tiles unless a round was interrupted).
struct Accum {
    width: u32,
    height: u32,
    tiles_x: u32,
    sums: Vec<[DVec3; 2]>,
    counts: Vec<u64>,
}

impl Accum {
    fn new(width: u32, height: u32) -> Self {
        let tiles_x = width.div_ceil(TILE);
        let tiles = tiles_x as usize * height.div_ceil(TILE) as usize;
        Accum {
            width,
            height,
            tiles_x,
            sums: vec![[DVec3::ZERO; 2]; tiles * TILE_PIXELS],
            counts: vec![0; tiles],
        }
    }

    /// The image `f(sums, samples of the pixel's tile)` in row-major order.
    fn image(&self, f: impl Fn(&[DVec3; 2], u64) -> DVec3) -> ImageRgb {
        let (w, h) = (self.width, self.height);
        let mut data = vec![Vec3::ZERO; w as usize * h as usize];
        for (t, tile) in self.sums.chunks(TILE_PIXELS).enumerate() {
            let (tx, ty) = (t as u32 % self.tiles_x, t as u32 / self.tiles_x);
            for (i, s) in tile.iter().enumerate() {
                let (x, y) = (tx * TILE + i as u32 % TILE, ty * TILE + i as u32 / TILE);
                if x < w && y < h {
                    data[(y * w + x) as usize] = f(s, self.counts[t]).as_vec3();
                }
            }
        }
        ImageRgb {
            width: w,
            height: h,
            data,
        }
    }

    /// The mean of every pixel's samples.
    fn mean(&self) -> ImageRgb {
        self.image(|s, n| (s[0] + s[1]) / n.max(1) as f64)
    }

    /// The two halves' means (of n samples, half 0 has ⌈n/2⌉, half 1 ⌊n/2⌋; an empty half
    /// 1 is a copy of half 0).
    fn halves(&self) -> (ImageRgb, ImageRgb) {
        let a = self.image(|s, n| s[0] / n.div_ceil(2).max(1) as f64);
        let b = if self.counts.iter().all(|&n| n >= 2) {
            self.image(|s, n| s[1] / (n / 2) as f64)
        } else {
            a.clone()
        };
        (a, b)
    }

    /// The samples per pixel every tile has reached.
    fn done(&self) -> u64 {
        self.counts.iter().copied().min().unwrap_or(0)
    }

    /// Pixel samples taken over the image.
    fn pixel_samples(&self) -> u64 {
        (0..self.counts.len())
            .map(|t| {
                let (tx, ty) = (t as u32 % self.tiles_x, t as u32 / self.tiles_x);
                let tw = TILE.min(self.width - tx * TILE) as u64;
                let th = TILE.min(self.height - ty * TILE) as u64;
                tw * th * self.counts[t]
            })
            .sum()
    }
}

/// Pixels per tile.
const TILE_PIXELS: usize = (TILE * TILE) as usize;
/// Stream key of the per-pixel offset of the hero-wavelength sequence.
const LAMBDA_KEY: u64 = 0x1A4B_DA00;
/// 1/φ, the golden ratio's fractional part: the rank-1 lattice generator.
const INV_PHI: f64 = 0.618_033_988_749_894_9;

/// The camera ray of one sample of pixel (x, y): through the pixel centre when the render
/// takes one sample per pixel (`centre`), else jittered by the first two numbers of `rng`,
/// the sample's stream `Rng::new(&[seed, x, y, k])`. The coverage pass
/// ([`super::coverage`]) replays it.
pub(super) fn primary_ray(camera: &Camera, x: u32, y: u32, centre: bool, rng: &mut Rng) -> Ray {
    let jitter = if centre {
        Vec2::splat(0.5)
    } else {
        Vec2::new(rng.next_f32(), rng.next_f32())
    };
    camera.generate_ray(Vec2::new(x as f32, y as f32) + jitter)
}

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
    sample_rounds(
        camera,
        settings,
        setup,
        observer,
        u64::MAX,
        &guard::stop_requested,
        estimate,
    )
}

/// [`render_samples`] with rounds of at most `max_round` samples per pixel (tests split
/// the rounds with it; the image must not change), and `stop` asked before each tile of a
/// round after the first (a `true` skips the rest of the round's tiles and ends the
/// render).
fn sample_rounds(
    camera: &Camera,
    settings: &RenderSettings,
    setup: Setup,
    mut observer: Option<Observer>,
    max_round: u64,
    stop: &(dyn Fn() -> bool + Sync),
    estimate: impl Fn(&Ray, f32, &mut Context) -> Vec3 + Sync,
) -> Result<(ImageRgb, RenderStats)> {
    let (w, h) = (settings.width, settings.height);
    let target = settings.spp.max(1) as u64;
    let mut acc = Accum::new(w, h);
    let tiles_x = acc.tiles_x;
    let n_tiles = acc.counts.len();
    let bar = progress_bar(settings.quiet, target * n_tiles as u64, "rendering");
    let mut last_estimate: Option<f64> = None;
    let sampling_start = Instant::now();
    let (mut done, mut rays, mut next_checkpoint) = (0u64, setup.rays, 1u64);
    let mut bad = 0u64;
    let mut interrupted;
    loop {
        // Samples to the next checkpoint, fewer if the time limit would be crossed.
        let mut n = (next_checkpoint.min(target) - done).min(max_round.max(1));
        if let (Some(limit), true) = (settings.time_limit, done > 0) {
            let per_sample = sampling_start.elapsed().as_secs_f64() / done as f64;
            let left = limit.saturating_sub(setup.start.elapsed()).as_secs_f64();
            n = n.min(((left / per_sample.max(1e-12)) as u64).max(1));
        }
        let (k0, k1) = (done, done + n);
        let (round_rays, round_bad) = acc
            .sums
            .par_chunks_mut(TILE_PIXELS)
            .zip(acc.counts.par_iter_mut())
            .enumerate()
            .map(|(t, (tile, count))| {
                if k0 > 0 && stop() {
                    return (0, 0);
                }
                let (tx, ty) = (t as u32 % tiles_x, t as u32 / tiles_x);
                let (mut rays, mut bad) = (0, 0);
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
                        let ray = primary_ray(camera, x, y, target == 1, &mut ctx.rng);
                        let u_lambda =
                            ((offset + k as f64 * INV_PHI).fract() as f32).min(1.0 - f32::EPSILON);
                        let l = guard::admit(estimate(&ray, u_lambda, &mut ctx), &mut bad);
                        sums[(k % 2) as usize] += l.as_dvec3();
                        rays += ctx.rays;
                    }
                }
                *count = k1;
                bar.inc(n);
                (rays, bad)
            })
            .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
        rays += round_rays;
        bad += round_bad;
        interrupted = k0 > 0 && stop();
        done = acc.done();
        bar.set_message(format!(
            "{done} spp, {rays} rays{}",
            super::estimate_note(last_estimate)
        ));
        let out_of_time = settings
            .time_limit
            .is_some_and(|t| setup.start.elapsed() >= t);
        let finished = done >= target || out_of_time || interrupted;
        if done < next_checkpoint && !finished {
            continue;
        }
        while next_checkpoint <= done {
            next_checkpoint *= 2;
        }
        if !settings.quiet && observer.is_none() && done >= 2 {
            let (a, b) = acc.halves();
            last_estimate = super::relative_error_estimate(&a, &b);
            bar.set_message(format!(
                "{done} spp, {rays} rays{}",
                super::estimate_note(last_estimate)
            ));
        }
        if let Some(obs) = observer.as_mut() {
            let image = acc.mean();
            let (a, b) = acc.halves();
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
        acc.mean(),
        RenderStats {
            time: setup.start.elapsed(),
            rays,
            samples: acc.pixel_samples(),
            photons: setup.photons,
            passes: 1,
            bad_samples: bad,
            interrupted,
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
        let (img, seen, _) = render_with(19, 13, 23, max_round, threads, &|| false);
        (img, seen)
    }

    /// Renders the synthetic estimate at `w`×`h`, `spp`, with rounds of at most
    /// `max_round` and the stop request `stop`.
    fn render_with(
        w: u32,
        h: u32,
        spp: u32,
        max_round: u64,
        threads: usize,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> (ImageRgb, Vec<u64>, RenderStats) {
        let settings = RenderSettings {
            width: w,
            height: h,
            spp,
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
        let (img, stats) = pool
            .install(|| {
                sample_rounds(
                    &camera,
                    &settings,
                    Setup::now(),
                    Some(&mut obs),
                    max_round,
                    stop,
                    |ray, u, ctx| {
                        if ray.dir.x > 0.3 && u < 0.01 {
                            // A numerical failure on a few samples: counted, never painted.
                            Vec3::NAN
                        } else {
                            Vec3::new(ctx.rng.next_f32(), u, ray.dir.x)
                        }
                    },
                )
            })
            .unwrap();
        (img, seen, stats)
    }

    #[test]
    fn bad_samples_are_counted_not_painted() {
        let (img, _, stats) = render_with(19, 13, 23, u64::MAX, 2, &|| false);
        assert!(img.data.iter().all(|p| p.is_finite()));
        // About 1 % of the samples of the right-hand pixels hit the failure.
        assert!(stats.bad_samples > 0, "{}", stats.bad_samples);
        assert!(
            stats.bad_samples < stats.samples / 50,
            "{}",
            stats.bad_samples
        );
        assert!(!stats.interrupted);
    }

    #[test]
    fn an_interrupted_round_keeps_whole_tiles() {
        // 40×40 = 3×3 tiles. Rounds 1, 1→2, 2→4, 4→8; every round after the first asks
        // once per tile and once at its end: the stop request comes during the last round,
        // after 3 of its tiles started.
        let calls = std::sync::atomic::AtomicU64::new(0);
        let stop = || calls.fetch_add(1, std::sync::atomic::Ordering::SeqCst) >= 10 + 10 + 3;
        let (img, seen, stats) = render_with(40, 40, 8, u64::MAX, 1, &stop);
        let (four, ..) = render_with(40, 40, 4, u64::MAX, 1, &|| false);
        let (eight, ..) = render_with(40, 40, 8, u64::MAX, 1, &|| false);
        assert!(stats.interrupted);
        assert_eq!(seen, [1, 2, 4, 4]);
        let tile_of = |i: usize| (i % 40 / 16, i / 40 / 16);
        let mut whole = [[None; 3]; 3];
        for (i, p) in img.data.iter().enumerate() {
            let (tx, ty) = tile_of(i);
            let n = if *p == eight.data[i] {
                8
            } else {
                assert_eq!(
                    *p, four.data[i],
                    "pixel {i} is neither the 4- nor the 8-spp one"
                );
                4
            };
            assert!(
                whole[ty][tx].is_none_or(|m| m == n),
                "tile ({tx}, {ty}) is mixed"
            );
            whole[ty][tx] = Some(n);
        }
        let tiles8 = whole.iter().flatten().filter(|n| **n == Some(8)).count() as u64;
        assert_eq!(tiles8, 3);
        let px8: u64 = (0..1600).filter(|&i| img.data[i] == eight.data[i]).count() as u64;
        assert_eq!(stats.samples, px8 * 8 + (1600 - px8) * 4);
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
