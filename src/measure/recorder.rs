//! Measuring a progressive render: at each checkpoint ([`Progress`], what the renderer shows
//! its observer), the error against a reference (if one was given) and the half-buffer estimate
//! (always), as [`ReportRow`]s; and the `--reference` file checks. (The `--target-error`
//! stop is `crate::app::budget`'s.)
//!
//! Units: times are wall seconds since rendering started (loading and the acceleration build
//! are their own rows); errors are on the linear image ([`crate::image::metrics`]). The
//! *relative error* used for `--target-error`, the plots and the levels table is the
//! relative RMSE `sqrt(rel_mse)`, with `rel_mse = mean((x−r)²/(r²+0.01))`.

use super::report::ReportRow;
use crate::error::{Error, Result};
use crate::image::metrics::{compare, half_buffer_estimate, ErrorMetrics};
use crate::image::ImageRgb;
use crate::output::display::Picture;
use crate::render::Progress;
use std::path::Path;
use std::time::Duration;

/// The relative RMSE `sqrt(rel_mse)` of a metrics triple.
pub fn relative_rmse(m: &ErrorMetrics) -> f64 {
    m.rel_mse.max(0.0).sqrt()
}

/// Reads `--reference FILE`; errors name the flag and the file.
pub fn read_reference_file(path: &Path) -> Result<ImageRgb> {
    crate::output::read_exr(path).map_err(|e| Error::Usage(format!("--reference: {e}")))
}

/// Checks that the reference is `width`×`height`; the error names the reference file and
/// the render (`what`) with both sizes.
pub fn check_reference_size(
    reference: &ImageRgb,
    path: &Path,
    width: u32,
    height: u32,
    what: &str,
) -> Result<()> {
    if (reference.width, reference.height) != (width, height) {
        return Err(Error::Usage(format!(
            "--reference {} is {}x{} but {what} is {width}x{height} (pass --size {}x{} or a matching reference)",
            path.display(),
            reference.width,
            reference.height,
            reference.width,
            reference.height
        )));
    }
    Ok(())
}

/// Collects one [`ReportRow`] per checkpoint of one run.
#[derive(Debug)]
pub struct Recorder<'a> {
    /// Run name written in the `run` column (the method).
    pub run: String,
    /// The reference, if any.
    pub reference: Option<&'a ImageRgb>,
    /// The output's display transform, when it is display-referred (a PNG): the rows then
    /// carry the picture's estimated error, and with a reference its error.
    pub picture: Option<Picture<'a>>,
    /// Print one line per checkpoint on stderr.
    pub verbose: bool,
    /// The rows so far ("render" stage only).
    pub rows: Vec<ReportRow>,
}

impl<'a> Recorder<'a> {
    /// A recorder for run `run`.
    pub fn new(run: &str, reference: Option<&'a ImageRgb>) -> Self {
        Recorder {
            run: run.to_string(),
            reference,
            picture: None,
            verbose: false,
            rows: Vec::new(),
        }
    }

    /// Records a checkpoint; returns `true` (stop rendering) when the target error is
    /// reached.
    pub fn record(&mut self, p: &Progress) -> Result<()> {
        self.record_denoised(p, None)
    }

    /// [`Recorder::record`] with the checkpoint's denoised image and the time denoising it
    /// took, when it was denoised: the row gets that time and, with a reference, the
    /// denoised image's error.
    pub fn record_denoised(
        &mut self,
        p: &Progress,
        denoised: Option<(&ImageRgb, Duration)>,
    ) -> Result<()> {
        // One unit makes both halves that unit: no estimate before two.
        let estimate = (p.samples >= 2)
            .then(|| half_buffer_estimate(p.halves.0, p.halves.1))
            .transpose()?;
        let error = match self.reference {
            Some(r) => Some(compare(p.image, r)?),
            None => None,
        };
        let denoised_error = match (self.reference, denoised) {
            (Some(r), Some((d, _))) => Some(compare(d, r)?),
            _ => None,
        };
        // The picture written: the denoised image when there is one.
        let display_error = match (self.reference, self.picture) {
            (Some(r), Some(pic)) => Some(pic.error(denoised.map_or(p.image, |d| d.0), r)?),
            _ => None,
        };
        let display_estimate = p.judged.get().filter(|j| j.absolute).map(|j| j.estimate);
        // A final call (`done`) at the same count as the last checkpoint replaces its row.
        if self
            .rows
            .last()
            .is_some_and(|r| r.samples == p.samples && r.passes == p.passes)
        {
            self.rows.pop();
        }
        self.rows.push(ReportRow {
            run: self.run.clone(),
            stage: "render".into(),
            wall_s: p.elapsed.as_secs_f64(),
            samples: p.samples,
            passes: p.passes,
            rays: p.rays,
            photons: p.photons,
            error,
            estimate,
            denoised: denoised_error,
            denoise_s: denoised.map(|(_, t)| t.as_secs_f64()),
            display_estimate,
            display_error,
        });
        if self.verbose && !p.done {
            let mut line = checkpoint_line(&self.run, p, estimate.as_ref(), error.as_ref());
            if let Some(e) = denoised_error {
                line.push_str(&format!(" (denoised {:.4})", relative_rmse(&e)));
            }
            if let Some(e) = display_estimate {
                line.push_str(&format!("; display error est. {e:.4}"));
            }
            if let Some(e) = display_error {
                line.push_str(&format!(" (vs reference {e:.4})"));
            }
            eprintln!("{line}");
        }
        Ok(())
    }

    /// (seconds, error) points for a plot: the error against the reference if there is one,
    /// else the estimate; relative RMSE.
    pub fn points(&self) -> Vec<(f64, f64)> {
        points(&self.rows)
    }
}

/// (seconds, relative RMSE) of the "render" rows: against the reference when the rows have
/// it, else the half-buffer estimate.
pub fn points(rows: &[ReportRow]) -> Vec<(f64, f64)> {
    rows.iter()
        .filter(|r| r.stage == "render")
        .filter_map(|r| {
            r.error
                .or(r.estimate)
                .map(|m| (r.wall_s, relative_rmse(&m)))
        })
        .collect()
}

/// (seconds, relative RMSE against the reference) of the denoised images of the "render"
/// rows that have one (`--reference` with denoising active).
pub fn denoised_points(rows: &[ReportRow]) -> Vec<(f64, f64)> {
    rows.iter()
        .filter(|r| r.stage == "render")
        .filter_map(|r| r.denoised.map(|m| (r.wall_s, relative_rmse(&m))))
        .collect()
}

/// `path: 16 spp, 3 passes, 1.25 s: estimated relative error 0.081 (vs reference 0.094)`,
/// or `… s: no estimate yet` before two units.
fn checkpoint_line(
    run: &str,
    p: &Progress,
    estimate: Option<&ErrorMetrics>,
    error: Option<&ErrorMetrics>,
) -> String {
    let estimate = estimate.map_or("no estimate yet".to_string(), |e| {
        format!("estimated relative error {:.4}", relative_rmse(e))
    });
    let mut s = format!(
        "{run}: {} spp, {} passes, {:.2} s: {estimate}",
        p.samples,
        p.passes,
        p.elapsed.as_secs_f64(),
    );
    if let Some(e) = error {
        s.push_str(&format!(" (vs reference {:.4})", relative_rmse(e)));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recorder_merges_the_final_call() {
        use glam::Vec3;
        let img = |v: f32| ImageRgb {
            width: 2,
            height: 1,
            data: vec![Vec3::splat(v); 2],
        };
        // Halves 0.9 and 1.1: per channel (a−b)²/4 = 0.01 over m² + 0.01 = 1.01, so the
        // estimated relative RMSE is sqrt(0.01/1.01) ≈ 0.0995.
        let (a, b, m) = (img(0.9), img(1.1), img(1.0));
        let reference = img(1.0);
        let mut rec = Recorder::new("path", Some(&reference));
        let progress = |done| Progress {
            elapsed: std::time::Duration::from_millis(5),
            rays: 8,
            ..Progress::at(&m, (&a, &b), 4, done)
        };
        rec.record(&progress(false)).unwrap();
        rec.record(&progress(true)).unwrap();
        assert_eq!(
            rec.rows.len(),
            1,
            "the final call at 4 spp replaces the checkpoint row"
        );
        let est = rec.rows[0].estimate.unwrap();
        assert!((relative_rmse(&est) - (0.01f64 / 1.01).sqrt()).abs() < 1e-6);
        assert_eq!(rec.rows[0].error.unwrap().rmse, 0.0);
    }

    #[test]
    fn one_unit_has_no_estimate() {
        use glam::Vec3;
        let m = ImageRgb {
            width: 2,
            height: 1,
            data: vec![Vec3::splat(1.0); 2],
        };
        let p = Progress {
            elapsed: std::time::Duration::from_millis(5),
            ..Progress::at(&m, (&m, &m), 1, false)
        };
        let mut rec = Recorder::new("path", None);
        rec.record(&p).unwrap();
        assert_eq!(rec.rows[0].estimate, None);
        assert!(points(&rec.rows).is_empty());
        let line = checkpoint_line("path", &p, None, None);
        assert!(
            line.ends_with("1 spp, 1 passes, 0.01 s: no estimate yet"),
            "{line}"
        );
        let two = Progress { samples: 2, ..p };
        let line = checkpoint_line(
            "path",
            &two,
            Some(&half_buffer_estimate(&m, &m).unwrap()),
            None,
        );
        assert!(line.ends_with("estimated relative error 0.0000"), "{line}");
    }

    #[test]
    fn points_prefer_the_reference_error() {
        let m = |rel: f64| ErrorMetrics {
            rmse: 1.0,
            rel_mse: rel,
            mae: 1.0,
        };
        let row = |error, estimate| ReportRow {
            run: "x".into(),
            stage: "render".into(),
            wall_s: 2.0,
            samples: 1,
            passes: 1,
            rays: 0,
            photons: 0,
            error,
            estimate,
            denoised: None,
            denoise_s: None,
            display_estimate: None,
            display_error: None,
        };
        // sqrt(0.25) = 0.5 (reference) wins over sqrt(0.04) = 0.2 (estimate).
        assert_eq!(
            points(&[row(Some(m(0.25)), Some(m(0.04)))]),
            vec![(2.0, 0.5)]
        );
        assert_eq!(points(&[row(None, Some(m(0.04)))]), vec![(2.0, 0.2)]);
    }
}
