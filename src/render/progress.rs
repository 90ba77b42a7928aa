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
    /// The two half images the observer judged the render by, if not `halves` (the
    /// error-target stop of a denoised image sets its denoised halves): adaptive sampling
    /// ([`super::adaptive`]) then measures the tiles on them, so samples go where the
    /// image the stop sees is noisy.
    pub judged: std::cell::OnceCell<(ImageRgb, ImageRgb)>,
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
