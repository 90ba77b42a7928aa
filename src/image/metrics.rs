//! Image error metrics: how far a rendered image is from a reference, and an estimate of that
//! distance when no reference exists.
//!
//! Units and conventions:
//! - Images are **linear** RGB ([`ImageRgb`], the numbers as rendered, before exposure or tone
//!   mapping); every metric is a mean over all pixels **and** all three channels, computed in
//!   `f64`.
//! - RMSE and MAE are in the image's radiance units; relative MSE is dimensionless, each
//!   squared error divided by `r² + 0.01` (the 0.01 keeps black reference pixels from
//!   dominating; Rousselle et al. 2011, "Adaptive sampling and reconstruction using greedy
//!   error minimization", eq. 7, and the `relMSE` of later denoising papers).
//! - Both images must have the same size and hold `width·height` pixels; otherwise the
//!   functions return [`Error::Usage`] naming both sizes. Empty images are an error too (a
//!   mean over zero pixels is undefined).
//! - Non-finite pixels propagate into the result (NaN/∞); callers print them as they are.

use super::ImageRgb;
use crate::error::{Error, Result};

/// Offset in the denominator of the relative MSE: `(x−r)² / (r² + REL_EPS)`.
pub const REL_EPS: f64 = 0.01;

/// Error of an image: root mean squared error, relative mean squared error and mean absolute
/// error, each a mean over pixels and channels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorMetrics {
    /// `sqrt(mean((x−r)²))`, radiance units.
    pub rmse: f64,
    /// `mean((x−r)² / (r² + 0.01))`, dimensionless.
    pub rel_mse: f64,
    /// `mean(|x−r|)`, radiance units.
    pub mae: f64,
}

/// Checks that two images have the same size and that each holds `width·height` pixels.
fn check_pair(a: &ImageRgb, b: &ImageRgb, what: (&str, &str)) -> Result<()> {
    if a.width != b.width || a.height != b.height {
        return Err(Error::Usage(format!(
            "image sizes differ: {} is {}×{}, {} is {}×{}",
            what.0, a.width, a.height, what.1, b.width, b.height
        )));
    }
    let n = u64::from(a.width) * u64::from(a.height);
    if n == 0 {
        return Err(Error::Usage(format!(
            "cannot compare empty images ({}×{})",
            a.width, a.height
        )));
    }
    for (img, name) in [(a, what.0), (b, what.1)] {
        if img.data.len() as u64 != n {
            return Err(Error::Usage(format!(
                "{name} is {}×{} but holds {} pixels",
                img.width,
                img.height,
                img.data.len()
            )));
        }
    }
    Ok(())
}

/// Iterates over corresponding channel values of two same-size images, as `f64`.
fn channels<'a>(a: &'a ImageRgb, b: &'a ImageRgb) -> impl Iterator<Item = (f64, f64)> + 'a {
    a.data
        .iter()
        .zip(&b.data)
        .flat_map(|(p, q)| (0..3).map(move |c| (f64::from(p[c]), f64::from(q[c]))))
}

/// The metrics from per-value terms: `terms(x, y)` of each pair of corresponding channel
/// values gives (squared error, relative squared error, absolute error); each is averaged
/// over all pairs, and the RMSE is the root of the first mean.
fn mean_metrics(
    a: &ImageRgb,
    b: &ImageRgb,
    terms: impl Fn(f64, f64) -> (f64, f64, f64),
) -> ErrorMetrics {
    let (mut se, mut rel, mut ae) = (0.0f64, 0.0f64, 0.0f64);
    let mut n = 0u64;
    for (x, y) in channels(a, b) {
        let (s, r, e) = terms(x, y);
        se += s;
        rel += r;
        ae += e;
        n += 1;
    }
    let n = n as f64;
    ErrorMetrics {
        rmse: (se / n).sqrt(),
        rel_mse: rel / n,
        mae: ae / n,
    }
}

/// Error of `image` against `reference` (both linear, same size).
///
/// RMSE over pixels and channels; relative MSE = mean over pixels and channels of
/// `(x−r)²/(r²+0.01)`; MAE = mean `|x−r|`.
///
/// Errors: [`Error::Usage`] naming both sizes when they differ, or when an image is empty or
/// its pixel buffer does not match its size.
pub fn compare(image: &ImageRgb, reference: &ImageRgb) -> Result<ErrorMetrics> {
    check_pair(image, reference, ("the image", "the reference"))?;
    Ok(mean_metrics(image, reference, |x, r| {
        let d = x - r;
        (d * d, d * d / (r * r + REL_EPS), d.abs())
    }))
}

/// Estimated error of the full image `(a+b)/2` from two independent half images `a`, `b`
/// (each the mean of half of the samples), without a reference.
///
/// Per pixel and channel, `a−b` has mean 0 (both estimate the same value) and variance
/// `2σ_h²`, where `σ_h²` is the variance of one half; the full image's variance is
/// `σ² = σ_h²/2`, so `(a−b)²/4` is an unbiased estimate of `σ²` (the "two half-buffer"
/// estimate of Rousselle et al. 2012, "Adaptive rendering with non-local means filtering").
/// Assuming the renderer is unbiased, the error against the true image is this noise:
/// - `rmse = sqrt(mean((a−b)²/4))`;
/// - `rel_mse = mean((a−b)²/4 / (m²+0.01))` with `m = (a+b)/2`;
/// - `mae = mean(|a−b|/2)`: for Gaussian noise `E|a−b|/2 = σ·sqrt(2/π) = E|error|`. This
///   equals the plan's `sqrt(2/π)·rmse` when σ is the same everywhere and, unlike it, stays
///   unbiased when σ varies between pixels (Jensen: `mean σ ≤ sqrt(mean σ²)`).
///
/// `rel_mse` uses the noisy `m` for the unknown reference, so it reads high by about
/// `3σ²/m²` where the noise is comparable to the value (`E[1/m²] ≈ (1 + 3σ²/μ²)/μ²`); it is
/// accurate once the image is nearly converged, which is when it is used to stop.
///
/// The estimate itself is noisy per pixel but averages over all pixels and channels; it misses
/// bias (e.g. a photon map's blur), which only [`compare`] against a reference can see.
///
/// Errors: as [`compare`].
pub fn half_buffer_estimate(a: &ImageRgb, b: &ImageRgb) -> Result<ErrorMetrics> {
    check_pair(a, b, ("half image A", "half image B"))?;
    Ok(mean_metrics(a, b, half_pair_terms))
}

/// One channel's terms of [`half_buffer_estimate`] for half means `x` and `y`: the
/// squared error, the relative squared error and the absolute error of their mean.
pub fn half_pair_terms(x: f64, y: f64) -> (f64, f64, f64) {
    let d = x - y;
    let v = d * d / 4.0;
    let m = 0.5 * (x + y);
    (v, v / (m * m + REL_EPS), 0.5 * d.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn img(width: u32, height: u32, px: &[[f32; 3]]) -> ImageRgb {
        ImageRgb {
            width,
            height,
            data: px.iter().map(|p| Vec3::from_array(*p)).collect(),
        }
    }

    // Hand-computed values are exact in f64 up to rounding of a handful of operations on
    // values representable in f32, so 1e-12 leaves room only for rounding.
    const TOL: f64 = 1e-12;

    #[test]
    fn compare_2x1_hand_computed() {
        let x = img(2, 1, &[[1.0, 2.0, 0.0], [0.5, 0.0, 3.0]]);
        let r = img(2, 1, &[[1.0, 1.0, 1.0], [0.0, 0.0, 1.0]]);
        // Differences: 0, 1, −1, 0.5, 0, 2 → squares 0, 1, 1, 0.25, 0, 4 (sum 6.25).
        let m = compare(&x, &r).unwrap();
        assert!((m.rmse - (6.25f64 / 6.0).sqrt()).abs() < TOL, "{m:?}");
        // |d| sum = 0 + 1 + 1 + 0.5 + 0 + 2 = 4.5.
        assert!((m.mae - 4.5 / 6.0).abs() < TOL, "{m:?}");
        // Relative: 0/1.01 + 1/1.01 + 1/1.01 + 0.25/0.01 + 0/0.01 + 4/1.01.
        let rel = (6.0 / 1.01 + 0.25 / 0.01) / 6.0;
        assert!((m.rel_mse - rel).abs() < TOL, "{} vs {rel}", m.rel_mse);
    }

    #[test]
    fn compare_2x2_hand_computed_and_identity() {
        let r = img(
            2,
            2,
            &[[0.0; 3], [2.0; 3], [0.1, 0.2, 0.3], [1.0, 0.0, 0.0]],
        );
        let mut x = r.clone();
        x.data[0] = Vec3::splat(0.1); // d = 0.1 on r = 0: rel 0.01/0.01 = 1 per channel
        x.data[1] = Vec3::new(3.0, 2.0, 2.0); // d = 1 on r = 2: rel 1/4.01
        let m = compare(&x, &r).unwrap();
        let d0 = f64::from(0.1f32); // the f32 value actually stored
        let se = 3.0 * d0 * d0 + 1.0;
        assert!((m.rmse - (se / 12.0).sqrt()).abs() < TOL);
        assert!((m.mae - (3.0 * d0 + 1.0) / 12.0).abs() < TOL);
        let rel = (3.0 * d0 * d0 / 0.01 + 1.0 / 4.01) / 12.0;
        assert!((m.rel_mse - rel).abs() < TOL, "{} vs {rel}", m.rel_mse);
        let zero = compare(&r, &r).unwrap();
        assert_eq!(
            zero,
            ErrorMetrics {
                rmse: 0.0,
                rel_mse: 0.0,
                mae: 0.0
            }
        );
    }

    #[test]
    fn size_mismatch_names_both_sizes() {
        let a = ImageRgb::new(2, 1);
        let b = ImageRgb::new(2, 2);
        for err in [compare(&a, &b), half_buffer_estimate(&a, &b)] {
            let msg = err.unwrap_err().to_string();
            assert!(msg.contains("2×1") && msg.contains("2×2"), "{msg}");
        }
        let empty = ImageRgb::new(0, 3);
        assert!(compare(&empty, &empty).is_err());
        let mut short = ImageRgb::new(2, 2);
        short.data.pop();
        assert!(compare(&short, &ImageRgb::new(2, 2)).is_err());
    }

    #[test]
    fn half_buffer_hand_computed() {
        let a = img(2, 1, &[[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]]);
        let b = img(2, 1, &[[3.0, 1.0, 1.0], [0.0, 0.0, 0.2]]);
        // d: −2, 0, 0, 0, 0, −0.2 → (d²/4): 1, 0, 0, 0, 0, 0.01; means m: 2, 1, 1, 0, 0, 0.1.
        let m = half_buffer_estimate(&a, &b).unwrap();
        let d5 = f64::from(0.2f32);
        let v5 = d5 * d5 / 4.0;
        assert!((m.rmse - ((1.0 + v5) / 6.0).sqrt()).abs() < TOL);
        let rel = (1.0 / 4.01 + v5 / ((d5 / 2.0).powi(2) + 0.01)) / 6.0;
        assert!((m.rel_mse - rel).abs() < TOL);
        assert!((m.mae - (1.0 + d5 / 2.0) / 6.0).abs() < TOL);
    }

    /// SplitMix64 (Steele et al. 2014) → uniform in (0, 1]; deterministic, no dependency.
    struct Rng(u64);
    impl Rng {
        fn uniform(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            ((z >> 11) as f64 + 1.0) / (1u64 << 53) as f64
        }
        /// Standard normal by Box–Muller.
        fn normal(&mut self) -> f64 {
            let (u, v) = (self.uniform(), self.uniform());
            (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        }
    }

    #[test]
    fn half_buffer_matches_true_error_on_synthetic_noise() {
        // Truth: a gradient ≥ 0.5; each half = truth + independent N(0, σ_h²) noise, with σ_h
        // varying by pixel (0.02 or 0.08) so the MAE formula's heteroscedastic case is tested.
        // The noise stays well below the values: rel_mse divides by the noisy m², which
        // inflates it by ≈ 3σ²/m² (≤ 4 % here; see the function's doc).
        let (w, h) = (64u32, 64u32);
        let mut rng = Rng(12345);
        let truth = ImageRgb {
            width: w,
            height: h,
            data: (0..w * h)
                .map(|i| Vec3::new(0.5 + (i % w) as f32 / w as f32, 0.5, 2.0))
                .collect(),
        };
        let mut noisy = |img: &ImageRgb| {
            let mut out = img.clone();
            for (i, p) in out.data.iter_mut().enumerate() {
                let s = if i % 2 == 0 { 0.02 } else { 0.08 };
                *p += Vec3::from_array([(); 3].map(|_| (s * rng.normal()) as f32));
            }
            out
        };
        let (a, b) = (noisy(&truth), noisy(&truth));
        let full = a.mean_with(&b);
        let actual = compare(&full, &truth).unwrap();
        let est = half_buffer_estimate(&a, &b).unwrap();
        // 12288 channel values: the estimate's relative standard deviation is ~1–2 % (the
        // variance of a χ²₁ mean), so 10 % is a > 5σ margin, while a factor-2 mistake in the
        // formula (e.g. forgetting the /4, or using the half's variance) is caught.
        for (name, e, t) in [
            ("rmse", est.rmse, actual.rmse),
            ("rel_mse", est.rel_mse, actual.rel_mse),
            ("mae", est.mae, actual.mae),
        ] {
            assert!(
                (e / t - 1.0).abs() < 0.10,
                "{name}: estimate {e} vs true {t}"
            );
        }
        // Sanity: the true RMSE is near the analytic sqrt(mean σ²/2) = sqrt((0.02²+0.08²)/4).
        let analytic = ((0.02f64.powi(2) + 0.08f64.powi(2)) / 4.0).sqrt();
        assert!(
            (actual.rmse / analytic - 1.0).abs() < 0.05,
            "{}",
            actual.rmse
        );
    }
}
