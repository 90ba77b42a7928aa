//! The progressive driver: the one loop every method renders through. It advances a
//! [`Film`] in rounds of units (camera samples per pixel, or SPPM passes) to checkpoints
//! 1, 2, 4, 8, … units (and in between where the observer asks, [`Control::ContinueTo`])
//! and the target, and owns what a long render needs around the maths:
//! the time limit, the stop request (SIGINT, [`super::guard`]), the progress bar with the
//! half-buffer error estimate, the observer called at checkpoints, and the stats.
//!
//! Invariants:
//! - Units have absolute indices: a render takes `first..first + target` (`first` > 0 for a
//!   shard, [`crate::app::shard`]); the step gets absolute `k0..k1`, and the film, the
//!   checkpoints and the progress count units from `first`.
//! - A round covers units `k0..k1`; the method's step adds exactly `k1 − k0` units to every
//!   active tile it renders, from the tile's own next unit (`k0` unless adaptive sampling
//!   rested it, [`super::adaptive`]; a stop request may skip whole tiles of a round after
//!   the first, never part of a tile), so the image after N units does not depend on how
//!   rounds were split.
//! - With adaptive sampling ([`RenderSettings::adaptive`] and [`Schedule::adaptive`]) the
//!   checkpoints also choose which tiles take the next rounds; `done` counts the rounds'
//!   units, the most any tile has.
//! - At least one unit is always taken; the time limit shortens a round to the units that
//!   fit the time left (from the mean time per unit so far) and ends the render after the
//!   round that crosses it.
//! - The observer sees every checkpoint and the end (`done`); [`Control::Stop`] ends the
//!   render with the image it saw.
//! - The stats say what ended the render ([`EndReason`]; the order of precedence is the
//!   enum's docs).
//! - An open schedule ([`Schedule::open`]: a render of [`super::OPEN_UNITS`] units, or a
//!   shard of one) relies on the time limit or the observer: the progress bar then shows
//!   elapsed time and the time limit, not a fraction of the units.
//!
//! Times are wall-clock from [`Prepass::start`] (work before the first unit, such as photon
//! maps, counts).

use super::film::Film;
use super::progress::{
    estimate_note, judged_note, progress_bar, relative_error_estimate, time_to_target, Judged,
};
use super::{Control, EndReason, Observer, Prepass, Progress, RenderSettings, RenderStats};
use crate::error::Result;
use crate::image::ImageRgb;
use indicatif::ProgressBar;
use std::time::{Duration, Instant};

/// How a method's units are scheduled.
#[derive(Debug, Clone, Copy)]
pub struct Schedule {
    /// The absolute index of the first unit (0 unless the render is a shard).
    pub first: u64,
    /// Units to take from `first` on (at least 1).
    pub target: u64,
    /// Open-ended: the time limit or the observer is expected to end the render first.
    pub open: bool,
    /// Most units per round (1 for SPPM: a pass is a round).
    pub max_round: u64,
    /// Whether units are passes (SPPM: `Progress::passes` counts them) or samples.
    pub passes: bool,
    /// The progress bar's title.
    pub label: &'static str,
    /// Whether the method lets tiles rest ([`super::adaptive`], when the settings ask for
    /// it): a tile's units then go on from its own count.
    pub adaptive: bool,
}

/// What one round did, beyond the units the film counts.
#[derive(Debug, Default, Clone)]
pub struct Round {
    /// Rays traced.
    pub rays: u64,
    /// Samples dropped as NaN or infinite ([`super::guard::admit`]).
    pub bad: u64,
    /// Photons emitted.
    pub photons: u64,
    /// Extra text for the progress bar (e.g. SPPM's radius and stored photons).
    pub note: String,
}

/// What a step may use during its round.
pub struct RoundEnv<'a> {
    /// Asked before each tile of a round after the first; `true` skips the rest of the
    /// round's tiles and ends the render.
    pub stop: &'a (dyn Fn() -> bool + Sync),
    /// The render's own stop request: skips any tile, the first round's too.
    pub cancel: &'a super::guard::Cancel,
    /// The absolute index of the render's first unit.
    pub first: u64,
    /// The progress bar; its length is `target · tiles`: a step adds 1 per tile and unit.
    pub bar: &'a ProgressBar,
}

impl RoundEnv<'_> {
    /// Whether a tile of round `k0..` (absolute) should be skipped: on the render's
    /// cancellation, or on the stop request in a round after the first.
    pub fn skip(&self, k0: u64) -> bool {
        self.cancel.is_cancelled() || (k0 > self.first && (self.stop)())
    }
}

/// [`drive`] for the methods whose unit is a pass (the hybrid, VCM): `step(film, pass,
/// env)` for each round's pass, stopping on the stop request ([`super::guard`]) before any
/// round after the first.
pub fn drive_passes(
    settings: &RenderSettings,
    schedule: Schedule,
    setup: Prepass,
    observer: Option<Observer>,
    mut step: impl FnMut(&mut Film, u32, &RoundEnv) -> Result<Round>,
) -> Result<(Film, RenderStats)> {
    let stop = super::guard::stop_requested;
    drive(
        settings,
        schedule,
        setup,
        observer,
        &stop,
        |film, k0, _k1, env| {
            if env.skip(k0) {
                return Ok(Round::default());
            }
            step(film, k0 as u32, env)
        },
    )
}

/// Renders progressively: calls `step(film, k0, k1, env)` for rounds of units (absolute
/// indices) until the schedule's target, the time limit, a stop request or the observer
/// ends it. Returns the film (its exact sums, for a shard's partial image) and the stats.
pub fn drive(
    settings: &RenderSettings,
    schedule: Schedule,
    setup: Prepass,
    mut observer: Option<Observer>,
    stop: &(dyn Fn() -> bool + Sync),
    mut step: impl FnMut(&mut Film, u64, u64, &RoundEnv) -> Result<Round>,
) -> Result<(Film, RenderStats)> {
    let target = schedule.target.max(1);
    let first = schedule.first;
    let mut film = Film::new(settings.width, settings.height, first);
    let unit = if schedule.passes { "passes" } else { "spp" };
    let open = schedule.open;
    let bar = progress_bar(
        settings.quiet,
        (!open).then(|| target * film.tiles() as u64),
        schedule.label,
    );
    let env = RoundEnv {
        stop,
        cancel: &settings.cancel,
        first,
        bar: &bar,
    };
    let limit_note = match (open, settings.time_limit) {
        (true, Some(t)) => format!(", time limit {:.0} s", t.as_secs_f64()),
        _ => String::new(),
    };
    let started = Instant::now();
    let (mut done, mut next_checkpoint) = (0u64, 1u64);
    let (mut rays, mut photons, mut bad) = (setup.rays, setup.photons, 0u64);
    let mut shown = Shown::Raw(None);
    let mut interrupted;
    let mut observer_stopped = false;
    let mut out_of_time;
    let adaptive = settings.adaptive.filter(|_| schedule.adaptive);
    loop {
        let n = round_size(
            settings,
            &schedule,
            (&setup, started),
            done,
            next_checkpoint,
        );
        let k0 = first + done;
        let expected = film.pixel_samples() + n * film.active_pixels();
        let round = step(&mut film, k0, k0 + n, &env)?;
        (rays, photons, bad) = (rays + round.rays, photons + round.photons, bad + round.bad);
        let note = round.note;
        // A stop request after the last unit is not an interruption: the image is whole.
        let stop_asked = env.skip(k0);
        let whole = film.pixel_samples() == expected;
        done = if whole { done + n } else { film.done() };
        interrupted = stop_asked && (!whole || done < target);
        let resting = resting_note(&film);
        let message = |e: &Shown| {
            format!(
                "{done} {unit}, {rays} rays{note}{resting}{}{limit_note}",
                e.note(settings.time_limit, setup.start)
            )
        };
        bar.set_message(message(&shown));
        out_of_time = settings
            .time_limit
            .is_some_and(|t| setup.start.elapsed() >= t);
        let finished = done >= target || out_of_time || interrupted;
        if done < next_checkpoint && !finished {
            continue;
        }
        while next_checkpoint <= done {
            next_checkpoint *= 2;
        }
        let want_halves =
            (observer.is_some() || !settings.quiet || adaptive.is_some()) && done >= 2;
        let halves = (observer.is_some() || want_halves).then(|| film.halves());
        if let (Some((a, b)), true) = (&halves, want_halves) {
            shown = Shown::Raw(relative_error_estimate(a, b));
        }
        let mut judged = None;
        if let (Some(obs), Some((a, b))) = (observer.as_mut(), &halves) {
            let image = film.mean();
            let progress = Progress {
                image: &image,
                halves: (a, b),
                elapsed: setup.start.elapsed(),
                samples: done,
                passes: if schedule.passes { done as u32 } else { 1 },
                rays,
                photons,
                done: finished,
                judged: Default::default(),
            };
            if answer(obs(&progress)?, &mut next_checkpoint, done) {
                observer_stopped = true;
                break;
            }
            judged = progress.judged.into_inner();
        }
        if let Some(j) = &judged {
            shown = Shown::Judged(j.numbers(), started.elapsed(), Instant::now());
        }
        bar.set_message(message(&shown));
        // The tiles for the next rounds, measured on what the observer judged by, else
        // on the raw halves.
        if let (Some(a), Some((ha, hb)), false) = (&adaptive, &halves, finished) {
            let (ja, jb, absolute) = measured_on(judged.as_ref(), (ha, hb));
            film.set_active(super::adaptive::choose(&film, (ja, jb), absolute, done, a));
        }
        if finished {
            break;
        }
    }
    bar.finish_and_clear();
    debug_assert!(interrupted || observer_stopped || done >= target || out_of_time);
    let end = end_reason(interrupted, observer_stopped, done >= target);
    let passes = if schedule.passes { done as u32 } else { 1 };
    let stats = end_stats(&setup, &film, (rays, photons, bad), passes, end);
    Ok((film, stats))
}

/// The halves adaptive sampling measures the tiles on, and whether in an absolute measure:
/// the observer's judged halves if it set them, else the raw `halves`, relative.
fn measured_on<'a>(
    judged: Option<&'a Judged>,
    halves: (&'a ImageRgb, &'a ImageRgb),
) -> (&'a ImageRgb, &'a ImageRgb, bool) {
    match judged {
        Some(Judged {
            halves: Some((a, b)),
            absolute,
            ..
        }) => (a, b, *absolute),
        _ => (halves.0, halves.1, false),
    }
}

/// The estimate the progress line shows: the raw image's relative error, or the
/// observer's judgement (the stop test's measure and target) with the render time it was
/// made at and when, for the expected time to the target.
enum Shown {
    Raw(Option<f64>),
    Judged(Judged, Duration, Instant),
}

impl Shown {
    /// The progress line's note.
    /// The render's time limit, if any, counts from `start`.
    fn note(&self, limit: Option<Duration>, start: Instant) -> String {
        let limit_left = limit.map(|t| t.saturating_sub(start.elapsed()));
        match self {
            Shown::Raw(e) => estimate_note(*e),
            Shown::Judged(j, at, when) => {
                let left = time_to_target(j.estimate, j.target, *at)
                    .map(|d| d.saturating_sub(when.elapsed()));
                let past = matches!((left, limit_left), (Some(l), Some(m)) if l > m);
                judged_note(j, left, past)
            }
        }
    }
}

/// Why a render ended: an interruption first, then the observer's stop (its error target),
/// then the schedule's units (`reached`), else the time limit.
fn end_reason(interrupted: bool, observer_stopped: bool, reached: bool) -> EndReason {
    match (interrupted, observer_stopped, reached) {
        (true, _, _) => EndReason::Interrupted,
        (_, true, _) => EndReason::Target,
        (_, _, true) => EndReason::Samples,
        _ => EndReason::TimeLimit,
    }
}

/// The stats of a render that ended for `end` with `film`, the `(rays, photons, bad
/// samples)` counted and `passes` (1 for per-sample methods).
fn end_stats(
    setup: &Prepass,
    film: &Film,
    (rays, photons, bad): (u64, u64, u64),
    passes: u32,
    end: EndReason,
) -> RenderStats {
    RenderStats {
        time: setup.start.elapsed(),
        rays,
        samples: film.pixel_samples(),
        unit_span: film.unit_span(),
        photons,
        photons_per_pass: 0,
        passes,
        bad_samples: bad,
        end,
    }
}

/// Units of the next round after `done`: to the next checkpoint (or the target), at most
/// the schedule's round, fewer if the time limit would be crossed (from the mean time per
/// unit since `started`).
fn round_size(
    settings: &RenderSettings,
    schedule: &Schedule,
    (setup, started): (&Prepass, Instant),
    done: u64,
    next_checkpoint: u64,
) -> u64 {
    let target = schedule.target.max(1);
    let n = (next_checkpoint.min(target) - done).min(schedule.max_round.max(1));
    match (settings.time_limit, done > 0) {
        (Some(limit), true) => {
            let per_unit = started.elapsed().as_secs_f64() / done as f64;
            let left = limit.saturating_sub(setup.start.elapsed()).as_secs_f64();
            n.min(((left / per_unit.max(1e-12)) as u64).max(1))
        }
        _ => n,
    }
}

/// ", 40 % of tiles resting" for the progress bar while adaptive sampling rests tiles.
fn resting_note(film: &Film) -> String {
    let resting = film.tile_states().filter(|t| !t.active).count();
    if resting == 0 {
        return String::new();
    }
    let share = 100.0 * resting as f64 / film.tiles() as f64;
    format!(", {share:.0} % of tiles resting")
}

/// Applies an observer's answer after `done` units: [`Control::ContinueTo`] moves the next
/// checkpoint within one more unit and the doubling. Returns whether it stops the render.
fn answer(control: Control, next_checkpoint: &mut u64, done: u64) -> bool {
    match control {
        Control::Stop => true,
        Control::ContinueTo(units) => {
            *next_checkpoint = units.clamp(done + 1, *next_checkpoint);
            false
        }
        Control::Continue => false,
    }
}
