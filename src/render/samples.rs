//! The sample loop of the per-sample methods (path, Whitted, photon): rounds of camera
//! samples to checkpoints 1, 2, 4, … samples per pixel, accumulated per pixel in two halves
//! (sample k in half k mod 2). The invariants (numbers per (seed, x, y, k) from the render's
//! [`PixelSampler`], stratified hero wavelength, additions in sample order) are the parent module's; they make the image after
//! N samples independent of the round split and the thread count. Units: linear RGB
//! radiance; pixel (x, y) has its centre at (x + ½, y + ½) in raster space.

use super::driver::{drive, Round, RoundEnv};
use super::film::Film;
use super::{guard, Context, Observer, Prepass, RenderSettings, RenderStats};
use crate::camera::Camera;
use crate::error::Result;
use crate::math::Ray;
use crate::sampler::{PixelSampler, SampleStream};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// The camera ray of one sample of pixel (x, y): through the pixel centre when the render
/// takes one sample per pixel (`centre`), else jittered by the sample's pixel dimensions.
/// The coverage pass ([`super::coverage`]) replays it.
pub fn primary_ray(
    camera: &Camera,
    x: u32,
    y: u32,
    centre: bool,
    sample: &mut SampleStream,
) -> Ray {
    let jitter = if centre {
        Vec2::splat(0.5)
    } else {
        sample.pixel()
    };
    camera.generate_ray(Vec2::new(x as f32, y as f32) + jitter)
}

/// The sampler of a render with `settings`: Sobol' blocks of `spp` samples per pixel over
/// its resolution (the same for every round, thread and shard).
pub fn pixel_sampler(settings: &RenderSettings, spp: u64) -> PixelSampler {
    PixelSampler::new(
        settings.sampler,
        spp,
        (settings.width, settings.height),
        settings.seed,
    )
}

/// One camera sample to take: sample `k` (absolute index) of pixel (`x`, `y`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Job {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// The pixel's sample index.
    pub k: u64,
}

/// How a [`Job`] begins, the same for every estimator: the render's sampler restarted at
/// the job's sample, its camera ray ([`primary_ray`]) and, in spectral transport, its
/// hero-wavelength variate (0 in RGB), drawn in that order.
pub struct Starts<'a> {
    camera: &'a Camera,
    sampler: &'a PixelSampler,
    centre: bool,
    spectral: bool,
}

impl<'a> Starts<'a> {
    /// Jobs through `camera` from the numbers of `sampler`: each camera ray through the
    /// pixel centre when `centre`, else jittered; a hero variate drawn when `spectral`.
    pub fn new(
        camera: &'a Camera,
        sampler: &'a PixelSampler,
        centre: bool,
        spectral: bool,
    ) -> Self {
        Starts {
            camera,
            sampler,
            centre,
            spectral,
        }
    }

    /// A context for [`Starts::start`] to restart (its numbers are those of sample 0 of
    /// pixel (0, 0) until then): one per sample in flight (a lane of the SoA path kernel
    /// holds one).
    pub fn context(&self) -> Context {
        Context {
            sample: self.sampler.start(0, 0, 0),
            rays: 0,
        }
    }

    /// Starts `job` in `ctx` (its ray count reset): the camera ray and the hero variate.
    pub fn start(&self, job: Job, ctx: &mut Context) -> (Ray, f32) {
        self.sampler.restart(&mut ctx.sample, job.x, job.y, job.k);
        ctx.rays = 0;
        let ray = primary_ray(self.camera, job.x, job.y, self.centre, &mut ctx.sample);
        let u_lambda = if self.spectral {
            ctx.sample.wavelength()
        } else {
            0.0
        };
        (ray, u_lambda)
    }
}

/// Jobs handed to a batch estimator at once (at most; a tile's round is split into
/// batches of this many, in order).
pub const BATCH: usize = 512;

/// The sample loop of the per-sample methods: samples k = 0, 1, … per pixel (or the
/// absolute `range` of a shard), each a jittered camera ray (the pixel centre for a single
/// sample per pixel) estimated by `estimate(ray, u_lambda, ctx)` (linear RGB), in rounds to
/// the checkpoints (see the module docs). `setup` is the work done before (photon maps):
/// its start time, rays and photons count in the progress and the stats. Runs on the
/// current rayon pool.
pub fn render_samples(
    camera: &Camera,
    settings: &RenderSettings,
    range: Option<std::ops::Range<u64>>,
    setup: Prepass,
    observer: Option<Observer>,
    estimate: impl Fn(&Ray, f32, &mut Context) -> Vec3 + Sync,
) -> Result<(Film, RenderStats)> {
    render_batches(
        camera,
        settings,
        range,
        setup,
        observer,
        one_by_one(estimate),
    )
}

/// [`render_samples`] with an estimator of whole batches of jobs:
/// `estimate(starts, jobs, out)` writes job `i`'s linear RGB to `out[i]` and returns the
/// rays it traced; it begins each job with [`Starts::start`] and may take them in any
/// order (the lanes of [`crate::integrator::path`]), as each job's numbers are its own.
/// The film receives the estimates in job order.
pub fn render_batches(
    camera: &Camera,
    settings: &RenderSettings,
    range: Option<std::ops::Range<u64>>,
    setup: Prepass,
    observer: Option<Observer>,
    estimate: impl Fn(&Starts, &[Job], &mut [Vec3]) -> u64 + Sync,
) -> Result<(Film, RenderStats)> {
    sample_rounds(
        camera,
        settings,
        (range, u64::MAX),
        setup,
        observer,
        &guard::stop_requested,
        estimate,
    )
}

/// A per-sample estimator as a batch estimator: the jobs one after the other.
fn one_by_one(
    estimate: impl Fn(&Ray, f32, &mut Context) -> Vec3 + Sync,
) -> impl Fn(&Starts, &[Job], &mut [Vec3]) -> u64 + Sync {
    move |starts, jobs, out| {
        let mut ctx = starts.context();
        let mut rays = 0;
        for (job, l) in jobs.iter().zip(out.iter_mut()) {
            let (ray, u_lambda) = starts.start(*job, &mut ctx);
            *l = estimate(&ray, u_lambda, &mut ctx);
            rays += ctx.rays;
        }
        rays
    }
}

/// [`render_batches`] with rounds of at most `max_round` samples per pixel (tests split
/// the rounds with it; the image must not change), and `stop` asked before each tile of a
/// round after the first (a `true` skips the rest of the round's tiles and ends the
/// render).
fn sample_rounds(
    camera: &Camera,
    settings: &RenderSettings,
    (range, max_round): (Option<std::ops::Range<u64>>, u64),
    setup: Prepass,
    observer: Option<Observer>,
    stop: &(dyn Fn() -> bool + Sync),
    estimate: impl Fn(&Starts, &[Job], &mut [Vec3]) -> u64 + Sync,
) -> Result<(Film, RenderStats)> {
    let target = settings.spp.max(1) as u64;
    let sampler = pixel_sampler(settings, target);
    let schedule = super::schedule(target, range, max_round, false, "rendering");
    let starts = Starts {
        camera,
        sampler: &sampler,
        centre: target == 1,
        spectral: settings.spectral,
    };
    drive(
        settings,
        schedule,
        setup,
        observer,
        stop,
        |film, k0, k1, env| Ok(round(&starts, film, (k0, k1), env, &estimate)),
    )
}

/// `k1 − k0` more samples of every pixel of the active tiles, tiles in parallel: tile by
/// tile from its own next unit ([`FilmTile::next_unit`], `k0` unless adaptive sampling
/// rested it before); a tile skipped on a stop request keeps its count. Within a tile,
/// pixel by pixel and sample by sample, in batches of at most [`BATCH`] jobs.
fn round(
    starts: &Starts,
    film: &mut Film,
    (k0, k1): (u64, u64),
    env: &RoundEnv,
    estimate: &(impl Fn(&Starts, &[Job], &mut [Vec3]) -> u64 + Sync),
) -> Round {
    let (rays, bad) = film
        .par_tiles_mut()
        .map(|mut tile| {
            if !tile.active() {
                env.bar.inc(k1 - k0);
                return (0, 0);
            }
            if env.skip(k0) {
                return (0, 0);
            }
            let (mut rays, mut bad) = (0, 0);
            let pixels: Vec<_> = (0..tile.slots())
                .filter_map(|i| tile.pixel(i).map(|p| (i, p)))
                .collect();
            let (t0, t1) = (tile.next_unit(), tile.next_unit() + (k1 - k0));
            let all = pixels
                .into_iter()
                .flat_map(|(i, (x, y))| (t0..t1).map(move |k| (i, Job { x, y, k })));
            let (mut batch, mut jobs) = (Vec::with_capacity(BATCH), Vec::with_capacity(BATCH));
            let mut out = vec![Vec3::ZERO; BATCH];
            let mut all = all.peekable();
            while all.peek().is_some() {
                batch.clear();
                batch.extend(all.by_ref().take(BATCH));
                jobs.clear();
                jobs.extend(batch.iter().map(|&(_, j)| j));
                rays += estimate(starts, &jobs, &mut out[..jobs.len()]);
                for (&(i, job), l) in batch.iter().zip(&out) {
                    tile.add(i, job.k, l.as_dvec3(), &mut bad);
                }
            }
            tile.take(k1 - k0, rays);
            env.bar.inc(k1 - k0);
            (rays, bad)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    Round {
        rays,
        bad,
        ..Round::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::look_at;
    use crate::image::ImageRgb;
    use crate::render::{Control, Progress};
    use crate::sampler::SamplerKind;
    use crate::scene::desc::{CameraDesc, Projection};

    const ZSOBOL: SamplerKind = SamplerKind::ZSobol;

    /// A synthetic estimate that uses every input: the sample's random stream, the hero
    /// variate and the ray; any dependence on the round split changes it.
    fn render_split(max_round: u64, threads: usize) -> (ImageRgb, Vec<u64>) {
        let (img, seen, _) = render_with(19, 13, 23, max_round, threads, &|| false, ZSOBOL);
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
        sampler: SamplerKind,
    ) -> (ImageRgb, Vec<u64>, RenderStats) {
        let (film, seen, stats) =
            render_range(w, h, spp, (None, None), max_round, threads, stop, sampler);
        (film.mean(), seen, stats)
    }

    /// [`render_with`] of the samples `range` only, returning the film; with
    /// `cancel_at` = Some(n), the estimate cancels the render ([`crate::render::guard::Cancel`])
    /// as it takes its n-th sample.
    #[allow(clippy::too_many_arguments)]
    fn render_range(
        w: u32,
        h: u32,
        spp: u32,
        (range, cancel_at): (Option<std::ops::Range<u64>>, Option<u64>),
        max_round: u64,
        threads: usize,
        stop: &(dyn Fn() -> bool + Sync),
        sampler: SamplerKind,
    ) -> (Film, Vec<u64>, RenderStats) {
        let settings = RenderSettings {
            width: w,
            height: h,
            spp,
            seed: 4,
            threads,
            quiet: true,
            spectral: true,
            time_limit: None,
            sampler,
            adaptive: None,
            cancel: crate::render::guard::Cancel::new(),
            kernel: Default::default(),
        };
        let taken = std::sync::atomic::AtomicU64::new(0);
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
        let (film, stats) = pool
            .install(|| {
                sample_rounds(
                    &camera,
                    &settings,
                    (range, max_round),
                    Prepass::now(),
                    Some(&mut obs),
                    stop,
                    one_by_one(|ray, u, ctx| {
                        let n = taken.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
                        if cancel_at == Some(n) {
                            settings.cancel.cancel();
                        }
                        if ray.dir.x > 0.3 && u < 0.01 {
                            // A numerical failure on a few samples: counted, never painted.
                            Vec3::NAN
                        } else {
                            Vec3::new(ctx.sample.get_1d(9), u, ray.dir.x)
                        }
                    }),
                )
            })
            .unwrap();
        (film, seen, stats)
    }

    #[test]
    fn shards_of_the_samples_add_up_to_the_whole_render() {
        for sampler in [ZSOBOL, SamplerKind::Independent] {
            let never = &|| false;
            let (whole, ..) = render_range(19, 13, 23, (None, None), u64::MAX, 2, never, sampler);
            let mut merged = crate::image::ExactImage::new(19, 13);
            // Shards in any order, with their own round splits.
            for (range, max_round) in [(15..23, 3), (0..8, u64::MAX), (8..15, 1)] {
                let (film, seen, stats) = render_range(
                    19,
                    13,
                    23,
                    (Some(range.clone()), None),
                    max_round,
                    1,
                    never,
                    sampler,
                );
                assert_eq!(film.first(), range.start);
                assert_eq!(film.done(), range.end - range.start);
                assert_eq!(*seen.last().unwrap(), range.end - range.start);
                assert_eq!(stats.samples, 19 * 13 * (range.end - range.start));
                merged.add(&film.exact());
            }
            assert_eq!(merged, whole.exact(), "{sampler:?}");
            assert_eq!(merged.mean(), whole.mean());
            assert_eq!(merged.halves(), whole.halves());
        }
    }

    #[test]
    fn bad_samples_are_counted_not_painted() {
        let (img, _, stats) = render_with(19, 13, 23, u64::MAX, 2, &|| false, ZSOBOL);
        assert!(img.data.iter().all(|p| p.is_finite()));
        // About 1 % of the samples of the right-hand pixels hit the failure.
        assert!(stats.bad_samples > 0, "{}", stats.bad_samples);
        assert!(
            stats.bad_samples < stats.samples / 50,
            "{}",
            stats.bad_samples
        );
        assert_eq!(stats.end, crate::render::EndReason::Samples);
    }

    #[test]
    fn a_cancelled_render_stops_within_the_tile_in_flight() {
        // 40×40 = 3×3 tiles of 16, 16 and 8 columns; one thread takes them in order. The
        // cancellation comes with the first sample of the third tile, in the first round
        // (which a stop request never cuts): that tile finishes, the six others are skipped.
        for cancel_at in [16 * 16 * 2 + 1, 16 * 16 * 2 + 8 * 16] {
            let never = &|| false;
            let ind = SamplerKind::Independent;
            let (film, seen, stats) =
                render_range(40, 40, 8, (None, Some(cancel_at)), u64::MAX, 1, never, ind);
            assert!(stats.interrupted());
            assert_eq!(
                stats.samples,
                16 * 16 * 2 + 8 * 16,
                "cancel at sample {cancel_at}"
            );
            assert_eq!(film.tile_states().filter(|t| t.units > 0).count(), 3);
            assert!(seen.len() <= 1, "{seen:?}");
        }
    }

    #[test]
    fn an_interrupted_round_keeps_whole_tiles() {
        // 40×40 = 3×3 tiles. Rounds 1, 1→2, 2→4, 4→8; every round after the first asks
        // once per tile and once at its end: the stop request comes during the last round,
        // after 3 of its tiles started. The independent sampler: its 4-spp image does not
        // depend on the spp cap (the Sobol' sampler's blocks do).
        let calls = std::sync::atomic::AtomicU64::new(0);
        let stop = || calls.fetch_add(1, std::sync::atomic::Ordering::SeqCst) >= 10 + 10 + 3;
        let ind = SamplerKind::Independent;
        let (img, seen, stats) = render_with(40, 40, 8, u64::MAX, 1, &stop, ind);
        let (four, ..) = render_with(40, 40, 4, u64::MAX, 1, &|| false, ind);
        let (eight, ..) = render_with(40, 40, 8, u64::MAX, 1, &|| false, ind);
        assert!(stats.interrupted());
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
