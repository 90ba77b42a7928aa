//! The bridge from the renderer's observer to the measuring recorder: a [`Recorder`]
//! observes a progressive render's checkpoints ([`Progress`]) and lets it run on
//! ([`crate::measure`] knows nothing of the renderer's control flow).

use crate::error::Result;
use crate::measure::{Progress, Recorder};
use crate::render::Control;

impl Recorder<'_> {
    /// Records a render checkpoint ([`Recorder::record`]); always [`Control::Continue`]
    /// (`iris converge` runs each method for its whole time).
    pub fn observe(&mut self, p: &Progress) -> Result<Control> {
        self.record(p)?;
        Ok(Control::Continue)
    }
}
