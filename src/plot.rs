//! STAND-IN until X lands: error-against-time plots (the real module draws with plotters).

use crate::error::{Error, Result};
use std::path::Path;

/// One line of the plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// (seconds, error) points.
    pub points: Vec<(f64, f64)>,
}

/// Least-squares slope of log(error) against log(time).
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let p: Vec<(f64, f64)> = points
        .iter()
        .filter(|(t, e)| *t > 0.0 && *e > 0.0 && t.is_finite() && e.is_finite())
        .map(|(t, e)| (t.ln(), e.ln()))
        .collect();
    if p.len() < 2 {
        return None;
    }
    let n = p.len() as f64;
    let (mx, my) = (
        p.iter().map(|q| q.0).sum::<f64>() / n,
        p.iter().map(|q| q.1).sum::<f64>() / n,
    );
    let sxx: f64 = p.iter().map(|q| (q.0 - mx) * (q.0 - mx)).sum();
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Writes a placeholder plot (blank PNG or minimal SVG).
pub fn plot_error_vs_time(
    path: &Path,
    title: &str,
    _y_label: &str,
    series: &[Series],
) -> Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let bytes = match ext.as_deref() {
        Some("svg") => format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"480\"><title>{title}</title><!-- {} series --></svg>\n",
            series.len()
        )
        .into_bytes(),
        Some("png") => {
            use image::ImageEncoder;
            let mut bytes = Vec::new();
            image::codecs::png::PngEncoder::new(std::io::Cursor::new(&mut bytes))
                .write_image(&vec![255u8; 64 * 48 * 3], 64, 48, image::ExtendedColorType::Rgb8)
                .map_err(|e| Error::Output {
                    path: path.to_path_buf(),
                    reason: e.to_string(),
                })?;
            bytes
        }
        _ => {
            return Err(Error::Usage(format!(
                "{}: unknown plot format (accepted extensions: .png, .svg)",
                path.display()
            )))
        }
    };
    crate::output::atomic::write_file_atomic(path, &bytes)
}
