//! A homogeneous scattering medium: what fills a closed mesh whose material scatters
//! (KHR_materials_volume + KHR_materials_volume_scatter / KHR_materials_scatter, or Iris's
//! `iris_medium` extras) or the air of a whole scene (`--fog`, [`super::fog`]).
//!
//! Units: coefficients in inverse scene units (m⁻¹ for metric files); wavelengths in nm.
//! Invariants (checked by [`Medium::check`] before a scene is built): every coefficient is
//! finite and ≥ 0 (an attenuation colour channel of 0 is an opaque channel, σ_t clamped to
//! [`SIGMA_MAX`]); the phase function's anisotropy lies in (−1, 1).
//!
//! Coefficients per wavelength ([`Medium::coeffs`]), for RGB or spectral transport alike:
//! - [`Scattering::Albedo`] (the glTF drafts): σ_t(λ) = −ln c(λ) / d from the attenuation
//!   colour c upsampled as a reflectance (the same spectrum the Beer–Lambert absorption of
//!   non-scattering volumes uses), and σ_s = ρ_ss(ρ_ms(λ)) σ_t with ρ_ms the
//!   `multiscatterColor` upsampled likewise and ρ_ss the single-scattering albedo
//!   ([`super::coefficients::single_scatter_albedo`]).
//! - [`Scattering::Rayleigh`]: σ_s(λ) = σ_s(550) (550/λ)⁴ (at Rec. 709's dominant
//!   wavelengths in RGB, [`super::coefficients::Spectral::rgb`]), the attenuation then being
//!   absorption on top: σ_t = σ_a + σ_s.

use super::coefficients::{single_scatter_albedo, Spectral};
use super::phase::Phase;
use crate::spectrum::Carrier;
use glam::Vec3;

/// The largest extinction used (an attenuation colour of 0 is opaque: σ_t = +∞ is clamped
/// here so that σ_t·e^(−σ_t t) stays finite).
pub const SIGMA_MAX: f32 = 1e30;

/// How a medium scatters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scattering {
    /// The glTF drafts: a part of the attenuation scatters, given by the multiple-scattering
    /// albedo per channel (`multiscatterColor`, linear RGB in [0, 1]).
    Albedo {
        /// Multiple-scattering albedo ρ_ms.
        multiscatter: Vec3,
    },
    /// Rayleigh scattering (small particles): σ_s at 550 nm, falling as λ⁻⁴.
    Rayleigh {
        /// σ_s(550 nm), inverse scene units.
        at_550: f32,
    },
}

/// A homogeneous scattering medium.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Medium {
    /// KHR_materials_volume's attenuation colour (linear RGB, in [0, 1]).
    pub attenuation_color: Vec3,
    /// KHR_materials_volume's attenuation distance (scene units, +∞ for none).
    pub attenuation_distance: f32,
    /// What scatters.
    pub scattering: Scattering,
    /// The phase function of a scattering event.
    pub phase: Phase,
}

/// What a material says about scattering in its volume; the attenuation comes from its
/// KHR_materials_volume fields ([`VolumeScatter::medium`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VolumeScatter {
    /// What scatters.
    pub scattering: Scattering,
    /// The phase function.
    pub phase: Phase,
}

impl VolumeScatter {
    /// The medium of a volume with this scattering and KHR_materials_volume's attenuation
    /// colour and distance.
    pub fn medium(&self, attenuation_color: Vec3, attenuation_distance: f32) -> Medium {
        Medium {
            attenuation_color,
            attenuation_distance,
            scattering: self.scattering,
            phase: self.phase,
        }
    }
}

/// σ_t and σ_s at a path's wavelengths (or RGB channels).
#[derive(Debug, Clone, Copy)]
pub struct Coeffs<C: Carrier> {
    /// Extinction σ_t = σ_a + σ_s.
    pub sigma_t: C,
    /// Scattering σ_s ≤ σ_t.
    pub sigma_s: C,
}

impl Medium {
    /// The coefficients at the wavelengths `l` (module docs).
    pub fn coeffs<C: Carrier>(&self, l: &C::Lambda) -> Coeffs<C> {
        let attenuation = self.attenuation::<C>(l);
        match self.scattering {
            Scattering::Albedo { multiscatter } => {
                let ms = C::reflectance(multiscatter, l).to_lanes();
                let t = attenuation.to_lanes();
                let s = std::array::from_fn(|k| single_scatter_albedo(ms[k]) * t[k]);
                Coeffs {
                    sigma_t: attenuation,
                    sigma_s: C::from_lanes(s),
                }
            }
            Scattering::Rayleigh { at_550 } => {
                let law = Spectral::Rayleigh { at_550 };
                let s = match C::lanes_nm(l) {
                    Some(nm) => C::from_lanes(nm.map(|x| law.at(x).unwrap_or(0.0))),
                    None => {
                        let [r, g, b] = law.rgb();
                        C::from_lanes([r, g, b, 0.0])
                    }
                };
                Coeffs {
                    sigma_t: attenuation + s,
                    sigma_s: s,
                }
            }
        }
    }

    /// −ln c(λ) / d per lane: the attenuation colour's extinction (zero without a distance).
    fn attenuation<C: Carrier>(&self, l: &C::Lambda) -> C {
        let d = self.attenuation_distance;
        if !d.is_finite() {
            return C::ZERO;
        }
        let c = C::reflectance(self.attenuation_color, l).to_lanes();
        C::from_lanes(c.map(|c| {
            if c <= 0.0 {
                SIGMA_MAX
            } else {
                (-c.min(1.0).ln() / d).min(SIGMA_MAX)
            }
        }))
    }

    /// Whether the medium is chromatic in a way RGB transport only approximates (Rayleigh's
    /// λ⁻⁴): the plan then renders spectrally.
    pub fn wants_spectral(&self) -> bool {
        matches!(self.scattering, Scattering::Rayleigh { .. })
    }

    /// Whether anything scatters (σ_s > 0 somewhere in the spectrum).
    pub fn scatters(&self) -> bool {
        match self.scattering {
            Scattering::Albedo { multiscatter } => {
                self.attenuation_distance.is_finite() && multiscatter.max_element() > 0.0
            }
            Scattering::Rayleigh { at_550 } => at_550 > 0.0,
        }
    }

    /// A one-line description: the coefficients' source and the phase function.
    pub fn describe(&self) -> String {
        let phase = match self.phase {
            Phase::Isotropic => "isotropic".to_string(),
            Phase::HenyeyGreenstein { g } => format!("Henyey-Greenstein g = {g}"),
            Phase::Rayleigh => "Rayleigh phase".to_string(),
        };
        let absorbing = if self.attenuation_distance.is_finite() {
            let c = self.attenuation_color;
            format!(
                "attenuation ({:.3}, {:.3}, {:.3}) over {}",
                c.x, c.y, c.z, self.attenuation_distance
            )
        } else {
            "no absorption".to_string()
        };
        match self.scattering {
            Scattering::Albedo { multiscatter: m } => format!(
                "{absorbing}, multiscatter ({:.3}, {:.3}, {:.3}), {phase}",
                m.x, m.y, m.z
            ),
            Scattering::Rayleigh { at_550 } => {
                format!("Rayleigh σ_s(550 nm) = {at_550} per unit, {absorbing}, {phase}")
            }
        }
    }

    /// The invariants of the module docs; the error names the offending field.
    pub fn check(&self) -> Result<(), String> {
        let c = self.attenuation_color;
        if !c.is_finite() || c.min_element() < 0.0 {
            return Err(format!(
                "attenuationColor {c} must be finite and not negative"
            ));
        }
        let d = self.attenuation_distance;
        if d.is_nan() || d <= 0.0 {
            return Err(format!("attenuationDistance {d} must be > 0"));
        }
        match self.scattering {
            Scattering::Albedo { multiscatter: m } => {
                if !m.is_finite() || m.min_element() < 0.0 || m.max_element() > 1.0 {
                    return Err(format!("multiscatterColor {m} must lie in [0, 1]"));
                }
            }
            Scattering::Rayleigh { at_550 } => {
                if !at_550.is_finite() || at_550 < 0.0 {
                    return Err(format!(
                        "the Rayleigh scattering coefficient {at_550} must be finite and not negative"
                    ));
                }
            }
        }
        if let Phase::HenyeyGreenstein { g } = self.phase {
            if !(g.is_finite() && g > -1.0 && g < 1.0) {
                return Err(format!("scatterAnisotropy {g} must lie in (−1, 1)"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::spectrum::{Lambdas, SampledSpectrum, SampledWavelengths};

    fn milk(g: f32) -> Medium {
        Medium {
            attenuation_color: Vec3::splat(0.5),
            attenuation_distance: 0.1,
            scattering: Scattering::Albedo {
                multiscatter: Vec3::splat(0.8),
            },
            phase: Phase::HenyeyGreenstein { g },
        }
    }

    /// Grey attenuation: σ_t = ln 2 / 0.1 in every channel and lane; σ_s = ρ_ss(0.8) σ_t.
    #[test]
    fn grey_attenuation_gives_one_extinction_everywhere() {
        let m = milk(0.3);
        let expected = std::f32::consts::LN_2 / 0.1;
        let rgb = m.coeffs::<Vec3>(&());
        assert!((rgb.sigma_t - Vec3::splat(expected)).abs().max_element() < 1e-4);
        let ss = single_scatter_albedo(0.8) * expected;
        assert!((rgb.sigma_s - Vec3::splat(ss)).abs().max_element() < 1e-4);
        let l = Lambdas::new(SampledWavelengths::sample_visible(0.3));
        let sp = m.coeffs::<SampledSpectrum>(&l);
        for k in 0..4 {
            assert!((sp.sigma_t.to_lanes()[k] - expected).abs() < 1e-3);
        }
    }

    /// Rayleigh: σ_s follows λ⁻⁴ lane by lane, σ_t adds the absorption.
    #[test]
    fn rayleigh_follows_the_inverse_fourth_power() {
        let m = Medium {
            attenuation_color: Vec3::ONE,
            attenuation_distance: f32::INFINITY,
            scattering: Scattering::Rayleigh { at_550: 2.0 },
            phase: Phase::Rayleigh,
        };
        let l = Lambdas::new(SampledWavelengths::sample_visible(0.61));
        let c = m.coeffs::<SampledSpectrum>(&l);
        let nm = SampledSpectrum::lanes_nm(&l).unwrap();
        for k in 0..4 {
            let want = 2.0 * (550.0 / nm[k]).powi(4);
            assert!((c.sigma_s.to_lanes()[k] - want).abs() < 1e-4 * want);
            assert_eq!(c.sigma_t.to_lanes()[k], c.sigma_s.to_lanes()[k]);
        }
        assert!(m.wants_spectral() && m.scatters());
    }

    #[test]
    fn checks_name_the_bad_field() {
        assert!(milk(0.7).check().is_ok());
        assert!(milk(1.0).check().unwrap_err().contains("scatterAnisotropy"));
        assert!(milk(f32::NAN).check().is_err());
        let mut m = milk(0.0);
        m.scattering = Scattering::Albedo {
            multiscatter: Vec3::new(0.5, -0.1, 0.5),
        };
        assert!(m.check().unwrap_err().contains("multiscatterColor"));
        m.scattering = Scattering::Rayleigh {
            at_550: f32::INFINITY,
        };
        assert!(m.check().unwrap_err().contains("Rayleigh"));
        m.scattering = Scattering::Rayleigh { at_550: 1.0 };
        m.attenuation_color = Vec3::new(1.0, f32::NAN, 1.0);
        assert!(m.check().unwrap_err().contains("attenuationColor"));
    }
}
