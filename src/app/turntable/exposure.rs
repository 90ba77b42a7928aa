//! One exposure for the whole turn. `--exposure auto` scales each image's log-average
//! luminance to 0.18 ([`crate::output::tonemap`]); decided per frame, the whole picture
//! (background and floor included) would pump as the stone turns. Measured on a bare
//! round diamond under the jeweller studio (120×90, 8 spp, 12 frames 30° apart): the
//! per-frame choice varied by 0.07 EV (5 % brightness) on the denoised frames, 0.11 EV
//! raw, with the facets' period; with `--background transparent` (exposure measured on
//! the stone alone) an oval ruby's choice at 0° and at 90° differed by 2.7 EV. A gem video
//! is shot with a locked exposure, so a turntable locks it too.
//!
//! Frames are independent jobs, so the locked value must come from the scene alone, the
//! same in every job: the log-average (the one `--exposure auto` takes, over the pixels it
//! measures for the `--background`, [`crate::output::background::exposure_pixels`]) of
//! [`PROBES`] probe renders of the model turned by 0°, 90°, 180° and 270° (whatever
//! `--frames` is), each at most [`PROBE_WIDTH`] pixels wide at the frames' aspect, with the
//! frames' method, seed and sampler and at most [`PROBE_SAMPLES`] samples per pixel (SPPM:
//! passes), denoised when the build has the denoiser (whatever `--denoise` says for the
//! frames): a noisy image's log-average is biased low, its dark samples weighing more in
//! the log (the diamond's raw 8-spp frames: −5.52 EV on average, denoised −6.11; the
//! locked value: −6.11). An explicit `--exposure EV` is used as given. The linear EXR
//! frames do not depend on exposure at all.

use super::TurntableOptions;
use crate::camera::Camera;
use crate::denoise::aux;
use crate::error::Result;
use crate::image::ImageRgb;
use crate::integrator::{Integrator, Method};
use crate::output::background::exposure_pixels;
use crate::output::tonemap::exposure_scale;
use crate::output::{Background, Exposure};
use crate::prepare::turntable::Spin;
use crate::render::RenderSettings;

/// Probe renders: the model at quarter turns.
pub const PROBES: u32 = 4;
/// Largest probe width in pixels (narrower frames are probed at their own size).
pub const PROBE_WIDTH: u32 = 160;
/// Samples per pixel (SPPM: passes) of each probe, at most the frames' own.
pub const PROBE_SAMPLES: u32 = 16;

/// The exposure every frame uses: the flag's EV, or for `--exposure auto` the locked EV
/// (module docs) with the note that says how it was found. `method` is the frames'
/// (resolved) method.
pub fn locked(opts: &TurntableOptions, method: Method) -> Result<(Exposure, Option<String>)> {
    let r = &opts.render;
    if let Exposure::Ev(e) = r.display.exposure {
        return Ok((Exposure::Ev(e), None));
    }
    // Denoised when the build can: a noisy image's log-average is biased low (its dark
    // samples weigh more in the log), which would lock the exposure too bright.
    let denoise = crate::denoise::available();
    let mut pixels = Vec::new();
    let mut probe_size = (0, 0);
    for quarter in 0..PROBES {
        let mut prep = r.prepare_options(None);
        prep.spin = Some(Spin::new(quarter, PROBES)?);
        let p = crate::prepare::prepare(&r.scene, &prep)?;
        let (w, h) = p.size;
        let pw = w.min(PROBE_WIDTH);
        let ph = ((f64::from(h) * f64::from(pw) / f64::from(w)).round() as u32).max(1);
        probe_size = (pw, ph);
        let units = r.units(method).min(PROBE_SAMPLES);
        let mut photon = r.photon;
        photon.passes = units;
        let settings = RenderSettings {
            width: pw,
            height: ph,
            spp: units,
            seed: r.seed,
            sampler: r.sampler,
            threads: r.threads,
            quiet: true,
            spectral: crate::plan::Plan::new(&p.scene, &p.camera.projection, method, r.spectral)
                .spectral,
            time_limit: None,
            adaptive: None,
            cancel: Default::default(),
            kernel: Default::default(),
        };
        let camera = Camera::new(&p.camera, pw, ph);
        let integrator = Integrator::new(method, r.max_depth, &photon)?;
        let (image, _) = integrator.render_progressive(&p.scene, &camera, &settings, None)?;
        let image = if denoise {
            let pool = crate::render::thread_pool(&settings)?;
            let rays = aux::aux_samples(settings.spp);
            let aux = pool.install(|| aux::aux_pass(&p.scene, &camera, &settings, rays));
            crate::denoise::denoise(&image, Some(&aux))?.image
        } else {
            image
        };
        let bg = r.preview.background;
        let coverage = (bg != Background::Environment)
            .then(|| -> Result<_> {
                Ok(crate::render::thread_pool(&settings)?.install(|| {
                    crate::render::coverage::coverage(
                        &p.scene,
                        &camera,
                        &settings,
                        u64::from(units),
                    )
                }))
            })
            .transpose()?;
        pixels.extend(exposure_pixels(&image, coverage.as_ref(), bg));
    }
    let all = ImageRgb {
        width: pixels.len() as u32,
        height: 1,
        data: pixels,
    };
    let ev = exposure_scale(&all, Exposure::Auto).log2();
    let note = format!(
        "exposure locked for the whole turn at {ev:+.2} EV (--exposure auto: the log-average \
         luminance of {PROBES} probe renders at 0°, 90°, 180° and 270°, {}x{}{}; --exposure \
         EV sets it)",
        probe_size.0,
        probe_size.1,
        if denoise { ", denoised" } else { "" }
    );
    Ok((Exposure::Ev(ev), Some(note)))
}
