//! Error-against-time plots on log-log axes, drawn with `plotters`.
//!
//! - x: wall-clock seconds, y: an error (RMSE, relative MSE, …); both axes logarithmic.
//! - One line with circle markers per [`Series`]; the legend reads `label (slope −0.48)`, the
//!   least-squares slope of `log(error)` against `log(time)` ([`loglog_slope`]). An unbiased
//!   Monte Carlo method converges with RMSE slope −0.5 (relative MSE −1); a flatter slope means
//!   bias or too few samples to be in the asymptotic regime.
//! - Points that a log axis cannot show (time or error ≤ 0, NaN, ∞) are **skipped**, in the
//!   plot and in the slope alike; a series with no usable point appears in the legend only,
//!   with `slope n/a`. With no usable point at all, the axes span 0.1–10.
//! - Format by extension (case-insensitive): `.png` (800×600 RGB, plotters' bitmap backend,
//!   encoded by the `image` crate) or `.svg` (plotters' SVG backend). Anything else is
//!   [`Error::Usage`] naming the file. Files are replaced atomically.
//! - Text uses Ubuntu Light, compiled into the binary (`epaint_default_fonts`), registered
//!   with plotters' `ab_glyph` renderer: no system fonts are needed.

use crate::error::{Error, Result};
use crate::output::atomic::write_file_atomic;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// Size of every plot, in pixels (SVG user units).
pub const PLOT_SIZE: (u32, u32) = (800, 600);

/// One line of the plot: a run or a method.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// `(seconds, error)` points, in time order.
    pub points: Vec<(f64, f64)>,
}

/// True if a point can be placed on log-log axes.
fn usable(&(t, e): &(f64, f64)) -> bool {
    t.is_finite() && e.is_finite() && t > 0.0 && e > 0.0
}

/// Least-squares slope of `log(error)` against `log(time)`, over the usable points (time and
/// error finite and > 0). `None` with fewer than 2 usable points or when all usable times are
/// equal. For `error = c·t^k` it returns `k`.
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| usable(p))
        .map(|&(t, e)| (t.ln(), e.ln()))
        .collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    // Centred sums (numerically stable): slope = Σ(x−x̄)(y−ȳ) / Σ(x−x̄)².
    let (sxy, sxx) = logs.iter().fold((0.0, 0.0), |(sxy, sxx), &(x, y)| {
        (sxy + (x - mx) * (y - my), sxx + (x - mx) * (x - mx))
    });
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The legend text of a series: `label (slope −0.48)` or `label (slope n/a)`.
pub fn legend_label(series: &Series) -> String {
    match loglog_slope(&series.points) {
        // U+2212 MINUS SIGN, as typeset; the font has the glyph.
        Some(k) => format!(
            "{} (slope {})",
            series.label,
            format!("{k:.2}").replace('-', "−")
        ),
        None => format!("{} (slope n/a)", series.label),
    }
}

/// Which file format a plot path asks for.
enum Format {
    Png,
    Svg,
}

/// Registers the embedded font once; `false` if plotters rejected it.
fn font_ready() -> bool {
    static READY: OnceLock<bool> = OnceLock::new();
    *READY.get_or_init(|| {
        plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        )
        .is_ok()
    })
}

/// Log-log plot of error against time, one line + markers per series, legend
/// `label (slope −0.48)`, written to `path` (`.png` or `.svg`).
///
/// Errors: [`Error::Usage`] naming the file for another extension; [`Error::Output`] naming
/// the file if drawing or writing fails.
pub fn plot_error_vs_time(
    path: &Path,
    title: &str,
    y_label: &str,
    series: &[Series],
) -> Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("png") => Format::Png,
        Some("svg") => Format::Svg,
        _ => {
            return Err(Error::Usage(format!(
                "{}: plot format must be .png or .svg",
                path.display()
            )))
        }
    };
    let out_err = |reason: String| Error::Output {
        path: path.to_path_buf(),
        reason,
    };
    if !font_ready() {
        return Err(out_err("the embedded plot font could not be loaded".into()));
    }
    let (w, h) = PLOT_SIZE;
    let bytes = match format {
        Format::Png => {
            let mut buf = vec![0u8; w as usize * h as usize * 3];
            {
                let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
                draw(&root, title, y_label, series).map_err(out_err)?;
            }
            let img = image::RgbImage::from_raw(w, h, buf)
                .ok_or_else(|| out_err("plot buffer has the wrong size".into()))?;
            let mut png = std::io::Cursor::new(Vec::new());
            img.write_to(&mut png, image::ImageFormat::Png)
                .map_err(|e| out_err(e.to_string()))?;
            png.into_inner()
        }
        Format::Svg => {
            let mut svg = String::new();
            {
                let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
                draw(&root, title, y_label, series).map_err(out_err)?;
            }
            svg.into_bytes()
        }
    };
    write_file_atomic(path, &bytes)
}

/// Axis range `[lo, hi]` covering `values` (all > 0), widened by a factor 1.5 at each end
/// (and to a factor 10 span if all are equal) so markers do not sit on the frame.
fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if hi <= 0.0 || !lo.is_finite() {
        return (0.1, 10.0);
    }
    if hi / lo < 1.0 + 1e-9 {
        return (lo / 3.0, hi * 3.0);
    }
    (lo / 1.5, hi * 1.5)
}

/// Tick label: 3 significant digits, scientific notation outside [0.01, 10⁴).
fn tick(v: &f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(0.01..1e4).contains(&a) {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Draws the whole chart on `root`; errors as text.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    y_label: &str,
    series: &[Series],
) -> std::result::Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let all = || {
        series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| usable(p))
    };
    let (x0, x1) = log_range(all().map(|p| p.0));
    let (y0, y1) = log_range(all().map(|p| p.1));
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 26))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("wall time (s)")
        .y_desc(y_label)
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 18))
        .draw()
        .map_err(e)?;
    for (i, s) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(usable).collect();
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
            .map_err(e)?
            .label(legend_label(s))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2)));
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
            .map_err(e)?;
    }
    if !series.is_empty() {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(("sans-serif", 16))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(e)?;
    }
    root.present().map_err(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_power_laws() {
        // error = 3·t^−0.5 exactly (up to rounding): the fit is exact, 1e-9 covers rounding
        // of ln/pow over 8 points.
        let pts: Vec<_> = (0..8)
            .map(|i| {
                let t = 0.01 * 2f64.powi(i);
                (t, 3.0 * t.powf(-0.5))
            })
            .collect();
        assert!((loglog_slope(&pts).unwrap() + 0.5).abs() < 1e-9);
        // Unusable points are skipped, not fitted.
        let mut dirty = pts.clone();
        dirty.extend([
            (0.0, 1.0),
            (1.0, 0.0),
            (-1.0, 2.0),
            (f64::NAN, 1.0),
            (2.0, f64::INFINITY),
        ]);
        assert!((loglog_slope(&dirty).unwrap() + 0.5).abs() < 1e-9);
        assert_eq!(loglog_slope(&pts[..1]), None);
        assert_eq!(loglog_slope(&[(1.0, 1.0), (1.0, 2.0)]), None);
        assert_eq!(loglog_slope(&[]), None);
    }

    #[test]
    fn legend_text() {
        let s = Series {
            label: "path".into(),
            points: vec![(1.0, 1.0), (4.0, 0.5)],
        };
        assert_eq!(legend_label(&s), "path (slope −0.50)");
        let empty = Series {
            label: "sppm".into(),
            points: vec![],
        };
        assert_eq!(legend_label(&empty), "sppm (slope n/a)");
    }

    #[test]
    fn ranges_and_ticks() {
        assert_eq!(log_range(std::iter::empty()), (0.1, 10.0));
        let (lo, hi) = log_range([2.0, 2.0].into_iter());
        assert!(lo < 2.0 && hi > 2.0);
        assert_eq!(tick(&0.5), "0.5");
        assert_eq!(tick(&100.0), "100");
        assert_eq!(tick(&0.001), "1.0e-3");
    }
}
