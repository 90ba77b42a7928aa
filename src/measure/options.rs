//! The measuring flags of `iris render` (`--reference`, `--report`, `--plot`,
//! `--target-error`): what they ask for and their checks, made before anything renders.
//! Units: wall-clock seconds; errors on the linear image.

use super::plot::{plot_error_vs_time, Series};
use super::recorder::{denoised_points, points};
use super::report::{write_csv, ReportRow};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// The measuring flags of `iris render`; all off by default.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeasureOptions {
    /// `--reference ref.exr`: error against this image at each checkpoint.
    pub reference: Option<PathBuf>,
    /// `--report out.csv`: one row per checkpoint (plus "load" and "build").
    pub report: Option<PathBuf>,
    /// `--plot out.png|svg`: error against time, log-log.
    pub plot: Option<PathBuf>,
    /// `--target-error E`: stop once the estimated error of the image as written is ≤ E
    /// ([`crate::app::budget::TargetStop`]; a PNG's display error, an EXR's relative RMSE).
    pub target_error: Option<f64>,
    /// The target is the default budget's, not given: its value is the output's measure's
    /// default ([`crate::app::budget::DEFAULT_DISPLAY_TARGET`] for a PNG), resolved with the output.
    pub default_target: bool,
}

impl MeasureOptions {
    /// Whether any measuring flag was given.
    pub fn any(&self) -> bool {
        self.reference.is_some()
            || self.report.is_some()
            || self.plot.is_some()
            || self.target_error.is_some()
    }

    /// Checks the flags that need no scene: the plot's extension and the target's range.
    pub fn check_flags(&self) -> Result<()> {
        if let Some(p) = &self.plot {
            check_plot_extension(p)?;
        }
        if let Some(e) = self.target_error {
            if e.is_nan() || e <= 0.0 || e.is_infinite() {
                return Err(Error::Usage(format!(
                    "--target-error {e}: expected a finite error > 0 (a PNG's display RMSE, an EXR's relative RMSE)"
                )));
            }
        }
        Ok(())
    }

    /// `--plot` needs at least 2 checkpoints (at 1, 2, 4, … samples or passes), so the
    /// sample or pass bound must be at least 2.
    pub fn check_checkpoints(&self, bound: u32) -> Result<()> {
        if self.plot.is_some() && bound < 2 {
            return Err(Error::Usage(format!(
                "--plot needs at least 2 checkpoints, but the render stops after {bound} sample or pass (raise --spp, or --passes for SPPM)"
            )));
        }
        Ok(())
    }

    /// Writes the CSV and the plot asked for; returns notes (a plot skipped because the
    /// render stopped after one checkpoint).
    pub fn write_outputs(&self, rows: &[ReportRow], scene: &Path) -> Result<Vec<String>> {
        let mut notes = Vec::new();
        if let Some(path) = &self.report {
            write_csv(path, rows)?;
        }
        if let Some(path) = &self.plot {
            let points = points(rows);
            if points.len() < 2 {
                notes.push(format!(
                    "--plot {}: not written, the render stopped after {} checkpoint(s) (a line needs 2)",
                    path.display(),
                    points.len()
                ));
            } else {
                let label = rows
                    .iter()
                    .find(|r| r.stage == "render")
                    .map_or("render", |r| r.run.as_str());
                let y = if self.reference.is_some() {
                    "relative RMSE against the reference"
                } else {
                    "estimated relative RMSE (half buffers)"
                };
                let mut series = vec![Series {
                    label: label.to_string(),
                    points,
                }];
                // With denoising and a reference: the denoised image's error, second curve.
                let denoised = denoised_points(rows);
                if !denoised.is_empty() {
                    series[0].label = format!("{label}, raw");
                    series.push(Series {
                        label: format!("{label}, denoised"),
                        points: denoised,
                    });
                }
                plot_error_vs_time(
                    path,
                    &format!("{}: error against time", file_name(scene)),
                    y,
                    &series,
                )?;
            }
        }
        Ok(notes)
    }
}

/// `.png` or `.svg` (case-insensitive), else [`Error::Usage`] naming the file.
pub fn check_plot_extension(path: &Path) -> Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") | Some("svg") => Ok(()),
        _ => Err(Error::Usage(format!(
            "--plot {}: unknown plot format (accepted extensions: .png, .svg)",
            path.display()
        ))),
    }
}

/// The file name of `path` (the whole path when it has none), for titles.
pub fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}
