//! The `iris` command line: parses flags, calls [`iris::app`], prints a summary, and turns
//! errors into a message on stderr and a non-zero exit code.
//!
//! Interruption ([`iris::interrupt`]): during a render, the first SIGINT (Ctrl-C) or
//! SIGTERM asks it to stop ([`iris::render::guard::request_stop`]); it finishes the tiles
//! (SPPM: the pass) in flight, writes the image so far atomically, says so, and exits with
//! 130 (128 + SIGINT, so shells and scripts see the interruption). Outside a render
//! (loading, reading or merging images) nothing would act on the request, so the signal
//! exits at once with 130, as a second signal always does; outputs are written to a
//! temporary name and renamed, and an exit waits for a write in flight, so no half-written
//! or temporary file is left.
#![forbid(unsafe_code)]

use clap::Parser;
use iris::app;
use iris::cli::{Cli, Command};
use std::process::ExitCode;

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
            let spec = iris::authoring::cuts::preview::GemSpec {
                cut: a.cut,
                stone: a.stone,
                size_mm: a.size,
                bare: a.bare,
            };
            app::commands::gem(&spec, &a.output)
        }
        Command::Gallery(a) => app::commands::gallery(&a.options()),
        Command::GemReport(a) => app::commands::gem_report(&a.options()?),
        Command::GenAssets { dir } => app::commands::gen_assets(&dir),
        Command::Turntable(a) => app::commands::turntable(&a.options()?),
        Command::View(a) => iris::view::view_command(&iris::view::ViewOptions {
            scene: a.scene,
            port: a.port,
            open: !a.no_open,
            width: a.width,
            threads: a.threads,
            out_dir: a.out_dir,
        }),
        Command::Merge(a) => app::commands::merge(&iris::app::merge::MergeOptions {
            parts: a.parts,
            output: a.output,
            report: a.report,
            reference: a.reference,
            allow_partial: a.allow_partial,
            display: a.png.display(),
        }),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    iris::load::panic_net::show_caught_panics(cli.verbose);
    let handler = ctrlc::set_handler(|| {
        if iris::render::guard::stop_requested() || !iris::interrupt::honoured() {
            iris::interrupt::exit_now();
        }
        eprintln!("\niris: stopping: finishing the work in flight and writing what is done (again to quit at once)");
        iris::render::guard::request_stop();
    });
    if let Err(e) = handler {
        eprintln!("warning: cannot catch Ctrl-C ({e}): an interrupted render writes nothing");
    }
    match run(cli) {
        Ok(()) if iris::render::guard::stop_requested() => {
            ExitCode::from(iris::interrupt::EXIT_INTERRUPTED)
        }
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
