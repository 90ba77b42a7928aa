//! `Spectrum`: a full spectral distribution as a scene names it (constant, RGB reflectance,
//! RGB illuminant, blackbody, D65), evaluated at a path's wavelengths by materials and lights.
//!
//! Units: λ in nm. Reflectances are unitless in [0, 1]. Emission spectra are relative
//! radiance scaled so that their luminance Y (as in [`super::cie::spectrum_to_xyz`], where
//! the constant 1 has Y = 1) equals the luminance asked for: `Spectrum::blackbody(T, 1.0)`,
//! `Spectrum::d65(1.0)` and `Spectrum::illuminant([1.0; 3])` all have Y = 1, and the last
//! two are the same spectrum (sRGB white). Invalid inputs (NaN, negative temperature or
//! luminance) give the zero spectrum, never a panic.

use super::cie::{blackbody_normalized, d65_normalized, spectrum_to_xyz};
use super::{RgbIlluminant, RgbReflectance, SampledSpectrum, SampledWavelengths};

/// A spectral distribution over 360–830 nm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Spectrum {
    /// The same value at every wavelength.
    Constant(f32),
    /// A reflectance upsampled from linear sRGB.
    Reflectance(RgbReflectance),
    /// An emission spectrum upsampled from linear sRGB.
    Illuminant(RgbIlluminant),
    /// Planck's law at `kelvin`, peak-normalised, times `scale`.
    Blackbody {
        /// Temperature, K.
        kelvin: f32,
        /// Factor on the peak-normalised curve (set so that Y is the requested luminance).
        scale: f32,
    },
    /// CIE D65 normalised to Y = 1, times `scale`.
    D65 {
        /// Luminance Y.
        scale: f32,
    },
}

/// `v` if finite and ≥ 0, else 0.
fn sanitize(v: f32) -> f32 {
    if v.is_finite() && v > 0.0 {
        v
    } else {
        0.0
    }
}

impl Spectrum {
    /// A constant spectrum (NaN → 0).
    pub fn constant(c: f32) -> Self {
        Spectrum::Constant(if c.is_nan() { 0.0 } else { c })
    }

    /// A reflectance from linear sRGB (clamped to [0, 1]); grey RGB gives a constant.
    pub fn reflectance(rgb: [f32; 3]) -> Self {
        Spectrum::Reflectance(RgbReflectance::new(rgb))
    }

    /// An emission spectrum from linear sRGB radiance; RGB (1, 1, 1) is D65 with Y = 1.
    pub fn illuminant(rgb: [f32; 3]) -> Self {
        Spectrum::Illuminant(RgbIlluminant::new(rgb))
    }

    /// A blackbody at `kelvin` with luminance Y = `luminance`.
    pub fn blackbody(kelvin: f32, luminance: f32) -> Self {
        let (kelvin, luminance) = (sanitize(kelvin), sanitize(luminance));
        if kelvin == 0.0 || luminance == 0.0 {
            return Spectrum::Constant(0.0);
        }
        let y = spectrum_to_xyz(|l| blackbody_normalized(l, kelvin))[1];
        if y.is_nan() || y <= 0.0 {
            // Too cold to emit visibly in f32 (below ~300 K).
            return Spectrum::Constant(0.0);
        }
        Spectrum::Blackbody {
            kelvin,
            scale: luminance / y,
        }
    }

    /// CIE D65 with luminance Y = `luminance`.
    pub fn d65(luminance: f32) -> Self {
        Spectrum::D65 {
            scale: sanitize(luminance),
        }
    }

    /// Value at `lambda` nm.
    pub fn eval(&self, lambda: f32) -> f32 {
        match self {
            Spectrum::Constant(c) => *c,
            Spectrum::Reflectance(r) => r.eval(lambda),
            Spectrum::Illuminant(e) => e.eval(lambda),
            Spectrum::Blackbody { kelvin, scale } => scale * blackbody_normalized(lambda, *kelvin),
            Spectrum::D65 { scale } => scale * d65_normalized(lambda),
        }
    }

    /// Values at the path's wavelengths.
    pub fn sample(&self, lambda: &SampledWavelengths) -> SampledSpectrum {
        match self {
            Spectrum::Constant(c) => SampledSpectrum::splat(*c),
            _ => SampledSpectrum::from_fn(lambda, |l| self.eval(l)),
        }
    }

    /// CIE XYZ of the spectrum (1 nm Riemann sum; for emission, Y is the luminance used to
    /// pick lights by power). Costs 471 evaluations: call once per light, not per sample.
    pub fn xyz(&self) -> [f32; 3] {
        spectrum_to_xyz(|l| self.eval(l))
    }
}

#[cfg(test)]
mod tests {
    use super::super::cie::{chromaticity, xyz_to_linear_srgb};
    use super::*;

    #[test]
    fn emission_luminance_is_as_requested() {
        for s in [
            Spectrum::blackbody(2700.0, 3.0),
            Spectrum::blackbody(6500.0, 3.0),
            Spectrum::d65(3.0),
            Spectrum::illuminant([3.0; 3]),
        ] {
            // Y is normalised through the same 1 nm sum, so only f32 rounding remains.
            assert!((s.xyz()[1] - 3.0).abs() < 1e-4, "{s:?}: {:?}", s.xyz());
        }
    }

    #[test]
    fn d65_and_white_illuminant_agree() {
        let (a, b) = (Spectrum::d65(1.0), Spectrum::illuminant([1.0; 3]));
        for l in [361.0, 450.0, 555.5, 700.0, 829.0] {
            assert_eq!(a.eval(l), b.eval(l));
        }
        let rgb = xyz_to_linear_srgb(a.xyz());
        assert!(rgb.iter().all(|c| (c - 1.0).abs() < 1e-3), "{rgb:?}");
    }

    #[test]
    fn blackbody_chromaticity_on_planckian_locus() {
        // Planckian locus (CIE 1931 2°, c2 = 1.4388e-2 m·K): 6500 K → (0.3135, 0.3237),
        // 3000 K → (0.4369, 0.4041). 1e-3 covers the CMF table's 1 nm truncation.
        let [x, y] = chromaticity(Spectrum::blackbody(6500.0, 1.0).xyz());
        assert!(
            (x - 0.3135).abs() < 1e-3 && (y - 0.3237).abs() < 1e-3,
            "({x}, {y})"
        );
        let [x, y] = chromaticity(Spectrum::blackbody(3000.0, 1.0).xyz());
        assert!(
            (x - 0.4369).abs() < 1e-3 && (y - 0.4041).abs() < 1e-3,
            "({x}, {y})"
        );
    }

    #[test]
    fn invalid_inputs_give_zero() {
        for s in [
            Spectrum::blackbody(-5.0, 1.0),
            Spectrum::blackbody(f32::NAN, 1.0),
            Spectrum::blackbody(5000.0, f32::INFINITY),
            Spectrum::blackbody(1.0, 1.0),
            Spectrum::d65(-1.0),
            Spectrum::constant(f32::NAN),
        ] {
            assert_eq!(s.eval(550.0), 0.0, "{s:?}");
        }
    }

    #[test]
    fn sample_matches_eval() {
        let w = SampledWavelengths::sample_visible(0.37);
        let s = Spectrum::reflectance([0.8, 0.3, 0.1]);
        let v = s.sample(&w);
        for i in 0..4 {
            assert_eq!(v[i], s.eval(w.lambda(i)));
        }
        assert_eq!(
            Spectrum::constant(0.25).sample(&w),
            SampledSpectrum::splat(0.25)
        );
    }
}
