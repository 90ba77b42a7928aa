//! What a render shows while it runs: the [`Progress`] an observer sees at checkpoints, its
//! answer ([`Control`]), the start of the clock ([`Prepass`]) and the progress bar with the
//! half-buffer error estimate. Images are linear RGB; times are wall-clock.

use crate::error::Result;
use crate::image::ImageRgb;
use indicatif::{ProgressBar, ProgressStyle};
use std::time::{Duration, Instant};

/// The state of a render at a checkpoint, shown to an observer ([`Observer`]) and to a
/// [`crate::measure::Recorder`].
#[derive(Debug, Clone)]
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
    /// What the observer judged the render by at this checkpoint, if it measured it
    /// (the error-target stop sets it): the progress line shows its estimate, and adaptive
    /// sampling ([`super::adaptive`]) measures the tiles on its halves, so samples go where
    /// the picture the stop sees is noisy.
    pub judged: std::cell::OnceCell<Judged>,
}

/// An observer's judgement of a checkpoint ([`Progress::judged`]).
#[derive(Debug, Clone)]
pub struct Judged {
    /// The two half images the estimate was measured on, when they are not
    /// [`Progress::halves`] (denoised halves, or their display values).
    pub halves: Option<(ImageRgb, ImageRgb)>,
    /// Whether the measure is absolute (display values in [0, 1]) rather than relative to
    /// the pixel's value: what adaptive sampling's tiles are then measured in.
    pub absolute: bool,
    /// The estimated error.
    pub estimate: f64,
    /// The error target it is compared with, if any.
    pub target: Option<f64>,
    /// What the estimate measures, for the progress line ("display error", …).
    pub name: &'static str,
}

impl<'a> Progress<'a> {
    /// A checkpoint after `samples` units (one pass, no time, rays or photons yet) showing
    /// `image` and its `halves`, nothing judged: what an observer's tests hand it.
    pub fn at(
        image: &'a ImageRgb,
        halves: (&'a ImageRgb, &'a ImageRgb),
        samples: u64,
        done: bool,
    ) -> Self {
        Progress {
            image,
            halves,
            elapsed: Duration::ZERO,
            samples,
            passes: 1,
            rays: 0,
            photons: 0,
            done,
            judged: Default::default(),
        }
    }
}

/// An observer's answer: render on, or end the render with the image just shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// Keep rendering.
    Continue,
    /// Keep rendering and look again after this many units (samples per pixel, SPPM
    /// passes) in all, sooner than the next doubling: the error-target stop's prediction
    /// ([`crate::app::budget`]). The driver keeps it within one more unit and the doubling.
    ContinueTo(u64),
    /// Stop now; the render returns the image the observer just saw.
    Stop,
}

/// Called at checkpoints 1, 2, 4, 8, … samples per pixel (SPPM: passes), at the checkpoints
/// it asks for ([`Control::ContinueTo`]) and at the end.
/// An error aborts the render and is returned.
pub type Observer<'a> = &'a mut (dyn FnMut(&Progress) -> Result<Control> + Send);

/// Work done before the first camera sample (photon maps): its start time and counts.
#[derive(Debug, Clone, Copy)]
pub struct Prepass {
    /// When the render started.
    pub start: Instant,
    /// Rays traced building (photon maps).
    pub rays: u64,
    /// Photons emitted.
    pub photons: u64,
}

impl Prepass {
    /// Nothing done yet: starts the clock now.
    pub fn now() -> Self {
        Prepass {
            start: Instant::now(),
            rays: 0,
            photons: 0,
        }
    }
}

/// The relative error of the full image estimated from its two halves
/// ([`crate::image::metrics::half_buffer_estimate`], √ of the relative MSE), for the
/// progress bar.
pub fn relative_error_estimate(a: &ImageRgb, b: &ImageRgb) -> Option<f64> {
    crate::image::metrics::half_buffer_estimate(a, b)
        .ok()
        .map(|e| e.rel_mse.sqrt())
}

/// ", est. rel. error 0.123" for the progress bar, or ", no estimate yet" before the first
/// estimate (which needs two units).
pub fn estimate_note(e: Option<f64>) -> String {
    e.map_or(", no estimate yet".to_string(), |e| {
        format!(", est. rel. error {e:.3}")
    })
}

impl Judged {
    /// The judgement without its halves: what the progress line keeps.
    pub fn numbers(&self) -> Judged {
        Judged {
            halves: None,
            ..*self
        }
    }
}

/// ", est. display error 0.0123 (target 0.0100, ≈ 40 s more)" for the progress bar: an
/// observer's judgement after `done` units, `left` the expected time to its target
/// ([`time_to_target`]); `past_limit` when that is beyond the render's time limit, which
/// will end it first.
pub fn judged_note(j: &Judged, left: Option<Duration>, past_limit: bool) -> String {
    let mut s = format!(", est. {} {:.4}", j.name, j.estimate);
    if let Some(t) = j.target {
        s.push_str(&format!(" (target {t}"));
        match left {
            Some(d) if j.estimate > t => {
                let after = if past_limit {
                    ", after the time limit"
                } else {
                    ""
                };
                s.push_str(&format!(", ≈ {} more{after})", short_duration(d)));
            }
            _ => s.push(')'),
        }
    }
    s
}

/// The expected wall time until an estimate `e` after `done` units, which took `spent`,
/// meets `target`, if the error falls as 1/√units (Monte Carlo's rate) and units keep
/// their measured cost: `spent·((e/target)² − 1)`; zero at or below the target, `None`
/// without a target or a finite answer.
pub fn time_to_target(e: f64, target: Option<f64>, spent: Duration) -> Option<Duration> {
    let t = target?;
    let ratio = (e / t).powi(2) - 1.0;
    Duration::try_from_secs_f64(spent.as_secs_f64() * ratio.max(0.0)).ok()
}

/// "40 s", "3 min 20 s", "2 h 05 min".
fn short_duration(d: Duration) -> String {
    let s = d.as_secs_f64().round() as u64;
    match s {
        0..=99 => format!("{s} s"),
        100..=5999 => format!("{} min {:02} s", s / 60, s % 60),
        _ => format!("{} h {:02} min", s / 3600, (s / 60) % 60),
    }
}

/// A progress bar on stderr (hidden with `quiet`): elapsed time, the bar, and a message
/// (samples or passes done, rays). With no length (an open-ended render, ended by time or
/// error) a spinner with the elapsed time and the message, redrawn every 250 ms.
pub fn progress_bar(quiet: bool, len: Option<u64>, what: &str) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let Some(len) = len else {
        let b = ProgressBar::new_spinner();
        b.set_style(
            ProgressStyle::with_template(&format!(
                "{{spinner}} {what} [{{elapsed_precise}}] {{msg}}"
            ))
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        b.enable_steady_tick(std::time::Duration::from_millis(250));
        return b;
    };
    let b = ProgressBar::new(len);
    b.set_style(
        ProgressStyle::with_template(&format!(
            "{{spinner}} {what} [{{elapsed_precise}}] {{bar:40}} {{percent}}% {{msg}} eta {{eta}}"
        ))
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    fn judged(estimate: f64, target: Option<f64>) -> Judged {
        Judged {
            halves: None,
            absolute: true,
            estimate,
            target,
            name: "display error",
        }
    }

    #[test]
    fn the_time_to_the_target_follows_the_monte_carlo_rate() {
        let spent = Duration::from_secs(10);
        // Twice the target: four times the samples, three more times the time spent.
        assert_eq!(
            time_to_target(0.02, Some(0.01), spent),
            Some(Duration::from_secs(30))
        );
        assert_eq!(
            time_to_target(0.005, Some(0.01), spent),
            Some(Duration::ZERO)
        );
        assert_eq!(time_to_target(0.02, None, spent), None);
        assert_eq!(time_to_target(f64::INFINITY, Some(0.01), spent), None);
    }

    #[test]
    fn the_progress_note_names_the_measure_the_target_and_the_time_left() {
        let j = judged(0.0153, Some(0.01));
        assert_eq!(
            judged_note(&j, Some(Duration::from_secs(41)), false),
            ", est. display error 0.0153 (target 0.01, ≈ 41 s more)"
        );
        assert_eq!(
            judged_note(&j, Some(Duration::from_secs(200)), false),
            ", est. display error 0.0153 (target 0.01, ≈ 3 min 20 s more)"
        );
        assert_eq!(
            judged_note(&j, Some(Duration::from_secs(549)), true),
            ", est. display error 0.0153 (target 0.01, ≈ 9 min 09 s more, after the time limit)"
        );
        assert_eq!(
            judged_note(&judged(0.008, Some(0.01)), Some(Duration::ZERO), false),
            ", est. display error 0.0080 (target 0.01)"
        );
        assert_eq!(
            judged_note(&judged(0.02, None), None, false),
            ", est. display error 0.0200"
        );
    }
}
