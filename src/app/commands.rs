//! One function per `iris` command: each takes the options main.rs parsed from the flags,
//! runs the command through the library, and prints what the command prints (summaries on
//! stderr, tables on stdout). main.rs calls exactly one of these per command.

use super::RenderOptions;
use crate::app::converge::{converge_command, ConvergeOptions};
use crate::error::Result;
use crate::measure::relative_rmse;
use std::path::Path;

/// `iris render`: renders, prints the notes, warnings and a summary line, then what ended
/// the render ([`super::RenderSummary::end_text`]) with the error estimate (and the error
/// against `--reference` when given). With `--explain` the
/// plan and its measured costs go to stderr before the render starts.
pub fn render(opts: &RenderOptions) -> Result<()> {
    let job = super::RenderJob::new(opts)?;
    if opts.explain {
        eprint!("{}", job.plan.text_with_costs());
    }
    let s = job.run()?;
    for n in &s.notes {
        eprintln!("note: {n}");
    }
    if s.stats.bad_samples > 0 {
        eprintln!(
            "warning: {} samples were NaN or infinite and were left out of the image (a numerical failure: please report it with the scene)",
            s.stats.bad_samples
        );
    }
    let secs = s.stats.time.as_secs_f64();
    let work = s.work_done();
    eprintln!(
        "iris: {} -> {}: {}x{}, {}, {} triangles, {}, render {:.2} s (load {:.2} s, build {:.2} s), {:.2} Mrays/s",
        opts.scene.display(),
        s.output.display(),
        s.image.width,
        s.image.height,
        work,
        s.triangles,
        s.backend,
        secs,
        s.load_time.as_secs_f64(),
        s.build_time.as_secs_f64(),
        s.stats.rays as f64 / secs.max(1e-9) / 1e6
    );
    // What ended the render, then the image's error: estimated (unless the end's words
    // gave it, with the target), and against the reference.
    let mut line = format!("iris: {}", s.end_text());
    // One sample (pass) makes both half images that sample: no estimate then.
    let estimated = s.rows.last().is_some_and(|r| r.samples >= 2);
    let said = s.target_estimate.is_some();
    let display = s.rows.last().and_then(|r| r.display_estimate);
    if let Some(e) = display.filter(|_| !said) {
        line.push_str(&format!("; estimated display error {e:.4}"));
    } else if let Some(e) = s.final_estimate().filter(|_| estimated && !said) {
        line.push_str(&format!(
            "; estimated relative error {:.4}",
            relative_rmse(&e)
        ));
    }
    if let Some(r) = s.final_error() {
        line.push_str(&format!(
            ", against the reference {:.4} (rmse {:.4e}, mae {:.4e})",
            relative_rmse(&r),
            r.rmse,
            r.mae
        ));
    }
    if let Some(d) = s.final_denoised_error() {
        line.push_str(&format!(", denoised {:.4}", relative_rmse(&d)));
    }
    eprintln!("{line}");
    Ok(())
}

/// `iris turntable`: renders the frames (each frame's turn and output, then its summary
/// line; the first frame's notes), then says where the animation went, or which frame an
/// interruption stopped.
pub fn turntable(opts: &super::turntable::TurntableOptions) -> Result<()> {
    use super::turntable::{turntable_command, Event};
    let total = opts.frames;
    let mut first = true;
    let s = turntable_command(opts, |event| match event {
        Event::Note(n) => eprintln!("note: {n}"),
        Event::Starting {
            frame,
            degrees,
            plan,
        } => {
            if let Some(p) = plan {
                eprint!("{p}");
            }
            if !opts.render.quiet {
                eprintln!(
                    "iris: frame {frame} of {total} (0–{}), {degrees:.2}°",
                    total - 1
                );
            }
        }
        Event::Done {
            frame,
            output,
            summary,
        } => {
            if first {
                for n in &summary.notes {
                    eprintln!("note: {n}");
                }
                first = false;
            }
            eprintln!(
                "iris: frame {frame} -> {}: {}x{}, {}, render {:.2} s; {}",
                output.display(),
                summary.image.width,
                summary.image.height,
                summary.work_done(),
                summary.stats.time.as_secs_f64(),
                summary.end_text()
            );
        }
    })?;
    if let Some(f) = s.interrupted {
        eprintln!(
            "iris: interrupted (Ctrl-C or SIGTERM) during frame {f}: its partial image was \
             removed; {} frame(s) done, no animation written (render the rest with --frame F, \
             then --assemble)",
            s.rendered.len()
        );
    }
    if let Some(a) = &s.assembled {
        eprintln!(
            "iris: {} frames {}x{} at {} fps -> {}{}",
            a.frames,
            a.size.0,
            a.size.1,
            a.fps,
            a.apng.display(),
            a.gif
                .as_ref()
                .map(|g| format!(" and {}", g.display()))
                .unwrap_or_default()
        );
    }
    Ok(())
}

/// `iris merge`: merges the parts, then prints what was merged, the samples per pixel, the
/// estimated error (and against `--reference`), and the missing ranges under
/// `--allow-partial`.
pub fn merge(opts: &super::merge::MergeOptions) -> Result<()> {
    let s = super::merge::merge_command(opts)?;
    for m in &s.missing {
        eprintln!("warning: {m} (--allow-partial: merged without them)");
    }
    if s.counts.2 > 0 {
        eprintln!(
            "warning: {} samples were NaN, infinite or out of range and were left out of the parts",
            s.counts.2
        );
    }
    let total = s
        .total
        .map_or("an open budget".to_string(), |t| format!("{t} {}", s.unit));
    let (lo, hi) = s.units_per_pixel;
    let per_pixel = if lo == hi {
        format!("{lo} {} per pixel", s.unit)
    } else {
        format!("{lo} to {hi} {} per pixel", s.unit)
    };
    let mut line = format!(
        "iris: merged {} of {} shards of {total} ({}) -> {}: {}x{}, {per_pixel}",
        s.parts,
        s.shards,
        s.method,
        s.output.display(),
        s.image.width,
        s.image.height
    );
    if let Some(e) = &s.estimate {
        line.push_str(&format!(
            "; estimated relative error {:.4}",
            relative_rmse(e)
        ));
    }
    if let Some(r) = &s.error {
        line.push_str(&format!(
            ", against the reference {:.4} (rmse {:.4e}, mae {:.4e})",
            relative_rmse(r),
            r.rmse,
            r.mae
        ));
    }
    eprintln!("{line}");
    Ok(())
}

/// `iris converge`: runs every method for the same time, prints one line per run, the
/// table of who reached each error level first, and the files written.
pub fn converge(opts: &ConvergeOptions) -> Result<()> {
    let s = converge_command(opts)?;
    for n in &s.notes {
        eprintln!("note: {n}");
    }
    if let Some((m, path)) = &s.rendered_reference {
        println!(
            "reference: rendered with {} for {:.1} s -> {}",
            m.name(),
            4.0 * opts.time.as_secs_f64(),
            path.display()
        );
    }
    for r in &s.runs {
        println!(
            "{}: {:.2} s, {} spp, {} passes, {} photons, relative error {:.4}",
            r.name,
            r.stats.time.as_secs_f64(),
            r.spp,
            r.stats.passes,
            r.stats.photons,
            r.relative_error
        );
    }
    print!("{}", s.table);
    for f in &s.files {
        eprintln!("wrote {}", f.display());
    }
    Ok(())
}

/// `iris info`: prints the scene's description and the render plan (after any `--stone` /
/// `--metal` overrides).
pub fn info(scene: &Path, looks: &[crate::prepare::looks::LookFlag]) -> Result<()> {
    print!("{}", super::info_command_with(scene, looks)?);
    Ok(())
}

/// `iris diff`: prints RMSE, relative RMSE, relative MSE and the means of an image and its
/// reference.
pub fn diff(image: &Path, reference: &Path, exact: bool) -> Result<()> {
    let d = super::diff_command(image, reference)?;
    println!(
        "rmse {:.6e} relative {:.6e} relmse {:.6e} mean {:.6e} reference mean {:.6e} \
         differing pixels {}",
        d.rmse, d.relative_rmse, d.rel_mse, d.mean, d.reference_mean, d.differing
    );
    if exact && d.differing > 0 {
        return Err(crate::error::Error::Usage(format!(
            "{} and {} are not bit-identical: {} pixels differ (--exact)",
            image.display(),
            reference.display(),
            d.differing
        )));
    }
    Ok(())
}

/// `iris gem`: writes the gem's .glb and says so.
pub fn gem(spec: &crate::authoring::cuts::preview::GemSpec, output: &Path) -> Result<()> {
    crate::fileio::output::check_file(output)?;
    crate::authoring::cuts::preview::write_gem(output, spec)?;
    eprintln!("wrote {}", output.display());
    Ok(())
}

/// `iris gallery`: renders the entries and writes the page, one line per image.
pub fn gallery(opts: &crate::app::gallery::GalleryOptions) -> Result<()> {
    let s = crate::app::gallery::run(opts)?;
    for r in &s.rendered {
        eprintln!(
            "{}: {}, {}, render {:.2} s -> {}",
            r.entry.name,
            r.summary.method.name(),
            r.summary.work_done(),
            r.summary.stats.time.as_secs_f64(),
            r.summary.output.display()
        );
    }
    eprintln!("wrote {}", s.page.display());
    Ok(())
}

/// `iris gen-assets`: regenerates the project's scenes under `dir`, one line per file.
pub fn gen_assets(dir: &Path) -> Result<()> {
    crate::fileio::output::check_dir(dir)?;
    for p in crate::assets::write_all_assets(dir)? {
        eprintln!("wrote {}", p.display());
    }
    Ok(())
}

/// `iris gem-report`: renders the shots (a line each, unless `--quiet`), then prints the
/// face-up figures on stdout and where the report went; after an interruption says that
/// nothing was written.
pub fn gem_report(opts: &crate::app::gem_report::GemReportOptions) -> Result<()> {
    let r = crate::app::gem_report::gem_report(opts)?;
    let Some(f) = &r.figures else {
        eprintln!(
            "iris: gem-report interrupted after {} renders: nothing written to {}",
            r.renders.len(),
            opts.out_dir.display()
        );
        return Ok(());
    };
    let p = |x: f64| 100.0 * x;
    let u = &f.face_up;
    println!(
        "light return {:.1} %  (high {:.1} %, low {:.1} %)  obscured {:.1} %  leakage {:.1} %  other {:.1} %",
        p(u.light_return()),
        p(u.high),
        p(u.low),
        p(u.obscured),
        p(u.leakage),
        p(u.other)
    );
    println!(
        "brilliance {:.1} %  fire {:.1} % (median spread {:.2}°)  flashes {} ({:.1} % lit)",
        p(f.brilliance),
        p(f.fire),
        f.median_spread,
        f.flashes,
        p(f.lit)
    );
    eprintln!(
        "iris: gem-report {} -> {}: {} renders, {} files, {:.2} s",
        opts.scene.display(),
        opts.out_dir.display(),
        r.renders.len(),
        r.written.len(),
        r.time.as_secs_f64()
    );
    Ok(())
}
