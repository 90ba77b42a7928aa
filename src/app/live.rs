//! A render that refines until it is cancelled, for the live view ([`crate::view`]): the
//! same job as `iris render` (options checked, scene prepared, plan made by
//! [`RenderJob::new`]) rendered without writing anything, showing the image after every
//! unit (sample per pixel, or pass) to a callback.
//!
//! - The image after N units is the one `iris render` with the same flags has after N
//!   units: the same integrator, settings and sample streams (the progress bar, time limit,
//!   error target and adaptive sampling left out, which only decide when to stop or where
//!   the samples go).
//! - **Resting.** From `rest` seconds after the start (the camera has not moved since), the
//!   frames shown are denoised (when the build and the flags denoise: the auxiliary pass runs
//!   then, once) at units 2ᵏ only, the units between reported without an image, so the
//!   picture does not flicker between noisy and clean.
//! - **Stopping.** The render ends when its [`Cancel`] is set (before the next tile, the
//!   image then incomplete and not shown), when the callback answers `false`, or at the
//!   options' unit count.
//!
//! - **Estimates.** Every frame from 2 units on carries the estimated display error of the
//!   raw picture (the view's display transform, [`crate::output::display`]); a resting
//!   denoised frame also carries the display error of the denoised picture, measured as
//!   `iris render`'s stop test measures a denoised PNG ([`super::budget::stop_error`] on the
//!   denoised halves), so the view can say when the picture is clean by the command's
//!   standard ([`super::budget::DEFAULT_DISPLAY_TARGET`]).
//!
//! Images are linear RGB; times wall-clock.

use super::budget::{stop_error, Measure};
use super::render::RenderJob;
use super::render_denoise::RenderDenoiser;
use crate::camera::Camera;
use crate::error::Result;
use crate::image::ImageRgb;
use crate::integrator::Integrator;
use crate::output::display::Picture;
use crate::output::Background;
use crate::render::guard::Cancel;
use crate::render::{Control, Progress, RenderStats};
use std::time::Duration;

/// What the live render shows after a unit.
pub struct LiveFrame<'a> {
    /// The image (denoised when `denoised`), or `None` between the resting frames.
    pub image: Option<&'a ImageRgb>,
    /// Whether `image` is the denoised one.
    pub denoised: bool,
    /// Units so far (samples per pixel; passes for pass methods).
    pub units: u64,
    /// Time since the render started.
    pub elapsed: Duration,
    /// The estimated display error of the raw picture (from 2 units on).
    pub estimate: Option<f64>,
    /// The estimated display error of the denoised picture (resting denoised frames from
    /// [`super::budget::MIN_STOP_UNITS`] units on), as the command's stop test measures it.
    pub denoised_estimate: Option<f64>,
}

impl RenderJob<'_> {
    /// Renders until `cancel`, `show` answering `false`, or the unit count (module docs);
    /// returns the render's stats.
    pub fn live(
        &self,
        cancel: &Cancel,
        rest: Duration,
        mut show: impl FnMut(&LiveFrame) -> bool + Send,
    ) -> Result<RenderStats> {
        let (scene, (w, h)) = (&self.prepared.scene, self.prepared.size);
        let camera = Camera::new(&self.prepared.camera, w, h);
        let integrator = Integrator::new(self.plan.method, self.opts.max_depth, &self.opts.photon)?
            .with_polarization(self.plan.polarization);
        let mut settings = self.settings();
        settings.quiet = true;
        settings.time_limit = None;
        settings.adaptive = None;
        settings.cancel = cancel.clone();
        let mut denoiser: Option<RenderDenoiser> = None;
        // The view shows the environment behind the model (`crate::view::encode`).
        let picture = Picture::new(self.opts.display, Background::Environment, None);
        let mut observe = |p: &Progress| -> Result<Control> {
            if cancel.is_cancelled() {
                return Ok(Control::Stop);
            }
            let estimate = (p.samples >= 2)
                .then(|| picture.estimate(p.halves.0, p.halves.1).ok())
                .flatten();
            let resting = p.elapsed >= rest && self.denoise.runs();
            let frame = if !resting {
                LiveFrame {
                    image: Some(p.image),
                    denoised: false,
                    units: p.samples,
                    elapsed: p.elapsed,
                    estimate,
                    denoised_estimate: None,
                }
            } else {
                let at_power = p.samples.is_power_of_two() || p.done;
                if at_power && denoiser.is_none() {
                    denoiser = Some(RenderDenoiser::new(
                        &self.denoise,
                        scene,
                        &camera,
                        &settings,
                    )?);
                }
                let denoised_estimate = match (&denoiser, at_power) {
                    (Some(d), true) => stop_error(p, d.denoised_stop(), Measure::Display(picture))?,
                    _ => None,
                };
                let d = match (&mut denoiser, at_power) {
                    (Some(d), true) => d.checkpoint(p.image, true)?.map(|d| &d.image),
                    _ => None,
                };
                LiveFrame {
                    image: d,
                    denoised: d.is_some(),
                    units: p.samples,
                    elapsed: p.elapsed,
                    estimate,
                    denoised_estimate,
                }
            };
            if !show(&frame) {
                return Ok(Control::Stop);
            }
            Ok(Control::ContinueTo(p.samples + 1))
        };
        let (_, stats) =
            integrator.render_units(scene, &camera, &settings, None, Some(&mut observe))?;
        Ok(stats)
    }
}
