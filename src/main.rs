//! The `iris` command line: parses flags, calls [`iris::app`], prints a summary, and turns
//! errors into a message on stderr and a non-zero exit code.
//!
//! Interruption: the first SIGINT (Ctrl-C) or SIGTERM asks the render to stop
//! ([`iris::render::guard::request_stop`]); it finishes the tiles (SPPM: the pass) in
//! flight, writes the image so far atomically, says so, and exits with 130 (128 + SIGINT,
//! so shells and scripts see the interruption). A second one exits at once with 130;
//! outputs are written to a temporary name and renamed, so no half-written file is left
//! under the output's name.
#![forbid(unsafe_code)]

mod cli;

use clap::{Parser, Subcommand};
use cli::other_args::*;
use cli::render_args::*;
use iris::app;
use iris::output::DisplayOptions;
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
