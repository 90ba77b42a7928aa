//! `iris render` as a library call: the job between plan and render ([`RenderJob`]: flags
//! checked, scene prepared, plan made, then the render and its outputs) for the options
//! ([`RenderOptions`], every flag, in [`super::render_options`]), and the summary
//! ([`RenderSummary`], in [`super::summary`]). Images are linear RGB until written; times
//! are wall-clock.
//!
//! Denoising (`--denoise`, [`crate::denoise::mode`]): when the plan's `denoise` stage is
//! used, the auxiliary pass runs once before rendering, and every write (checkpoints
//! included) denoises the image then: the PNG shows the denoised image, an EXR under
//! `--denoise on` gets it as an extra layer. With `--reference` every checkpoint is
//! denoised so its report row has the denoised error too.

use super::budget::{stop_error, Measure, TargetStop};
use super::checkpoint_writes::CheckpointWrites;
use super::render_denoise::RenderDenoiser;
pub use super::render_hooks::RunHooks;
use super::render_options::{unit_name, RenderOptions};
pub use super::summary::RenderSummary;
use crate::camera::Camera;
use crate::denoise::DenoiseChoice;
use crate::error::Result;
use crate::image::ImageRgb;
use crate::integrator::Integrator;
use crate::measure::Recorder;
use crate::output;
use crate::plan::SpectralMode;
use crate::prepare::input::check_size;
use crate::render::{Control, Film, Progress, RenderSettings, RenderStats};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;

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
    pub(super) opts: &'a RenderOptions,
    output: PathBuf,
    reference: Option<ImageRgb>,
    /// The prepared scene, camera and size.
    pub prepared: crate::prepare::Prepared,
    pub(super) denoise: DenoiseChoice,
    adaptive: super::adaptive::AdaptiveChoice,
    /// The render plan (method and transport resolved; its last stages are `denoise` and
    /// `adaptive`).
    pub plan: crate::plan::Plan,
}

impl<'a> RenderJob<'a> {
    /// Checks every flag, prepares the scene and makes the plan.
    pub fn new(opts: &'a RenderOptions) -> Result<RenderJob<'a>> {
        RenderJob::build(opts, Source::File)
    }

    /// [`RenderJob::new`] for a scene the caller prepared itself (an instrument's stage,
    /// [`crate::prepare::stage`]): the same flag checks and plan; `opts.scene` only names
    /// the render, and the flags that shape a preparation (`--size`, `--env`, cameras,
    /// looks) are the caller's business.
    pub fn with_prepared(
        opts: &'a RenderOptions,
        prepared: crate::prepare::Prepared,
    ) -> Result<RenderJob<'a>> {
        RenderJob::build(opts, Source::Prepared(Box::new(prepared)))
    }

    /// [`RenderJob::new`] for the description of `opts.scene` the caller loaded
    /// ([`crate::load::load_scene`], which took `load_time`): the same checks, preparation
    /// ([`crate::prepare::prepare_loaded`]) and plan, without reading the file again, so a
    /// scene loaded once renders many times with other flags (the Python module's `Scene`).
    pub fn with_loaded(
        opts: &'a RenderOptions,
        desc: crate::scene::desc::SceneDesc,
        load_time: std::time::Duration,
    ) -> Result<RenderJob<'a>> {
        RenderJob::build(opts, Source::Loaded(Box::new(desc), load_time))
    }

    /// The checks, the preparation (unless `given` prepared) and the plan.
    fn build(opts: &'a RenderOptions, given: Source) -> Result<RenderJob<'a>> {
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
        opts.check_outputs(opts.output.as_deref())?;
        let reference = measure
            .reference
            .as_deref()
            .map(crate::measure::read_reference_file)
            .transpose()?;
        let prepare_options =
            || opts.prepare_options(reference.as_ref().map(|r| (r.width, r.height)));
        let prepared = match given {
            Source::Prepared(p) => *p,
            Source::File => crate::prepare::prepare(&opts.scene, &prepare_options())?,
            Source::Loaded(desc, load_time) => {
                crate::prepare::prepare_loaded(*desc, load_time, &prepare_options())?
            }
        };
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
        let mut plan = crate::plan::Plan::new(
            &prepared.scene,
            &prepared.camera.projection,
            opts.method,
            opts.spectral,
        );
        plan.decide_polarization(
            &prepared.scene,
            (opts.polarization, opts.polarizer),
            (opts.method, opts.spectral),
        )?;
        plan.stages.push(denoise.stage());
        let adaptive = super::adaptive::choose(
            super::adaptive::AdaptiveFlags {
                mode: opts.adaptive,
                open: opts.watch,
                target: opts.target_error(&output),
                shard: opts.shard.is_some(),
                media: prepared.scene.has_media(),
            },
            plan.method,
        )?;
        plan.stages.push(adaptive.stage());
        // What the method cannot render is refused now, before any pass runs.
        Integrator::new(plan.method, opts.max_depth, &opts.photon)?
            .with_polarization(plan.polarization)
            .check_scene(
                &prepared.scene,
                &Camera::new(&prepared.camera, w, h),
                plan.spectral,
            )?;
        if opts.shard.is_some()
            && opts.watch
            && !opts.quiet
            && !adaptive.reason.contains("--adaptive off")
        {
            eprintln!("note: adaptive sampling {}", adaptive.reason);
        }
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
            adaptive,
            plan,
        })
    }

    /// Renders through the plan's integrator, writing checkpoints (`--checkpoint`) and the
    /// image, then the measuring outputs; returns the summary.
    pub fn run(self) -> Result<RenderSummary> {
        self.run_with(RunHooks {
            write_image: true,
            progress: None,
            cancel: Default::default(),
        })
    }

    /// [`RenderJob::run`] with the caller's [`RunHooks`]: without `write_image` the image
    /// stays in the summary (no output, checkpoint or shard file; `--report` and `--plot`
    /// are still written); `progress` sees every checkpoint and may stop the render.
    pub fn run_with(self, hooks: RunHooks) -> Result<RenderSummary> {
        let RunHooks {
            write_image,
            mut progress,
            cancel,
        } = hooks;
        // A signal from here on stops the render at a safe point, and its image and
        // measuring outputs are written ([`crate::interrupt`]).
        let _honour = crate::interrupt::Honour::begin();
        if !write_image && self.opts.shard.is_some() {
            return Err(crate::Error::Usage(
                "--shard writes a partial image: give it an output file".into(),
            ));
        }
        if write_image {
            // The default output (`-o` not given) is checked here, before rendering.
            self.opts.check_outputs(Some(&self.output))?;
        }
        let (opts, measure) = (self.opts, &self.opts.measure);
        let (scene, (w, h)) = (&self.prepared.scene, self.prepared.size);
        let camera = Camera::new(&self.prepared.camera, w, h);
        let method = self.plan.method;
        let integrator = Integrator::new(method, opts.max_depth, &opts.photon)?
            .with_polarization(self.plan.polarization);
        let settings = RenderSettings {
            cancel,
            ..self.settings()
        };
        let run = method.name();
        let total = integrator.total_units(&settings);
        let shard = self.shard_part(total, (&integrator, &settings))?;
        let mut rows = crate::measure::report::setup_rows(
            run,
            self.prepared.load_time,
            scene.accel_build_time(),
        );
        let mut recorder = Recorder::new(run, self.reference.as_ref());
        recorder.verbose = !opts.quiet && measure.any();
        let target = opts.target_error(&self.output);
        let mut stop = TargetStop::for_render(target, scene, method);
        let coverage = self.coverage(&camera, &settings)?;
        recorder.picture = self.picture(coverage.as_ref());
        let judge_in = recorder.picture.map_or(Measure::Linear, Measure::Display);
        // `--denoise`: the auxiliary pass, once, before rendering.
        let mut denoiser = RenderDenoiser::new(&self.denoise, scene, &camera, &settings)?;
        // `--checkpoint K` (K more units: samples, or SPPM passes, which the driver counts
        // in `Progress::samples`) or watching (an open budget): the image so far. With
        // `--reference` every checkpoint is denoised for the report.
        let mut writes = CheckpointWrites::new(
            opts.checkpoint.filter(|_| write_image),
            write_image && opts.watch && shard.is_none(),
        );
        let measure_denoised = self.reference.is_some();
        let mut observe = |p: &Progress| -> Result<Control> {
            let write_now = writes.due(p, Instant::now());
            let denoised = denoiser
                .checkpoint(p.image, write_now || measure_denoised)?
                .map(|d| (d.image.clone(), d.time));
            if write_now {
                let start = Instant::now();
                let (main, layer) = denoiser.layout(p.image, denoised.as_ref().map(|d| &d.0));
                self.write_image(&self.output, main, layer, coverage.as_ref())?;
                writes.wrote(p, start.elapsed(), Instant::now());
            }
            let control = stop.check(p, denoiser.stop_image(), judge_in)?;
            // Without a target, `--report` and the last line still get the estimate in the
            // output's measure.
            if target.is_none() && (measure.report.is_some() || p.done) {
                stop_error(p, denoiser.stop_image(), judge_in)?;
            }
            recorder.record_denoised(p, denoised.as_ref().map(|(img, t)| (img, *t)))?;
            if let Some(go_on) = progress.as_mut() {
                if !go_on(p) {
                    return Ok(crate::render::Control::Stop);
                }
            }
            Ok(control)
        };
        let range = shard.as_ref().map(|s| s.range.clone());
        let (film, stats) =
            integrator.render_units(scene, &camera, &settings, range, Some(&mut observe))?;
        let image = film.mean();
        let denoised = denoiser.finish(&image)?;
        let shard_note = match shard {
            Some(part) => Some(self.write_partial(part, &film, &stats, total)?),
            None if write_image => {
                let d = denoised.as_ref();
                self.write_final(&image, d, &denoiser, coverage.as_ref())?;
                None
            }
            None => None,
        };
        rows.append(&mut recorder.rows);
        let measure_notes = measure.write_outputs(&rows, &opts.scene)?;
        let mut notes = self.scene_notes(settings.spectral);
        notes.extend(measure_notes);
        notes.extend(denoised.as_ref().and_then(|d| denoiser.note(d)));
        notes.extend(stop.note());
        notes.extend(shard_note);
        Ok(RenderSummary {
            image,
            stats,
            load_time: self.prepared.load_time,
            build_time: scene.accel_build_time(),
            triangles: scene.triangle_count(),
            backend: scene.backend_name(),
            notes,
            rows,
            target_error: target,
            target_estimate: stop.last,
            target_measure: stop.name,
            time_limit: opts.time_limit,
            method,
            denoised: denoised.map(|d| d.image),
            output: self.output,
            plan: self.plan,
        })
    }

    /// The output file (`-o`, or the scene's name as PNG).
    pub(super) fn output(&self) -> &Path {
        &self.output
    }

    /// The render's settings: the flags' counts and seed, the plan's transport.
    pub(super) fn settings(&self) -> RenderSettings {
        let (opts, (width, height)) = (self.opts, self.prepared.size);
        RenderSettings {
            width,
            height,
            spp: opts.spp,
            seed: opts.seed,
            sampler: opts.sampler,
            threads: opts.threads,
            quiet: opts.quiet,
            spectral: self.plan.spectral,
            time_limit: opts.time_limit,
            adaptive: self.adaptive.adaptive,
            cancel: Default::default(),
            kernel: Default::default(),
        }
    }

    /// `--shard`: the units to take of the render's `total` and the render's identity
    /// (with the integrator and settings it renders with), before rendering; `None`
    /// without the flag.
    fn shard_part(
        &self,
        total: u64,
        rendered: (&Integrator, &RenderSettings),
    ) -> Result<Option<ShardPart>> {
        let Some(shard) = self.opts.shard else {
            return Ok(None);
        };
        let method = self.plan.method;
        let range = shard.range(total, unit_name(method))?;
        let identity = super::shard_id::identity(
            self.opts,
            (&self.prepared.scene, &self.prepared.camera),
            rendered,
            (total < crate::render::OPEN_UNITS).then_some(total),
        )?;
        Ok(Some(ShardPart {
            shard,
            range,
            identity,
        }))
    }

    /// Writes a shard's partial image (its exact sums and header) to the output; returns
    /// the note saying which units it holds.
    fn write_partial(
        &self,
        part: ShardPart,
        film: &Film,
        stats: &RenderStats,
        total: u64,
    ) -> Result<String> {
        let ShardPart {
            shard,
            range,
            identity,
        } = part;
        let header = super::shard::ShardHeader::new(
            identity,
            &self.opts.scene,
            shard,
            (range.clone(), film.done()),
            stats,
        );
        output::partial::write(&self.output, &header.entries(), &film.exact())?;
        Ok(format!(
            "shard {shard}: {} {}..{} of {} (iris merge adds the shards' partial images)",
            unit_name(self.plan.method),
            range.start,
            range.end,
            if total < crate::render::OPEN_UNITS {
                total.to_string()
            } else {
                "an open budget".into()
            }
        ))
    }

    /// What the preparation, the plan and the scene say, in order: looks, preparation
    /// notes, the method, the transport (when `spectral`), the camera, scene warnings.
    fn scene_notes(&self, spectral: bool) -> Vec<String> {
        let (prepared, scene) = (&self.prepared, &self.prepared.scene);
        let mut notes: Vec<String> = prepared.looks.iter().map(ToString::to_string).collect();
        notes.extend(prepared.notes.iter().map(ToString::to_string));
        notes.extend(self.plan.method_note.clone());
        if spectral {
            notes.push(match (self.opts.spectral, self.plan.stage("transport")) {
                (SpectralMode::On, _) => "spectral transport (--spectral on)".into(),
                (_, Some(stage)) => format!(
                    "spectral transport, the plan's choice: {} (--spectral off for RGB)",
                    stage.reason.trim_start_matches("spectral: ")
                ),
                (_, None) => "spectral transport (--spectral off for RGB)".into(),
            });
        }
        notes.extend(prepared.camera_note.as_ref().map(|n| n.to_string()));
        notes.extend(scene.warnings().iter().cloned());
        notes
    }
}

/// Where [`RenderJob::build`] gets its scene.
enum Source {
    /// Load and prepare `opts.scene`.
    File,
    /// Prepare this description (loaded in this time).
    Loaded(Box<crate::scene::desc::SceneDesc>, std::time::Duration),
    /// Already prepared by the caller.
    Prepared(Box<crate::prepare::Prepared>),
}

/// A shard's part of the render (`--shard`): the shard, its units and the render's identity
/// ([`super::shard_id::identity`]).
struct ShardPart {
    shard: super::shard::Shard,
    range: Range<u64>,
    identity: Vec<(String, String)>,
}
