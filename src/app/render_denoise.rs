//! The denoising side of `iris render` (`--denoise`, [`crate::denoise`]): the auxiliary
//! pass, run once before rendering at the render's size and sample positions; the denoised
//! image at the checkpoints that need one (a `--checkpoint` write, or every checkpoint with
//! `--reference`, for the report's denoised error), the last one kept so the final write
//! reuses it when the render ended on that image; what the written file holds; the note.
//! Images are linear RGB; times are wall-clock.

use super::budget::StopImage;
use crate::camera::Camera;
use crate::denoise::{aux, AuxImages, DenoiseChoice, Denoised, EXR_LAYER};
use crate::error::Result;
use crate::image::ImageRgb;
use crate::render::RenderSettings;
use crate::scene::Scene;
use std::time::{Duration, Instant};

/// The denoiser of one render.
pub(super) struct RenderDenoiser<'a> {
    choice: &'a DenoiseChoice,
    /// The auxiliary images, the pass's time and its rays per pixel (when denoising).
    aux: Option<(AuxImages, Duration, u64)>,
    /// The last image denoised: (the raw image, the result).
    last: Option<(ImageRgb, Denoised)>,
}

impl<'a> RenderDenoiser<'a> {
    /// Runs the auxiliary pass (on a worker pool for `settings`) when `choice` denoises.
    pub(super) fn new(
        choice: &'a DenoiseChoice,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
    ) -> Result<Self> {
        let aux = choice
            .runs()
            .then(|| -> Result<_> {
                let start = Instant::now();
                let rays = aux::aux_samples(settings.spp);
                let pool = crate::render::thread_pool(settings)?;
                let images = pool.install(|| aux::aux_pass(scene, camera, settings, rays));
                Ok((images, start.elapsed(), rays))
            })
            .transpose()?;
        Ok(RenderDenoiser {
            choice,
            aux,
            last: None,
        })
    }

    /// Whether this render denoises.
    pub(super) fn runs(&self) -> bool {
        self.choice.runs()
    }

    /// The image the stop test estimates ([`StopImage`]): the denoised one when the written
    /// image is denoised (a PNG), else the raw one (an EXR keeps its raw main image).
    pub(super) fn stop_image(&self) -> StopImage<'_> {
        if self.choice.image {
            StopImage::Denoised(self.aux.as_ref().map(|a| &a.0))
        } else {
            StopImage::Raw
        }
    }

    /// The denoised image's stop test ([`StopImage::Denoised`]) with this render's
    /// auxiliary images, whatever the written file holds (the live view shows the
    /// denoised picture).
    pub(super) fn denoised_stop(&self) -> StopImage<'_> {
        StopImage::Denoised(self.aux.as_ref().map(|a| &a.0))
    }

    /// Denoises `image` when `needed` and the render denoises, keeping the result.
    pub(super) fn checkpoint(
        &mut self,
        image: &ImageRgb,
        needed: bool,
    ) -> Result<Option<&Denoised>> {
        if !(needed && self.runs()) {
            return Ok(None);
        }
        let d = crate::denoise::denoise(image, self.aux.as_ref().map(|a| &a.0))?;
        self.last = Some((image.clone(), d));
        Ok(self.last.as_ref().map(|(_, d)| d))
    }

    /// The final image denoised (the last checkpoint's result when it is that image).
    pub(super) fn finish(&mut self, image: &ImageRgb) -> Result<Option<Denoised>> {
        match self.last.take() {
            Some((raw, d)) if raw == *image => Ok(Some(d)),
            _ => Ok(self.checkpoint(image, true)?.cloned()),
        }
    }

    /// What the output file holds: the main image and the extra EXR layer, from the raw
    /// image and its denoised version (the PNG shows the denoised image; an EXR keeps the
    /// raw one and, under `--denoise on`, adds the denoised one as [`EXR_LAYER`]).
    pub(super) fn layout<'i>(
        &self,
        raw: &'i ImageRgb,
        denoised: Option<&'i ImageRgb>,
    ) -> (&'i ImageRgb, Option<(&'static str, &'i ImageRgb)>) {
        match denoised {
            Some(d) if self.choice.exr_layer => (raw, Some((EXR_LAYER, d))),
            Some(d) => (d, None),
            None => (raw, None),
        }
    }

    /// The summary note for the final denoised image `d`.
    pub(super) fn note(&self, d: &Denoised) -> Option<String> {
        let (_, aux_time, rays) = self.aux.as_ref()?;
        let what = if self.choice.exr_layer {
            format!("EXR layer `{EXR_LAYER}`, --denoise on")
        } else {
            "PNG preview; --denoise off for the raw image".to_string()
        };
        let bad = if d.non_finite > 0 {
            format!(
                "; {} non-finite pixels set to 0 before filtering",
                d.non_finite
            )
        } else {
            String::new()
        };
        Some(format!(
            "denoised with Open Image Denoise ({what}): auxiliary pass {rays} rays/pixel \
             {:.2} s, filter {:.2} s{bad}",
            aux_time.as_secs_f64(),
            d.time.as_secs_f64()
        ))
    }
}
