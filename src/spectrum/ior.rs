//! Index-of-refraction models n(λ) and named dispersive materials.
//!
//! Units: λ in nm (vacuum) at the API; Cauchy and Sellmeier coefficients are defined with λ
//! in µm (their sources' convention) and converted inside. n is the absolute (vacuum) index.
//! Invariants: dispersive models return n ≥ 1 (clamped, as KHR_materials_dispersion does);
//! `Constant` returns its value unchanged (the loader validates it and owns the
//! KHR_materials_ior `ior = 0` special case, for which `from_khr` yields a non-dispersive
//! model). Evaluation is in f64, never panics, and maps non-finite results (NaN λ, a
//! resonance hit exactly) to 1.

use std::fmt;

/// Fraunhofer d line (helium), nm: where catalogues quote n_d.
pub const LAMBDA_D: f32 = 587.56;
/// Fraunhofer F line (hydrogen), nm.
pub const LAMBDA_F: f32 = 486.13;
/// Fraunhofer C line (hydrogen), nm.
pub const LAMBDA_C: f32 = 656.27;

/// How a material's index of refraction varies with wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IorModel {
    /// The same n at every wavelength (no dispersion).
    Constant(f32),
    /// KHR_materials_dispersion: n(λ) = max(n_d + (n_d − 1)·(D/20)·(523655/λ² − 1.5168), 1),
    /// λ in nm; `dispersion` D = 20/V_d (Abbe number V_d).
    KhrDispersion {
        /// n at the d line.
        n_d: f32,
        /// The extension's `dispersion` value, 20/V_d; 0 means none.
        dispersion: f32,
    },
    /// Cauchy: n(λ) = b + c/λ², λ in µm (crown glass: b ≈ 1.5, c ≈ 0.0042 µm²).
    Cauchy {
        /// Constant term.
        b: f32,
        /// Coefficient of 1/λ², µm².
        c: f32,
    },
    /// Sellmeier: n² = 1 + Σ_i b_i λ² / (λ² − c_i), λ in µm, c_i in µm². Unused terms are 0.
    /// Four terms because water (Daimon & Masumura 2007) needs them.
    Sellmeier {
        /// Oscillator strengths B_i.
        b: [f32; 4],
        /// Resonance wavelengths squared C_i, µm².
        c: [f32; 4],
    },
}

/// A name given to [`IorModel::named`] that is not in the built-in list.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownIorName(pub String);

impl fmt::Display for UnknownIorName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown dispersive material \"{}\"; known: ", self.0)?;
        f.write_str(&KNOWN_NAMES.join(", "))
    }
}

impl std::error::Error for UnknownIorName {}

/// Canonical names accepted by [`IorModel::named`] (case-insensitive; ' ', '_' ≡ '-').
pub const KNOWN_NAMES: [&str; 6] = [
    "N-BK7",
    "N-SF11",
    "fused silica",
    "diamond",
    "water",
    "sapphire",
];

/// Three-term Sellmeier coefficients padded to four.
fn sellmeier3(b: [f32; 3], c: [f32; 3]) -> IorModel {
    IorModel::Sellmeier {
        b: [b[0], b[1], b[2], 0.0],
        c: [c[0], c[1], c[2], 0.0],
    }
}

/// Squares resonance wavelengths (µm → µm²), for sources that tabulate λ_i rather than C_i.
fn squared<const K: usize>(l: [f32; K]) -> [f32; K] {
    l.map(|x| x * x)
}

impl IorModel {
    /// A built-in material by name (case-insensitive; spaces, '_' and '-' are interchangeable;
    /// "BK7", "SF11", "silica" are accepted aliases). Coefficients keep their sources' digits.
    #[allow(clippy::excessive_precision)]
    pub fn named(name: &str) -> Result<IorModel, UnknownIorName> {
        let key: String = name
            .trim()
            .chars()
            .map(|ch| match ch {
                ' ' | '_' => '-',
                _ => ch.to_ascii_lowercase(),
            })
            .collect();
        Ok(match key.as_str() {
            // SCHOTT optical glass data sheet N-BK7 (catalogue 2017): n_d = 1.5168, V_d = 64.17.
            "n-bk7" | "bk7" => sellmeier3(
                [1.03961212, 0.231792344, 1.01046945],
                [0.00600069867, 0.0200179144, 103.560653],
            ),
            // SCHOTT optical glass data sheet N-SF11 (catalogue 2017): n_d = 1.78472,
            // V_d = 25.68.
            "n-sf11" | "sf11" => sellmeier3(
                [1.73759695, 0.313747346, 1.89878101],
                [0.013188707, 0.0623068142, 155.23629],
            ),
            // I. H. Malitson, "Interspecimen comparison of the refractive index of fused
            // silica", JOSA 55, 1205 (1965), 20 °C; the paper lists λ_i in µm.
            "fused-silica" | "silica" | "fused-quartz" => sellmeier3(
                [0.6961663, 0.4079426, 0.8974794],
                squared([0.0684043, 0.1162414, 9.896161]),
            ),
            // F. Peter, Z. Phys. 15, 358 (1923), two-term fit as on refractiveindex.info
            // (main/C/Peter); λ_i in µm.
            "diamond" => IorModel::Sellmeier {
                b: [0.3306, 4.3356, 0.0, 0.0],
                c: squared([0.1750, 0.1060, 0.0, 0.0]),
            },
            // M. Daimon & A. Masumura, "Measurement of the refractive index of distilled water
            // from the near-infrared region to the ultraviolet region", Appl. Opt. 46, 3811
            // (2007), 20.0 °C four-term fit (refractiveindex.info main/H2O/Daimon-20.0C).
            "water" => IorModel::Sellmeier {
                b: [
                    5.684027565e-1,
                    1.726177391e-1,
                    2.086189578e-2,
                    1.130748688e-1,
                ],
                c: [
                    5.101829712e-3,
                    1.821153936e-2,
                    2.620722293e-2,
                    1.069792721e1,
                ],
            },
            // I. H. Malitson & M. J. Dodge, "Refractive index and birefringence of synthetic
            // sapphire", JOSA 62, 1405 (1972), ordinary ray, 20 °C; λ_i in µm.
            "sapphire" => sellmeier3(
                [1.4313493, 0.65054713, 5.3414021],
                squared([0.0726631, 0.1193242, 18.028251]),
            ),
            _ => return Err(UnknownIorName(name.to_string())),
        })
    }

    /// The model for glTF KHR_materials_ior `ior` + KHR_materials_dispersion `dispersion`:
    /// `Constant(ior)` when dispersion is 0 (or not finite/positive) or `ior` is 0 (the
    /// KHR_materials_ior special mode, which disables dispersion), else `KhrDispersion`.
    pub fn from_khr(ior: f32, dispersion: f32) -> IorModel {
        if ior == 0.0 || dispersion.is_nan() || dispersion <= 0.0 || !dispersion.is_finite() {
            IorModel::Constant(ior)
        } else {
            IorModel::KhrDispersion {
                n_d: ior,
                dispersion,
            }
        }
    }

    /// n at `lambda_nm` (vacuum wavelength, nm).
    pub fn ior(&self, lambda_nm: f32) -> f32 {
        let l = lambda_nm as f64;
        let n = match *self {
            IorModel::Constant(n) => return n,
            IorModel::KhrDispersion { n_d, dispersion } => {
                let (n_d, d) = (n_d as f64, dispersion as f64);
                n_d + (n_d - 1.0) * (d / 20.0) * (523_655.0 / (l * l) - 1.5168)
            }
            IorModel::Cauchy { b, c } => {
                let um = l * 1e-3;
                b as f64 + c as f64 / (um * um)
            }
            IorModel::Sellmeier { b, c } => {
                let l2 = (l * 1e-3) * (l * 1e-3);
                let sum: f64 = b
                    .iter()
                    .zip(&c)
                    .filter(|(bi, _)| **bi != 0.0)
                    .map(|(&bi, &ci)| bi as f64 * l2 / (l2 - ci as f64))
                    .sum();
                (1.0 + sum).max(1.0).sqrt()
            }
        };
        if !n.is_finite() {
            return 1.0;
        }
        // Saturate instead of overflowing to +∞ in the cast (Cauchy c = 3e38 at 360 nm is
        // 2e39 in f64): +∞ is reserved for the `ior: 0` mode.
        n.clamp(1.0, f64::from(f32::MAX)) as f32
    }

    /// The resonance wavelengths (poles) of a Sellmeier model in nm, λ_i = 1000·√C_i, for
    /// the terms in use (b_i ≠ 0, C_i > 0); none for the other models, whose n(λ) has no
    /// pole at λ > 0.
    pub fn poles_nm(&self) -> Vec<f32> {
        match *self {
            IorModel::Sellmeier { b, c } => b
                .iter()
                .zip(&c)
                .filter(|(bi, ci)| **bi != 0.0 && **ci > 0.0)
                .map(|(_, &ci)| (f64::from(ci).sqrt() * 1e3) as f32)
                .collect(),
            _ => Vec::new(),
        }
    }

    /// The first pole ([`IorModel::poles_nm`]) in the closed range `[lo, hi]` nm, if any.
    /// Validation rejects a model with a pole in the sampled range
    /// [`LAMBDA_MIN`](super::LAMBDA_MIN)–[`LAMBDA_MAX`](super::LAMBDA_MAX): n(λ) diverges
    /// there (and n² < 0 just below it), so no clamp gives a meaningful index.
    pub fn pole_in(&self, lo: f32, hi: f32) -> Option<f32> {
        self.poles_nm().into_iter().find(|&p| p >= lo && p <= hi)
    }

    /// Whether n depends on λ (the integrator then calls `terminate_secondary`).
    pub fn is_dispersive(&self) -> bool {
        match *self {
            IorModel::Constant(_) => false,
            IorModel::KhrDispersion { dispersion, .. } => dispersion != 0.0,
            IorModel::Cauchy { c, .. } => c != 0.0,
            IorModel::Sellmeier { b, .. } => b.iter().any(|&bi| bi != 0.0),
        }
    }

    /// n at the d line, 587.56 nm (the single value a non-spectral renderer would use).
    pub fn n_d(&self) -> f32 {
        self.ior(LAMBDA_D)
    }

    /// Abbe number V_d = (n_d − 1)/(n_F − n_C); infinite for non-dispersive models.
    pub fn abbe_number(&self) -> f32 {
        let (nf, nc) = (self.ior(LAMBDA_F) as f64, self.ior(LAMBDA_C) as f64);
        ((self.n_d() as f64 - 1.0) / (nf - nc)) as f32
    }
}

#[cfg(test)]
#[path = "ior_tests.rs"]
mod tests;
