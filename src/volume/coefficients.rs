//! The optical coefficients of a homogeneous scattering medium, per wavelength, and how
//! the glTF extensions and Iris's extras define them.
//!
//! Units: coefficients in inverse scene units (m⁻¹ for metric files), wavelengths in nm.
//! σ_t = σ_a + σ_s; the single-scattering albedo is σ_s/σ_t; transmittance over a distance
//! x is e^(−σ_t x) (Beer–Lambert).
//!
//! Sources of the numbers:
//! - KHR_materials_volume: `attenuationColor` c over `attenuationDistance` d gives
//!   σ_t = −ln(c)/d per channel (the colour white light takes after travelling d).
//! - KHR_materials_scatter (glTF PR #2579, which replaces KHR_materials_volume_scatter,
//!   PR #2453): `multiscatterColor` is the multiple-scattering albedo ρ_ms (Kulla & Conty
//!   2017); the single-scattering albedo is ρ_ss = 1 − (4.09712 + 4.20863 ρ_ms −
//!   √(9.59217 + 41.6808 ρ_ms + 17.7126 ρ_ms²))² (their isotropic fit), σ_s = ρ_ss σ_t.
//! - Rayleigh: σ_s(λ) = σ_s(550) (550/λ)⁴ (Rayleigh 1871's λ⁻⁴ law), no absorption.

/// A coefficient's spectral dependence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spectral {
    /// Linear-RGB coefficients (m⁻¹ per channel), upsampled to a spectrum for spectral
    /// transport by the caller.
    Rgb([f32; 3]),
    /// Rayleigh's law through its value at 550 nm.
    Rayleigh {
        /// σ_s at 550 nm, m⁻¹.
        at_550: f32,
    },
}

impl Spectral {
    /// The coefficient at `lambda` nm for spectral transport; an RGB coefficient needs the
    /// caller's upsampling and is `None` here.
    pub fn at(&self, lambda: f32) -> Option<f32> {
        match *self {
            Spectral::Rgb(_) => None,
            Spectral::Rayleigh { at_550 } => Some(at_550 * (550.0 / lambda).powi(4)),
        }
    }

    /// The coefficient per linear-RGB channel for RGB transport (Rayleigh's at the
    /// channels' nominal wavelengths 612, 549 and 465 nm, Rec. 709's dominant wavelengths).
    pub fn rgb(&self) -> [f32; 3] {
        match *self {
            Spectral::Rgb(c) => c,
            Spectral::Rayleigh { .. } => [612.0, 549.0, 465.0].map(|l| self.at(l).unwrap_or(0.0)),
        }
    }
}

/// σ_t per channel from KHR_materials_volume's attenuation colour and distance (`None` for
/// an infinite distance: no attenuation). A channel of colour 0 is opaque: σ_t = +∞.
pub fn extinction_from_attenuation(color: [f32; 3], distance: f32) -> Option<[f32; 3]> {
    if !distance.is_finite() || distance <= 0.0 {
        return None;
    }
    Some(color.map(|c| {
        if c <= 0.0 {
            f32::INFINITY
        } else {
            -c.min(1.0).ln() / distance
        }
    }))
}

/// The single-scattering albedo ρ_ss for the multiple-scattering albedo `ms` ∈ [0, 1]
/// (KHR_materials_scatter's isotropic inversion, module docs); clamped to [0, 1].
pub fn single_scatter_albedo(ms: f32) -> f32 {
    let ms = f64::from(ms.clamp(0.0, 1.0));
    let s = 4.09712 + 4.20863 * ms - (9.59217 + 41.6808 * ms + 17.7126 * ms * ms).sqrt();
    (1.0 - s * s).clamp(0.0, 1.0) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rayleigh_scatters_blue_nine_times_more_than_red() {
        let r = Spectral::Rayleigh { at_550: 1e-3 };
        let ratio = r.at(400.0).unwrap() / r.at(700.0).unwrap();
        assert!((ratio - (700.0f32 / 400.0).powi(4)).abs() < 1e-3, "{ratio}");
        assert!(ratio > 9.0);
        let rgb = r.rgb();
        assert!(rgb[2] > rgb[1] && rgb[1] > rgb[0]);
        assert!((rgb[1] / 1e-3 - 1.0).abs() < 0.01);
    }

    /// Attenuation colour c over d: after a distance d white light is c (e^(−σ_t d) = c).
    #[test]
    fn attenuation_gives_its_colour_after_its_distance() {
        let c = [0.8, 0.5, 0.1];
        let s = extinction_from_attenuation(c, 0.25).unwrap();
        for k in 0..3 {
            assert!(((-s[k] * 0.25).exp() - c[k]).abs() < 1e-6);
        }
        assert_eq!(extinction_from_attenuation(c, f32::INFINITY), None);
        assert_eq!(
            extinction_from_attenuation([0.0, 1.0, 1.0], 1.0).unwrap()[0],
            f32::INFINITY
        );
        assert_eq!(
            extinction_from_attenuation([1.0, 1.0, 1.0], 1.0).unwrap(),
            [0.0; 3]
        );
    }

    /// The inversion's ends and shape: ρ_ms 0 → 0, 1 → 1, increasing, and ρ_ss ≥ ρ_ms
    /// (many bounces darken a medium: the multiple-scattering albedo is the smaller).
    #[test]
    fn the_albedo_inversion_keeps_its_ends_and_order() {
        assert!(single_scatter_albedo(0.0).abs() < 1e-4);
        assert!((single_scatter_albedo(1.0) - 1.0).abs() < 1e-4);
        let mut last = -1.0;
        for i in 0..=100 {
            let ms = i as f32 / 100.0;
            let ss = single_scatter_albedo(ms);
            assert!(ss >= last, "not increasing at {ms}");
            assert!(ss + 1e-4 >= ms, "ρ_ss {ss} < ρ_ms {ms}");
            last = ss;
        }
    }
}
