//! `iris render` as a library call: the options ([`RenderOptions`], every flag), the job
//! between plan and render ([`RenderJob`]: flags checked, scene prepared, plan made), and
//! the summary ([`RenderSummary`], in [`super::summary`]). Images are linear RGB until written; times are
//! wall-clock.
//!
//! Denoising (`--denoise`, [`crate::denoise::mode`]): when the plan's `denoise` stage is
//! used, the auxiliary pass runs once before rendering, and every write (checkpoints
//! included) denoises the image then: the PNG shows the denoised image, an EXR under
//! `--denoise on` gets it as an extra layer. With `--reference` every checkpoint is
//! denoised so its report row has the denoised error too.

use super::budget::{Budget, CheckpointWrites, TargetStop};
use super::render_denoise::RenderDenoiser;
pub use super::summary::RenderSummary;
use crate::accel::Backend;
use crate::camera::Camera;
use crate::denoise::{DenoiseChoice, DenoiseMode};
use crate::error::Result;
use crate::image::ImageRgb;
use crate::integrator::{Integrator, Method};
use crate::measure::{MeasureOptions, Recorder};
use crate::output::{self, Background, DisplayOptions};
use crate::plan::SpectralMode;
use crate::prepare::input::check_size;
use crate::preview::PreviewOptions;
use crate::render::{Control, Progress, RenderSettings};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

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
    /// ([`super::budget::CheckpointWrites`]), so it can be watched; set for an open budget
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
    /// PNG display options.
    pub display: DisplayOptions,
    /// No progress bar.
    pub quiet: bool,
    /// Environment light from `--env`: `None` = flag not given (use the scene file's
    /// `iris_environment`, if any), `Some(None)` = `--env none` (no environment, even if
    /// the file names one), `Some(Some(e))` = use `e` instead of the file's.
    pub env: Option<Option<crate::light::env::Environment>>,
    /// `--spectral`: spectral transport always, never, or when the scene needs it.
    pub spectral: SpectralMode,
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
    /// The library's default budget is this fixed, quick one (the CLI's default before
    /// issue 18), not the CLI's default: callers (tests, tools, benches) want work bounded
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
            display: DisplayOptions::default(),
            quiet: false,
            env: None,
            spectral: SpectralMode::Auto,
            measure: MeasureOptions::default(),
            preview: PreviewOptions::default(),
            looks: Vec::new(),
            explain: false,
            denoise: DenoiseMode::Auto,
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
        self.watch = budget.open;
        self
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
            camera: self.camera.clone(),
            size: self.size.or(reference_size),
            preview: self.preview,
            looks: self.looks.clone(),
            spin: self.spin,
        }
    }

    /// The most units `method` takes: samples per pixel, or passes for SPPM.
    fn units(&self, method: Method) -> u32 {
        if method == Method::Sppm {
            self.photon.passes
        } else {
            self.spp
        }
    }
}

/// "samples" or "passes": what `method` counts in units.
pub fn unit_name(method: Method) -> &'static str {
    if method == Method::Sppm {
        "passes"
    } else {
        "samples"
    }
}

/// `iris render`: every flag is checked (sizes, bounds, extensions, the reference's file
/// and size) before rendering; the image, then the CSV, then the plot are written, each
/// atomically. The same as [`RenderJob::new`] then [`RenderJob::run`].
pub fn render_command(opts: &RenderOptions) -> Result<RenderSummary> {
    RenderJob::new(opts)?.run()
}

/// An `iris render` between its plan and its render: the options checked, the scene
/// prepared ([`crate::prepare::prepare`]) and the plan made (with costs under
/// `--explain`), so a caller can show the plan before the render starts.
pub struct RenderJob<'a> {
    opts: &'a RenderOptions,
    output: PathBuf,
    reference: Option<ImageRgb>,
    prepared: crate::prepare::Prepared,
    denoise: DenoiseChoice,
    /// The render plan (method and transport resolved; its last stage is `denoise`).
    pub plan: crate::plan::Plan,
}

impl<'a> RenderJob<'a> {
    /// Checks every flag, prepares the scene and makes the plan.
    pub fn new(opts: &'a RenderOptions) -> Result<RenderJob<'a>> {
        if let Some((w, h)) = opts.size {
            check_size(w, h)?;
        }
        crate::render::check_threads(opts.threads)?;
        crate::integrator::check_depth(opts.max_depth)?;
        opts.photon.check()?;
        let output = match &opts.output {
            Some(o) => o.clone(),
            None => {
                let stem = opts
                    .scene
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned());
                PathBuf::from(format!("{}.png", stem.unwrap_or_else(|| "render".into())))
            }
        };
        output::check_extension(&output)?;
        if let Some(exr) = &opts.exr_copy {
            output::check_extension(exr)?;
        }
        super::shard::check_flags(opts, &output)?;
        let denoise = crate::denoise::mode::choose(opts.denoise, &output)?;
        let measure = &opts.measure;
        measure.check_flags()?;
        let reference = measure
            .reference
            .as_deref()
            .map(crate::measure::read_reference_file)
            .transpose()?;
        let prepared = crate::prepare::prepare(
            &opts.scene,
            &opts.prepare_options(reference.as_ref().map(|r| (r.width, r.height))),
        )?;
        let (w, h) = prepared.size;
        if let (Some(r), Some(path)) = (&reference, &measure.reference) {
            crate::measure::check_reference_size(
                r,
                path,
                w,
                h,
                &format!("the render of {}", opts.scene.display()),
            )?;
        }
        let mut plan = crate::plan::Plan::new(&prepared.scene, opts.method, opts.spectral);
        plan.stages.push(denoise.stage());
        if opts.explain {
            plan.add_file_counts(&opts.scene);
            let (pw, ph) = crate::plan::PROBE_SIZE;
            let probe = Camera::new(&prepared.camera, pw, ph);
            plan.measure_costs(&prepared.scene, &probe, opts.threads)?;
        }
        crate::integrator::check_memory(w, h, plan.method)?;
        measure.check_checkpoints(opts.units(plan.method))?;
        if let Some(shard) = opts.shard {
            shard.range(u64::from(opts.units(plan.method)), unit_name(plan.method))?;
        }
        Ok(RenderJob {
            opts,
            output,
            reference,
            prepared,
            denoise,
            plan,
        })
    }

    /// Renders through the plan's integrator, writing checkpoints (`--checkpoint`) and the
    /// image, then the measuring outputs; returns the summary.
    pub fn run(self) -> Result<RenderSummary> {
        let RenderJob {
            opts,
            output,
            reference,
            prepared,
            denoise,
            plan,
        } = self;
        let (scene, (w, h)) = (&prepared.scene, prepared.size);
        let camera = Camera::new(&prepared.camera, w, h);
        let method = plan.method;
        let integrator = Integrator::new(method, opts.max_depth, &opts.photon)?;
        let settings = RenderSettings {
            width: w,
            height: h,
            spp: opts.spp,
            seed: opts.seed,
            sampler: opts.sampler,
            threads: opts.threads,
            quiet: opts.quiet,
            spectral: plan.spectral,
            time_limit: opts.time_limit,
        };
        let (measure, preview) = (&opts.measure, &opts.preview);
        let run = method.name();
        // `--shard`: the units to take and the render's identity, before rendering.
        let total = integrator.total_units(&settings);
        let shard = opts
            .shard
            .map(|s| -> Result<_> {
                let range = s.range(total, unit_name(method))?;
                let identity = super::shard_id::identity(
                    opts,
                    scene,
                    &prepared.camera,
                    (w, h),
                    (method, plan.spectral),
                    (total < crate::render::OPEN_UNITS).then_some(total),
                )?;
                Ok((s, range, identity))
            })
            .transpose()?;
        let mut rows =
            crate::measure::report::setup_rows(run, prepared.load_time, scene.accel_build_time);
        let mut recorder = Recorder::new(run, reference.as_ref());
        recorder.verbose = !opts.quiet && measure.any();
        let mut stop = TargetStop::new(measure.target_error);
        let units = u64::from(opts.units(method));
        // `--background`: the coverage of the camera samples (as many as the render will
        // take at most, up to the pass's cap), computed once before rendering.
        let coverage = (preview.background != Background::Environment)
            .then(|| -> Result<_> {
                Ok(crate::render::thread_pool(&settings)?.install(|| {
                    crate::render::coverage::coverage(scene, &camera, &settings, units)
                }))
            })
            .transpose()?;
        // `--denoise`: the auxiliary pass, once, before rendering.
        let mut denoiser = RenderDenoiser::new(&denoise, scene, &camera, &settings)?;
        let write = |img: &ImageRgb, denoised: Option<&ImageRgb>, d: &RenderDenoiser| {
            let (main, layer) = d.layout(img, denoised);
            output::write_image_with_layer(
                &output,
                main,
                layer,
                coverage.as_ref(),
                preview.background,
                &opts.display,
            )
        };
        // `--checkpoint K` (K more units: samples, or SPPM passes, which the driver counts
        // in `Progress::samples`) or watching (an open budget): the image so far. With
        // `--reference` every checkpoint is denoised for the report.
        let mut writes = CheckpointWrites::new(opts.checkpoint, opts.watch && shard.is_none());
        let measure_denoised = reference.is_some();
        let mut observe = |p: &Progress| -> Result<Control> {
            let write_now = writes.due(p, Instant::now());
            let denoised = denoiser
                .checkpoint(p.image, write_now || measure_denoised)?
                .map(|d| (d.image.clone(), d.time));
            if write_now {
                let start = Instant::now();
                write(p.image, denoised.as_ref().map(|d| &d.0), &denoiser)?;
                writes.wrote(p, start.elapsed(), Instant::now());
            }
            recorder.record_denoised(p, denoised.as_ref().map(|(img, t)| (img, *t)))?;
            stop.check(p, denoiser.stop_image())
        };
        let range = shard.as_ref().map(|s| s.1.clone());
        let (film, stats) =
            integrator.render_units(scene, &camera, &settings, range, Some(&mut observe))?;
        let image = film.mean();
        let denoised = denoiser.finish(&image)?;
        let mut shard_note = None;
        if let Some((s, range, identity)) = shard {
            let header = super::shard::ShardHeader::new(
                identity,
                &opts.scene,
                s,
                (range.clone(), film.done()),
                &stats,
            );
            output::partial::write(&output, &header.entries(), &film.exact())?;
            shard_note = Some(format!(
                "shard {s}: {} {}..{} of {} (iris merge adds the shards' partial images)",
                unit_name(method),
                range.start,
                range.end,
                if total < crate::render::OPEN_UNITS {
                    total.to_string()
                } else {
                    "an open budget".into()
                }
            ));
        } else {
            write(&image, denoised.as_ref().map(|d| &d.image), &denoiser)?;
            if let Some(exr) = &opts.exr_copy {
                let layer = denoised
                    .as_ref()
                    .filter(|_| opts.denoise == DenoiseMode::On)
                    .map(|d| (crate::denoise::EXR_LAYER, &d.image));
                output::write_image_with_layer(
                    exr,
                    &image,
                    layer,
                    coverage.as_ref(),
                    preview.background,
                    &opts.display,
                )?;
            }
        }
        rows.append(&mut recorder.rows);
        let measure_notes = measure.write_outputs(&rows, &opts.scene)?;
        let mut notes: Vec<String> = prepared.looks.iter().map(ToString::to_string).collect();
        notes.extend(prepared.notes.iter().map(ToString::to_string));
        notes.extend(plan.method_note.clone());
        if settings.spectral {
            notes.push(match opts.spectral {
                SpectralMode::On => "spectral transport (--spectral on)".into(),
                _ if scene.materials.iter().any(|m| m.conductor().is_some()) => {
                    "spectral transport: the scene has measured metals, dispersive materials \
                     or spectral lights (--spectral off for RGB)"
                        .into()
                }
                _ => "spectral transport: the scene has dispersive materials or spectral \
                      lights (--spectral off for RGB)"
                    .into(),
            });
        }
        notes.extend(prepared.camera_note.as_ref().map(|n| n.to_string()));
        notes.extend(scene.warnings.iter().cloned());
        notes.extend(measure_notes);
        notes.extend(denoised.as_ref().and_then(|d| denoiser.note(d)));
        if stop.denoised {
            notes.push(format!(
                "error target checked on the denoised image at {} checkpoints (both halves \
                 denoised each time: {:.2} s)",
                stop.checks.0,
                stop.checks.1.as_secs_f64()
            ));
        }
        notes.extend(shard_note);
        Ok(RenderSummary {
            output,
            image,
            stats,
            load_time: prepared.load_time,
            build_time: scene.accel_build_time,
            triangles: scene.triangle_count(),
            backend: scene.backend_name(),
            notes,
            rows,
            target_error: measure.target_error,
            target_estimate: stop.last,
            target_denoised: stop.denoised,
            time_limit: opts.time_limit,
            method,
            plan,
            denoised: denoised.map(|d| d.image),
        })
    }
}
