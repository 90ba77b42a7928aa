//! STAND-IN until X lands: error metrics of linear images (same signatures as the shared
//! plan in issue 6). Units: the image's linear radiance; all pixels and channels weigh alike.

use crate::error::{Error, Result};
use crate::output::ImageRgb;

/// Errors of an image against a reference (or estimated from two half images).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorMetrics {
    /// Root-mean-square error.
    pub rmse: f64,
    /// Mean of (x−r)²/(r²+0.01).
    pub rel_mse: f64,
    /// Mean absolute error.
    pub mae: f64,
}

fn same_size(a: &ImageRgb, b: &ImageRgb) -> Result<()> {
    if (a.width, a.height) != (b.width, b.height) || a.data.len() != b.data.len() {
        return Err(Error::Usage(format!(
            "images differ in size: {}x{} and {}x{}",
            a.width, a.height, b.width, b.height
        )));
    }
    Ok(())
}

/// RMSE, relative MSE and MAE of `image` against `reference`.
pub fn compare(image: &ImageRgb, reference: &ImageRgb) -> Result<ErrorMetrics> {
    same_size(image, reference)?;
    let n = (image.data.len() * 3).max(1) as f64;
    let (mut se, mut rel, mut ae) = (0f64, 0f64, 0f64);
    for (x, r) in image.data.iter().zip(&reference.data) {
        for c in 0..3 {
            let (x, r) = (f64::from(x[c]), f64::from(r[c]));
            se += (x - r) * (x - r);
            rel += (x - r) * (x - r) / (r * r + 0.01);
            ae += (x - r).abs();
        }
    }
    Ok(ErrorMetrics {
        rmse: (se / n).sqrt(),
        rel_mse: rel / n,
        mae: ae / n,
    })
}

/// Error of (a+b)/2 estimated from two independent half images.
pub fn half_buffer_estimate(a: &ImageRgb, b: &ImageRgb) -> Result<ErrorMetrics> {
    same_size(a, b)?;
    let n = (a.data.len() * 3).max(1) as f64;
    let (mut var, mut rel) = (0f64, 0f64);
    for (p, q) in a.data.iter().zip(&b.data) {
        for c in 0..3 {
            let (p, q) = (f64::from(p[c]), f64::from(q[c]));
            let v = (p - q) * (p - q) / 4.0;
            let m = (p + q) / 2.0;
            var += v;
            rel += v / (m * m + 0.01);
        }
    }
    let mse = var / n;
    Ok(ErrorMetrics {
        rmse: mse.sqrt(),
        rel_mse: rel / n,
        mae: (2.0 / std::f64::consts::PI).sqrt() * mse.sqrt(),
    })
}
