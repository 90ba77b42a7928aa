//! The flags of `iris gem-report` and their conversion into
//! [`crate::app::gem_report::GemReportOptions`] (the bounds are checked there, before the
//! stone is loaded).

use super::parse::{parse_seconds, parse_threads};
use crate::accel::Backend;
use crate::app::gem_report::{GemReportOptions, DEFAULT_SIZE, DEFAULT_SPP};
use crate::error::{Error, Result};
use crate::prepare::looks::LookFlag;
use crate::prepare::stage::Table;
use std::path::PathBuf;

/// `iris gem-report`: the stone, the output directory and how to render.
#[derive(clap::Args)]
pub struct GemReportArgs {
    /// The stone: a glTF (.gltf/.glb) or OBJ file with a transmissive mesh (the meshes
    /// with a transmissive volume material are the stone; everything else is left out).
    pub scene: PathBuf,
    /// Output directory (created if missing): aset.png, ideal-scope.png, tilt-*.png,
    /// face-up.png, fire.png, directions.png, report.md, report.html, report.json.
    #[arg(short, long, value_name = "DIR")]
    pub output: PathBuf,
    /// Side of every (square) image in pixels, 16 to 2048.
    #[arg(long, default_value_t = DEFAULT_SIZE)]
    pub size: u32,
    /// Samples per pixel of each image, 1 to 4096 (the direction-code images take 1).
    #[arg(long, default_value_t = DEFAULT_SPP)]
    pub spp: u32,
    /// Tilts besides face-up, degrees, comma-separated (each non-zero, at most 60 either
    /// way, at most 12), or `none`.
    #[arg(long, default_value = "10,20,30", allow_hyphen_values = true)]
    pub tilts: String,
    /// Wall-time cap of each render in seconds (more than 0): the images then depend on
    /// the machine's speed; without it the same flags give the same bytes.
    #[arg(long, value_parser = parse_seconds, allow_hyphen_values = true)]
    pub time: Option<f64>,
    /// The table's direction in the file: `auto` (the largest flat facet facing up within
    /// 45° of +Y, else +Y) or X,Y,Z.
    #[arg(long, default_value = "auto", value_parser = Table::parse, allow_hyphen_values = true)]
    pub table: Table,
    /// Make the file's materials a stone first (repeatable), as `iris render --stone`:
    /// diamond, sapphire, ruby, emerald, cubic-zirconia, quartz or crown-glass, with an
    /// optional =SELECTOR.
    #[arg(long, value_name = "NAME[=SELECTOR]")]
    pub stone: Vec<String>,
    /// Random seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads, 0 to 1024 (0 = one per core).
    #[arg(long, default_value_t = 0, value_parser = parse_threads())]
    pub threads: usize,
    /// Intersection backend: auto (Embree when compiled in), embree, bvh.
    #[arg(long, default_value = "auto", value_parser = Backend::parse)]
    pub accel: Backend,
    /// No progress lines.
    #[arg(short, long)]
    pub quiet: bool,
}

impl GemReportArgs {
    /// The options these flags ask for; the command line is kept for the report's page.
    pub fn options(&self) -> Result<GemReportOptions> {
        let mut o = GemReportOptions::new(&self.scene, &self.output);
        o.size = self.size;
        o.spp = self.spp;
        o.tilts = parse_tilts(&self.tilts)?;
        o.time_limit = self.time.map(std::time::Duration::from_secs_f64);
        o.table = self.table;
        o.looks = self
            .stone
            .iter()
            .map(|a| LookFlag::stone(a))
            .collect::<Result<_>>()?;
        o.seed = self.seed;
        o.threads = self.threads;
        o.accel = self.accel;
        o.quiet = self.quiet;
        o.command = std::iter::once("iris".to_string())
            .chain(std::env::args().skip(1))
            .collect::<Vec<_>>()
            .join(" ");
        Ok(o)
    }
}

/// `--tilts`: `none` or comma-separated degrees (their bounds are checked with the other
/// flags, [`crate::app::gem_report::check`]). An empty value is an error, not `none`: an
/// unset shell variable must not silently drop the tilted views.
pub fn parse_tilts(s: &str) -> Result<Vec<f32>> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("none") {
        return Ok(Vec::new());
    }
    if t.is_empty() {
        return Err(Error::Usage(format!(
            "--tilts {s:?} is empty: give degrees separated by commas (e.g. 10,20), or none              for face-up alone"
        )));
    }
    t.split(',')
        .map(|p| {
            p.trim().parse::<f32>().map_err(|_| {
                Error::Usage(format!(
                    "--tilts {s:?}: expected degrees separated by commas, or none"
                ))
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tilts_parse() {
        assert_eq!(parse_tilts("10, 20,30").unwrap(), vec![10.0, 20.0, 30.0]);
        assert_eq!(parse_tilts("none").unwrap(), Vec::<f32>::new());
        for empty in ["", " "] {
            let e = parse_tilts(empty).unwrap_err().to_string();
            assert!(
                e.contains("--tilts") && e.contains("empty"),
                "{empty:?}: {e}"
            );
        }
        assert_eq!(parse_tilts("-5").unwrap(), vec![-5.0]);
        assert!(parse_tilts("10,x")
            .unwrap_err()
            .to_string()
            .contains("--tilts"));
    }
}
