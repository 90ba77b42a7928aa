//! The `iris` command line as clap definitions: [`Cli`] with one [`Command`] per subcommand
//! (the binary `src/main.rs` parses it and dispatches to [`crate::app`]; `tests/cli/docs/mod.rs`
//! parses every command shown in the documentation with it). The flags, by command:
//! [`render_args`] (`iris render`, and the overrides shared with converge and info),
//! [`other_args`] (merge, turntable, gallery, gem, converge), [`gem_report_args`]
//! (gem-report), [`parse`] (value parsers with their bounds).

pub mod gem_report_args;
pub mod other_args;
mod parse;
pub mod render_args;

use clap::{Parser, Subcommand};
use gem_report_args::GemReportArgs;
use other_args::*;
use render_args::*;
use std::path::PathBuf;

/// The `iris` command line: one subcommand with its flags.
#[derive(Parser)]
#[command(
    name = "iris",
    version,
    about = "Iris: a spectral renderer for glass, gems and caustics"
)]
pub struct Cli {
    /// The command and its flags.
    #[command(subcommand)]
    pub command: Command,
    /// Say more about problems Iris recovered from while loading: when a third-party
    /// decoder (Draco, images) panics on a file, its error names the panic's message and
    /// source location (without --verbose: only that the decoder panicked).
    #[arg(long, global = true)]
    pub verbose: bool,
}

/// The commands, each with its flags.
#[derive(Subcommand)]
pub enum Command {
    /// Render a glTF (.gltf/.glb) or OBJ scene to PNG or EXR. With no --method, --spp,
    /// --passes, --time or --target-error: the method --method auto picks, rendered until
    /// the estimated error of the picture written is 0.01 (an EXR: relative error 0.03) or
    /// for 120 s, whichever comes first (or Ctrl-C), the output rewritten as it improves;
    /// the last line says what ended it.
    Render(RenderArgs),
    /// Describe a scene: meshes, triangles, materials with their KHR values, lights, cameras.
    Info {
        /// Scene file.
        scene: PathBuf,
        /// `--stone`, `--metal`, `--metal-roughness`.
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
    /// The gemologist's images and cut figures of a stone: ASET and Ideal-Scope images
    /// face-up and tilted, light return, obscuration and leakage (overall and by zone),
    /// brilliance, fire and scintillation (flashes), rendered under the standard
    /// instruments, into DIR as PNGs, report.md, report.html and report.json. Nothing is
    /// written unless everything rendered.
    GemReport(GemReportArgs),
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
    /// Look at a scene live in the browser: a local web server (127.0.0.1 only, a random
    /// token in the URL it prints) showing the render as it refines; orbit, zoom and pan
    /// with the mouse, turn the model, choose stone, metal, studio, environment, exposure,
    /// method and spectral mode, and render the final image with the `iris render` command
    /// line that reproduces it. Ctrl-C stops the server.
    View(ViewArgs),
}

/// The long names of the `iris render` flags (`spp`, `camera-look-at`, …, their aliases
/// too), without `help` and `version`: what a caller building the arguments from names
/// (the Python module's keyword arguments) may pass to [`parse_render`].
pub fn render_flags() -> Vec<String> {
    use clap::CommandFactory;
    let cli = Cli::command();
    let Some(render) = cli.get_subcommands().find(|c| c.get_name() == "render") else {
        return Vec::new();
    };
    let mut names: Vec<String> = render
        .get_arguments()
        .chain(cli.get_arguments().filter(|a| a.is_global_set()))
        .flat_map(|a| {
            a.get_long()
                .into_iter()
                .chain(a.get_all_aliases().into_iter().flatten())
        })
        .filter(|n| !matches!(*n, "help" | "version"))
        .map(String::from)
        .collect();
    names.sort();
    names.dedup();
    names
}

/// `iris render ARGS…` (the arguments after `render`) parsed and checked as the command
/// line does: the live view and the Python module build their renders through this, so
/// every value obeys the flags' rules and a printed command line reproduces the render.
/// A bad flag or value is a usage error naming it (clap's first line).
pub fn parse_render(args: &[String]) -> crate::Result<crate::app::RenderOptions> {
    let argv = ["iris", "render"]
        .into_iter()
        .map(String::from)
        .chain(args.iter().cloned());
    let cli = Cli::try_parse_from(argv).map_err(|e| {
        let text = e.to_string();
        let first = text.lines().next().unwrap_or("bad arguments");
        crate::Error::Usage(first.trim_start_matches("error: ").to_string())
    })?;
    match cli.command {
        Command::Render(a) => a.options(),
        _ => Err(crate::Error::Usage("expected render arguments".into())),
    }
}
