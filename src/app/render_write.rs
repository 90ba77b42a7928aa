//! The image outputs of `iris render` ([`RenderJob`]): the coverage a background needs,
//! the image and its checkpoints written with the render's display options, `--exr-copy`,
//! and the transform a PNG's picture is judged through ([`crate::output::display`]).

use super::render::RenderJob;
use super::render_denoise::RenderDenoiser;
use crate::camera::Camera;
use crate::denoise::{DenoiseMode, Denoised};
use crate::error::Result;
use crate::image::{Coverage, ImageRgb};
use crate::output::display::Picture;
use crate::output::{self, Background};
use crate::render::RenderSettings;
use std::path::Path;

impl RenderJob<'_> {
    /// The transform the written file's picture is judged through: `Some` for a
    /// display-referred output (a PNG), `None` for an EXR (judged on its numbers).
    pub(super) fn picture<'c>(&self, coverage: Option<&'c Coverage>) -> Option<Picture<'c>> {
        let opts = self.opts;
        output::is_display_referred(self.output())
            .then(|| Picture::new(opts.display, opts.preview.background, coverage))
    }

    /// Writes the final image: the output (denoised as the output is) and `--exr-copy`.
    pub(super) fn write_final(
        &self,
        image: &ImageRgb,
        denoised: Option<&Denoised>,
        denoiser: &RenderDenoiser,
        coverage: Option<&Coverage>,
    ) -> Result<()> {
        let (main, layer) = denoiser.layout(image, denoised.map(|d| &d.image));
        self.write_image(self.output(), main, layer, coverage)?;
        self.write_exr_copy(image, denoised, coverage)
    }

    /// `--background`: the coverage of the camera samples (as many as the render will take
    /// at most, up to the pass's cap), computed once before rendering; `None` for the
    /// environment background.
    pub(super) fn coverage(
        &self,
        camera: &Camera,
        settings: &RenderSettings,
    ) -> Result<Option<Coverage>> {
        if self.opts.preview.background == Background::Environment {
            return Ok(None);
        }
        let units = u64::from(self.opts.units(self.plan.method));
        let scene = &self.prepared.scene;
        Ok(Some(crate::render::thread_pool(settings)?.install(|| {
            crate::render::coverage::coverage(scene, camera, settings, units)
        })))
    }

    /// Writes `img` (with the extra EXR `layer`, if any) to `path` with the render's
    /// background and display options.
    pub(super) fn write_image(
        &self,
        path: &Path,
        img: &ImageRgb,
        layer: Option<(&str, &ImageRgb)>,
        coverage: Option<&Coverage>,
    ) -> Result<()> {
        let opts = self.opts;
        output::write_image_with_layer(
            path,
            img,
            layer,
            coverage,
            opts.preview.background,
            &opts.display,
        )
    }

    /// `--exr-copy`: the final image again as EXR, with the denoised layer under
    /// `--denoise on`.
    fn write_exr_copy(
        &self,
        image: &ImageRgb,
        denoised: Option<&Denoised>,
        coverage: Option<&Coverage>,
    ) -> Result<()> {
        let Some(exr) = &self.opts.exr_copy else {
            return Ok(());
        };
        let layer = denoised
            .filter(|_| self.opts.denoise == DenoiseMode::On)
            .map(|d| (crate::denoise::EXR_LAYER, &d.image));
        self.write_image(exr, image, layer, coverage)
    }
}
