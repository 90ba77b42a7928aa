//! The `iris` command line: parses flags, calls [`iris::app`], prints a summary, and turns
//! errors into a message on stderr and a non-zero exit code.
//!
//! Interruption: the first SIGINT (Ctrl-C) or SIGTERM asks the render to stop
//! ([`iris::render::guard::request_stop`]); it finishes the tiles (SPPM: the pass) in
//! flight, writes the image so far atomically, says so, and exits with 130 (128 + SIGINT,
//! so shells and scripts see the interruption). A second one exits at once with 130;
//! outputs are written to a temporary name and renamed, so no half-written file is left
//! under the output's name.

use clap::{Parser, Subcommand};
use iris::accel::Backend;
use iris::app::converge::{parse_methods, ConvergeOptions};
use iris::app::{self, RenderOptions};
use iris::app::{BudgetFlags, SpectralMode};
use iris::integrator::{CausticMode, Method, PhotonSettings};
use iris::measure::MeasureOptions;
use iris::output::{DisplayOptions, Exposure, ToneMap};
use iris::photon::trace::Roulette;
use iris::sampler::SamplerKind;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "iris",
    version,
    about = "Iris: a spectral renderer for glass, gems and caustics"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a glTF (.gltf/.glb) or OBJ scene to PNG or EXR. With no --method, --spp,
    /// --passes, --time or --target-error: the method --method auto picks, rendered until
    /// the estimated relative error is 0.03 or for 120 s, whichever comes first (or Ctrl-C),
    /// the output rewritten as it improves; the last line says what ended it.
    Render(RenderArgs),
    /// Describe a scene: meshes, triangles, materials with their KHR values, lights, cameras.
    Info {
        /// Scene file.
        scene: PathBuf,
        #[command(flatten)]
        looks: LookArgs,
    },
    /// Compare an EXR image with a reference EXR of the same size: RMSE (linear RGB, all
    /// channels), RMSE relative to the reference's mean, and the mean of each.
    Diff {
        /// Image to measure.
        image: PathBuf,
        /// Reference image.
        reference: PathBuf,
        /// Fail (exit 1) unless every stored value is bit-identical to the reference's.
        #[arg(long)]
        exact: bool,
    },
    /// Render a scene with several methods for the same time budget and compare their error
    /// against time: DIR/<method>.exr/.png, DIR/report.csv, DIR/convergence.png, and which
    /// method reached each error level first. Without --reference, a reference is rendered
    /// first (SPPM for caustic scenes, the path tracer otherwise) for 4× the budget and
    /// written to DIR/reference.exr.
    Converge(ConvergeArgs),
    /// Regenerate the project's own scenes into DIR/paper (the paper's figures),
    /// DIR/scenes (glass of water, ruby, prism under the sky + sky.hdr) and DIR/gems.
    GenAssets {
        /// Asset root, e.g. `assets`.
        dir: PathBuf,
    },
    /// Write a gem in a standard cut as .glb (KHR ior, transmission, volume, dispersion),
    /// in a preview scene (camera, lights, white floor) unless --bare.
    Gem(GemArgs),
    /// Render the gallery (the paper's figure scenes, the gems, the Khronos dispersion
    /// samples) into DIR/<name>.png with a Markdown page DIR/README.md (plan, method, time).
    Gallery(GalleryArgs),
    /// Render a turntable: the model turning once (360°) about the vertical axis through
    /// its centre under fixed lights and a fixed camera, as a jeweller's rotating stage
    /// does, in --frames N frames DIR/frame_0000.png … (numbered from 0; frame F turned by
    /// 360°·F/N), then an animated preview DIR/turntable.png (APNG, lossless; --gif adds
    /// DIR/turntable.gif). Every `iris render` flag applies to each frame; every frame has
    /// the same --seed, and `--method auto` is decided on frame 0 for all. --frame F renders
    /// one frame (one job of an array); --assemble only checks that every frame is there
    /// (naming the missing ones, writing nothing then) and writes the animation.
    #[command(mut_arg("output", |a| a
        .required(true)
        .value_name("DIR")
        .help("Output directory for the frames and the animation (created if missing)")))]
    // Per-image measurements: refused by `iris turntable` (app::turntable::check).
    #[command(mut_arg("reference", |a| a.hide(true)))]
    #[command(mut_arg("report", |a| a.hide(true)))]
    #[command(mut_arg("plot", |a| a.hide(true)))]
    Turntable(TurntableArgs),
    /// Merge the partial images of a render's shards (iris render --shard I/N -o PART.exr)
    /// into its image: checks they belong to one render (scene, method, seed, size,
    /// options) and that no sample is missing or twice; with a fixed --spp/--passes the
    /// result is bit for bit one iris render of all the samples.
    Merge(MergeArgs),
}

#[derive(clap::Args)]
struct MergeArgs {
    /// The shards' partial images.
    #[arg(required = true)]
    parts: Vec<PathBuf>,
    /// Output file: .exr (linear) or .png (tone-mapped).
    #[arg(short, long)]
    output: PathBuf,
    /// Write the merge's error row as CSV (iris render's columns, stage `merge`).
    #[arg(long)]
    report: Option<PathBuf>,
    /// Reference EXR (same size): the merged image's error against it.
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Merge what is there when shards (or samples) are missing, and say how many samples
    /// each pixel got.
    #[arg(long)]
    allow_partial: bool,
    /// PNG exposure: `auto` (log-average luminance to 0.18) or stops in [-64, 64], e.g. -1.5.
    #[arg(long, default_value = "auto", value_parser = parse_exposure, allow_hyphen_values = true)]
    exposure: Exposure,
    /// PNG tone map: aces, reinhard, clamp.
    #[arg(long, default_value = "aces", value_parser = ToneMap::parse)]
    tonemap: ToneMap,
}

#[derive(clap::Args)]
struct TurntableArgs {
    /// Frames in the whole turn, 1 to 10000.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(iris::prepare::turntable::MAX_FRAMES)))]
    frames: u32,
    /// Render only frame F (0 to frames − 1) and no animation.
    #[arg(long, value_name = "F", conflicts_with = "assemble")]
    frame: Option<u32>,
    /// Render nothing: check that every frame is in DIR and write the animation.
    #[arg(long)]
    assemble: bool,
    /// Frames per second of the animation, 1 to 50 (GIF rounds the delay to whole
    /// centiseconds).
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u32).range(1..=i64::from(iris::output::animation::MAX_FPS)))]
    fps: u32,
    /// Also write each frame as linear EXR (DIR/frame_0000.exr).
    #[arg(long)]
    exr: bool,
    /// Also write the animation as GIF (DIR/turntable.gif; 256 colours a frame, lossy).
    #[arg(long)]
    gif: bool,
    #[command(flatten)]
    render: RenderArgs,
}

/// `--stone`, `--metal`, `--metal-roughness`: material overrides for render, converge, info.
#[derive(clap::Args, Clone, Default)]
struct LookArgs {
    /// Make materials a stone (repeatable): NAME is diamond, sapphire, ruby, emerald,
    /// cubic-zirconia, quartz or crown-glass. Without =SELECTOR it changes every material
    /// no other --stone/--metal names; NAME=MATERIAL changes that material (a mesh name if
    /// no material has it), NAME=material:MATERIAL or NAME=mesh:MESH say which.
    #[arg(long, value_name = "NAME[=SELECTOR]")]
    stone: Vec<String>,
    /// Make materials a measured metal (repeatable), for settings: gold, silver, platinum,
    /// copper, rose-gold, spectral n and k (see README, "Stones and settings"); selectors as
    /// for --stone.
    #[arg(long, value_name = "NAME[=SELECTOR]")]
    metal: Vec<String>,
    /// GGX perceptual roughness of every --metal surface, 0 (polished mirror, the default)
    /// to 1.
    #[arg(long, default_value_t = 0.0, value_parser = parse_unit, allow_hyphen_values = true)]
    metal_roughness: f32,
}

impl LookArgs {
    /// The flags, stones first, each in the order given.
    fn flags(&self) -> iris::Result<Vec<iris::prepare::looks::LookFlag>> {
        use iris::prepare::looks::LookFlag;
        let stones = self.stone.iter().map(|a| LookFlag::stone(a));
        let metals = self
            .metal
            .iter()
            .map(|a| LookFlag::metal(a, self.metal_roughness));
        stones.chain(metals).collect()
    }
}

fn parse_unit(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("expected a value from 0 to 1, got {s:?}")),
    }
}

#[derive(clap::Args)]
struct GalleryArgs {
    /// Output directory (created if missing).
    #[arg(long, default_value = "docs/gallery")]
    out: PathBuf,
    /// Image size WxH (576x324 keeps the committed gallery under 4 MB of PNG); at most
    /// 2^26 pixels (8192x8192).
    #[arg(long, default_value = "576x324", value_parser = parse_size)]
    size: (u32, u32),
    /// Time limit of each image's render, seconds (more than 0, at most 10000000): the
    /// whole budget, as `iris render --time`. Default: `iris render`'s default budget
    /// (estimated error 0.03 of the written image, or 120 s).
    #[arg(long, value_parser = parse_seconds)]
    time: Option<f64>,
    /// Render only the entries whose name contains SUBSTR (repeatable).
    #[arg(long, value_name = "SUBSTR")]
    only: Vec<String>,
    /// No progress output.
    #[arg(short, long)]
    quiet: bool,
}

#[derive(clap::Args)]
struct GemArgs {
    /// Cut: round (Tolkowsky brilliant), emerald (step cut), oval (brilliant, L/W 1.4),
    /// pear (brilliant, L/W 1.6).
    #[arg(long, value_parser = iris::model::cuts::Cut::parse)]
    cut: iris::model::cuts::Cut,
    /// Stone: diamond, sapphire, ruby, emerald, cubic-zirconia, quartz, crown-glass.
    #[arg(long, value_parser = iris::model::stones::Stone::parse)]
    stone: iris::model::stones::Stone,
    /// Girdle diameter (round) or length (emerald, oval, pear) in millimetres, from 0.1 to
    /// 1000.
    #[arg(long, default_value_t = iris::model::cuts::DEFAULT_SIZE_MM, value_parser = parse_gem_size, allow_hyphen_values = true)]
    size: f64,
    /// Only the stone: no camera, lights or floor.
    #[arg(long)]
    bare: bool,
    /// Output .glb file.
    #[arg(short, long)]
    output: PathBuf,
}

#[derive(clap::Args, Clone)]
struct RenderArgs {
    /// Scene file (.gltf, .glb, .obj).
    scene: PathBuf,
    /// Output image (.png or .exr); default `<scene stem>.png` here.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Image size WxH, e.g. 800x600 (default 800 wide at the camera's aspect): at most 2^26
    /// pixels (8192x8192) and 8 GiB of per-pixel buffers (about 55 M pixels, e.g.
    /// 8192x6400; for `--method sppm` about 19 M pixels, e.g. 4096x4096).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Samples per pixel, 1 to 1000000: the render stops there (or earlier at --time or
    /// --target-error). Without --spp and --passes the render is open-ended: it stops at
    /// --time / --target-error, by default at the estimated relative error 0.03 or after
    /// 120 s, whichever comes first, and rewrites the output as it goes.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    spp: Option<u32>,
    /// Rendering method: auto (the default: the path tracer when no light reaches a diffuse
    /// surface through specular ones, else the hybrid or SPPM by the caustics' share of the
    /// light; the reason is printed), whitted (recursive ray tracing, seed paper §4), path
    /// (path tracing with next-event estimation and MIS), photon (classic photon mapping:
    /// caustic + global maps, final gather), sppm (stochastic progressive photon mapping:
    /// passes, converges), hybrid (the path tracer plus a progressive caustic photon map for
    /// light that reaches a diffuse surface through specular ones only; one pass per
    /// sample, converges).
    #[arg(long, value_parser = Method::parse)]
    method: Option<Method>,
    /// Maximum number of bounces (reflections and refractions) per path, 1 to 1024 (also
    /// the Whitted tracer's recursion depth and the photons stored per photon path).
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=i64::from(iris::integrator::MAX_DEPTH)))]
    max_depth: u32,
    /// Intersection backend: auto (Embree when compiled in), embree, bvh.
    #[arg(long, default_value = "auto", value_parser = Backend::parse)]
    accel: Backend,
    /// Random seed (same seed, scene and backend → same image).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Numbers driving the camera paths: zsobol (Owen-scrambled Sobol' per pixel in Morton
    /// order, blue-noise error; the default) or independent (a PCG stream per sample).
    #[arg(long, default_value = "zsobol", value_parser = SamplerKind::parse)]
    sampler: SamplerKind,
    /// Worker threads, 0 to 1024 (0 = one per core).
    #[arg(long, default_value_t = 0, value_parser = parse_threads())]
    threads: usize,
    /// Camera name or index from the file.
    #[arg(long)]
    camera: Option<String>,
    /// PNG exposure: `auto` (log-average luminance to 0.18) or stops in [-64, 64], e.g. -1.5.
    #[arg(long, default_value = "auto", value_parser = parse_exposure, allow_hyphen_values = true)]
    exposure: Exposure,
    /// PNG tone map: aces, reinhard, clamp.
    #[arg(long, default_value = "aces", value_parser = ToneMap::parse)]
    tonemap: ToneMap,
    /// Environment light: `none`, a grey value or `R,G,B` radiance, or an equirectangular
    /// .exr/.hdr map (+Y up; the image centre looks along −Z). Default: the scene file's
    /// `iris_environment` (glTF scene extras), else none.
    #[arg(long, allow_hyphen_values = true)]
    env: Option<String>,
    /// Spectral transport (4 wavelengths per sample, CIE colour): `auto` when a material is
    /// dispersive or a light names a spectrum, `on` always, `off` never (RGB, dispersive
    /// materials use n_d).
    #[arg(long, default_value = "auto", value_parser = SpectralMode::parse)]
    spectral: SpectralMode,
    /// Studio lighting (not with `--env`): `soft` (grey, broad softboxes; the default for a
    /// file with no light of its own), `jeweller` (dark, small bright strips: fire),
    /// `bright` (white high-key), or `none` (plain directional key and fill). A file that
    /// brings its own light gets a studio only when this flag names one (added to the
    /// file's lights).
    #[arg(long, value_parser = iris::studio::Studio::parse)]
    studio: Option<iris::studio::Studio>,
    /// White floor under the model: `auto` (for a transmissive model with nothing under
    /// it, in a file that brings no light of its own), `on` or `off`.
    #[arg(long, default_value = "auto", value_parser = iris::studio::GroundMode::parse)]
    ground: iris::studio::GroundMode,
    /// SPPM passes, 1 to 10000000 (with --time or --target-error, whichever comes first).
    /// Given alone or with --spp, the other count is 4 spp or 64 passes.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=10_000_000))]
    passes: Option<u32>,
    /// Time budget in seconds (more than 0, at most 10000000): every method stops after the
    /// round of samples (SPPM: the pass) that crosses it, with at least one sample per pixel.
    /// Without --spp/--passes it is the whole budget (no error target unless given);
    /// otherwise the first limit reached ends the render. Default without any budget flag:
    /// 120.
    #[arg(long, value_parser = parse_seconds, allow_hyphen_values = true)]
    time: Option<f64>,
    /// Photons per SPPM or hybrid pass (default: one per pixel) or in total for `--method photon`
    /// (default 500000), 1 to 16777216 (2^24). A pass or map that would store more than
    /// 2^26 photons (2 GiB) stops with an error.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=iris::integrator::MAX_PHOTONS))]
    photons: Option<u64>,
    /// Initial SPPM / hybrid gather radius, largest photon-map radius, in scene units (default: from
    /// the pixel footprint): finite and > 0 (no memory depends on it).
    #[arg(long, value_parser = parse_radius, allow_hyphen_values = true)]
    radius: Option<f32>,
    /// SPPM / hybrid radius reduction α in (0, 1): r²ᵢ₊₁ = r²ᵢ (i+α)/(i+1) (Knaus & Zwicker 2011).
    #[arg(long, default_value_t = 2.0 / 3.0, value_parser = parse_alpha, allow_hyphen_values = true)]
    alpha: f32,
    /// Write the image so far at the checkpoints (1, 2, 4, … samples, or passes for SPPM)
    /// that are at least K samples or passes after the last one written; K from 1 to
    /// 10000000. Without it, an open-ended render (no --spp/--passes) rewrites the image at
    /// the checkpoints at most every 2 s.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=10_000_000))]
    checkpoint: Option<u32>,
    /// Photon Russian roulette rule: throughput (survivors keep their power), seed (the seed
    /// paper's rule: diffuse / reflect / refract by the material's colours).
    #[arg(long, default_value = "throughput", value_parser = Roulette::parse)]
    photon_rr: Roulette,
    /// How `--method hybrid` counts its caustics: map (the caustic photon map everywhere),
    /// light (light tracing splatted onto the image wherever the caustic light is seen
    /// directly, the map where it is seen through glass or mirrors) or mixed (light tracing
    /// for the caustic itself, the map for its later diffuse bounces, where seen directly).
    /// An orthographic camera keeps the map.
    #[arg(long, default_value = "map", value_parser = CausticMode::parse)]
    caustics: CausticMode,
    /// Reference EXR (same size as the render; sets the size if --size is not given): error
    /// against it at every checkpoint (1, 2, 4, … samples or passes).
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Write error against time as CSV: a "load" row, a "build" row, one "render" row per
    /// checkpoint.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Plot error against time, log-log (.png or .svg): against --reference if given, else
    /// the half-buffer estimate.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Stop once the estimated relative RMSE (half-buffer estimate, from 8 samples or
    /// passes on) is at or below E, finite and > 0. Upper bound: --time, --spp or
    /// --passes, whichever comes first; given alone, 120 s. Default without any budget
    /// flag: 0.03.
    #[arg(long, value_parser = parse_target, allow_hyphen_values = true)]
    target_error: Option<f64>,
    /// No progress bar.
    #[arg(short, long)]
    quiet: bool,
    /// Frame the model automatically from this view: threequarter (front-right, 35° above;
    /// the default for files without a camera), front, top, side. Replaces the file's
    /// camera; not with --camera.
    #[arg(long, value_parser = iris::framing::View::parse)]
    view: Option<iris::framing::View>,
    /// What camera rays that see no surface show: `env` (the default: the environment, or
    /// black), a colour (white, black, grey, #rrggbb, or R,G,B sRGB values in [0, 1]), or
    /// `transparent` (PNG with alpha, EXR with an A channel). The environment still lights
    /// the model; pixels count as covered when the camera ray hits a surface (glass too).
    #[arg(long, value_parser = iris::output::Background::parse)]
    background: Option<iris::output::Background>,
    #[command(flatten)]
    looks: LookArgs,
    /// Print the render plan to stderr before rendering: which stages the scene needs
    /// (spectral or RGB, photons, volumes, textures, acceleration, environment, nested
    /// media, denoise), why, and what each costs (a 32x24 probe render, 10 000 photons).
    #[arg(long)]
    explain: bool,
    /// Render only shard I of N (1 ≤ I ≤ N, counted from 1 like Slurm array indices) and
    /// write a partial image (-o PART.exr) for `iris merge`: with --spp/--passes T the
    /// units ⌊(I−1)T/N⌋..⌊I·T/N⌋; without, a segment of the Sobol' block until --time or
    /// --target-error (each per shard). Written only at the end.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    shard: Option<iris::app::shard::Shard>,
    /// Denoising with Intel Open Image Denoise (albedo and normals of the first
    /// non-specular surface seen through glass as auxiliary images): `auto` denoises a PNG
    /// and leaves an EXR raw, `on` denoises a PNG or adds the denoised image to an EXR as
    /// the layer `denoised` (channels denoised.R, .G, .B), `off` never.
    #[arg(long, default_value = "auto", value_parser = iris::denoise::DenoiseMode::parse)]
    denoise: iris::denoise::DenoiseMode,
}

#[derive(clap::Args)]
struct ConvergeArgs {
    /// Scene file (.gltf, .glb, .obj).
    scene: PathBuf,
    /// Methods to compare, comma-separated: whitted, path, photon, sppm, hybrid.
    #[arg(long, default_value = "path,photon,sppm")]
    methods: String,
    /// Time budget of each method in seconds (more than 0, at most 10000000).
    #[arg(long, value_parser = parse_seconds, allow_hyphen_values = true)]
    time: f64,
    /// Reference EXR; without it one is rendered for 4× --time (DIR/reference.exr).
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Output directory (created if missing).
    #[arg(short, long)]
    output: PathBuf,
    /// Image size WxH (default: the reference's, else 800 wide at the camera's aspect); at
    /// most 2^26 pixels (8192x8192) and 8 GiB of per-pixel buffers (about 55 M pixels;
    /// SPPM 19 M).
    #[arg(long, value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Random seed of the runs.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Numbers driving the camera paths: zsobol (default) or independent.
    #[arg(long, default_value = "zsobol", value_parser = SamplerKind::parse)]
    sampler: SamplerKind,
    /// Worker threads, 0 to 1024 (0 = one per core).
    #[arg(long, default_value_t = 0, value_parser = parse_threads())]
    threads: usize,
    /// Intersection backend: auto (Embree when compiled in), embree, bvh.
    #[arg(long, default_value = "auto", value_parser = Backend::parse)]
    accel: Backend,
    /// No progress output.
    #[arg(short, long)]
    quiet: bool,
    #[command(flatten)]
    looks: LookArgs,
}

fn parse_shard(s: &str) -> Result<iris::app::shard::Shard, String> {
    iris::app::shard::Shard::parse(s).map_err(|e| e.to_string())
}

fn parse_target(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "expected a relative error > 0, e.g. 0.05, got {s:?}"
        )),
    }
}

/// Largest `--time`, seconds (about 116 days).
const MAX_SECONDS: f64 = 1e7;

fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= MAX_SECONDS => Ok(v),
        _ => Err(format!(
            "expected seconds > 0 and at most {MAX_SECONDS}, got {s:?}"
        )),
    }
}

/// `--threads`: 0 to [`iris::render::MAX_THREADS`], checked before any thread is spawned.
fn parse_threads() -> clap::builder::RangedU64ValueParser<usize> {
    clap::builder::RangedU64ValueParser::new().range(0..=iris::render::MAX_THREADS as u64)
}

/// `gem --size`: millimetres in [0.1, 1000] ([`iris::model::cuts::size_metres`]).
fn parse_gem_size(s: &str) -> Result<f64, String> {
    use iris::model::cuts::{size_metres, MAX_SIZE_MM, MIN_SIZE_MM};
    match s.parse::<f64>() {
        Ok(v) if size_metres(v).is_ok() => Ok(v),
        _ => Err(format!(
            "expected millimetres from {MIN_SIZE_MM} to {MAX_SIZE_MM}, got {s:?}"
        )),
    }
}

fn parse_radius(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a finite radius > 0, got {s:?}")),
    }
}

fn parse_alpha(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v > 0.0 && v < 1.0 => Ok(v),
        _ => Err(format!("expected α strictly between 0 and 1, got {s:?}")),
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WxH, e.g. 800x600, got {s:?}"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in {s:?}"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in {s:?}"))?;
    app::check_size(w, h).map_err(|e| e.to_string())?;
    Ok((w, h))
}

fn parse_exposure(s: &str) -> Result<Exposure, String> {
    if s.eq_ignore_ascii_case("auto") {
        return Ok(Exposure::Auto);
    }
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v.abs() <= 64.0 => Ok(Exposure::Ev(v)),
        _ => Err(format!("expected `auto` or stops in [-64, 64], got {s:?}")),
    }
}

fn run(cli: Cli) -> iris::Result<()> {
    match cli.command {
        Command::Render(a) => app::commands::render(&a.options()?),
        Command::Converge(a) => app::commands::converge(&a.options()?),
        Command::Info { scene, looks } => app::commands::info(&scene, &looks.flags()?),
        Command::Diff {
            image,
            reference,
            exact,
        } => app::commands::diff(&image, &reference, exact),
        Command::Gem(a) => {
            let spec = iris::model::cuts::preview::GemSpec {
                cut: a.cut,
                stone: a.stone,
                size_mm: a.size,
                bare: a.bare,
            };
            app::commands::gem(&spec, &a.output)
        }
        Command::Gallery(a) => app::commands::gallery(&a.options()),
        Command::GenAssets { dir } => app::commands::gen_assets(&dir),
        Command::Turntable(a) => app::commands::turntable(&a.options()?),
        Command::Merge(a) => app::commands::merge(&iris::app::merge::MergeOptions {
            parts: a.parts,
            output: a.output,
            report: a.report,
            reference: a.reference,
            allow_partial: a.allow_partial,
            display: DisplayOptions {
                exposure: a.exposure,
                tonemap: a.tonemap,
            },
        }),
    }
}

impl RenderArgs {
    /// The render options (measurement and drop-in preview included) these flags ask for.
    fn options(&self) -> iris::Result<RenderOptions> {
        let a = self.clone();
        let budget = BudgetFlags {
            method: a.method,
            spp: a.spp,
            passes: a.passes,
            time: a.time.map(std::time::Duration::from_secs_f64),
            target_error: a.target_error,
        }
        .resolve();
        let options = RenderOptions {
            scene: a.scene,
            output: a.output,
            size: a.size,
            spp: budget.spp,
            method: budget.method,
            max_depth: a.max_depth,
            time_limit: budget.time_limit,
            checkpoint: a.checkpoint,
            watch: budget.open,
            photon: PhotonSettings {
                photons: a.photons.unwrap_or(0),
                radius: a.radius,
                alpha: a.alpha,
                passes: budget.passes,
                roulette: a.photon_rr,
                caustic_mode: a.caustics,
                ..PhotonSettings::default()
            },
            accel: a.accel,
            seed: a.seed,
            sampler: a.sampler,
            threads: a.threads,
            camera: a.camera,
            display: DisplayOptions {
                exposure: a.exposure,
                tonemap: a.tonemap,
            },
            quiet: a.quiet,
            env: a
                .env
                .as_deref()
                .map(iris::light::env::Environment::parse_arg)
                .transpose()?,
            spectral: a.spectral,
            measure: MeasureOptions {
                reference: a.reference,
                report: a.report,
                plot: a.plot,
                target_error: budget.target_error,
            },
            preview: app::PreviewOptions {
                studio: a.studio,
                ground: a.ground,
                view: a.view,
                background: a.background.unwrap_or_default(),
            },
            looks: a.looks.flags()?,
            explain: a.explain,
            denoise: a.denoise,
            spin: None,
            exr_copy: None,
            shard: a.shard,
        };
        Ok(options)
    }
}

impl TurntableArgs {
    /// The turntable options: the render flags of every frame and the turntable's own.
    fn options(&self) -> iris::Result<app::turntable::TurntableOptions> {
        use app::turntable::Step;
        let render = self.render.options()?;
        let dir = render.output.clone().ok_or_else(|| {
            iris::Error::Usage("iris turntable needs -o DIR, the frames' directory".into())
        })?;
        Ok(app::turntable::TurntableOptions {
            render,
            dir,
            frames: self.frames,
            step: match (self.frame, self.assemble) {
                (Some(f), _) => Step::Frame(f),
                (None, true) => Step::Assemble,
                (None, false) => Step::All,
            },
            fps: self.fps,
            exr: self.exr,
            gif: self.gif,
        })
    }
}

impl ConvergeArgs {
    /// The converge options these flags ask for.
    fn options(&self) -> iris::Result<ConvergeOptions> {
        Ok(ConvergeOptions {
            scene: self.scene.clone(),
            methods: parse_methods(&self.methods)?,
            time: std::time::Duration::from_secs_f64(self.time),
            reference: self.reference.clone(),
            out_dir: self.output.clone(),
            size: self.size,
            seed: self.seed,
            sampler: self.sampler,
            threads: self.threads,
            accel: self.accel,
            quiet: self.quiet,
            looks: self.looks.flags()?,
        })
    }
}

impl GalleryArgs {
    /// The gallery options, with the command line for the page: `iris` and the flags, after
    /// the shared-assets override when one was set (it decides which entries render).
    fn options(&self) -> iris::app::gallery::GalleryOptions {
        let mut args = std::env::args().skip(1).collect::<Vec<_>>();
        args.insert(0, "iris".into());
        if let Some(dir) = std::env::var_os("IRIS_SHARED_ASSETS") {
            args.insert(0, format!("IRIS_SHARED_ASSETS={}", dir.to_string_lossy()));
        }
        iris::app::gallery::GalleryOptions {
            out: self.out.clone(),
            size: self.size,
            time: self.time.map(std::time::Duration::from_secs_f64),
            only: self.only.clone(),
            quiet: self.quiet,
            command: args.join(" "),
        }
    }
}

/// Exit code of an interrupted run: 128 + SIGINT.
const INTERRUPTED: u8 = 130;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let handler = ctrlc::set_handler(|| {
        if iris::render::guard::stop_requested() {
            std::process::exit(INTERRUPTED.into());
        }
        eprintln!("\niris: stopping: finishing the samples in flight and writing the image (again to quit at once)");
        iris::render::guard::request_stop();
    });
    if let Err(e) = handler {
        eprintln!("warning: cannot catch Ctrl-C ({e}): an interrupted render writes nothing");
    }
    match run(cli) {
        Ok(()) if iris::render::guard::stop_requested() => ExitCode::from(INTERRUPTED),
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
