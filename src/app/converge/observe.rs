//! The bridge from the renderer's progress reports to the measuring recorder: a
//! [`Recorder`] observes [`render_progressive`](crate::render::render_progressive)'s
//! checkpoints ([`Progress`], passed on field for field as a [`Checkpoint`]) and answers
//! [`Control::Stop`] once the target error is reached. Kept here so that
//! [`crate::measure`] does not depend on the renderer.

use crate::error::Result;
use crate::measure::{Checkpoint, Recorder};
use crate::render::{Control, Progress};

impl Recorder<'_> {
    /// Records a render checkpoint ([`Recorder::record`]); [`Control::Stop`] when the
    /// target error is reached, [`Control::Continue`] otherwise.
    pub fn observe(&mut self, p: &Progress) -> Result<Control> {
        let checkpoint = Checkpoint {
            image: p.image,
            halves: p.halves,
            elapsed: p.elapsed,
            samples: p.samples,
            passes: p.passes,
            rays: p.rays,
            photons: p.photons,
            done: p.done,
        };
        Ok(if self.record(&checkpoint)? {
            Control::Stop
        } else {
            Control::Continue
        })
    }
}
