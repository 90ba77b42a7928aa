//! Jewellery metals (`--metal`): spectral complex indices of refraction n(λ) + i·k(λ) of
//! gold, silver, platinum, copper and rose gold, the reflectance they give at normal
//! incidence, and the per-channel indices the RGB transport uses.
//!
//! Units: λ in nm (vacuum); n and k are relative to vacuum (air, n = 1.0003, is taken as
//! vacuum, as everywhere in Iris). Convention: the complex index is n + ik with k ≥ 0
//! (absorbing), i.e. the permittivity ε = (n + ik)² has Im ε ≥ 0.
//!
//! | metal | data | source |
//! |---|---|---|
//! | gold, silver, copper | measured n, k tables, linear in λ between rows | pbrt-v4 `src/pbrt/util/spectrum.cpp` (`Au_eta`/`Au_k`, `Ag_*`, `Cu_*`; [`super::metals_data`]) |
//! | platinum | Lorentz–Drude model fitted to measured data (0.1–5 eV) | A. D. Rakić, A. B. Djurišić, J. M. Elazar, M. L. Majewski, "Optical properties of metallic films for vertical-cavity optoelectronic devices", Appl. Opt. 37, 5271 (1998), Table 1 (Pt); pbrt-v4 and Mitsuba ship no platinum |
//! | rose gold | **not measured**: permittivities of Au, Cu, Ag mixed by volume fraction | see [`Metal::RoseGold`] |
//!
//! Outside a table's range (298.8–885.6 nm, wider than the 360–830 nm Iris samples) the
//! end rows are held. The RGB transport ([`Metal::rgb_eta_k`]) cannot carry n(λ), k(λ):
//! each channel gets an (n, k) pair whose normal-incidence reflectance is that channel of
//! the metal's CIE-integrated reflectance ([`Metal::linear_srgb`]), so the two transports
//! agree head-on and differ only in how the colour shifts towards grazing angles.

use super::cie::{spectrum_to_xyz, xyz_to_linear_srgb};
use super::metals_data::{AG_ETA, AG_K, AU_ETA, AU_K, CU_ETA, CU_K, LAMBDA_NM};
use super::upsample::RgbIlluminant;
use crate::math::Complex;
use glam::Vec3;
use std::sync::OnceLock;

/// A metal with a spectral complex index of refraction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Metal {
    /// Gold (Au), measured.
    Gold,
    /// Silver (Ag), measured.
    Silver,
    /// Platinum (Pt), Rakić et al. 1998 Lorentz–Drude model.
    Platinum,
    /// Copper (Cu), measured.
    Copper,
    /// 18-carat rose gold, 75 % Au, 22.25 % Cu, 2.75 % Ag by mass. No measured optical
    /// constants of the alloy are published in the data sets renderers ship, so this is an
    /// approximation: the permittivities ε = (n + ik)² of the three elements mixed linearly
    /// by volume fraction (densities 19.32, 8.96 and 10.49 g/cm³: 59.3 % Au, 38.1 % Cu,
    /// 2.6 % Ag), then n + ik = √ε. A real alloy's interband edge moves continuously
    /// with composition rather than showing both elements' edges, so the colour is
    /// indicative (pinker than gold, less red than copper), not a measurement.
    RoseGold,
}

/// Every metal, in the order the CLI lists them.
pub const METALS: [Metal; 5] = [
    Metal::Gold,
    Metal::Silver,
    Metal::Platinum,
    Metal::Copper,
    Metal::RoseGold,
];

/// Volume fractions (Au, Cu, Ag) of 18-carat rose gold (see [`Metal::RoseGold`]): mass
/// fractions 0.75, 0.2225, 0.0275 divided by the densities 19.32, 8.96, 10.49 g/cm³,
/// normalised.
const ROSE_VOLUME: [f64; 3] = {
    let v = [0.75 / 19.32, 0.2225 / 8.96, 0.0275 / 10.49];
    let s = v[0] + v[1] + v[2];
    [v[0] / s, v[1] / s, v[2] / s]
};

/// hc in eV·nm (CODATA 2018): photon energy E = HC_EV_NM / λ.
const HC_EV_NM: f64 = 1_239.841_984;

/// Rakić et al. (1998), Table 1, platinum: plasma energy ω_p (eV), the free-electron
/// oscillator (f₀, Γ₀ in eV) and four bound oscillators (f_j, Γ_j, ω_j in eV). (3.141 eV
/// is the paper's ω₃, not an approximation of π.)
const PT_OMEGA_P: f64 = 9.59;
const PT_F0: f64 = 0.333;
const PT_GAMMA0: f64 = 0.080;
#[allow(clippy::approx_constant)]
const PT_OSCILLATORS: [(f64, f64, f64); 4] = [
    (0.191, 0.517, 0.780),
    (0.659, 1.838, 1.314),
    (0.547, 3.668, 3.141),
    (3.576, 8.517, 9.249),
];

/// Dominant wavelengths of the sRGB primaries (nm), where the RGB transport takes each
/// channel's k: red 611.4, green 549.1, blue 464.3 (the spectral locus met by the line
/// from D65 through each primary, CIE 1931 chromaticities of IEC 61966-2-1).
pub const RGB_WAVELENGTHS: [f32; 3] = [611.4, 549.1, 464.3];

impl Metal {
    /// The CLI name (`--metal`).
    pub fn name(self) -> &'static str {
        match self {
            Metal::Gold => "gold",
            Metal::Silver => "silver",
            Metal::Platinum => "platinum",
            Metal::Copper => "copper",
            Metal::RoseGold => "rose-gold",
        }
    }

    /// A metal by its CLI name or chemical symbol (`au`, `ag`, `pt`, `cu`), case-insensitive,
    /// `_` and ` ` as `-`.
    pub fn named(s: &str) -> Option<Metal> {
        let key: String = s
            .trim()
            .chars()
            .map(|c| match c {
                '_' | ' ' => '-',
                c => c.to_ascii_lowercase(),
            })
            .collect();
        let symbol = match key.as_str() {
            "au" => Some(Metal::Gold),
            "ag" => Some(Metal::Silver),
            "pt" => Some(Metal::Platinum),
            "cu" => Some(Metal::Copper),
            _ => None,
        };
        symbol.or_else(|| METALS.into_iter().find(|m| m.name() == key))
    }

    /// The complex index (n, k) at `lambda_nm` (see the module table for the sources).
    pub fn eta_k(self, lambda_nm: f32) -> (f32, f32) {
        let z = self.index(f64::from(lambda_nm));
        (z.re as f32, z.im as f32)
    }

    /// n + ik at λ nm, in f64.
    fn index(self, lambda_nm: f64) -> Complex {
        match self {
            Metal::Gold => table(&AU_ETA, &AU_K, lambda_nm),
            Metal::Silver => table(&AG_ETA, &AG_K, lambda_nm),
            Metal::Copper => table(&CU_ETA, &CU_K, lambda_nm),
            Metal::Platinum => platinum(lambda_nm),
            Metal::RoseGold => {
                let eps = |z: Complex| z * z;
                let [au, cu, ag] = ROSE_VOLUME;
                let mix = eps(table(&AU_ETA, &AU_K, lambda_nm)) * au
                    + eps(table(&CU_ETA, &CU_K, lambda_nm)) * cu
                    + eps(table(&AG_ETA, &AG_K, lambda_nm)) * ag;
                mix.sqrt()
            }
        }
    }

    /// Reflectance at normal incidence from air, R₀ = ((n − 1)² + k²)/((n + 1)² + k²)
    /// (Born & Wolf, Principles of Optics, 7th ed., §14.2, eq. 15).
    pub fn normal_reflectance(self, lambda_nm: f32) -> f32 {
        let z = self.index(f64::from(lambda_nm));
        let (n, k2) = (z.re, z.im * z.im);
        (((n - 1.0) * (n - 1.0) + k2) / ((n + 1.0) * (n + 1.0) + k2)) as f32
    }

    /// The colour of the metal seen head-on under white light, in linear sRGB: the CIE 1931
    /// XYZ of R₀(λ) times the illuminant white RGB (1, 1, 1) becomes in spectral transport
    /// ([`RgbIlluminant`]: D65 with luminance 1), by the 1 nm sum of
    /// [`spectrum_to_xyz`], then XYZ → linear sRGB. A perfect mirror gives (1, 1, 1) up to
    /// the upsampling's rounding; so this is what the spectral film converges to for the
    /// metal reflecting a white environment at normal incidence. Computed once per metal.
    pub fn linear_srgb(self) -> Vec3 {
        self.cached().0
    }

    /// The per-channel complex index the RGB transport uses (see the module docs): for
    /// channel c, k_c = k at [`RGB_WAVELENGTHS`]`[c]`, and n_c the smaller root of
    /// R₀(n, k_c) = [`Metal::linear_srgb`]`[c]`, i.e. of (1 − R)n² − 2(1 + R)n + (1 − R)(1 + k²)
    /// = 0 (metals have n < √(1 + k²)); when no n reaches R with that k (R below
    /// (√(1+k²) − 1)/(√(1+k²) + 1)), k is lowered to the largest that does. R is clamped to
    /// [0, 0.999]. Computed once per metal.
    pub fn rgb_eta_k(self) -> (Vec3, Vec3) {
        let (_, eta, k) = self.cached();
        (eta, k)
    }

    /// (linear sRGB colour, RGB n, RGB k), computed once per metal.
    fn cached(self) -> (Vec3, Vec3, Vec3) {
        static CACHE: OnceLock<[(Vec3, Vec3, Vec3); 5]> = OnceLock::new();
        let all = CACHE.get_or_init(|| METALS.map(|m| m.derive_rgb()));
        let i = METALS.iter().position(|&m| m == self).unwrap_or(0);
        all[i]
    }

    fn derive_rgb(self) -> (Vec3, Vec3, Vec3) {
        let white = RgbIlluminant::new([1.0; 3]);
        let xyz = spectrum_to_xyz(|l| self.normal_reflectance(l) * white.eval(l));
        let rgb = Vec3::from_array(xyz_to_linear_srgb(xyz));
        let mut eta = [0.0f32; 3];
        let mut kk = [0.0f32; 3];
        for c in 0..3 {
            let (_, k) = self.eta_k(RGB_WAVELENGTHS[c]);
            let (n, k) = eta_for_reflectance(f64::from(rgb[c]), f64::from(k));
            eta[c] = n as f32;
            kk[c] = k as f32;
        }
        (rgb, Vec3::from_array(eta), Vec3::from_array(kk))
    }
}

/// n (and k, lowered if needed) with normal-incidence reflectance `r` (see
/// [`Metal::rgb_eta_k`]).
fn eta_for_reflectance(r: f64, k: f64) -> (f64, f64) {
    let r = if r.is_nan() { 0.0 } else { r.clamp(0.0, 0.999) };
    let (a, b) = (1.0 - r, 1.0 + r);
    // Real roots need b² ≥ a²(1 + k²).
    let k_max = ((b / a).powi(2) - 1.0).max(0.0).sqrt();
    let k = k.clamp(0.0, k_max);
    let disc = (b * b - a * a * (1.0 + k * k)).max(0.0);
    ((b - disc.sqrt()) / a, k)
}

/// Linear interpolation of the (η, k) tables at λ nm; the end rows outside the range.
fn table(eta: &[f32], k: &[f32], lambda_nm: f64) -> Complex {
    let l = lambda_nm as f32;
    let last = LAMBDA_NM.len() - 1;
    if l.is_nan() || l <= LAMBDA_NM[0] {
        return Complex::new(eta[0].into(), k[0].into());
    }
    if l >= LAMBDA_NM[last] {
        return Complex::new(eta[last].into(), k[last].into());
    }
    let i = LAMBDA_NM.partition_point(|&x| x <= l).clamp(1, last) - 1;
    let t = f64::from((l - LAMBDA_NM[i]) / (LAMBDA_NM[i + 1] - LAMBDA_NM[i]));
    let lerp = |v: &[f32]| f64::from(v[i]) + (f64::from(v[i + 1]) - f64::from(v[i])) * t;
    Complex::new(lerp(eta), lerp(k))
}

/// Platinum's n + ik from the Lorentz–Drude model of Rakić et al. (1998), eq. 3 and Table 1:
/// ε(ω) = 1 − Ω_p²/(ω(ω + iΓ₀)) + Σ_j f_j ω_p²/((ω_j² − ω²) − iωΓ_j), Ω_p = √f₀ ω_p,
/// ω = hc/λ in eV; n + ik = √ε (principal root, k ≥ 0).
fn platinum(lambda_nm: f64) -> Complex {
    let w = HC_EV_NM / lambda_nm.clamp(200.0, 2000.0);
    let wp2 = PT_OMEGA_P * PT_OMEGA_P;
    let one = Complex::real(1.0);
    let mut eps = one - Complex::real(PT_F0 * wp2) / (Complex::new(w * w, w * PT_GAMMA0));
    for (f, gamma, wj) in PT_OSCILLATORS {
        eps = eps + Complex::real(f * wp2) / Complex::new(wj * wj - w * w, -w * gamma);
    }
    eps.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tables are read as pbrt-v4 gives them: exact at a row, halfway between rows.
    #[test]
    fn tables_interpolate_pbrt_rows() {
        let (i, j) = (38, 39); // 551.04 and 563.56 nm
        assert_eq!(Metal::Gold.eta_k(LAMBDA_NM[i]), (AU_ETA[i], AU_K[i]));
        let mid = 0.5 * (LAMBDA_NM[i] + LAMBDA_NM[j]);
        let (n, k) = Metal::Copper.eta_k(mid);
        assert!((n - 0.5 * (CU_ETA[i] + CU_ETA[j])).abs() < 1e-5);
        assert!((k - 0.5 * (CU_K[i] + CU_K[j])).abs() < 1e-5);
        assert_eq!(Metal::Silver.eta_k(100.0), (AG_ETA[0], AG_K[0]));
        assert_eq!(Metal::Silver.eta_k(2000.0), (AG_ETA[55], AG_K[55]));
    }

    /// Platinum from the model against values computed independently from Rakić's Table 1
    /// (Python, cmath, the same formula): at 400, 550 and 700 nm n = 1.72, 2.09, 2.53 and
    /// k = 2.85, 3.70, 4.51 (two decimals), i.e. R₀ = 0.557, 0.641, 0.692, within the
    /// 0.6–0.7 handbooks list for polished platinum in the visible.
    #[test]
    fn platinum_follows_the_lorentz_drude_fit() {
        for (l, n, k, r) in [
            (400.0, 1.72, 2.85, 0.557),
            (550.0, 2.09, 3.70, 0.641),
            (700.0, 2.53, 4.51, 0.692),
        ] {
            let (pn, pk) = Metal::Platinum.eta_k(l);
            assert!(
                (pn - n).abs() < 0.006 && (pk - k).abs() < 0.006,
                "{l}: {pn} {pk}"
            );
            let pr = Metal::Platinum.normal_reflectance(l);
            assert!((pr - r).abs() < 0.001, "{l}: R {pr}");
        }
    }

    /// Gold is yellow because its reflectance drops below ~500 nm (k(λ) and n(λ) there),
    /// copper's edge is further red, silver is flat and high: checks on the data, not on
    /// any RGB tint. Measured (2026-12-03) linear sRGB: gold (1.022, 0.783, 0.343), silver
    /// (0.972, 0.960, 0.915), copper (0.955, 0.638, 0.538), platinum (0.678, 0.638, 0.584),
    /// rose gold (0.999, 0.730, 0.431).
    #[test]
    fn colours_come_from_the_spectra() {
        let r = |m: Metal, l: f32| m.normal_reflectance(l);
        assert!(r(Metal::Gold, 450.0) < 0.45 && r(Metal::Gold, 650.0) > 0.9);
        assert!(r(Metal::Copper, 550.0) < 0.7 && r(Metal::Copper, 650.0) > 0.9);
        assert!((450..=700)
            .step_by(50)
            .all(|l| r(Metal::Silver, l as f32) > 0.9));
        let gold = Metal::Gold.linear_srgb();
        assert!(gold.x > gold.y && gold.y > gold.z, "gold {gold}");
        let silver = Metal::Silver.linear_srgb();
        assert!(silver.min_element() > 0.85, "silver {silver}");
        // Rose gold lies between gold and copper in the green, where their edges differ.
        let (au, cu, rose) = (
            r(Metal::Gold, 560.0),
            r(Metal::Copper, 560.0),
            r(Metal::RoseGold, 560.0),
        );
        assert!(rose < au && rose > cu, "{au} {rose} {cu}");
    }

    /// The RGB indices give back the CIE-integrated colour at normal incidence, channel by
    /// channel (the solve is exact up to f32 rounding).
    #[test]
    fn rgb_indices_reproduce_the_head_on_colour() {
        for m in METALS {
            let (eta, k) = m.rgb_eta_k();
            let want = m.linear_srgb();
            for c in 0..3 {
                let (n, k) = (f64::from(eta[c]), f64::from(k[c]));
                let r = ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k);
                assert!(
                    (r as f32 - want[c].clamp(0.0, 0.999)).abs() < 1e-4,
                    "{m:?} {c}: {r}"
                );
                assert!(n >= 0.0 && k >= 0.0, "{m:?} {c}: {n} {k}");
            }
        }
    }

    /// [`RGB_WAVELENGTHS`] are the dominant wavelengths of the sRGB primaries: the spectral
    /// locus point (CIE 1931, 0.1 nm steps) in the primary's direction from D65, to 0.3 nm.
    #[test]
    fn rgb_wavelengths_are_the_primaries_dominant_wavelengths() {
        use super::super::cie::{chromaticity, cmf};
        let white = [0.3127f32, 0.3290];
        let angle = |p: [f32; 2]| (p[1] - white[1]).atan2(p[0] - white[0]);
        for (primary, want) in [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]]
            .into_iter()
            .zip(RGB_WAVELENGTHS)
        {
            let target = angle(primary);
            let off = |l: f32| (angle(chromaticity(cmf(l))) - target).abs();
            let best = (4000..=7000)
                .map(|i| i as f32 * 0.1)
                .min_by(|a, b| off(*a).total_cmp(&off(*b)))
                .unwrap_or(0.0);
            assert!(
                (best - want).abs() < 0.3,
                "{primary:?}: {best} nm, table {want}"
            );
        }
    }

    #[test]
    fn names_and_symbols() {
        for m in METALS {
            assert_eq!(Metal::named(m.name()), Some(m));
        }
        assert_eq!(Metal::named("Rose_Gold"), Some(Metal::RoseGold));
        assert_eq!(Metal::named("AU"), Some(Metal::Gold));
        assert_eq!(Metal::named("brass"), None);
    }
}
