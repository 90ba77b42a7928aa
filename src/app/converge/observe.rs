//! The bridge from the renderer's observer to the measuring recorder: a [`Recorder`]
//! observes a progressive render's checkpoints ([`Progress`]) and answers
//! [`Control::Stop`] once the target error is reached ([`crate::measure`] knows nothing of
//! the renderer's control flow).

use crate::error::Result;
use crate::measure::{Progress, Recorder};
use crate::render::Control;

impl Recorder<'_> {
    /// Records a render checkpoint ([`Recorder::record`]); [`Control::Stop`] when the
    /// target error is reached, [`Control::Continue`] otherwise.
    pub fn observe(&mut self, p: &Progress) -> Result<Control> {
        Ok(if self.record(p)? {
            Control::Stop
        } else {
            Control::Continue
        })
    }

    /// [`Recorder::observe`] with the checkpoint's denoised image and its denoising time
    /// ([`Recorder::record_denoised`]).
    pub fn observe_denoised(
        &mut self,
        p: &Progress,
        denoised: Option<(&crate::output::ImageRgb, std::time::Duration)>,
    ) -> Result<Control> {
        Ok(if self.record_denoised(p, denoised)? {
            Control::Stop
        } else {
            Control::Continue
        })
    }
}
