//! What a caller of [`super::RenderJob::run_with`] adds to an `iris render` run
//! ([`RunHooks`]): whether the image is written, a progress observer, and the render's own
//! stop request.

/// What a caller of [`super::RenderJob::run_with`] adds to a render.
pub struct RunHooks<'h> {
    /// Write the output image (and checkpoints, an `--exr-copy`, a shard's partial image);
    /// `false` keeps the image in memory only.
    pub write_image: bool,
    /// Called at every checkpoint (1, 2, 4, … units and the end) with the image so far;
    /// `false` stops the render there.
    pub progress: Option<&'h mut (dyn FnMut(&crate::render::Progress) -> bool + Send)>,
    /// The render's own stop request ([`crate::render::guard::Cancel`]; the default is never
    /// set): once cancelled, the render skips its remaining tiles and returns what it has
    /// (ended as [`crate::render::EndReason::Interrupted`]; an image cancelled before its
    /// first checkpoint may miss tiles). For a caller that stops the render from another
    /// thread, as the Python module does on Ctrl-C.
    pub cancel: crate::render::guard::Cancel,
}
