//! The renders of a gem report ([`Shot`]): which instrument, tilt and wavelength each is,
//! and how one is rendered: on the gem stage ([`crate::prepare::stage`]) through the one
//! render job ([`crate::app::RenderJob::with_prepared`]), Whitted ray tracing in RGB
//! transport (every Fresnel branch followed, so the images are exact fractions of the
//! instruments' radiance, with no sampling noise but the pixel jitter), no denoising, no
//! adaptive sampling: the same file and flags give the same bytes.
//!
//! Images are linear RGB, square, the stage's field; the coverage (the fraction of a
//! pixel's camera samples that hit the stone, [`crate::render::coverage`]) is computed
//! once per tilt with the same samples.
//!
//! A birefringent stone ([`GemStage::birefringent`]) is rendered once per mode, each as the
//! isotropic stone of that mode's index ([`crate::prepare::stage`]'s module docs), and a
//! shot's image is the mean of the two: each mode carries half of the unpolarized light.

use crate::app::{RenderJob, RenderOptions, RunHooks};
use crate::error::Result;
use crate::image::{Coverage, ImageRgb};
use crate::integrator::Method;
use crate::light::env::Environment;
use crate::plan::SpectralMode;
use crate::polar::crystal::Which;
use crate::prepare::stage::{GemStage, ShotSetup};
use crate::spectrum::ior::{LAMBDA_C, LAMBDA_D, LAMBDA_F};
use crate::studio::instrument::Instrument;
use std::time::Duration;

/// Samples per pixel of the direction-code renders: one ray through each pixel centre, so
/// each pixel shows the exit directions of one point of the stone (no jitter mixing two
/// virtual facets).
pub const CODE_SPP: u32 = 1;

/// One render of the report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shot {
    /// The lighting.
    pub instrument: Instrument,
    /// Tilt about the image's horizontal axis, degrees.
    pub tilt: f32,
    /// The wavelength whose index the stone takes, nm.
    pub lambda_nm: f32,
}

impl Shot {
    /// A label for progress lines: `ASET, tilt 10°`, `spot dome at 486 nm`.
    pub fn label(&self) -> String {
        let mut s = self.instrument.name().to_string();
        if self.tilt != 0.0 {
            s += &format!(", tilt {}°", self.tilt);
        }
        if self.lambda_nm != LAMBDA_D {
            s += &format!(" at {:.0} nm", self.lambda_nm);
        }
        s
    }

    /// Samples per pixel of this shot given the report's `--spp`.
    pub fn spp(&self, spp: u32) -> u32 {
        match self.instrument {
            Instrument::Directions => CODE_SPP,
            _ => spp,
        }
    }
}

/// The report's shots, in render order: for every tilt (the first is the face-up view)
/// ASET then Ideal-Scope; the overcast face-up view; the direction code at the F, d and C
/// lines; the spot dome at the C, d and F lines (the fire picture's red, green and blue).
pub fn shots(tilts: &[f32]) -> Vec<Shot> {
    let at = |instrument, tilt, lambda_nm| Shot {
        instrument,
        tilt,
        lambda_nm,
    };
    let mut list = Vec::new();
    for &t in tilts {
        list.push(at(Instrument::Aset, t, LAMBDA_D));
        list.push(at(Instrument::IdealScope, t, LAMBDA_D));
    }
    list.push(at(Instrument::Overcast, 0.0, LAMBDA_D));
    for l in [LAMBDA_F, LAMBDA_D, LAMBDA_C] {
        list.push(at(Instrument::Directions, 0.0, l));
    }
    for l in [LAMBDA_C, LAMBDA_D, LAMBDA_F] {
        list.push(at(Instrument::Spots, 0.0, l));
    }
    list
}

/// How every shot is rendered.
#[derive(Debug, Clone)]
pub struct Settings {
    /// Image side, pixels.
    pub size: u32,
    /// Samples per pixel (the direction code takes [`CODE_SPP`]).
    pub spp: u32,
    /// Time limit per render, if any.
    pub time_limit: Option<Duration>,
    /// Worker threads (0 = all).
    pub threads: usize,
    /// Seed.
    pub seed: u64,
    /// Intersection backend.
    pub accel: crate::accel::Backend,
}

/// A rendered shot.
pub struct Rendered {
    /// The linear image.
    pub image: ImageRgb,
    /// Samples per pixel actually taken (fewer than asked when the time limit cut it).
    pub spp: u64,
    /// Render time.
    pub time: Duration,
    /// Whether a stop request (Ctrl-C) cut it short.
    pub interrupted: bool,
}

/// The render options of a shot (the file names the render; the stage is the scene).
fn options(stage_file: &std::path::Path, s: &Settings, spp: u32) -> RenderOptions {
    let mut o = RenderOptions::new(stage_file, None);
    o.size = Some((s.size, s.size));
    o.spp = spp;
    o.method = Method::Whitted;
    o.spectral = SpectralMode::Off;
    o.denoise = crate::denoise::DenoiseMode::Off;
    o.adaptive = crate::app::adaptive::AdaptiveMode::Off;
    o.quiet = true;
    o.threads = s.threads;
    o.seed = s.seed;
    o.accel = s.accel;
    o.time_limit = s.time_limit;
    o
}

/// Renders `shot` of `stage` under the already built `environment` (the shot's
/// instrument's): the mean of its two modes' images for a birefringent stone (module
/// docs), with their summed time.
pub fn render(
    stage: &GemStage,
    file: &std::path::Path,
    shot: &Shot,
    environment: &Environment,
    s: &Settings,
) -> Result<Rendered> {
    let first = render_mode(stage, file, shot, environment, s, Which::Fast)?;
    if !stage.birefringent || first.interrupted {
        return Ok(first);
    }
    let second = render_mode(stage, file, shot, environment, s, Which::Slow)?;
    let image = ImageRgb {
        data: first
            .image
            .data
            .iter()
            .zip(&second.image.data)
            .map(|(a, b)| 0.5 * (*a + *b))
            .collect(),
        ..first.image
    };
    Ok(Rendered {
        image,
        spp: first.spp.min(second.spp),
        time: first.time + second.time,
        interrupted: second.interrupted,
    })
}

/// Renders `shot` with the stone showing `mode` ([`ShotSetup::mode`]).
fn render_mode(
    stage: &GemStage,
    file: &std::path::Path,
    shot: &Shot,
    environment: &Environment,
    s: &Settings,
    mode: Which,
) -> Result<Rendered> {
    let setup = ShotSetup {
        environment: environment.clone(),
        tilt: shot.tilt,
        lambda_nm: shot.lambda_nm,
        size: s.size,
        grey_body: shot.instrument.codes_by_channel(),
        mode,
    };
    let prepared = stage.prepare(&setup, s.accel)?;
    let opts = options(file, s, shot.spp(s.spp));
    let summary = RenderJob::with_prepared(&opts, prepared)?.run_with(RunHooks {
        write_image: false,
        progress: None,
        cancel: Default::default(),
    })?;
    let pixels = u64::from(s.size) * u64::from(s.size);
    Ok(Rendered {
        spp: summary.stats.samples / pixels.max(1),
        time: summary.stats.time,
        interrupted: summary.stats.interrupted(),
        image: summary.image,
    })
}

/// The coverage of the stone at `tilt` with the report's camera samples.
pub fn coverage(
    stage: &GemStage,
    file: &std::path::Path,
    tilt: f32,
    s: &Settings,
) -> Result<Coverage> {
    let setup = ShotSetup {
        environment: Environment::Uniform {
            radiance: glam::Vec3::ZERO,
        },
        tilt,
        lambda_nm: LAMBDA_D,
        size: s.size,
        grey_body: false,
        mode: Which::Fast,
    };
    let prepared = stage.prepare(&setup, s.accel)?;
    let opts = options(file, s, s.spp);
    let job = RenderJob::with_prepared(&opts, prepared)?;
    let settings = job.settings();
    let camera = crate::camera::Camera::new(&job.prepared.camera, s.size, s.size);
    let scene = &job.prepared.scene;
    Ok(crate::render::thread_pool(&settings)?
        .install(|| crate::render::coverage::coverage(scene, &camera, &settings, u64::from(s.spp))))
}
