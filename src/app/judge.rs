//! What the error-target stop measures ([`super::budget`]): which image ([`StopImage`]:
//! the raw one or the denoised one the output shows) in which measure ([`Measure`]: a PNG's
//! picture, [`crate::output::display`], or an EXR's relative error), and the judgement of a
//! checkpoint ([`stop_error`], [`Judged`]) that the stop, the progress line, the report and
//! adaptive sampling read.

use crate::denoise::{denoised_halves, AuxImages};
use crate::error::Result;
use crate::image::metrics::half_buffer_estimate;
use crate::measure::relative_rmse;
use crate::output::display::Picture;
use crate::render::{Judged, Progress};

/// Which image the stop test estimates: the one the output file shows.
#[derive(Debug, Clone, Copy)]
pub enum StopImage<'a> {
    /// The raw image (an EXR, `--denoise off`).
    Raw,
    /// The denoised image, filtered with these auxiliary images (the PNG preview).
    Denoised(Option<&'a AuxImages>),
}

/// In which measure the stop test judges that image: the output's.
#[derive(Debug, Clone, Copy)]
pub enum Measure<'a> {
    /// The relative RMSE of the linear values (an EXR: scene-referred numbers for tools).
    Linear,
    /// The display RMSE of the picture this transform shows (a PNG, the live view:
    /// [`crate::output::display`]).
    Display(Picture<'a>),
}

impl Measure<'_> {
    /// How the progress line and the summary name an estimate of `what` in this measure.
    pub fn name(&self, what: StopImage) -> &'static str {
        match (self, what) {
            (Measure::Linear, StopImage::Raw) => "rel. error",
            (Measure::Linear, StopImage::Denoised(_)) => "rel. error of the denoised image",
            (Measure::Display(_), StopImage::Raw) => "display error",
            (Measure::Display(_), StopImage::Denoised(_)) => {
                "display error of the denoised picture"
            }
        }
    }
}

/// The error a render's target is compared with, at a checkpoint: the estimate of `what`
/// in `measure` (the module docs' stop test), also left in [`Progress::judged`] (without a
/// target). `None` when there is nothing to compare yet (fewer than [`MIN_STOP_UNITS`](super::budget::MIN_STOP_UNITS)
/// units, or halves of different sizes).
pub fn stop_error(p: &Progress, what: StopImage, measure: Measure) -> Result<Option<f64>> {
    let judged = judge(p, (what, measure), super::budget::MIN_STOP_UNITS)?;
    let e = judged.as_ref().map(|j| j.estimate);
    if let Some(j) = judged {
        let _ = p.judged.set(j);
    }
    Ok(e)
}

/// The estimate of `what` in `measure` from `min_units` units on, and the halves it was
/// measured on when they are not the raw ones.
pub(super) fn judge(
    p: &Progress,
    (what, measure): (StopImage, Measure),
    min_units: u64,
) -> Result<Option<Judged>> {
    if p.samples < min_units.max(super::budget::MIN_STOP_UNITS) {
        return Ok(None);
    }
    let denoised = match what {
        StopImage::Raw => None,
        StopImage::Denoised(aux) => Some(denoised_halves(p.halves, aux)?),
    };
    let (a, b) = denoised.as_ref().map_or(p.halves, |(a, b)| (a, b));
    let name = measure.name(what);
    let (estimate, halves, absolute) = match measure {
        Measure::Linear => {
            let e = relative_rmse(&half_buffer_estimate(a, b)?);
            (e, denoised, false)
        }
        Measure::Display(picture) => {
            let (e, seen) = picture.judge(a, b)?;
            (e, Some(seen), true)
        }
    };
    Ok(Some(Judged {
        halves,
        absolute,
        estimate,
        target: None,
        name,
    }))
}
