//! [`EmissionSpectrum`]: the Iris key `iris_spectrum` on a light (glTF
//! KHR_lights_punctual `extras`) or an emissive material (glTF material `extras`, MTL
//! statement), and the colour the RGB transport derives from it.
//!
//! Units: temperatures in kelvin, wavelengths in nm. Invariant: every spectrum here has
//! luminance Y = 1 (CIE 1931 2°, Y of the constant 1 is 1, see
//! [`crate::spectrum::cie::spectrum_to_xyz`]), so the spectrum sets the colour and shape
//! only; the photometric intensity (cd, lx, emissive strength) keeps its meaning and the
//! file's RGB colour multiplies as a filter.

use crate::spectrum::cie::{spectrum_to_xyz, xyz_to_linear_srgb};
use crate::spectrum::{EmitterShape, Spectrum};
use glam::Vec3;
use std::fmt;

/// `filter` × the spectrum's linear-sRGB colour (Y = 1), or `filter` alone without one.
pub fn effective_color(filter: Vec3, spectrum: Option<EmissionSpectrum>) -> Vec3 {
    spectrum.map_or(filter, |s| filter * s.linear_srgb())
}

/// The spectral shape of an emitter, named by the Iris key `iris_spectrum` (glTF light or
/// material `extras`, MTL statement). Always normalised to luminance Y = 1 (CIE 1931 Y,
/// as in [`spectrum_to_xyz`]), so choosing a spectrum changes the colour, never the
/// luminous output; the file's RGB colour multiplies it as a filter (white = no change).
///
/// Written forms (case-insensitive): `"D65"`, `"sun"`, `{"blackbody": K}` or
/// `"blackbody K"` in glTF; `iris_spectrum D65`, `iris_spectrum sun`,
/// `iris_spectrum blackbody K` in MTL. `K` is in kelvin, within [`BLACKBODY_KELVIN`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EmissionSpectrum {
    /// CIE standard illuminant D65 (renders exactly white in RGB).
    D65,
    /// Planck's law at this temperature, K.
    Blackbody {
        /// Temperature, K.
        kelvin: f32,
    },
    /// Sunlight-like: a blackbody at [`SUN_KELVIN`], the Sun's nominal effective
    /// temperature (IAU 2015 Resolution B3). This is the solar disc's shape above the
    /// atmosphere, not a sea-level spectrum (no Rayleigh/ozone/water absorption).
    Sun,
}

/// The accepted blackbody temperatures, K (inclusive).
pub const BLACKBODY_KELVIN: (f32, f32) = (1000.0, 40000.0);

/// Temperature of [`EmissionSpectrum::Sun`]: the nominal solar effective temperature,
/// 5772 K (IAU 2015 Resolution B3, Prša et al. 2016, AJ 152:41).
pub const SUN_KELVIN: f32 = 5772.0;

impl EmissionSpectrum {
    /// What the spectral transport needs for an emitter of this spectrum filtered by
    /// `filter` (colour × intensity): the shape, the filter, and the RGB the RGB transport
    /// uses for it ([`effective_color`]).
    pub fn emitter_shape(&self, filter: Vec3) -> EmitterShape {
        EmitterShape {
            shape: self.spectrum(),
            filter,
            reference: effective_color(filter, Some(*self)),
        }
    }

    /// A blackbody, or the reason `kelvin` is not accepted (NaN, ±∞, outside
    /// [`BLACKBODY_KELVIN`]).
    pub fn blackbody(kelvin: f64) -> Result<Self, String> {
        let (lo, hi) = BLACKBODY_KELVIN;
        if kelvin.is_nan() || kelvin < f64::from(lo) || kelvin > f64::from(hi) {
            return Err(format!(
                "blackbody temperature {kelvin} K is outside {lo}–{hi} K"
            ));
        }
        Ok(EmissionSpectrum::Blackbody {
            kelvin: kelvin as f32,
        })
    }

    /// Parses the words of the text form: `d65`, `sun` or `blackbody K`
    /// (case-insensitive), or says what is wrong.
    pub fn parse_words(words: &[&str]) -> Result<Self, String> {
        let lower: Vec<String> = words.iter().map(|w| w.to_ascii_lowercase()).collect();
        let lower: Vec<&str> = lower.iter().map(String::as_str).collect();
        match lower.as_slice() {
            ["d65"] => Ok(EmissionSpectrum::D65),
            ["sun"] => Ok(EmissionSpectrum::Sun),
            ["blackbody", k] => {
                let kelvin = k
                    .parse::<f64>()
                    .map_err(|_| format!("blackbody temperature `{k}` is not a number"))?;
                Self::blackbody(kelvin)
            }
            ["blackbody", ..] => Err("`blackbody` expects one temperature in kelvin".into()),
            [] => Err(format!("expected a spectrum name, {}", Self::FORMS)),
            _ => Err(format!(
                "unknown spectrum `{}`, {}",
                words.join(" "),
                Self::FORMS
            )),
        }
    }

    /// The accepted forms, for error messages.
    const FORMS: &'static str = "expected D65, sun or blackbody K (1000–40000 K)";

    /// Re-checks a value built in code (validation): a blackbody must be in range.
    pub fn check(&self) -> Result<(), String> {
        match *self {
            EmissionSpectrum::Blackbody { kelvin } => Self::blackbody(f64::from(kelvin)).map(drop),
            EmissionSpectrum::D65 | EmissionSpectrum::Sun => Ok(()),
        }
    }

    /// The spectral power distribution with luminance Y = 1 (relative radiance per nm);
    /// the spectral transport multiplies it by the intensity and the colour filter.
    pub fn spectrum(&self) -> Spectrum {
        match *self {
            EmissionSpectrum::D65 => Spectrum::d65(1.0),
            EmissionSpectrum::Blackbody { kelvin } => Spectrum::blackbody(kelvin, 1.0),
            EmissionSpectrum::Sun => Spectrum::blackbody(SUN_KELVIN, 1.0),
        }
    }

    /// CIE 1931 XYZ of [`Self::spectrum`] (Y = 1).
    pub fn xyz(&self) -> [f32; 3] {
        spectrum_to_xyz(|l| self.spectrum().eval(l))
    }

    /// The RGB transport's colour for this spectrum: XYZ → linear sRGB (IEC 61966-2-1),
    /// negative (out-of-gamut, e.g. below ~1900 K) components clamped to 0, then scaled so
    /// that its luminance 0.2126 R + 0.7152 G + 0.0722 B is 1. D65 gives (1, 1, 1).
    /// Costs a 471-sample sum: call once per light or material, not per shading point.
    pub fn linear_srgb(&self) -> Vec3 {
        let rgb = Vec3::from(xyz_to_linear_srgb(self.xyz())).max(Vec3::ZERO);
        let y = rgb.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        if y.is_nan() || y <= 0.0 {
            return Vec3::ONE;
        }
        rgb / y
    }
}

impl fmt::Display for EmissionSpectrum {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EmissionSpectrum::D65 => write!(f, "D65"),
            EmissionSpectrum::Blackbody { kelvin } => write!(f, "blackbody {kelvin} K"),
            EmissionSpectrum::Sun => write!(f, "sun (blackbody {SUN_KELVIN} K)"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_names_case_insensitively() {
        let p = |s: &str| EmissionSpectrum::parse_words(&s.split_whitespace().collect::<Vec<_>>());
        assert_eq!(p("d65"), Ok(EmissionSpectrum::D65));
        assert_eq!(p("SUN"), Ok(EmissionSpectrum::Sun));
        assert_eq!(
            p("BlackBody 2700.5"),
            Ok(EmissionSpectrum::Blackbody { kelvin: 2700.5 })
        );
        for bad in [
            "",
            "neon",
            "blackbody",
            "blackbody x",
            "blackbody 1 2",
            "blackbody 999.9",
        ] {
            assert!(p(bad).is_err(), "{bad:?}");
        }
        let e = p("blackbody 50000").unwrap_err();
        assert!(e.contains("1000") && e.contains("40000"), "{e}");
    }

    #[test]
    fn effective_colour_filters_the_spectrum() {
        let warm = EmissionSpectrum::Blackbody { kelvin: 2700.0 };
        let filter = Vec3::new(0.5, 1.0, 2.0);
        assert_eq!(effective_color(filter, None), filter);
        assert_eq!(
            effective_color(filter, Some(warm)),
            filter * warm.linear_srgb()
        );
        // The spectrum module's `blackbody` test checks the SPD itself; here its Y = 1.
        assert!((warm.xyz()[1] - 1.0).abs() < 1e-4);
    }
}
