//! The error-against-time report: one CSV row per checkpoint of a run, plus rows for the
//! stages a user also waits for (scene load, acceleration-structure build).
//!
//! Format (RFC 4180 CSV, UTF-8, `\n` line ends), columns exactly [`CSV_HEADER`]:
//! - `run`: free text naming the run (method, backend, …); quoted if it holds `,` `"` or a
//!   line break, with `"` doubled.
//! - `stage`: `load`, `build` or `render`.
//! - `wall_s`: wall-clock seconds since the run started (cumulative, so a `render` row's time
//!   includes nothing hidden); `samples_per_pixel`, `passes`, `rays`, `photons`: counts so far.
//! - `rmse, rel_mse, mae`: error against a reference ([`crate::image::metrics::compare`]);
//!   `est_*`: the reference-free half-buffer estimate
//!   ([`crate::image::metrics::half_buffer_estimate`]). Empty cells where not computed.
//! - `denoised_rmse, denoised_rel_mse, denoised_mae`: the denoised image's error against the
//!   reference (`--reference` with denoising active, [`crate::denoise`]); `denoise_s`: wall
//!   seconds the denoiser took at that checkpoint (auxiliary pass not included; it runs
//!   once, before rendering). Empty when the checkpoint was not denoised.
//! - `display_est`: the estimated display RMSE of the picture as written (a PNG: after
//!   exposure, tone map and clipping, denoised when the PNG is; [`crate::output::display`]),
//!   the number a PNG's `--target-error` is compared with; empty where not measured (an EXR,
//!   fewer than 8 units, a render with neither an error target nor `--report`).
//!   `display_rmse`: that picture's display RMSE against the reference's picture
//!   (`--reference` with a PNG output).
//!
//! Numbers are written with Rust's shortest round-trip formatting, so `str::parse::<f64>` /
//! `parse::<u64>` read back the exact values (NaN and infinities as `NaN`, `inf`, `-inf`).
//! The file is replaced atomically ([`crate::output::atomic`]).

use crate::error::Result;
use crate::image::metrics::ErrorMetrics;
use crate::output::atomic::write_file_atomic;
use std::fmt::Write as _;
use std::path::Path;

/// The CSV header line (without the line end); the column order of every row.
pub const CSV_HEADER: &str = "run,stage,wall_s,samples_per_pixel,passes,rays,photons,rmse,rel_mse,mae,est_rmse,est_rel_mse,est_mae,denoised_rmse,denoised_rel_mse,denoised_mae,denoise_s,display_est,display_rmse";

/// One line of the report: a checkpoint of a run, or a load/build stage.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportRow {
    /// Name of the run (method, backend, …).
    pub run: String,
    /// `"load"`, `"build"` or `"render"`.
    pub stage: String,
    /// Wall-clock seconds since the run started.
    pub wall_s: f64,
    /// Samples per pixel so far.
    pub samples: u64,
    /// Photon passes so far (0 for methods without passes).
    pub passes: u32,
    /// Rays traced so far.
    pub rays: u64,
    /// Photons traced so far.
    pub photons: u64,
    /// Error against a reference, if one was given.
    pub error: Option<ErrorMetrics>,
    /// Reference-free estimate from two half images, if available.
    pub estimate: Option<ErrorMetrics>,
    /// The denoised image's error against the reference, when both exist.
    pub denoised: Option<ErrorMetrics>,
    /// Wall seconds the denoiser took at this checkpoint, when it ran.
    pub denoise_s: Option<f64>,
    /// The estimated display RMSE of the picture as written, when measured.
    pub display_estimate: Option<f64>,
    /// The picture's display RMSE against the reference's, when both exist.
    pub display_error: Option<f64>,
}

impl ReportRow {
    /// A row of stage `stage` of run `run` at `wall_s` seconds, with no counts and no
    /// error metrics (a load or build stage).
    pub fn stage(run: &str, stage: &str, wall_s: f64) -> Self {
        ReportRow {
            run: run.to_string(),
            stage: stage.to_string(),
            wall_s,
            samples: 0,
            passes: 0,
            rays: 0,
            photons: 0,
            error: None,
            estimate: None,
            denoised: None,
            denoise_s: None,
            display_estimate: None,
            display_error: None,
        }
    }
}

/// Appends `field` as one CSV cell, quoting it when needed (RFC 4180 §2.6–2.7).
fn push_text(out: &mut String, field: &str) {
    if field.contains([',', '"', '\n', '\r']) {
        out.push('"');
        out.push_str(&field.replace('"', "\"\""));
        out.push('"');
    } else {
        out.push_str(field);
    }
}

/// Appends the three cells of `m` (each preceded by a comma), empty when `None`.
fn push_metrics(out: &mut String, m: Option<&ErrorMetrics>) {
    match m {
        // Writing to a String cannot fail.
        Some(m) => {
            let _ = write!(out, ",{},{},{}", m.rmse, m.rel_mse, m.mae);
        }
        None => out.push_str(",,,"),
    }
}

/// The CSV text for `rows`: [`CSV_HEADER`], then one line per row, each ending in `\n`.
pub fn format_csv(rows: &[ReportRow]) -> String {
    let mut out = String::with_capacity(CSV_HEADER.len() + 1 + rows.len() * 120);
    out.push_str(CSV_HEADER);
    out.push('\n');
    for r in rows {
        push_text(&mut out, &r.run);
        out.push(',');
        push_text(&mut out, &r.stage);
        let _ = write!(
            out,
            ",{},{},{},{},{}",
            r.wall_s, r.samples, r.passes, r.rays, r.photons
        );
        push_metrics(&mut out, r.error.as_ref());
        push_metrics(&mut out, r.estimate.as_ref());
        push_metrics(&mut out, r.denoised.as_ref());
        for cell in [r.denoise_s, r.display_estimate, r.display_error] {
            match cell {
                Some(v) => {
                    let _ = write!(out, ",{v}");
                }
                None => out.push(','),
            }
        }
        out.push('\n');
    }
    out
}

/// Writes `rows` as CSV ([`format_csv`]) to `path`, atomically (temporary file + rename).
///
/// Errors: [`crate::Error::Output`] naming `path` if it cannot be written.
pub fn write_csv(path: &Path, rows: &[ReportRow]) -> Result<()> {
    write_file_atomic(path, format_csv(rows).as_bytes())
}

/// The "load" (parse + validation, without the acceleration build) and "build" rows.
pub fn setup_rows(
    run: &str,
    load_and_build: std::time::Duration,
    build: std::time::Duration,
) -> Vec<ReportRow> {
    let row = |stage: &str, t: std::time::Duration| ReportRow::stage(run, stage, t.as_secs_f64());
    vec![
        row("load", load_and_build.saturating_sub(build)),
        row("build", build),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoting_and_empty_cells() {
        let rows = [ReportRow::stage("path, \"bvh\"", "load", 0.25)];
        let csv = format_csv(&rows);
        assert_eq!(
            csv,
            format!("{CSV_HEADER}\n\"path, \"\"bvh\"\"\",load,0.25,0,0,0,0,,,,,,,,,,,,\n")
        );
    }

    #[test]
    fn header_has_nineteen_columns() {
        assert_eq!(CSV_HEADER.split(',').count(), 19);
    }
}
