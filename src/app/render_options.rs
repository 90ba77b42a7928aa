//! The options of `iris render` ([`RenderOptions`], one field per flag) and their defaults
//! for library callers; what a method counts in units ([`unit_name`]). The job that checks
//! and runs them is [`super::render::RenderJob`].

use super::budget::Budget;
use crate::accel::Backend;
use crate::denoise::DenoiseMode;
use crate::integrator::capability::Units;
use crate::integrator::Method;
use crate::measure::MeasureOptions;
use crate::output::DisplayOptions;
use crate::plan::SpectralMode;
use crate::prepare::drop_in::PreviewOptions;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Everything `iris render` needs.
#[derive(Debug, Clone)]
pub struct RenderOptions {
    /// Scene file.
    pub scene: PathBuf,
    /// Output file (.png or .exr); default `<scene stem>.png` in the current directory.
    pub output: Option<PathBuf>,
    /// Image size; default 800 wide with the camera's aspect (or 4:3).
    pub size: Option<(u32, u32)>,
    /// Samples per pixel.
    pub spp: u32,
    /// Rendering method.
    pub method: Method,
    /// Recursion depth limit.
    pub max_depth: u32,
    /// `--time`: stop after the round (SPPM: pass) that crosses this wall time (every method;
    /// at least one sample or pass).
    pub time_limit: Option<Duration>,
    /// `--checkpoint K`: write the image at the checkpoints (1, 2, 4, … samples or passes)
    /// that come at least K samples (passes) after the last write.
    pub checkpoint: Option<u32>,
    /// Without `--checkpoint`: rewrite the output at the checkpoints, throttled
    /// ([`super::checkpoint_writes::CheckpointWrites`]), so it can be watched; set for an open budget
    /// ([`Budget::open`]).
    pub watch: bool,
    /// Photon-mapping settings (`--photons`, `--radius`, `--alpha`, `--passes`, …).
    pub photon: crate::integrator::PhotonSettings,
    /// Acceleration backend.
    pub accel: Backend,
    /// Seed.
    pub seed: u64,
    /// The numbers driving camera paths (`--sampler`).
    pub sampler: crate::sampler::SamplerKind,
    /// Threads (0 = all), at most [`crate::render::MAX_THREADS`].
    pub threads: usize,
    /// Camera name or index.
    pub camera: Option<String>,
    /// `--camera-look-at`: eye, target and field of view ([`crate::prepare::look_at`]).
    pub look_at: Option<crate::prepare::look_at::LookAt>,
    /// PNG display options.
    pub display: DisplayOptions,
    /// No progress bar.
    pub quiet: bool,
    /// Environment light from `--env`: `None` = flag not given (use the scene file's
    /// `iris_environment`, if any), `Some(None)` = `--env none` (no environment, even if
    /// the file names one), `Some(Some(e))` = use `e` instead of the file's.
    pub env: Option<Option<crate::light::env::Environment>>,
    /// `--fog`: `None` = flag not given (the file's `iris_fog`), `Some(None)` = `--fog
    /// none`, `Some(Some(m))` = fog with medium `m` instead of the file's.
    pub fog: Option<Option<crate::volume::Medium>>,
    /// `--spectral`: spectral transport always, never, or when the scene needs it.
    pub spectral: SpectralMode,
    /// `--polarization`: polarized transport always, never, or when the scene needs it.
    pub polarization: crate::plan::PolarizationMode,
    /// `--polarizer`: a linear polarizer on the camera, degrees from the image horizontal.
    pub polarizer: Option<f32>,
    /// The measuring flags (`--reference`, `--report`, `--plot`, `--target-error`).
    pub measure: MeasureOptions,
    /// The drop-in preview choices (`--studio`, `--ground`, `--view`, `--background`).
    pub preview: PreviewOptions,
    /// `--stone` / `--metal` material overrides, in order ([`crate::prepare::looks`]).
    pub looks: Vec<crate::prepare::looks::LookFlag>,
    /// `--explain`: measure the plan's costs before rendering (a 32×24 probe render each
    /// way and 10 000 photons, [`crate::plan::Plan::measure_costs`]).
    pub explain: bool,
    /// `--denoise auto|on|off` ([`crate::denoise::mode`]).
    pub denoise: DenoiseMode,
    /// `--adaptive auto|on|off` ([`super::adaptive`]).
    pub adaptive: super::adaptive::AdaptiveMode,
    /// A turntable frame (`iris turntable`): the model turned about the vertical axis
    /// ([`crate::prepare::turntable`]); `None` = as the file has it.
    pub spin: Option<crate::prepare::turntable::Spin>,
    /// Also write the final image to this `.exr` (linear; under `--denoise on` with the
    /// denoised layer, as `iris render -o FILE.exr` writes it), after the main output.
    pub exr_copy: Option<PathBuf>,
    /// `--shard I/N`: render only this shard's units and write a partial image
    /// ([`super::shard`]).
    pub shard: Option<super::shard::Shard>,
}

impl RenderOptions {
    /// `iris render SCENE -o OUTPUT --method whitted --spp 4` with every other flag at the
    /// CLI's default (depth 64, no time limit, automatic backend, seed 0, all threads, the
    /// file's first camera and environment, automatic spectral transport, the drop-in
    /// preview's choices).
    ///
    /// The library's default budget is this fixed, quick one, not the CLI's
    /// default: callers (tests, tools, benches) want work bounded
    /// by counts, whose images do not depend on the machine's speed. `iris render`'s
    /// default (auto method, render until the error target or the time limit) is
    /// `RenderOptions::new(..).with_budget(&Budget::default())`.
    pub fn new(scene: &Path, output: Option<&Path>) -> RenderOptions {
        RenderOptions {
            scene: scene.to_path_buf(),
            output: output.map(Path::to_path_buf),
            size: None,
            spp: 4,
            method: Method::Whitted,
            max_depth: 64,
            time_limit: None,
            checkpoint: None,
            watch: false,
            photon: crate::integrator::PhotonSettings::default(),
            accel: Backend::Auto,
            seed: 0,
            sampler: Default::default(),
            threads: 0,
            camera: None,
            look_at: None,
            display: DisplayOptions::default(),
            quiet: false,
            env: None,
            fog: None,
            spectral: SpectralMode::Auto,
            polarization: crate::plan::PolarizationMode::Auto,
            polarizer: None,
            measure: MeasureOptions::default(),
            preview: PreviewOptions::default(),
            looks: Vec::new(),
            explain: false,
            denoise: DenoiseMode::Auto,
            adaptive: Default::default(),
            spin: None,
            exr_copy: None,
            shard: None,
        }
    }

    /// These options with `budget`'s method, counts, time limit and error target, watched
    /// when the budget is open ([`super::budget`]).
    pub fn with_budget(mut self, budget: &Budget) -> RenderOptions {
        self.method = budget.method;
        self.spp = budget.spp;
        self.photon.passes = budget.passes;
        self.time_limit = budget.time_limit;
        self.measure.target_error = budget.target_error;
        self.measure.default_target = budget.default_target;
        self.watch = budget.open;
        self
    }

    /// The error target of a render writing `output`: `--target-error`, or for the default
    /// budget the default of the output's measure (a PNG's display error, an EXR's
    /// relative error: [`super::budget::DEFAULT_DISPLAY_TARGET`], [`super::budget::DEFAULT_TARGET`]).
    pub fn target_error(&self, output: &std::path::Path) -> Option<f64> {
        if self.measure.default_target {
            let display = crate::output::is_display_referred(output);
            Some(super::budget::default_target(display))
        } else {
            self.measure.target_error
        }
    }

    /// The scene preparation these options (with their drop-in preview choices) ask for;
    /// `reference_size` is the `--reference` image's size, used when `--size` is not given.
    pub fn prepare_options(
        &self,
        reference_size: Option<(u32, u32)>,
    ) -> crate::prepare::PrepareOptions {
        crate::prepare::PrepareOptions {
            accel: self.accel,
            env: self.env.clone(),
            fog: self.fog,
            camera: self.camera.clone(),
            look_at: self.look_at,
            size: self.size.or(reference_size),
            preview: self.preview,
            looks: self.looks.clone(),
            spin: self.spin,
            subject: false,
        }
    }

    /// Checks the outputs before any work ([`crate::fileio::output`]): `output` (the image,
    /// when one is written), `--exr-copy`, `--report` and `--plot` are writable, no two name
    /// one file, and none is the scene or the `--reference`.
    pub(super) fn check_outputs(&self, output: Option<&Path>) -> crate::error::Result<()> {
        use crate::fileio::output::{check_distinct, check_file};
        let mut outputs: Vec<(&str, &Path)> = output.map(|o| ("-o", o)).into_iter().collect();
        outputs.extend(self.exr_copy.as_deref().map(|p| ("--exr-copy", p)));
        outputs.extend(self.measure.report.as_deref().map(|p| ("--report", p)));
        outputs.extend(self.measure.plot.as_deref().map(|p| ("--plot", p)));
        for (_, path) in &outputs {
            check_file(path)?;
        }
        let mut inputs = vec![("scene", self.scene.as_path())];
        inputs.extend(
            self.measure
                .reference
                .as_deref()
                .map(|p| ("--reference", p)),
        );
        check_distinct(&outputs, &inputs)
    }

    /// The most units `method` takes ([`Units`]): samples per pixel, or passes.
    pub(super) fn units(&self, method: Method) -> u32 {
        match method.caps().units {
            Units::Passes => self.photon.passes,
            Units::Samples => self.spp,
        }
    }
}

/// "samples" or "passes": what `method` counts in units.
pub fn unit_name(method: Method) -> &'static str {
    method.caps().units.name()
}
