//! The commands behind the CLI (`iris render`, `iris info`), as library functions so tests
//! can run them without a subprocess. They load, validate, build, render and write, and
//! return a summary; `main.rs` only parses flags and prints.

pub mod commands;
pub mod converge;
pub mod gallery;
pub mod info;

use crate::accel::Backend;
use crate::app::converge::MeasureOptions;
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::integrator::{Integrator, Method};
use crate::measure::{metrics::ErrorMetrics, report::ReportRow, Recorder};
use crate::output::{self, Background, DisplayOptions, ImageRgb};
pub use crate::plan::SpectralMode;
pub use crate::prepare::default_preview_scene;
pub use crate::prepare::input::{
    check_size, default_size, load, load_with_environment, resolve_environment, MAX_PIXELS,
};
pub use crate::preview::{choose_camera, choose_camera_view, load_for_preview, PreviewOptions};
use crate::render::{Control, Progress, RenderSettings, RenderStats};
pub use info::info_command;
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
    /// Photon-mapping settings (`--photons`, `--radius`, `--alpha`, `--passes`, …).
    pub photon: crate::integrator::PhotonSettings,
    /// Acceleration backend.
    pub accel: Backend,
    /// Seed.
    pub seed: u64,
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
}

impl RenderOptions {
    /// `iris render SCENE -o OUTPUT` with every other flag at the CLI's default (4 spp,
    /// Whitted, depth 64, no time limit, automatic backend, seed 0, all threads, the
    /// file's first camera and environment, automatic spectral transport).
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
            photon: crate::integrator::PhotonSettings::default(),
            accel: Backend::Auto,
            seed: 0,
            threads: 0,
            camera: None,
            display: DisplayOptions::default(),
            quiet: false,
            env: None,
            spectral: SpectralMode::Auto,
        }
    }
}

/// What a render did, for the one-line summary.
#[derive(Debug, Clone)]
pub struct RenderSummary {
    /// Where the image went.
    pub output: PathBuf,
    /// The linear image.
    pub image: ImageRgb,
    /// Render figures.
    pub stats: RenderStats,
    /// Scene load + validation time.
    pub load_time: Duration,
    /// Acceleration build time.
    pub build_time: Duration,
    /// Triangles.
    pub triangles: usize,
    /// Backend name.
    pub backend: &'static str,
    /// Decisions taken for the user and loader warnings.
    pub notes: Vec<String>,
    /// Report rows: "load", "build", then one "render" row per checkpoint.
    pub rows: Vec<ReportRow>,
    /// Whether `--target-error` stopped the render.
    pub reached_target: bool,
    /// The method that rendered (`--method auto` resolved).
    pub method: Method,
    /// The render plan the render followed (costs measured with `--explain`).
    pub plan: crate::plan::Plan,
}

impl RenderSummary {
    /// The last checkpoint's error against the reference (with `--reference`).
    pub fn final_error(&self) -> Option<ErrorMetrics> {
        self.rows.last().and_then(|r| r.error)
    }

    /// "12 spp" or "40 passes, 9216000 photons": the work the render did, as `iris render`
    /// and the gallery print it.
    pub fn work_done(&self) -> String {
        let pixels = u64::from(self.image.width) * u64::from(self.image.height);
        let spp = self.stats.samples / pixels.max(1);
        match self.method {
            Method::Sppm => format!(
                "{} passes, {} photons",
                self.stats.passes, self.stats.photons
            ),
            Method::Photon => format!("{spp} spp, {} photons", self.stats.photons),
            _ => format!("{spp} spp"),
        }
    }

    /// The last checkpoint's half-buffer error estimate.
    pub fn final_estimate(&self) -> Option<ErrorMetrics> {
        self.rows.last().and_then(|r| r.estimate)
    }
}

impl RenderOptions {
    /// The scene preparation these options (and the drop-in `preview` choices) ask for;
    /// `reference_size` is the `--reference` image's size, used when `--size` is not given.
    pub fn prepare_options(
        &self,
        preview: &PreviewOptions,
        reference_size: Option<(u32, u32)>,
    ) -> crate::prepare::PrepareOptions {
        crate::prepare::PrepareOptions {
            accel: self.accel,
            env: self.env.clone(),
            camera: self.camera.clone(),
            size: self.size.or(reference_size),
            preview: *preview,
        }
    }
}

/// `iris render`.
pub fn render_command(opts: &RenderOptions) -> Result<RenderSummary> {
    render_command_measured(opts, &MeasureOptions::default())
}

/// `iris render` with `--reference`, `--report`, `--plot` and `--target-error`: every flag is
/// checked (extensions, the reference's file and size) before rendering; the image, then the
/// CSV, then the plot are written, each atomically.
pub fn render_command_measured(
    opts: &RenderOptions,
    measure: &MeasureOptions,
) -> Result<RenderSummary> {
    render_command_preview(opts, measure, &PreviewOptions::default())
}

/// [`render_command_measured`] with the drop-in preview choices ([`PreviewOptions`]:
/// `--studio`, `--ground`, `--view`, `--background`). With a background other than the
/// environment, a coverage pass ([`crate::render::coverage`]) precedes the render and the
/// image is composited when written (checkpoints too); the returned `image` stays the
/// linear render.
pub fn render_command_preview(
    opts: &RenderOptions,
    measure: &MeasureOptions,
    preview: &PreviewOptions,
) -> Result<RenderSummary> {
    render_command_planned(opts, measure, preview, false, &mut |_| {})
}

/// [`render_command_preview`] that hands the render plan to `on_plan` before rendering;
/// the plan is made after the preview's studio and floor are in the scene. With `explain`
/// (`--explain`) the plan's costs are measured first (a 32×24 probe render each way and
/// 10 000 photons, see [`crate::plan::Plan::measure_costs`]).
pub fn render_command_planned(
    opts: &RenderOptions,
    measure: &MeasureOptions,
    preview: &PreviewOptions,
    explain: bool,
    on_plan: &mut dyn FnMut(&crate::plan::Plan),
) -> Result<RenderSummary> {
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
    measure.check_flags()?;
    let reference = measure
        .reference
        .as_deref()
        .map(crate::measure::read_reference_file)
        .transpose()?;
    let prepared = crate::prepare::prepare(
        &opts.scene,
        &opts.prepare_options(preview, reference.as_ref().map(|r| (r.width, r.height))),
    )?;
    let crate::prepare::Prepared {
        scene,
        camera: cam_desc,
        size: (w, h),
        load_time,
        notes: prepared_notes,
        camera_note: cam_note,
    } = prepared;
    if let (Some(r), Some(path)) = (&reference, &measure.reference) {
        crate::measure::check_reference_size(
            r,
            path,
            w,
            h,
            &format!("the render of {}", opts.scene.display()),
        )?;
    }
    let camera = Camera::new(&cam_desc, w, h);
    let mut plan = crate::plan::Plan::new(&scene, opts.method, opts.spectral);
    if explain {
        plan.add_file_counts(&opts.scene);
        let (pw, ph) = crate::plan::PROBE_SIZE;
        plan.measure_costs(&scene, &Camera::new(&cam_desc, pw, ph), opts.threads)?;
    }
    on_plan(&plan);
    let (method, method_note) = (plan.method, plan.method_note.clone());
    crate::integrator::check_memory(w, h, method)?;
    measure.check_checkpoints(if method == Method::Sppm {
        opts.photon.passes
    } else {
        opts.spp
    })?;
    let integrator = Integrator::new(method, opts.max_depth, &opts.photon)?;
    let settings = RenderSettings {
        width: w,
        height: h,
        spp: opts.spp,
        seed: opts.seed,
        threads: opts.threads,
        quiet: opts.quiet,
        spectral: plan.spectral,
        time_limit: opts.time_limit,
    };
    let run = method.name();
    let mut rows = crate::app::converge::setup_rows(run, load_time, scene.accel_build_time);
    let mut recorder = Recorder::new(run, reference.as_ref(), measure.target_error);
    recorder.verbose = !opts.quiet && measure.any();
    // `--background`: the coverage of the camera samples (as many as the render will take
    // at most, up to the pass's cap), computed once before rendering.
    let coverage = (preview.background != Background::Environment)
        .then(|| -> Result<_> {
            let n = u64::from(if method == Method::Sppm {
                opts.photon.passes
            } else {
                opts.spp
            });
            Ok(crate::render::thread_pool(&settings)?
                .install(|| crate::render::coverage::coverage(&scene, &camera, &settings, n)))
        })
        .transpose()?;
    let write = |img: &ImageRgb| {
        output::write_image_with_background(
            &output,
            img,
            coverage.as_ref(),
            preview.background,
            &opts.display,
        )
    };
    // `--checkpoint K`: write the image whenever K more samples (passes for SPPM) are done.
    let mut last_written = 0u64;
    let mut observe = |p: &Progress| -> Result<Control> {
        if let Some(k) = opts.checkpoint {
            let units = if method == Method::Sppm {
                u64::from(p.passes)
            } else {
                p.samples
            };
            if !p.done && units >= last_written + u64::from(k) {
                write(p.image)?;
                last_written = units;
            }
        }
        recorder.observe(p)
    };
    let (image, stats) =
        integrator.render_progressive(&scene, &camera, &settings, Some(&mut observe))?;
    write(&image)?;
    let reached_target = recorder.reached_target;
    rows.append(&mut recorder.rows);
    let measure_notes = measure.write_outputs(&rows, &opts.scene)?;
    let mut notes: Vec<String> = prepared_notes.iter().map(ToString::to_string).collect();
    notes.extend(method_note);
    if settings.spectral {
        notes.push(match opts.spectral {
            SpectralMode::On => "spectral transport (--spectral on)".into(),
            _ => "spectral transport: the scene has dispersive materials or spectral lights \
                  (--spectral off for RGB)"
                .into(),
        });
    }
    notes.extend(cam_note.map(|n| n.to_string()));
    notes.extend(scene.warnings.iter().cloned());
    notes.extend(measure_notes);
    Ok(RenderSummary {
        output,
        image,
        stats,
        load_time,
        build_time: scene.accel_build_time,
        triangles: scene.triangle_count(),
        backend: scene.backend_name(),
        notes,
        rows,
        reached_target,
        method,
        plan,
    })
}

/// What `iris diff` measures.
#[derive(Debug, Clone, Copy)]
pub struct DiffSummary {
    /// Root-mean-square difference over all pixels and channels (linear RGB).
    pub rmse: f64,
    /// `rmse` divided by the reference's mean value.
    pub relative_rmse: f64,
    /// Mean value of the image (all channels).
    pub mean: f64,
    /// Mean value of the reference.
    pub reference_mean: f64,
}

/// `iris diff IMAGE REFERENCE`: error of an EXR against a reference EXR of the same size.
pub fn diff_command(image: &Path, reference: &Path) -> Result<DiffSummary> {
    let a = output::read_exr(image)?;
    let b = output::read_exr(reference)?;
    if (a.width, a.height) != (b.width, b.height) {
        return Err(Error::Usage(format!(
            "{} is {}x{} but the reference {} is {}x{}",
            image.display(),
            a.width,
            a.height,
            reference.display(),
            b.width,
            b.height
        )));
    }
    let n = (a.data.len() * 3).max(1) as f64;
    let (mut se, mut sa, mut sb) = (0f64, 0f64, 0f64);
    for (p, q) in a.data.iter().zip(&b.data) {
        let (p, q) = (p.as_dvec3(), q.as_dvec3());
        se += (p - q).length_squared();
        sa += p.element_sum();
        sb += q.element_sum();
    }
    let rmse = (se / n).sqrt();
    let reference_mean = sb / n;
    Ok(DiffSummary {
        rmse,
        relative_rmse: if reference_mean > 0.0 {
            rmse / reference_mean
        } else {
            f64::INFINITY
        },
        mean: sa / n,
        reference_mean,
    })
}
