//! `iris gem-report STONE -o DIR`: the gemologist's images and cut figures of any glTF (or
//! OBJ) stone, rendered by Iris under the standard instruments.
//!
//! What it does, in order:
//! 1. checks the flags ([`check`]: size, samples, tilts, the output directory), before
//!    loading anything;
//! 2. puts the stone on the gem stage ([`crate::prepare::stage`]: the transmissive
//!    meshes alone, table up, centred; an error naming the file and its meshes if there
//!    is none);
//! 3. renders the shots ([`shots`]): ASET and Ideal-Scope face-up and at each tilt, the
//!    face-up view under the overcast sky, the direction code at the F, d and C lines,
//!    the spot dome at the C, d and F lines ([`crate::studio::instrument`]);
//! 4. measures the figures ([`figures`]: light return, obscuration, leakage overall, by
//!    zone and by tilt; brilliance; fire; scintillation);
//! 5. only then writes DIR (created if missing): the PNGs, `report.md`, `report.html` and
//!    `report.json` ([`pictures`], [`page`], [`json`]), each atomically. An error or a
//!    Ctrl-C before step 5 writes nothing.
//!
//! Determinism: fixed sample counts, Whitted tracing with per-pixel seeds and the film's
//! exact sums make the same file and flags give the same bytes on any thread count
//! (`report.json` holds no times); `--time` caps each render by wall time instead, and
//! then the images depend on the machine.

pub mod figures;
mod json;
mod outputs;
mod page;
mod pictures;
pub mod shots;

pub use figures::Figures;

use crate::error::{Error, Result};
use crate::image::{Coverage, ImageRgb};
use crate::light::env::Environment;
use crate::prepare::looks::LookFlag;
use crate::prepare::stage::{GemStage, Table};
use crate::studio::instrument::Instrument;
use glam::Vec3;
use shots::{Rendered, Settings, Shot};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Default image side, pixels.
pub const DEFAULT_SIZE: u32 = 400;
/// Default samples per pixel (the direction code takes one).
pub const DEFAULT_SPP: u32 = 8;
/// Default tilts besides face-up, degrees.
pub const DEFAULT_TILTS: [f32; 3] = [10.0, 20.0, 30.0];
/// Image sides accepted, pixels (every image of a report is kept in memory until the
/// figures are measured: at 2048 px about 50 MB each).
pub const SIZES: std::ops::RangeInclusive<u32> = 16..=2048;
/// Largest `--spp`.
pub const MAX_SPP: u32 = 4096;
/// Largest |tilt|, degrees.
pub const MAX_TILT: f32 = 60.0;
/// Most tilts besides face-up.
pub const MAX_TILTS: usize = 12;

/// Everything `iris gem-report` needs.
#[derive(Debug, Clone)]
pub struct GemReportOptions {
    /// The stone's file.
    pub scene: PathBuf,
    /// Output directory.
    pub out_dir: PathBuf,
    /// Image side, pixels.
    pub size: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// Tilts besides face-up, degrees.
    pub tilts: Vec<f32>,
    /// Wall-time cap of each render.
    pub time_limit: Option<Duration>,
    /// Worker threads (0 = all).
    pub threads: usize,
    /// Seed.
    pub seed: u64,
    /// Intersection backend.
    pub accel: crate::accel::Backend,
    /// `--stone` flags.
    pub looks: Vec<LookFlag>,
    /// How the table direction is found.
    pub table: Table,
    /// No progress lines.
    pub quiet: bool,
    /// The command line, for the page.
    pub command: String,
}

impl GemReportOptions {
    /// The defaults for `scene` into `out_dir`.
    pub fn new(scene: &Path, out_dir: &Path) -> GemReportOptions {
        GemReportOptions {
            scene: scene.to_path_buf(),
            out_dir: out_dir.to_path_buf(),
            size: DEFAULT_SIZE,
            spp: DEFAULT_SPP,
            tilts: DEFAULT_TILTS.to_vec(),
            time_limit: None,
            threads: 0,
            seed: 0,
            accel: crate::accel::Backend::Auto,
            looks: Vec::new(),
            table: Table::Auto,
            quiet: false,
            command: String::new(),
        }
    }
}

/// What the stone on the stage is (for the page).
#[derive(Debug, Clone)]
pub struct StoneInfo {
    /// Its mesh names.
    pub meshes: Vec<String>,
    /// Table direction in the file's frame.
    pub table: Vec3,
    /// Whether `auto` found the table as a facet.
    pub table_found: bool,
    /// Girdle radius, file units.
    pub girdle_radius: f32,
    /// Height along the axis, file units.
    pub height: f32,
    /// Whether the stone is birefringent (each picture the mean of its two modes').
    pub birefringent: bool,
}

/// What a report did.
pub struct GemReport {
    /// The stone.
    pub stone: StoneInfo,
    /// The figures (`None` when interrupted).
    pub figures: Option<Figures>,
    /// Each render: label, samples per pixel, time.
    pub renders: Vec<(String, u64, Duration)>,
    /// The files written, in order (empty when interrupted).
    pub written: Vec<PathBuf>,
    /// Wall time of the whole report.
    pub time: Duration,
}

/// Checks the flags that need no file (see [`GemReportOptions`]'s limits).
pub fn check(opts: &GemReportOptions) -> Result<()> {
    if !SIZES.contains(&opts.size) {
        return Err(Error::Usage(format!(
            "--size {}: the image side must be {} to {} pixels",
            opts.size,
            SIZES.start(),
            SIZES.end()
        )));
    }
    if opts.spp == 0 || opts.spp > MAX_SPP {
        return Err(Error::Usage(format!(
            "--spp {}: samples per pixel must be 1 to {MAX_SPP}",
            opts.spp
        )));
    }
    check_tilts(&opts.tilts)?;
    crate::render::check_threads(opts.threads)?;
    if opts.out_dir.exists() && !opts.out_dir.is_dir() {
        return Err(Error::Usage(format!(
            "-o {}: exists and is not a directory",
            opts.out_dir.display()
        )));
    }
    crate::fileio::output::check_dir(&opts.out_dir)?;
    Ok(())
}

/// Tilts: finite, non-zero (face-up is always rendered), |t| ≤ [`MAX_TILT`], distinct,
/// at most [`MAX_TILTS`].
fn check_tilts(tilts: &[f32]) -> Result<()> {
    if tilts.len() > MAX_TILTS {
        return Err(Error::Usage(format!(
            "--tilts: at most {MAX_TILTS} tilts (face-up comes on its own)"
        )));
    }
    for (i, &t) in tilts.iter().enumerate() {
        if !t.is_finite() || t == 0.0 || t.abs() > MAX_TILT {
            return Err(Error::Usage(format!(
                "--tilts {t}: each tilt must be non-zero (face-up comes on its own) and at \
                 most {MAX_TILT}° either way"
            )));
        }
        if tilts[..i].contains(&t) {
            return Err(Error::Usage(format!("--tilts: {t}° is given twice")));
        }
    }
    Ok(())
}

/// `iris gem-report`: see the module docs.
pub fn gem_report(opts: &GemReportOptions) -> Result<GemReport> {
    let start = Instant::now();
    check(opts)?;
    let tilts: Vec<f32> = std::iter::once(0.0)
        .chain(opts.tilts.iter().copied())
        .collect();
    let stage = GemStage::new(&opts.scene, &opts.looks, opts.table, &tilts)?;
    let stone = StoneInfo {
        meshes: stage.meshes.clone(),
        table: stage.table,
        table_found: stage.table_found,
        girdle_radius: stage.girdle_radius,
        height: stage.height,
        birefringent: stage.birefringent,
    };
    let settings = Settings {
        size: opts.size,
        spp: opts.spp,
        time_limit: opts.time_limit,
        threads: opts.threads,
        seed: opts.seed,
        accel: opts.accel,
    };
    let list = shots::shots(&tilts);
    let mut report = GemReport {
        stone,
        figures: None,
        renders: Vec::new(),
        written: Vec::new(),
        time: Duration::ZERO,
    };
    let Some(images) = render_all(&stage, opts, &settings, &list, &mut report)? else {
        report.time = start.elapsed();
        return Ok(report);
    };
    let covers = tilts
        .iter()
        .map(|&t| shots::coverage(&stage, &opts.scene, t, &settings))
        .collect::<Result<Vec<Coverage>>>()?;
    let layout = figures::Layout {
        girdle_px: stage.girdle_radius / stage.half_field * 0.5 * opts.size as f32,
    };
    let set = pictures::Images::new(&list, &images, &tilts);
    let figs = figures::measure(&set, &covers, layout);
    report.written = outputs::write_outputs(opts, &set, &report, &figs)?;
    report.figures = Some(figs);
    report.time = start.elapsed();
    Ok(report)
}

/// Renders every shot, building each instrument's lighting once (shots of one instrument
/// are consecutive after sorting); `None` when a stop request cut a render short.
fn render_all(
    stage: &GemStage,
    opts: &GemReportOptions,
    settings: &Settings,
    list: &[Shot],
    report: &mut GemReport,
) -> Result<Option<Vec<ImageRgb>>> {
    let mut order: Vec<usize> = (0..list.len()).collect();
    order.sort_by_key(|&i| instrument_rank(list[i].instrument));
    let mut images: Vec<Option<ImageRgb>> = vec![None; list.len()];
    let mut built: Option<(Instrument, Environment)> = None;
    // A signal stops the shot in flight, and nothing is written.
    let _honour = crate::interrupt::Honour::begin();
    for (k, &i) in order.iter().enumerate() {
        let shot = &list[i];
        let lighting = match built.take() {
            Some((kind, env)) if kind == shot.instrument => (kind, env),
            _ => (shot.instrument, shot.instrument.environment()?),
        };
        let rendered = shots::render(stage, &opts.scene, shot, &lighting.1, settings);
        built = Some(lighting);
        let Rendered {
            image,
            spp,
            time,
            interrupted,
        } = rendered?;
        if !opts.quiet {
            eprintln!(
                "gem-report: {}/{} {}: {spp} spp, {:.2} s",
                k + 1,
                list.len(),
                shot.label(),
                time.as_secs_f64()
            );
        }
        report.renders.push((shot.label(), spp, time));
        if interrupted || crate::render::guard::stop_requested() {
            return Ok(None);
        }
        images[i] = Some(image);
    }
    Ok(Some(images.into_iter().flatten().collect()))
}

/// Sort key grouping shots by instrument (the order of [`shots::shots`] within a group).
fn instrument_rank(i: Instrument) -> u8 {
    match i {
        Instrument::Aset => 0,
        Instrument::IdealScope => 1,
        Instrument::Overcast => 2,
        Instrument::Directions => 3,
        Instrument::Spots => 4,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_are_checked_before_loading() {
        let ok = GemReportOptions::new(Path::new("missing.glb"), Path::new("out"));
        assert!(check(&ok).is_ok());
        let bad = |f: &dyn Fn(&mut GemReportOptions)| {
            let mut o = ok.clone();
            f(&mut o);
            check(&o).unwrap_err().to_string()
        };
        assert!(bad(&|o| o.size = 8).contains("--size 8"));
        assert!(bad(&|o| o.spp = 0).contains("--spp 0"));
        assert!(bad(&|o| o.tilts = vec![0.0]).contains("--tilts 0"));
        assert!(bad(&|o| o.tilts = vec![70.0]).contains("--tilts 70"));
        assert!(bad(&|o| o.tilts = vec![10.0, 10.0]).contains("twice"));
        assert!(bad(&|o| o.tilts = vec![f32::NAN]).contains("--tilts NaN"));
    }
}
