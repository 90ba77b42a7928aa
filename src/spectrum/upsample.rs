//! RGB → spectrum upsampling after Smits 1999 ("An RGB-to-Spectrum Conversion for
//! Reflectances", JGT 4(4)), with basis spectra fitted here for linear sRGB under D65.
//!
//! Units: RGB is linear sRGB (D65 white); λ in nm. A reflectance RGB is the sRGB of the
//! reflectance lit by D65 normalised to Y = 1, i.e. rgb(s) = M·∫cmf·s·D65 / ∫ȳ·D65.
//!
//! Smits writes any RGB as `min·white + (mid−min)·secondary + (max−mid)·primary`, with
//! white ≡ 1 and six smooth basis spectra (cyan, magenta, yellow, red, green, blue). Smits'
//! published bins were fitted for another RGB space; `basis()` instead fits them, once, by
//! minimising the first-difference roughness Σ(s_{j+1} − s_j)² on a 10 nm grid subject to
//! rgb(s) = the basis colour exactly and 0 ≤ s ≤ 1 (Smits' §3 criterion; solved as an
//! equality-constrained least-squares problem whose out-of-range nodes are pinned to the
//! bound one at a time). Invariants, all tested:
//! - rgb(upsample(c)) = c for c in [0, 1]³, up to the 4-digit sRGB matrix (~2e-4), because
//!   the map is linear in the basis and each basis colour is met exactly;
//! - RGB (g, g, g) gives the constant spectrum g exactly, so white stays white through any
//!   non-dispersive path; reflectance spectra stay in [0, 1];
//! - the illuminant of RGB (1, 1, 1) is D65 with Y = 1, which the film maps to sRGB (1, 1, 1).

use super::cie::{cmf, d65, d65_normalized, table_point, XYZ_TO_SRGB};
use super::{SampledSpectrum, SampledWavelengths, LAMBDA_MIN};
use std::sync::OnceLock;

/// Basis grid: nodes every 10 nm from 360 to 830 nm, piecewise-linear in between.
const NODES: usize = 48;
const STEP: f32 = 10.0;

/// Which fitted basis spectrum (index into [`basis`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Basis {
    Cyan = 0,
    Magenta = 1,
    Yellow = 2,
    Red = 3,
    Green = 4,
    Blue = 5,
}

/// Target linear sRGB of each [`Basis`].
const TARGETS: [[f64; 3]; 6] = [
    [0.0, 1.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];

/// Node values of the six basis spectra, fitted on first use (a few hundred µs).
fn basis() -> &'static [[f32; NODES]; 6] {
    static B: OnceLock<[[f32; NODES]; 6]> = OnceLock::new();
    B.get_or_init(|| TARGETS.map(|t| super::fit::fit_smooth_spectrum(&rgb_weights(), t)))
}

/// The 3×NODES matrix R with rgb(s) = R·s for node values s (1 nm Riemann sums of each
/// node's hat function against cmf·D65, normalised by ∫ȳ·D65, then the sRGB matrix).
pub(super) fn rgb_weights() -> [[f64; NODES]; 3] {
    let mut xyz = [[0.0f64; NODES]; 3];
    let mut y_norm = 0.0f64;
    for i in 0..=470 {
        let l = LAMBDA_MIN + i as f32;
        let c = cmf(l);
        let e = d65(l) as f64;
        y_norm += c[1] as f64 * e;
        let x = i as f32 / STEP;
        let j = (x as usize).min(NODES - 2);
        let t = (x - j as f32) as f64;
        for k in 0..3 {
            xyz[k][j] += (1.0 - t) * c[k] as f64 * e;
            xyz[k][j + 1] += t * c[k] as f64 * e;
        }
    }
    let mut r = [[0.0f64; NODES]; 3];
    for (row, m) in r.iter_mut().zip(XYZ_TO_SRGB) {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..3).map(|k| m[k] as f64 * xyz[k][j]).sum::<f64>() / y_norm;
        }
    }
    r
}

/// Where `lambda` nm falls on the basis grid: the node below and the fraction of the way to
/// the next (`None` outside 360–830 nm). Shared by every basis spectrum at that wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
struct GridPoint(Option<(usize, f32)>);

impl GridPoint {
    fn at(lambda: f32) -> Self {
        GridPoint(table_point(NODES, STEP, lambda))
    }

    /// Piecewise-linear evaluation of node values here (0 outside 360–830 nm).
    #[inline]
    fn eval(self, nodes: &[f32; NODES]) -> f32 {
        match self.0 {
            Some((j, t)) => nodes[j] * (1.0 - t) + nodes[j + 1] * t,
            None => 0.0,
        }
    }
}

/// A reflectance spectrum upsampled from an RGB triple: `white + a·b1(λ) + c·b2(λ)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RgbReflectance {
    white: f32,
    terms: [(Basis, f32); 2],
}

impl RgbReflectance {
    /// Upsamples linear sRGB `rgb`; components are clamped to [0, 1] (NaN → 0), so the
    /// spectrum lies in [0, 1].
    pub fn new(rgb: [f32; 3]) -> Self {
        let [r, g, b] = rgb.map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) });
        use Basis::*;
        // Smits 1999, §3: subtract the grey part, then the secondary, then the primary.
        let (white, terms) = if r <= g && r <= b {
            if g <= b {
                (r, [(Cyan, g - r), (Blue, b - g)])
            } else {
                (r, [(Cyan, b - r), (Green, g - b)])
            }
        } else if g <= r && g <= b {
            if r <= b {
                (g, [(Magenta, r - g), (Blue, b - r)])
            } else {
                (g, [(Magenta, b - g), (Red, r - b)])
            }
        } else if r <= g {
            (b, [(Yellow, r - b), (Green, g - r)])
        } else {
            (b, [(Yellow, g - b), (Red, r - g)])
        };
        RgbReflectance { white, terms }
    }

    /// Reflectance at `lambda` nm, in [0, 1].
    pub fn eval(&self, lambda: f32) -> f32 {
        self.eval_with(basis(), GridPoint::at(lambda))
    }

    /// Reflectance at the path's wavelengths: [`Self::eval`] at each, with the basis fetched
    /// and each wavelength's grid point found once for both terms, and neither for a grey
    /// (both terms 0: the clamped white in every lane, as [`Self::eval`] gives).
    pub fn sample(&self, lambda: &SampledWavelengths) -> SampledSpectrum {
        if self.terms.iter().all(|&(_, w)| w == 0.0) {
            return SampledSpectrum::splat(self.white.clamp(0.0, 1.0));
        }
        let basis = basis();
        SampledSpectrum::from_fn(lambda, |l| self.eval_with(basis, GridPoint::at(l)))
    }

    /// `white + Σ w·basis(λ)` clamped to [0, 1], at grid point `at`.
    #[inline]
    fn eval_with(&self, basis: &[[f32; NODES]; 6], at: GridPoint) -> f32 {
        let mut v = self.white;
        for (b, w) in self.terms {
            if w != 0.0 {
                v += w * at.eval(&basis[b as usize]);
            }
        }
        v.clamp(0.0, 1.0)
    }
}

/// An emission spectrum upsampled from an RGB triple: `max(rgb) · reflectance(rgb / max) ·
/// D65/Y(D65)`, so RGB (1, 1, 1) is D65 with luminance 1 and scaling the RGB scales the
/// spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RgbIlluminant {
    scale: f32,
    shape: RgbReflectance,
}

impl RgbIlluminant {
    /// Upsamples linear sRGB radiance `rgb` (any non-negative values; negative and NaN → 0).
    pub fn new(rgb: [f32; 3]) -> Self {
        let rgb = rgb.map(|v| if v.is_nan() { 0.0 } else { v.max(0.0) });
        let m = rgb[0].max(rgb[1]).max(rgb[2]);
        let shape = if m > 0.0 && m.is_finite() {
            RgbReflectance::new(rgb.map(|v| v / m))
        } else {
            RgbReflectance::new([0.0; 3])
        };
        let scale = if m.is_finite() { m } else { 0.0 };
        RgbIlluminant { scale, shape }
    }

    /// Spectral radiance at `lambda` nm.
    pub fn eval(&self, lambda: f32) -> f32 {
        self.scale * self.shape.eval(lambda) * d65_normalized(lambda)
    }

    /// Radiance at the path's wavelengths.
    pub fn sample(&self, lambda: &SampledWavelengths) -> SampledSpectrum {
        self.sample_with_d65(lambda, SampledSpectrum::from_fn(lambda, d65_normalized))
    }

    /// `RgbIlluminant::new(rgb).sample_with_d65(lambda, d65)`, the same bits, without the
    /// decomposition for a grey `(g, g, g)`: then `rgb / max` is exactly (1, 1, 1), whose
    /// reflectance is 1 at every λ, so the radiance is `d65 · g` (0 unless g is positive and
    /// finite). White lights and grey environments take this path at every hit.
    pub fn sample_rgb(
        rgb: [f32; 3],
        lambda: &SampledWavelengths,
        d65: SampledSpectrum,
    ) -> SampledSpectrum {
        let [r, g, b] = rgb;
        if r == g && g == b {
            return if g > 0.0 && g.is_finite() {
                d65 * g
            } else {
                SampledSpectrum::zero()
            };
        }
        Self::new(rgb).sample_with_d65(lambda, d65)
    }

    /// [`Self::sample`] with D65/Y(D65) at those wavelengths already looked up (the spectral
    /// transport caches it per camera sample).
    pub fn sample_with_d65(
        &self,
        lambda: &SampledWavelengths,
        d65: SampledSpectrum,
    ) -> SampledSpectrum {
        if self.scale == 0.0 {
            return SampledSpectrum::zero();
        }
        self.shape.sample(lambda) * d65 * self.scale
    }
}

#[cfg(test)]
#[path = "upsample_tests.rs"]
mod tests;
