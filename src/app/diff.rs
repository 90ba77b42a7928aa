//! `iris diff`: the error of an EXR image against a reference EXR of the same size, on the
//! linear values (all pixels and channels): RMSE, RMSE relative to the reference's mean,
//! and the relative MSE of [`crate::image::metrics`].

use crate::error::{Error, Result};
use crate::output;
use std::path::Path;

/// What `iris diff` measures.
#[derive(Debug, Clone, Copy)]
pub struct DiffSummary {
    /// Root-mean-square difference over all pixels and channels (linear RGB).
    pub rmse: f64,
    /// `rmse` divided by the reference's mean value.
    pub relative_rmse: f64,
    /// Relative MSE, mean of (x − r)²/(r² + 0.01) ([`crate::image::metrics::compare`]).
    pub rel_mse: f64,
    /// Mean value of the image (all channels).
    pub mean: f64,
    /// Mean value of the reference.
    pub reference_mean: f64,
    /// Pixels whose stored values differ from the reference's in any bit (`--exact`: a
    /// merge of shards against one render, say).
    pub differing: u64,
}

/// `iris diff IMAGE REFERENCE`: error of an EXR against a reference EXR of the same size.
pub fn diff_command(image: &Path, reference: &Path) -> Result<DiffSummary> {
    let a = output::read_exr(image)?;
    let b = output::read_exr(reference)?;
    if (a.width, a.height) != (b.width, b.height) {
        return Err(Error::Usage(format!(
            "{} is {}x{} but the reference {} is {}x{}",
            image.display(),
            a.width,
            a.height,
            reference.display(),
            b.width,
            b.height
        )));
    }
    let n = (a.data.len() * 3).max(1) as f64;
    let (mut se, mut sa, mut sb) = (0f64, 0f64, 0f64);
    let differing = a
        .data
        .iter()
        .zip(&b.data)
        .filter(|(p, q)| p.to_array().map(f32::to_bits) != q.to_array().map(f32::to_bits))
        .count() as u64;
    for (p, q) in a.data.iter().zip(&b.data) {
        let (p, q) = (p.as_dvec3(), q.as_dvec3());
        se += (p - q).length_squared();
        sa += p.element_sum();
        sb += q.element_sum();
    }
    let rmse = (se / n).sqrt();
    let reference_mean = sb / n;
    let rel_mse = crate::image::metrics::compare(&a, &b)?.rel_mse;
    Ok(DiffSummary {
        rmse,
        rel_mse,
        relative_rmse: if reference_mean > 0.0 {
            rmse / reference_mean
        } else {
            f64::INFINITY
        },
        mean: sa / n,
        reference_mean,
        differing,
    })
}
