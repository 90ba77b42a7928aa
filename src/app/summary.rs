//! The summary of one `iris render` ([`RenderSummary`]): what was written, the work and
//! time it took, the report rows, the notes, and what ended the render in words
//! ([`RenderSummary::end_text`]). Times are wall-clock; errors are relative RMSE unless
//! named otherwise.

use crate::image::metrics::ErrorMetrics;
use crate::image::ImageRgb;
use crate::integrator::capability::{Photons, Units};
use crate::integrator::Method;
use crate::measure::report::ReportRow;
use crate::render::{EndReason, RenderStats};
use std::path::PathBuf;
use std::time::Duration;

/// What a render did, for the one-line summary.
#[derive(Debug, Clone)]
pub struct RenderSummary {
    /// Where the image went.
    pub output: PathBuf,
    /// The linear image.
    pub image: ImageRgb,
    /// Render figures.
    pub stats: RenderStats,
    /// Scene load + validation time.
    pub load_time: Duration,
    /// Acceleration build time.
    pub build_time: Duration,
    /// Triangles.
    pub triangles: usize,
    /// Backend name.
    pub backend: &'static str,
    /// Decisions taken for the user and loader warnings.
    pub notes: Vec<String>,
    /// Report rows: "load", "build", then one "render" row per checkpoint.
    pub rows: Vec<ReportRow>,
    /// The error target the render had (`--target-error`, or the default target).
    pub target_error: Option<f64>,
    /// The last error compared with the target ([`super::budget::stop_error`]), if any.
    pub target_estimate: Option<f64>,
    /// What [`Self::target_estimate`] measures ([`super::budget::Measure::name`]: a PNG's
    /// display error, of the denoised picture when it is denoised; an EXR's relative error).
    pub target_measure: &'static str,
    /// The time limit the render had (`--time`, or the default limit).
    pub time_limit: Option<Duration>,
    /// The method that rendered (`--method auto` resolved).
    pub method: Method,
    /// The render plan the render followed (costs measured with `--explain`).
    pub plan: crate::plan::Plan,
    /// The denoised final image, when the render denoised (the PNG shows it; an EXR under
    /// `--denoise on` holds it as its extra layer).
    pub denoised: Option<ImageRgb>,
}

impl RenderSummary {
    /// The last checkpoint's error against the reference (with `--reference`).
    pub fn final_error(&self) -> Option<ErrorMetrics> {
        self.rows.last().and_then(|r| r.error)
    }

    /// "12 spp" or "40 passes, 9216000 photons": the work the render did, as `iris render`
    /// and the gallery print it.
    pub fn work_done(&self) -> String {
        let pixels = u64::from(self.image.width) * u64::from(self.image.height);
        let (lo, hi) = self.stats.unit_span;
        let spp = if lo < hi {
            // Adaptive sampling: the range and the mean.
            let mean = self.stats.samples as f64 / pixels.max(1) as f64;
            format!("{lo} to {hi} (mean {mean:.1})")
        } else {
            (self.stats.samples / pixels.max(1)).to_string()
        };
        match self.method.caps().photons {
            Photons::Passes => format!(
                "{} passes, {} photons",
                self.stats.passes, self.stats.photons
            ),
            Photons::Map => format!("{spp} spp, {} photons", self.stats.photons),
            Photons::Caustic => format!(
                "{spp} spp, {} caustic photons ({} in the last pass)",
                self.stats.photons, self.stats.photons_per_pass
            ),
            Photons::None | Photons::LightSubpaths => format!("{spp} spp"),
        }
    }

    /// The last checkpoint's half-buffer error estimate.
    pub fn final_estimate(&self) -> Option<ErrorMetrics> {
        self.rows.last().and_then(|r| r.estimate)
    }

    /// What ended the render ([`RenderStats::end`]).
    pub fn end(&self) -> EndReason {
        self.stats.end
    }

    /// What ended the render, in words: "stopped at the error target 0.01 (estimated
    /// display error of the denoised picture 0.0087)", "stopped at the time limit 120 s
    /// (error target 0.01, estimated display error 0.0123)", "interrupted (Ctrl-C or
    /// SIGTERM): the image so far", "64 spp done".
    pub fn end_text(&self) -> String {
        let name = if self.target_measure.is_empty() {
            "error"
        } else {
            self.target_measure
        };
        let target = |s: &mut String| {
            if let (Some(t), Some(e)) = (self.target_error, self.target_estimate) {
                s.push_str(&format!(" (error target {t}, estimated {name} {e:.4})"));
            } else if let Some(t) = self.target_error {
                s.push_str(&format!(" (error target {t} not yet measurable)"));
            }
        };
        match self.stats.end {
            EndReason::Target => format!(
                "stopped at the error target {} (estimated {name} {:.4})",
                self.target_error.unwrap_or(f64::NAN),
                self.target_estimate.unwrap_or(f64::NAN)
            ),
            EndReason::TimeLimit => {
                let secs = self.time_limit.map_or(f64::NAN, |t| t.as_secs_f64());
                let mut s = format!("stopped at the time limit {secs} s");
                target(&mut s);
                s
            }
            EndReason::Interrupted => "interrupted (Ctrl-C or SIGTERM): the image so far".into(),
            EndReason::Samples => {
                let unit = if self.method.caps().units == Units::Passes {
                    format!("{} passes", self.stats.passes)
                } else {
                    let pixels = u64::from(self.image.width) * u64::from(self.image.height);
                    format!("{} spp", self.stats.samples / pixels.max(1))
                };
                format!("{unit} done")
            }
        }
    }

    /// The last checkpoint's denoised error against the reference (`--reference` while
    /// denoising).
    pub fn final_denoised_error(&self) -> Option<ErrorMetrics> {
        self.rows.last().and_then(|r| r.denoised)
    }
}
