//! How long `iris render` renders: the budget the flags ask for, resolved in one
//! place ([`BudgetFlags::resolve`]); the stop test against an error target ([`stop_error`],
//! [`TargetStop`]); and when the output is rewritten while the render runs
//! ([`super::checkpoint_writes::CheckpointWrites`]).
//!
//! ## The rule
//! | flags given | unit cap (spp; SPPM: passes) | time limit | error target |
//! |---|---|---|---|
//! | `--spp N` and/or `--passes N` | N (the other: [`FIXED_SPP`] / [`FIXED_PASSES`]) | `--time` if given | `--target-error` if given |
//! | `--time T` alone | open | T | none |
//! | `--target-error E` alone | open | [`DEFAULT_TIME_LIMIT`] | E |
//! | `--time T --target-error E` | open | T | E |
//! | none of them | open | [`DEFAULT_TIME_LIMIT`] | [`DEFAULT_DISPLAY_TARGET`] (PNG), [`DEFAULT_TARGET`] (EXR) |
//!
//! "Open" is [`OPEN_UNITS`] (2²⁰) samples per pixel and passes: more than `--spp` accepts,
//! so the time limit or the target ends the render. Without `--method` the method is
//! `auto` ([`crate::plan::resolve_method`]); `--method whitted` and the others still work.
//! An open budget also rewrites the output at the driver's checkpoints (1, 2, 4, …
//! samples or passes), throttled by [`super::checkpoint_writes::CheckpointWrites`], so the file can be watched;
//! `--checkpoint K` replaces that rule by its own.
//!
//! ## The stop test
//! The target is compared with [`stop_error`] at each checkpoint from [`MIN_STOP_UNITS`]
//! on: the half-buffer estimate of the error of the image as written ([`StopImage`]) in the
//! output's measure ([`Measure`]):
//! - the image: the raw one (an EXR, `--denoise off`, a build without the denoiser), or the
//!   denoised one (the PNG preview under `--denoise auto|on`): the two half images each
//!   denoised with the render's auxiliary images ([`crate::denoise::denoised_halves`]), so
//!   the render stops when the picture it writes is clean, far sooner than the raw image
//!   would be;
//! - the measure: for a PNG the display error of the picture a viewer sees
//!   ([`crate::output::display`]: after exposure, tone map, clipping and the eye's blur at
//!   FLIP's viewing distance; its noise and the bias noise puts into it), so a sparkle that
//!   clips to white counts for nothing and grain on a grey floor in full; for an EXR the
//!   relative RMSE of the linear values ([`crate::image::metrics::half_buffer_estimate`]),
//!   scene-referred numbers for tools.
//!
//! Adaptive sampling measures its tiles on the same halves ([`Judged`]), and the progress
//! line shows the estimate, the target and the time to it ([`crate::render::judged_note`]).
//!
//! Checkpoints double; once an estimate is above the target the stop asks for the next
//! check where the error, falling as 1/√n (Monte Carlo's rate), would meet it, at least
//! [`MIN_CHECK_STEP`] × the units so far ([`next_check`]), so a render stops within about
//! a quarter more units than the target needs rather than up to twice as many (or at the
//! end of its time). The rate is not fitted to the estimates: a denoised image's estimate
//! jumps up and down between checks, and a slope fitted to two of them would schedule more
//! checks, where a lucky low one is likelier to stop the render early. The estimate sees
//! noise, not bias (a denoised image's blur of a caustic edge or a sparkle is bias:
//! BENCHMARKS.md, "Denoised against raw"), and
//! misses what neither half has found yet (a caustic no sample reached): hence the
//! minimum count and the time limit as a safety net.
//!
//! ## The defaults
//! [`DEFAULT_TARGET`] (an EXR), [`DEFAULT_DISPLAY_TARGET`] (a PNG) and [`DEFAULT_TIME_LIMIT`] are documented in `docs/error-and-time.md`
//! ("How long a render takes"); the measurements behind them are beside the constants. Units:
//! wall-clock seconds; errors are relative RMSE, `sqrt(rel_mse)` ([`crate::measure`]), or
//! display RMSE in [0, 1] ([`crate::output::display`]).

pub use super::judge::{stop_error, Measure, StopImage};
use crate::error::Result;
use crate::integrator::Method;
use crate::render::{Control, Progress};
use std::time::{Duration, Instant};

/// The samples per pixel (and SPPM passes) of an open budget: effectively unbounded
/// ([`crate::render::OPEN_UNITS`], 2²⁰ = 1 048 576, above `--spp`'s 10⁶ limit), so the
/// time limit or the error target ends the render. It is also the size of a pixel's Sobol'
/// block ([`crate::sampler::zsobol`]): a render stopped after N samples takes the first N
/// of that block, stratified like any prefix of it.
pub const OPEN_UNITS: u32 = crate::render::OPEN_UNITS as u32;

/// Samples per pixel when only `--passes` fixes the count.
pub const FIXED_SPP: u32 = 4;

/// SPPM passes when only `--spp` fixes the count.
pub const FIXED_PASSES: u32 = 64;

/// The error target of a render given no `--spp`, `--passes`, `--time` or
/// `--target-error`: an estimated relative RMSE ([`stop_error`]) of 0.03.
///
/// Chosen from the estimate at each checkpoint of `iris render SCENE --time T --checkpoint 1
/// --report R.csv` against the checkpoints' images, on plain, enclosed, glass and
/// dispersive scenes (the figures: BENCHMARKS.md, "Figures behind choices in the
/// code"): 0.03 is where the grain of a plain scene has gone at normal viewing size, and
/// what it costs is known (the estimate falls as spp^−1/2: quadrupling the samples halves
/// it); glass, caustics, dispersion and small lights stay above it for minutes, and
/// [`DEFAULT_TIME_LIMIT`] ends those when the output is raw. A denoised PNG is judged by its
/// own estimate ([`StopImage::Denoised`]), which reaches the target sooner (BENCHMARKS.md,
/// "The default stop on the denoised image").
pub const DEFAULT_TARGET: f64 = 0.03;

/// The error target of a render given no budget flag that writes a display-referred image
/// (a PNG): an estimated display RMSE ([`crate::output::display`]) of 0.01, 2.55 levels of
/// 255, of the picture as written (denoised, tone mapped, clipped).
///
/// Chosen from the gallery (BENCHMARKS.md, "Judging the picture written"): the display
/// estimate at each checkpoint against a long reference's picture and against a second
/// seed's picture.
pub const DEFAULT_DISPLAY_TARGET: f64 = 0.01;

/// The default budget's error target for an output: [`DEFAULT_DISPLAY_TARGET`] for a
/// display-referred one (a PNG), [`DEFAULT_TARGET`] for an EXR.
pub fn default_target(display_referred: bool) -> f64 {
    if display_referred {
        DEFAULT_DISPLAY_TARGET
    } else {
        DEFAULT_TARGET
    }
}

/// The time limit of a render given no `--spp`, `--passes` or `--time`: 120 s.
///
/// The safety net for scenes that do not reach [`DEFAULT_TARGET`] soon: long enough for the
/// whole picture, its noise still visible in the hard cases (BENCHMARKS.md, "Figures behind
/// choices in the code"). A longer render is one flag away (`--time`, `--target-error`);
/// the default should not keep a preview waiting longer.
pub const DEFAULT_TIME_LIMIT: Duration = Duration::from_secs(120);

/// The stop test is not applied before this many samples per pixel (SPPM: passes): with
/// one sample both half images are that sample and the estimate is 0, and with very few a
/// sparse light path (a caustic, a small light seen through glass) is in neither half.
pub const MIN_STOP_UNITS: u64 = 8;

/// [`MIN_STOP_UNITS`] for the hybrid in a scene with scattering media: its volumetric
/// caustic map starts with a wide gather radius that only passes shrink, and sparse
/// photons blur into blotches the two denoised halves share, so the denoised estimate of
/// the gallery's hazy prism after [`MIN_STOP_UNITS`] passes is far below the target over an
/// image of coloured blotches (BENCHMARKS.md, "Figures behind choices in the code").
/// 64 passes shrink r² to about a third of the first (α = 0.7). Adaptive
/// sampling is off there under `--adaptive auto` ([`super::adaptive::choose`]), so every
/// tile has the passes.
pub const MIN_STOP_UNITS_MEDIA_HYBRID: u64 = 64;

/// The budget flags of `iris render` as given (`None` = not given).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BudgetFlags {
    /// `--method`.
    pub method: Option<Method>,
    /// `--spp`.
    pub spp: Option<u32>,
    /// `--passes`.
    pub passes: Option<u32>,
    /// `--time`.
    pub time: Option<Duration>,
    /// `--target-error`.
    pub target_error: Option<f64>,
}

/// What a render may spend and when it stops (the module docs' table, resolved).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    /// The method (`auto` when `--method` is not given).
    pub method: Method,
    /// Most samples per pixel (not SPPM).
    pub spp: u32,
    /// Most SPPM passes.
    pub passes: u32,
    /// Stop after the round that crosses this wall time.
    pub time_limit: Option<Duration>,
    /// Stop once [`stop_error`] is at or below this.
    pub target_error: Option<f64>,
    /// `target_error` is the default target, not given: the render replaces it by its
    /// output's measure's default ([`DEFAULT_TARGET`] or [`DEFAULT_DISPLAY_TARGET`]).
    pub default_target: bool,
    /// No count was given: the time limit or the target ends the render, and the output is
    /// rewritten at checkpoints ([`super::checkpoint_writes::CheckpointWrites`]).
    pub open: bool,
}

impl BudgetFlags {
    /// The budget these flags ask for (the table of the module docs).
    pub fn resolve(&self) -> Budget {
        let method = self.method.unwrap_or(Method::Auto);
        if self.spp.is_some() || self.passes.is_some() {
            return Budget {
                method,
                spp: self.spp.unwrap_or(FIXED_SPP),
                passes: self.passes.unwrap_or(FIXED_PASSES),
                time_limit: self.time,
                target_error: self.target_error,
                default_target: false,
                open: false,
            };
        }
        let (time_limit, target_error) = match (self.time, self.target_error) {
            (Some(t), e) => (t, e),
            (None, Some(e)) => (DEFAULT_TIME_LIMIT, Some(e)),
            (None, None) => (DEFAULT_TIME_LIMIT, Some(DEFAULT_TARGET)),
        };
        Budget {
            method,
            spp: OPEN_UNITS,
            passes: OPEN_UNITS,
            time_limit: Some(time_limit),
            target_error,
            default_target: self.time.is_none() && self.target_error.is_none(),
            open: true,
        }
    }
}

impl Default for Budget {
    /// `iris render SCENE` with no budget flag: auto method, [`DEFAULT_TARGET`],
    /// [`DEFAULT_TIME_LIMIT`], open count.
    fn default() -> Self {
        BudgetFlags::default().resolve()
    }
}

/// The error-target stop of one render: compares [`stop_error`] with the target at each
/// checkpoint and remembers the last value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetStop {
    /// The target (`None`: never stops).
    pub target: Option<f64>,
    /// The last [`stop_error`] computed.
    pub last: Option<f64>,
    /// What `last` measures ([`Measure::name`]).
    pub name: &'static str,
    /// Whether `last` is the estimate of a denoised image.
    pub denoised: bool,
    /// Units before the first check (at least [`MIN_STOP_UNITS`]).
    pub min_units: u64,
    /// Checks made, and the wall time they took (two filter runs each for a denoised
    /// image): the stop test's own cost, reported in the render's notes.
    pub checks: (u32, Duration),
}

impl TargetStop {
    /// A stop at `target`.
    pub fn new(target: Option<f64>) -> Self {
        TargetStop {
            target,
            last: None,
            name: "",
            denoised: false,
            min_units: MIN_STOP_UNITS,
            checks: (0, Duration::ZERO),
        }
    }

    /// The stop for `method` on `scene`: from [`MIN_STOP_UNITS_MEDIA_HYBRID`] units for a
    /// method whose error estimate is not to be trusted early in a scene with media (its
    /// declaration, [`crate::integrator::capability::Capabilities::estimate_in_media`]: the
    /// hybrid).
    pub fn for_render(target: Option<f64>, scene: &crate::scene::Scene, method: Method) -> Self {
        let mut stop = TargetStop::new(target);
        if scene.has_media() && !method.caps().estimate_in_media.is_yes() {
            stop.min_units = MIN_STOP_UNITS_MEDIA_HYBRID;
        }
        stop
    }

    /// [`Control::Stop`] once the checkpoint's [`stop_error`] of `what` in `measure` is at
    /// or below the target. The estimate and the target are left in [`Progress::judged`]
    /// for the progress line and adaptive sampling.
    pub fn check(&mut self, p: &Progress, what: StopImage, measure: Measure) -> Result<Control> {
        let Some(target) = self.target else {
            return Ok(Control::Continue);
        };
        let start = Instant::now();
        let Some(mut judged) = super::judge::judge(p, (what, measure), self.min_units)? else {
            return Ok(Control::Continue);
        };
        let e = judged.estimate;
        judged.target = Some(target);
        let _ = p.judged.set(judged);
        self.checks = (self.checks.0 + 1, self.checks.1 + start.elapsed());
        self.last = Some(e);
        self.name = measure.name(what);
        self.denoised = matches!(what, StopImage::Denoised(_));
        Ok(if e <= target {
            Control::Stop
        } else {
            Control::ContinueTo(next_check(p.samples, e, target))
        })
    }
}

impl TargetStop {
    /// The note on the stop test's own cost when it denoised the halves at its checks.
    pub fn note(&self) -> Option<String> {
        self.denoised.then(|| {
            format!(
                "error target checked on the denoised image at {} checkpoints (both halves \
                 denoised each time: {:.2} s)",
                self.checks.0,
                self.checks.1.as_secs_f64()
            )
        })
    }
}

/// Least growth of the units between two checks the stop asks for: each check of a
/// denoised image costs two filter runs.
pub const MIN_CHECK_STEP: f64 = 1.25;

/// Units at which an estimate `e` above `target` after `done` units is expected to meet
/// it if the error falls as 1/√n: ⌈done·(e/target)²⌉, at least ⌈done·[`MIN_CHECK_STEP`]⌉
/// and one more unit (the driver caps it at the next doubling).
pub fn next_check(done: u64, e: f64, target: f64) -> u64 {
    let d = done as f64;
    let need = d * (e / target).powi(2);
    let need = if need.is_finite() { need } else { 2.0 * d };
    (need.max(d * MIN_CHECK_STEP).ceil() as u64).max(done + 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::ImageRgb;
    use glam::Vec3;

    fn flags() -> BudgetFlags {
        BudgetFlags::default()
    }

    #[test]
    fn the_table_of_the_module_docs() {
        let secs = Duration::from_secs;
        let none = flags().resolve();
        assert_eq!(none.method, Method::Auto);
        assert_eq!((none.spp, none.passes), (OPEN_UNITS, OPEN_UNITS));
        assert_eq!(none.time_limit, Some(DEFAULT_TIME_LIMIT));
        assert_eq!(none.target_error, Some(DEFAULT_TARGET));
        assert!(none.open);
        assert_eq!(Budget::default(), none);

        let time = BudgetFlags {
            time: Some(secs(30)),
            ..flags()
        }
        .resolve();
        assert_eq!(
            (time.spp, time.time_limit, time.target_error),
            (OPEN_UNITS, Some(secs(30)), None)
        );
        assert!(time.open);

        let target = BudgetFlags {
            target_error: Some(0.05),
            ..flags()
        }
        .resolve();
        assert_eq!(
            (target.time_limit, target.target_error),
            (Some(DEFAULT_TIME_LIMIT), Some(0.05))
        );

        let both = BudgetFlags {
            time: Some(secs(5)),
            target_error: Some(0.1),
            ..flags()
        }
        .resolve();
        assert_eq!(
            (both.time_limit, both.target_error),
            (Some(secs(5)), Some(0.1))
        );

        let spp = BudgetFlags {
            spp: Some(16),
            method: Some(Method::Whitted),
            ..flags()
        }
        .resolve();
        assert_eq!(spp.method, Method::Whitted);
        assert_eq!((spp.spp, spp.passes), (16, FIXED_PASSES));
        assert_eq!(
            (spp.time_limit, spp.target_error, spp.open),
            (None, None, false)
        );

        let passes = BudgetFlags {
            passes: Some(8),
            time: Some(secs(2)),
            ..flags()
        }
        .resolve();
        assert_eq!((passes.spp, passes.passes), (FIXED_SPP, 8));
        assert_eq!(
            (passes.time_limit, passes.target_error, passes.open),
            (Some(secs(2)), None, false)
        );
    }

    fn img(v: f32) -> ImageRgb {
        ImageRgb {
            width: 2,
            height: 1,
            data: vec![Vec3::splat(v); 2],
        }
    }

    fn progress<'a>(
        m: &'a ImageRgb,
        a: &'a ImageRgb,
        b: &'a ImageRgb,
        samples: u64,
        done: bool,
    ) -> Progress<'a> {
        Progress::at(m, (a, b), samples, done)
    }

    #[test]
    fn the_target_stop_waits_for_enough_samples() {
        // Halves 0.9 and 1.1: per channel (a−b)²/4 = 0.01 over m² + 0.01 = 1.01, so the
        // estimated relative RMSE is sqrt(0.01/1.01) ≈ 0.0995.
        let (m, a, b) = (img(1.0), img(0.9), img(1.1));
        let mut stop = TargetStop::new(Some(0.1));
        let few = progress(&m, &a, &b, MIN_STOP_UNITS - 1, false);
        assert_eq!(
            stop.check(&few, StopImage::Raw, Measure::Linear).unwrap(),
            Control::Continue
        );
        assert_eq!(stop.last, None);
        let enough = progress(&m, &a, &b, MIN_STOP_UNITS, false);
        assert_eq!(
            stop.check(&enough, StopImage::Raw, Measure::Linear)
                .unwrap(),
            Control::Stop
        );
        assert!((stop.last.unwrap() - (0.01f64 / 1.01).sqrt()).abs() < 1e-6);
        // Above the target: look again at 8·(0.0995/0.09)² ≈ 9.8 units, at least 8·1.25.
        let mut strict = TargetStop::new(Some(0.09));
        assert_eq!(
            strict
                .check(&enough, StopImage::Raw, Measure::Linear)
                .unwrap(),
            Control::ContinueTo(10)
        );
        assert_eq!(
            TargetStop::new(None)
                .check(&enough, StopImage::Raw, Measure::Linear)
                .unwrap(),
            Control::Continue
        );
    }

    #[test]
    fn the_next_check_is_where_the_error_should_meet_the_target() {
        // 1/√n: twice the target needs 4× the units; the driver caps that at the doubling.
        assert_eq!(next_check(100, 0.06, 0.03), 400);
        // 0.0335 vs 0.03: 128·1.2469 = 159.6 → 160.
        assert_eq!(next_check(128, 0.0335, 0.03), 160);
        assert_eq!(next_check(200, 0.0335, 0.03), 250);
        // Just above the target: the least step, a quarter more.
        assert_eq!(next_check(128, 0.0301, 0.03), 160);
        assert_eq!(next_check(1, 0.0301, 0.03), 2);
        assert_eq!(next_check(64, f64::INFINITY, 0.03), 128);
    }
}
