//! The `iris converge` command ([`converge_command`]): renders one scene with several
//! methods under the same time budget and compares their error curves (the measuring
//! flags of `iris render` are [`crate::measure::MeasureOptions`]).
//!
//! Units and conventions: wall-clock seconds; errors on the linear image
//! ([`crate::image::metrics`]); "relative error" is the relative RMSE `sqrt(rel_mse)`
//! ([`measure::relative_rmse`]). Every file is written atomically (temporary file + rename),
//! and every flag and input file is checked before anything is rendered.

mod observe;

use super::RenderOptions;
use crate::accel::Backend;
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::image::ImageRgb;
use crate::integrator::{Integrator, Method, PhotonSettings};
use crate::measure::file_name;
use crate::measure::plot::{plot_error_vs_time, Series};
use crate::measure::report::{setup_rows, write_csv, ReportRow};
use crate::measure::{self, Recorder};
use crate::output::{self, DisplayOptions};
use crate::plan::SpectralMode;
use crate::render::{Control, Progress, RenderSettings, RenderStats};
use crate::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Parses `--methods path,photon,sppm`: names of the methods of the registry
/// ([`Method::ALL`] but `auto`), each at most once, at least one.
pub fn parse_methods(list: &str) -> Result<Vec<Method>> {
    let accepted: Vec<Method> = Method::ALL
        .into_iter()
        .filter(|m| *m != Method::Auto)
        .collect();
    let mut methods = Vec::new();
    for name in list.split(',').map(str::trim) {
        let lower = name.to_ascii_lowercase();
        let Some(&m) = accepted.iter().find(|m| m.name() == lower) else {
            let names: Vec<&str> = accepted.iter().map(|m| m.name()).collect();
            return Err(Error::Usage(format!(
                "--methods {list}: unknown method {name:?} (accepted: {})",
                names.join(", ")
            )));
        };
        if methods.contains(&m) {
            return Err(Error::Usage(format!(
                "--methods {list}: {name} is listed twice"
            )));
        }
        methods.push(m);
    }
    Ok(methods)
}

/// Everything `iris converge` needs.
#[derive(Debug, Clone)]
pub struct ConvergeOptions {
    /// Scene file.
    pub scene: PathBuf,
    /// Methods to compare, in order.
    pub methods: Vec<Method>,
    /// Time budget of each method.
    pub time: Duration,
    /// Reference image; `None` = render one first (see [`converge_command`]).
    pub reference: Option<PathBuf>,
    /// Output directory (created if missing).
    pub out_dir: PathBuf,
    /// Image size; default the reference's, else as `iris render`.
    pub size: Option<(u32, u32)>,
    /// Seed of the runs (the rendered reference uses another stream).
    pub seed: u64,
    /// The numbers driving camera paths (`--sampler`).
    pub sampler: crate::sampler::SamplerKind,
    /// Threads (0 = all), at most [`crate::render::MAX_THREADS`].
    pub threads: usize,
    /// Acceleration backend.
    pub accel: Backend,
    /// No progress output.
    pub quiet: bool,
    /// `--stone` / `--metal` material overrides, in order ([`crate::prepare::looks`]).
    pub looks: Vec<crate::prepare::looks::LookFlag>,
}

impl ConvergeOptions {
    /// The preparation `iris render` makes of the same file and flags (no `--env`, no
    /// `--camera`, the default drop-in preview, the same `--stone` / `--metal`): that of
    /// [`RenderOptions::prepare_options`], with the same meaning of `reference_size`.
    pub fn prepare_options(
        &self,
        reference_size: Option<(u32, u32)>,
    ) -> crate::prepare::PrepareOptions {
        RenderOptions {
            size: self.size,
            accel: self.accel,
            looks: self.looks.clone(),
            ..RenderOptions::new(&self.scene, None)
        }
        .prepare_options(reference_size)
    }
}

/// What `iris converge` did.
#[derive(Debug, Clone)]
pub struct ConvergeSummary {
    /// What the scene preparation decided (lights, floor, camera), as `iris render` notes.
    pub notes: Vec<String>,
    /// Every file written, in order.
    pub files: Vec<PathBuf>,
    /// The reference, when one was rendered: its method and file.
    pub rendered_reference: Option<(Method, PathBuf)>,
    /// Each run, in the order of `--methods`.
    pub runs: Vec<RunSummary>,
    /// The levels table ([`measure::levels_table`]).
    pub table: String,
}

/// One method's run in `iris converge`.
#[derive(Debug, Clone)]
pub struct RunSummary {
    /// Method name.
    pub name: String,
    /// Render figures.
    pub stats: RenderStats,
    /// Samples per pixel at the end.
    pub spp: u64,
    /// Final relative RMSE against the reference.
    pub relative_error: f64,
}

/// Largest sample and pass counts given to a run, so that the time budget stops it.
const UNBOUNDED_SPP: u32 = 1_000_000;
const UNBOUNDED_PASSES: u32 = 10_000_000;
/// Seed offset of a rendered reference, so its noise is independent of the runs'.
const REFERENCE_SEED: u64 = 0x5EED_0F2E_FE2E_7C00;
/// One run's error curve: its label and its (seconds, relative RMSE) points.
type Curve = (String, Vec<(f64, f64)>);

/// `iris converge`: renders the scene with each method for the same time budget, writes
/// DIR/<method>.exr and .png, DIR/report.csv (every checkpoint of every run, run = method)
/// and DIR/convergence.png (relative RMSE against time, one line per method), and returns
/// the table of which method reached each of [`measure::LEVELS`] first.
///
/// Without a reference it first renders one for 4× the budget with `--method auto`'s choice
/// (SPPM when the scene has caustic paths, the path tracer otherwise) on an independent
/// seed, and writes it to DIR/reference.exr.
pub fn converge_command(opts: &ConvergeOptions) -> Result<ConvergeSummary> {
    check_flags(opts)?;
    let given_reference = opts
        .reference
        .as_deref()
        .map(crate::measure::read_reference_file)
        .transpose()?;
    // The scene `iris render` renders for the same file and flags (the default drop-in
    // preview: floor, studio, framing), from the one preparation.
    let reference_size = given_reference.as_ref().map(|r| (r.width, r.height));
    let prepared = crate::prepare::prepare(&opts.scene, &opts.prepare_options(reference_size))?;
    let notes: Vec<String> = (prepared.looks.iter().map(ToString::to_string))
        .chain(prepared.notes().iter().map(ToString::to_string))
        .collect();
    let (scene, cam_desc, (w, h), load_time) = (
        prepared.scene,
        prepared.camera,
        prepared.size,
        prepared.load_time,
    );
    // The reference's method (without --reference).
    let reference_method = given_reference.is_none().then(|| {
        match crate::plan::resolve_method(Method::Auto, &scene, &cam_desc.projection).0 {
            // With media only the path tracer and the hybrid trace them, and only the hybrid
            // reaches a delta light's volumetric caustic: the reference is auto's choice
            // between them (on its own seed).
            m if scene.has_media() => m,
            // The reference stays SPPM for caustic scenes (not the hybrid or VCM under test).
            Method::Hybrid | Method::Vcm => Method::Sppm,
            m => m,
        }
    });
    check_fit(opts, given_reference.as_ref(), reference_method, (w, h))?;
    let job = Job::new(opts, &scene, Camera::new(&cam_desc, w, h), (w, h));
    job.check_methods(opts.methods.iter().chain(reference_method.as_ref()))?;
    check_outputs(opts, reference_method.is_some())?;
    prepare_dir(&opts.out_dir)?;
    // From the first render on, a signal asks the renders to stop at their safe points
    // and the report is written; before it (loading, checks) the process exits at once.
    let _honour = crate::interrupt::Honour::begin();
    let mut files = Vec::new();
    let (reference, rendered_reference) = match given_reference {
        Some(r) => (r, None),
        None => {
            // Always `Some` without a reference.
            let method = reference_method.unwrap_or(Method::Sppm);
            let (image, path) = render_reference(opts, &job, method)?;
            files.push(path.clone());
            (image, Some((method, path)))
        }
    };
    let mut rows = setup_rows("scene", load_time, scene.accel_build_time());
    let mut runs = Vec::new();
    let mut curves = Vec::new();
    for &method in &opts.methods {
        let (run, curve) = run_method(opts, &job, method, &reference, &mut files, &mut rows)?;
        runs.push(run);
        curves.push(curve);
    }
    files.push(write_report(opts, &rows)?);
    files.push(write_plot(opts, &curves)?);
    Ok(ConvergeSummary {
        notes,
        files,
        rendered_reference,
        runs,
        table: measure::levels_table(&curves),
    })
}

/// The flags checked before any file is read: at least one method, a valid `--size`, a
/// valid `--threads`.
fn check_flags(opts: &ConvergeOptions) -> Result<()> {
    if opts.methods.is_empty() {
        return Err(Error::Usage("--methods: name at least one method".into()));
    }
    if let Some((w, h)) = opts.size {
        crate::prepare::input::check_size(w, h)?;
    }
    crate::render::check_threads(opts.threads)
}

/// Checks, before anything is rendered, that every run (and the reference's, rendered
/// with `reference_method`) fits in memory at `(w, h)`, then that a given reference has
/// that size.
fn check_fit(
    opts: &ConvergeOptions,
    given_reference: Option<&ImageRgb>,
    reference_method: Option<Method>,
    (w, h): (u32, u32),
) -> Result<()> {
    for m in opts.methods.iter().chain(reference_method.as_ref()) {
        crate::integrator::check_memory(w, h, *m)?;
    }
    if let (Some(r), Some(path)) = (given_reference, &opts.reference) {
        measure::check_reference_size(
            r,
            path,
            w,
            h,
            &format!("--size of {}", opts.scene.display()),
        )?;
    }
    Ok(())
}

/// Renders the reference with `method` for 4× the budget on an independent seed and
/// writes it to DIR/reference.exr; returns the image and that path.
fn render_reference(
    opts: &ConvergeOptions,
    job: &Job,
    method: Method,
) -> Result<(ImageRgb, PathBuf)> {
    if !opts.quiet {
        eprintln!(
            "iris converge: no --reference: rendering one with {} for {:.1} s (4× the budget)",
            method.name(),
            4.0 * opts.time.as_secs_f64()
        );
    }
    let mut settings = job.base.clone();
    settings.seed ^= REFERENCE_SEED;
    settings.time_limit = Some(opts.time * 4);
    let (image, _) = job.run(method, &settings, None)?;
    let path = opts.out_dir.join("reference.exr");
    output::write_image(&path, &image, &DisplayOptions::default())?;
    Ok((image, path))
}

/// One method's run for the time budget, measured against `reference` at every
/// checkpoint: writes DIR/<method>.exr and .png (added to `files`), appends its checkpoint
/// rows to `rows`, and returns its summary and its error curve (label, points).
fn run_method(
    opts: &ConvergeOptions,
    job: &Job,
    method: Method,
    reference: &ImageRgb,
    files: &mut Vec<PathBuf>,
    rows: &mut Vec<ReportRow>,
) -> Result<(RunSummary, Curve)> {
    let name = method.name();
    let mut recorder = Recorder::new(name, Some(reference));
    recorder.verbose = !opts.quiet;
    let mut observe = |p: &Progress| -> Result<Control> { recorder.observe(p) };
    let (image, stats) = job.run(method, &job.base, Some(&mut observe))?;
    let display = DisplayOptions::default();
    for ext in ["exr", "png"] {
        let path = opts.out_dir.join(format!("{name}.{ext}"));
        output::write_image(&path, &image, &display)?;
        files.push(path);
    }
    let last = crate::image::metrics::compare(&image, reference)?;
    let run = RunSummary {
        name: name.to_string(),
        stats,
        spp: recorder.rows.last().map_or(0, |r| r.samples),
        relative_error: measure::relative_rmse(&last),
    };
    let curve = (name.to_string(), recorder.points());
    rows.append(&mut recorder.rows);
    Ok((run, curve))
}

/// Writes DIR/report.csv (every row) and returns its path.
fn write_report(opts: &ConvergeOptions, rows: &[ReportRow]) -> Result<PathBuf> {
    let report = opts.out_dir.join("report.csv");
    write_csv(&report, rows)?;
    Ok(report)
}

/// Writes DIR/convergence.png (one line per run) and returns its path.
fn write_plot(opts: &ConvergeOptions, curves: &[Curve]) -> Result<PathBuf> {
    let plot = opts.out_dir.join("convergence.png");
    let series: Vec<Series> = curves
        .iter()
        .map(|(label, points)| Series {
            label: label.clone(),
            points: points.clone(),
        })
        .collect();
    plot_error_vs_time(
        &plot,
        &format!(
            "{}: error against time ({} s each)",
            file_name(&opts.scene),
            opts.time.as_secs_f64()
        ),
        "relative RMSE against the reference",
        &series,
    )?;
    Ok(plot)
}

/// Refuses an output in DIR that names an input (the scene or `--reference`): the runs
/// would overwrite what the command reads.
fn check_outputs(opts: &ConvergeOptions, renders_reference: bool) -> Result<()> {
    let dir = &opts.out_dir;
    let mut outputs: Vec<PathBuf> = vec![dir.join("report.csv"), dir.join("convergence.png")];
    if renders_reference {
        outputs.push(dir.join("reference.exr"));
    }
    for m in &opts.methods {
        outputs.extend(["exr", "png"].map(|ext| dir.join(format!("{}.{ext}", m.name()))));
    }
    let outputs: Vec<(&str, &Path)> = outputs.iter().map(|p| ("-o", p.as_path())).collect();
    let mut inputs = vec![("scene", opts.scene.as_path())];
    inputs.extend(opts.reference.as_deref().map(|r| ("--reference", r)));
    crate::fileio::output::check_distinct(&outputs, &inputs)
}

/// Creates the output directory and proves it writable (a probe file, removed again), so a
/// bad `-o` fails before any rendering.
fn prepare_dir(dir: &Path) -> Result<()> {
    let fail = |e: std::io::Error| Error::Output {
        path: dir.to_path_buf(),
        reason: format!("-o: cannot write to this directory: {e}"),
    };
    std::fs::create_dir_all(dir).map_err(fail)?;
    let probe = dir.join(format!(".iris-converge-probe-{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(fail)?;
    std::fs::remove_file(&probe).map_err(fail)
}

/// The parts shared by every run of one `iris converge`.
struct Job<'a> {
    scene: &'a Scene,
    camera: Camera,
    base: RenderSettings,
}

impl<'a> Job<'a> {
    /// The runs' settings: `size`, unbounded samples stopped by the time budget, the
    /// runs' seed, the spectral mode `--spectral auto` picks for `scene`.
    fn new(opts: &ConvergeOptions, scene: &'a Scene, camera: Camera, (w, h): (u32, u32)) -> Self {
        Job {
            scene,
            camera,
            base: RenderSettings {
                width: w,
                height: h,
                spp: UNBOUNDED_SPP,
                seed: opts.seed,
                threads: opts.threads,
                quiet: opts.quiet,
                spectral: SpectralMode::Auto.resolve(scene, crate::integrator::Method::Path),
                time_limit: Some(opts.time),
                sampler: opts.sampler,
                adaptive: None,
                cancel: Default::default(),
                kernel: Default::default(),
            },
        }
    }

    /// Renders with `method` and `settings` (the budget stops it), reporting progress to
    /// `observer`.
    fn run(
        &self,
        method: Method,
        settings: &RenderSettings,
        observer: Option<crate::render::Observer>,
    ) -> Result<(ImageRgb, RenderStats)> {
        let (integrator, settings) = self.integrator(method, settings)?;
        integrator.render_progressive(self.scene, &self.camera, &settings, observer)
    }

    /// The integrator of `method` and the settings it renders with: as `iris render
    /// --polarization auto` without a polarizer, a scene with a crystal or a polarizer
    /// sheet is polarized (and so spectral) for the methods that trace polarized light.
    fn integrator(
        &self,
        method: Method,
        settings: &RenderSettings,
    ) -> Result<(Integrator, RenderSettings)> {
        let photon = PhotonSettings {
            passes: UNBOUNDED_PASSES,
            ..PhotonSettings::default()
        };
        let polarized = crate::plan::needs_polarization(self.scene)
            .then_some(crate::plan::Polarization { polarizer: None });
        let settings = RenderSettings {
            spectral: settings.spectral || polarized.is_some(),
            ..settings.clone()
        };
        let integrator = Integrator::new(method, 64, &photon)?.with_polarization(polarized);
        Ok((integrator, settings))
    }

    /// Refuses, before anything is rendered, a method in `methods` that cannot render the
    /// scene ([`Integrator::check_scene`]: media, the camera, the caustic modes).
    fn check_methods<'m>(&self, methods: impl IntoIterator<Item = &'m Method>) -> Result<()> {
        for &method in methods {
            let (integrator, settings) = self.integrator(method, &self.base)?;
            integrator
                .check_scene(self.scene, &self.camera, settings.spectral)
                .map_err(|e| match e {
                    Error::Usage(m) => Error::Usage(format!("--methods {}: {m}", method.name())),
                    e => e,
                })?;
        }
        Ok(())
    }
}
