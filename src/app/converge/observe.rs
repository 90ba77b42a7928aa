//! The bridge from the renderer's observer to the measuring recorder: a [`Recorder`]
//! observes a progressive render's checkpoints ([`Progress`]) and lets it run on
//! ([`crate::measure`] knows nothing of the renderer's control flow).

use crate::error::Result;
use crate::measure::Recorder;
use crate::render::Control;
use crate::render::Progress;

impl Recorder<'_> {
    /// Records a render checkpoint ([`Recorder::record`]); always [`Control::Continue`]
    /// (`iris converge` runs each method for its whole time).
    pub fn observe(&mut self, p: &Progress) -> Result<Control> {
        self.record(p)?;
        Ok(Control::Continue)
    }

    /// [`Recorder::observe`] with the checkpoint's denoised image and its denoising time
    /// ([`Recorder::record_denoised`]); always [`Control::Continue`].
    pub fn observe_denoised(
        &mut self,
        p: &Progress,
        denoised: Option<(&crate::image::ImageRgb, std::time::Duration)>,
    ) -> Result<Control> {
        self.record_denoised(p, denoised)?;
        Ok(Control::Continue)
    }
}
