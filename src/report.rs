//! STAND-IN until X lands: the error-against-time CSV report.

use crate::error::Result;
use crate::metrics::ErrorMetrics;
use std::fmt::Write as _;
use std::path::Path;

/// One CSV row.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportRow {
    /// Run name (method).
    pub run: String,
    /// "load" | "build" | "render".
    pub stage: String,
    /// Wall seconds.
    pub wall_s: f64,
    /// Samples per pixel.
    pub samples: u64,
    /// Passes.
    pub passes: u32,
    /// Rays.
    pub rays: u64,
    /// Photons.
    pub photons: u64,
    /// Error against the reference.
    pub error: Option<ErrorMetrics>,
    /// Half-buffer estimate.
    pub estimate: Option<ErrorMetrics>,
}

/// The header line.
pub const CSV_HEADER: &str = "run,stage,wall_s,samples_per_pixel,passes,rays,photons,rmse,rel_mse,mae,est_rmse,est_rel_mse,est_mae";

/// Writes the rows atomically.
pub fn write_csv(path: &Path, rows: &[ReportRow]) -> Result<()> {
    let mut s = String::from(CSV_HEADER);
    s.push('\n');
    let cells = |m: Option<ErrorMetrics>| match m {
        Some(m) => format!("{:e},{:e},{:e}", m.rmse, m.rel_mse, m.mae),
        None => ",,".into(),
    };
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{}",
            r.run,
            r.stage,
            r.wall_s,
            r.samples,
            r.passes,
            r.rays,
            r.photons,
            cells(r.error),
            cells(r.estimate)
        );
    }
    crate::output::atomic::write_file_atomic(path, s.as_bytes())
}
