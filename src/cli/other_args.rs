//! The flags of `iris merge`, `iris turntable`, `iris gallery`, `iris gem` and
//! `iris converge`: clap structs and their conversion into the app's options.

use super::parse::*;
use super::render_args::{LookArgs, PngArgs, RenderArgs};
use crate::accel::Backend;
use crate::app;
use crate::app::converge::{parse_methods, ConvergeOptions};
use crate::sampler::SamplerKind;
use std::path::PathBuf;

/// `iris merge`: the shards' partial images, the output and the merge's measurements.
#[derive(clap::Args)]
pub struct MergeArgs {
    /// The shards' partial images.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Output file: .exr (linear) or .png (tone-mapped).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Write the merge's error row as CSV (iris render's columns, stage `merge`).
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Reference EXR (same size): the merged image's error against it.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Merge what is there when shards (or samples) are missing, and say how many samples
    /// each pixel got.
    #[arg(long)]
    pub allow_partial: bool,
    /// PNG exposure and tone map.
    #[command(flatten)]
    pub png: PngArgs,
}

/// `iris turntable`: the turn's own flags and every `iris render` flag for each frame.
#[derive(clap::Args)]
pub struct TurntableArgs {
    /// Frames in the whole turn, 1 to 10000.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(crate::prepare::turntable::MAX_FRAMES)))]
    pub frames: u32,
    /// Render only frame F (0 to frames − 1) and no animation.
    #[arg(long, value_name = "F", conflicts_with = "assemble")]
    pub frame: Option<u32>,
    /// Render nothing: check that every frame is in DIR and write the animation.
    #[arg(long)]
    pub assemble: bool,
    /// Frames per second of the animation, 1 to 50 (GIF rounds the delay to whole
    /// centiseconds).
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u32).range(1..=i64::from(crate::output::animation::MAX_FPS)))]
    pub fps: u32,
    /// Also write each frame as linear EXR (DIR/frame_0000.exr).
    #[arg(long)]
    pub exr: bool,
    /// Also write the animation as GIF (DIR/turntable.gif; 256 colours a frame, lossy).
    #[arg(long)]
    pub gif: bool,
    /// The flags of each frame's render.
    #[command(flatten)]
    pub render: RenderArgs,
}

/// `iris gallery`: where the page goes, the image size, the budget and which entries.
#[derive(clap::Args)]
pub struct GalleryArgs {
    /// Output directory (created if missing).
    #[arg(long, default_value = "docs/gallery")]
    pub out: PathBuf,
    /// Image size WxH (576x324 keeps the committed gallery under 4 MB of PNG); at most
    /// 2^26 pixels (8192x8192).
    #[arg(long, default_value = "576x324", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Time limit of each image's render, seconds (more than 0, at most 10000000): the
    /// whole budget, as `iris render --time`. Default: `iris render`'s default budget
    /// (estimated error 0.03 of the written image, or 120 s).
    #[arg(long, value_parser = parse_seconds)]
    pub time: Option<f64>,
    /// Render only the entries whose name contains SUBSTR (repeatable); an existing page in
    /// the output directory keeps its other entries.
    #[arg(long, value_name = "SUBSTR")]
    pub only: Vec<String>,
    /// No progress output.
    #[arg(short, long)]
    pub quiet: bool,
}

/// `iris gem`: the cut, the stone, its size and whether the preview scene is added.
#[derive(clap::Args)]
pub struct GemArgs {
    /// Cut: round (Tolkowsky brilliant), emerald (step cut), oval (brilliant, L/W 1.4),
    /// pear (brilliant, L/W 1.6).
    #[arg(long, value_parser = crate::authoring::cuts::Cut::parse)]
    pub cut: crate::authoring::cuts::Cut,
    /// Stone: diamond, sapphire, ruby, emerald, cubic-zirconia, quartz, crown-glass, calcite,
    /// zircon, peridot, tourmaline, tanzanite, topaz, moissanite, rutile.
    #[arg(long, value_parser = crate::authoring::stones::Stone::parse)]
    pub stone: crate::authoring::stones::Stone,
    /// Girdle diameter (round) or length (emerald, oval, pear) in millimetres, from 0.1 to
    /// 1000.
    #[arg(long, default_value_t = crate::authoring::cuts::DEFAULT_SIZE_MM, value_parser = parse_gem_size, allow_hyphen_values = true)]
    pub size: f64,
    /// Only the stone: no camera, lights or floor.
    #[arg(long)]
    pub bare: bool,
    /// Output .glb file.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// `iris converge`: the scene, the methods, the common budget and the runs' settings.
#[derive(clap::Args)]
pub struct ConvergeArgs {
    /// Scene file (.gltf, .glb, .obj).
    pub scene: PathBuf,
    /// Methods to compare, comma-separated: whitted, path, photon, sppm, hybrid, vcm, bpt.
    #[arg(long, default_value = "path,photon,sppm")]
    pub methods: String,
    /// Time budget of each method in seconds (more than 0, at most 10000000).
    #[arg(long, value_parser = parse_seconds, allow_hyphen_values = true)]
    pub time: f64,
    /// Reference EXR; without it one is rendered for 4× --time (DIR/reference.exr).
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Output directory (created if missing).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Image size WxH (default: the reference's, else 800 wide at the camera's aspect); at
    /// most 2^26 pixels (8192x8192) and 8 GiB of per-pixel buffers (about 55 M pixels;
    /// SPPM 19 M).
    #[arg(long, value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Random seed of the runs.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Numbers driving the camera paths: zsobol (default) or independent.
    #[arg(long, default_value = "zsobol", value_parser = SamplerKind::parse)]
    pub sampler: SamplerKind,
    /// Worker threads, 0 to 1024 (0 = one per core).
    #[arg(long, default_value_t = 0, value_parser = parse_threads())]
    pub threads: usize,
    /// Intersection backend: auto (Embree when compiled in), embree, bvh.
    #[arg(long, default_value = "auto", value_parser = Backend::parse)]
    pub accel: Backend,
    /// No progress output.
    #[arg(short, long)]
    pub quiet: bool,
    /// `--stone`, `--metal`, `--metal-roughness`.
    #[command(flatten)]
    pub looks: LookArgs,
}

impl TurntableArgs {
    /// The turntable options: the render flags of every frame and the turntable's own.
    pub fn options(&self) -> crate::Result<app::turntable::TurntableOptions> {
        use app::turntable::Step;
        let render = self.render.options()?;
        let dir = render.output.clone().ok_or_else(|| {
            crate::Error::Usage("iris turntable needs -o DIR, the frames' directory".into())
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
    pub fn options(&self) -> crate::Result<ConvergeOptions> {
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
    pub fn options(&self) -> crate::app::gallery::GalleryOptions {
        let mut args = std::env::args().skip(1).collect::<Vec<_>>();
        args.insert(0, "iris".into());
        if let Some(dir) = std::env::var_os("IRIS_SHARED_ASSETS") {
            args.insert(0, format!("IRIS_SHARED_ASSETS={}", dir.to_string_lossy()));
        }
        crate::app::gallery::GalleryOptions {
            out: self.out.clone(),
            size: self.size,
            time: self.time.map(std::time::Duration::from_secs_f64),
            only: self.only.clone(),
            quiet: self.quiet,
            command: args.join(" "),
        }
    }
}

/// `iris view`: the live view's flags.
#[derive(clap::Args)]
pub struct ViewArgs {
    /// Scene file (.gltf, .glb, .obj).
    pub scene: PathBuf,
    /// Port on 127.0.0.1 (0: a free port the system chooses).
    #[arg(long, default_value_t = 0)]
    pub port: u16,
    /// Do not start a browser (print the URL only).
    #[arg(long)]
    pub no_open: bool,
    /// Width of the live image in pixels, 64 to 1920 (the height from the camera's aspect).
    #[arg(long, default_value_t = 640, value_parser = clap::value_parser!(u32).range(64..=1920))]
    pub width: u32,
    /// Worker threads, 0 to 1024 (0 = one per core).
    #[arg(long, default_value_t = 0, value_parser = parse_threads())]
    pub threads: usize,
    /// Directory for the final renders (`<scene>-view-<k>.png`).
    #[arg(long, default_value = ".")]
    pub out_dir: PathBuf,
}
