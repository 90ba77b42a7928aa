//! What a render shows while it runs: the [`Progress`] an observer sees at checkpoints, its
//! answer ([`Control`]), the start of the clock ([`Setup`]) and the progress bar with the
//! half-buffer error estimate. Images are linear RGB; times are wall-clock.

use crate::error::Result;
use crate::image::ImageRgb;
use indicatif::{ProgressBar, ProgressStyle};
use std::time::Instant;

pub use crate::measure::Progress;

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

/// The relative error of the full image estimated from its two halves
/// ([`crate::measure::metrics::half_buffer_estimate`], √ of the relative MSE), for the progress bar.
pub fn relative_error_estimate(a: &ImageRgb, b: &ImageRgb) -> Option<f64> {
    crate::measure::metrics::half_buffer_estimate(a, b)
        .ok()
        .map(|e| e.rel_mse.sqrt())
}

/// ", est. rel. error 0.123" for the progress bar, or nothing before the first estimate.
pub fn estimate_note(e: Option<f64>) -> String {
    e.map_or(String::new(), |e| format!(", est. rel. error {e:.3}"))
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
