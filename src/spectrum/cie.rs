//! CIE colorimetry: colour-matching functions, D65, Planck's law, XYZ ↔ linear sRGB.
//!
//! Units: wavelength λ in nanometres; XYZ normalised so that a spectrum's Y is
//! ∫ȳ(λ)s(λ)dλ / ∫ȳ(λ)dλ (pbrt-v4 `SpectrumToXYZ`), i.e. the constant spectrum 1 has Y = 1.
//! Linear sRGB uses the IEC 61966-2-1 primaries and the D65 white; no transfer curve here
//! (the film applies it). Lookups outside 360–830 nm return 0.

use super::cie_data::{CIE_D65, CIE_SAMPLES, CIE_X, CIE_Y, CIE_Z};
use super::{LAMBDA_MAX, LAMBDA_MIN};

/// ∫ȳ(λ)dλ over the 1 nm table (Riemann sum, nm); pbrt-v4 uses the same value.
pub const CIE_Y_INTEGRAL: f32 = 106.856_895;

/// Linear sRGB → XYZ (IEC 61966-2-1:1999, eq. 5.8; D65 white).
pub const SRGB_TO_XYZ: [[f32; 3]; 3] = [
    [0.4124, 0.3576, 0.1805],
    [0.2126, 0.7152, 0.0722],
    [0.0193, 0.1192, 0.9505],
];

/// XYZ → linear sRGB (IEC 61966-2-1:1999, eq. 5.6; D65 white).
pub const XYZ_TO_SRGB: [[f32; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];

/// Multiplies a 3×3 row-major matrix by a column vector.
pub fn mul3(m: &[[f32; 3]; 3], v: [f32; 3]) -> [f32; 3] {
    [
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    ]
}

/// CIE XYZ → linear sRGB (D65). Out-of-gamut colours give negative components; not clamped.
pub fn xyz_to_linear_srgb(xyz: [f32; 3]) -> [f32; 3] {
    mul3(&XYZ_TO_SRGB, xyz)
}

/// Linear sRGB (D65) → CIE XYZ.
pub fn linear_srgb_to_xyz(rgb: [f32; 3]) -> [f32; 3] {
    mul3(&SRGB_TO_XYZ, rgb)
}

/// Chromaticity (x, y) = (X, Y) / (X + Y + Z); (0, 0) for black.
pub fn chromaticity(xyz: [f32; 3]) -> [f32; 2] {
    let s = xyz[0] + xyz[1] + xyz[2];
    if s.is_nan() || s <= 0.0 {
        return [0.0, 0.0];
    }
    [xyz[0] / s, xyz[1] / s]
}

/// Where `lambda` nm falls in a table of `len` rows sampled every `step` nm from
/// [`LAMBDA_MIN`]: the row below and the fraction of the way to the next (`None` outside
/// 360–830 nm). Shared by every table looked up at one wavelength.
pub(super) fn table_point(len: usize, step: f32, lambda: f32) -> Option<(usize, f32)> {
    if lambda.is_nan() || !(LAMBDA_MIN..=LAMBDA_MAX).contains(&lambda) {
        return None;
    }
    let x = (lambda - LAMBDA_MIN) / step;
    let i = (x as usize).min(len - 2);
    Some((i, x - i as f32))
}

/// Linear interpolation in a table sampled every `step` nm from [`LAMBDA_MIN`].
fn lerp_table(table: &[f32], step: f32, lambda: f32) -> f32 {
    match table_point(table.len(), step, lambda) {
        Some((i, t)) => table[i] * (1.0 - t) + table[i + 1] * t,
        None => 0.0,
    }
}

/// The three colour-matching tables interleaved, one (x̄, ȳ, z̄) row per nm, so [`cmf`]
/// finds its rows once for all three.
static CIE_XYZ: [[f32; 3]; CIE_SAMPLES] = {
    let mut t = [[0.0; 3]; CIE_SAMPLES];
    let mut i = 0;
    while i < CIE_SAMPLES {
        t[i] = [CIE_X[i], CIE_Y[i], CIE_Z[i]];
        i += 1;
    }
    t
};

/// The CIE 1931 2° colour-matching functions (x̄, ȳ, z̄) at `lambda` nm (linear interpolation
/// of the 1 nm table; exact at integer nm). Each component is what `lerp_table` gives for
/// its own table: the same position and weights, looked up once.
pub fn cmf(lambda: f32) -> [f32; 3] {
    let Some((i, t)) = table_point(CIE_SAMPLES, 1.0, lambda) else {
        return [0.0; 3];
    };
    let (lo, hi) = (CIE_XYZ[i], CIE_XYZ[i + 1]);
    [0, 1, 2].map(|k| lo[k] * (1.0 - t) + hi[k] * t)
}

/// CIE D65 relative SPD at `lambda` nm (100 at 560 nm), linear between the 5 nm rows.
pub fn d65(lambda: f32) -> f32 {
    lerp_table(&CIE_D65, 5.0, lambda)
}

/// D65 scaled so its luminance Y is 1 (so `spectrum_to_xyz(d65_normalized)` is the sRGB
/// white (0.9505, 1, 1.089)); the illuminant of [`super::upsample`].
pub fn d65_normalized(lambda: f32) -> f32 {
    d65(lambda) * d65_inv_y()
}

/// 1 / Y(D65) with Y as in [`spectrum_to_xyz`]; computed once.
fn d65_inv_y() -> f32 {
    static INV: std::sync::OnceLock<f32> = std::sync::OnceLock::new();
    *INV.get_or_init(|| 1.0 / spectrum_to_xyz(d65)[1])
}

/// Planck's law: spectral radiance of a blackbody at temperature `kelvin`, in
/// W·sr⁻¹·m⁻³ (per metre of wavelength). 0 for non-positive or NaN temperatures.
/// B(λ, T) = 2hc² / (λ⁵ (exp(hc / (λ k T)) − 1)) (CODATA 2018 constants).
pub fn blackbody(lambda_nm: f32, kelvin: f32) -> f32 {
    if kelvin.is_nan() || kelvin <= 0.0 || lambda_nm.is_nan() || lambda_nm <= 0.0 {
        return 0.0;
    }
    const C: f64 = 299_792_458.0;
    const H: f64 = 6.626_070_15e-34;
    const KB: f64 = 1.380_649e-23;
    let l = lambda_nm as f64 * 1e-9;
    let le = (2.0 * H * C * C) / (l.powi(5) * ((H * C) / (l * KB * kelvin as f64)).exp_m1());
    le as f32
}

/// Blackbody radiance normalised to 1 at its peak (Wien's displacement law,
/// λ_max = 2.897771955e-3 m·K / T), as pbrt-v4's `BlackbodySpectrum`.
pub fn blackbody_normalized(lambda_nm: f32, kelvin: f32) -> f32 {
    if kelvin.is_nan() || kelvin <= 0.0 {
        return 0.0;
    }
    let peak_nm = (2.897_771_955e-3 / kelvin as f64 * 1e9) as f32;
    let peak = blackbody(peak_nm, kelvin);
    if peak.is_nan() || peak <= 0.0 {
        return 0.0;
    }
    blackbody(lambda_nm, kelvin) / peak
}

/// XYZ of a spectrum by a 1 nm Riemann sum over 360–830 nm, divided by
/// [`CIE_Y_INTEGRAL`] (pbrt-v4 `SpectrumToXYZ`). Accumulates in f64.
pub fn spectrum_to_xyz(s: impl Fn(f32) -> f32) -> [f32; 3] {
    let mut acc = [0.0f64; 3];
    for i in 0..CIE_X.len() {
        let v = s(LAMBDA_MIN + i as f32) as f64;
        acc[0] += CIE_X[i] as f64 * v;
        acc[1] += CIE_Y[i] as f64 * v;
        acc[2] += CIE_Z[i] as f64 * v;
    }
    let n = CIE_Y_INTEGRAL as f64;
    [
        (acc[0] / n) as f32,
        (acc[1] / n) as f32,
        (acc[2] / n) as f32,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn y_integral_matches_table() {
        let s: f64 = CIE_Y.iter().map(|&v| v as f64).sum();
        // f32 table storage changes the sum by < 1e-5; 0.01 is the brief's bound.
        assert!((s - 106.857).abs() < 0.01, "∫ȳ = {s}");
        assert!((s - CIE_Y_INTEGRAL as f64).abs() < 1e-4, "∫ȳ = {s}");
    }

    #[test]
    fn cmf_peaks_and_range() {
        // ȳ peaks at 555 nm with 1.0 exactly in the CIE table.
        assert!((cmf(555.0)[1] - 1.0).abs() < 1e-6);
        assert_eq!(cmf(359.0), [0.0; 3]);
        assert_eq!(cmf(831.0), [0.0; 3]);
        assert_eq!(cmf(f32::NAN), [0.0; 3]);
        // Interpolation halfway between 555 and 556 nm.
        let mid = cmf(555.5)[1];
        assert!((mid - 0.5 * (CIE_Y[195] + CIE_Y[196])).abs() < 1e-6);
        assert!((d65(560.0) - 100.0).abs() < 1e-4);
    }

    /// The fused lookup gives each table's own interpolation bit for bit, at integer and
    /// fractional nm, at both ends and outside the range.
    #[test]
    fn cmf_equals_each_table_interpolated() {
        let tables = [&CIE_X, &CIE_Y, &CIE_Z];
        let mut lambdas: Vec<f32> = (0..=47_200).map(|k| 359.0 + k as f32 * 0.01).collect();
        lambdas.extend([
            LAMBDA_MIN,
            LAMBDA_MAX,
            829.999_94,
            f32::NAN,
            -1.0,
            f32::INFINITY,
        ]);
        for l in lambdas {
            let want = tables.map(|t| lerp_table(t, 1.0, l).to_bits());
            assert_eq!(cmf(l).map(f32::to_bits), want, "{l} nm");
        }
    }

    #[test]
    fn d65_chromaticity() {
        let [x, y] = chromaticity(spectrum_to_xyz(d65));
        // CIE 15: D65 is (0.31272, 0.32903) with the 1 nm CMFs; sRGB rounds to (0.3127, 0.3290).
        assert!(
            (x - 0.3127).abs() < 2e-4 && (y - 0.3290).abs() < 2e-4,
            "({x}, {y})"
        );
        let xyz = spectrum_to_xyz(d65_normalized);
        assert!((xyz[1] - 1.0).abs() < 1e-5);
    }

    #[test]
    fn equal_energy_chromaticity() {
        let [x, y] = chromaticity(spectrum_to_xyz(|_| 1.0));
        // Illuminant E is (1/3, 1/3) by construction of the CMFs (∫x̄ = ∫ȳ = ∫z̄ to 1e-4).
        assert!(
            (x - 1.0 / 3.0).abs() < 1e-3 && (y - 1.0 / 3.0).abs() < 1e-3,
            "({x}, {y})"
        );
    }

    #[test]
    fn d65_is_srgb_white() {
        let rgb = xyz_to_linear_srgb(spectrum_to_xyz(d65_normalized));
        // The 4-digit IEC matrices reproduce the white point to ~2e-4.
        for c in rgb {
            assert!((c - 1.0).abs() < 1e-3, "{rgb:?}");
        }
    }

    #[test]
    fn matrices_are_inverse() {
        let p = mul3(&XYZ_TO_SRGB, linear_srgb_to_xyz([0.2, 0.5, 0.9]));
        // 4-digit published coefficients: the product is identity to ~3e-4.
        for (a, b) in p.iter().zip([0.2, 0.5, 0.9]) {
            assert!((a - b).abs() < 1e-3, "{p:?}");
        }
    }

    #[test]
    fn blackbody_peak_and_limits() {
        // Wien: the normalised curve is 1 at the peak and lower on both sides.
        let t = 5778.0;
        let peak = (2.897_771_955e6 / t as f64) as f32;
        assert!((blackbody_normalized(peak, t) - 1.0).abs() < 1e-5);
        assert!(blackbody_normalized(peak - 50.0, t) < 1.0);
        assert!(blackbody_normalized(peak + 50.0, t) < 1.0);
        assert_eq!(blackbody(500.0, 0.0), 0.0);
        assert_eq!(blackbody(500.0, f32::NAN), 0.0);
        // Hotter is bluer: x chromaticity falls from 2000 K to 10000 K.
        let x2k = chromaticity(spectrum_to_xyz(|l| blackbody_normalized(l, 2000.0)))[0];
        let x10k = chromaticity(spectrum_to_xyz(|l| blackbody_normalized(l, 10000.0)))[0];
        // Planckian locus: x(2000 K) ≈ 0.5267, x(10000 K) ≈ 0.2807 (CIE 15 / Wyszecki & Stiles).
        assert!((x2k - 0.5267).abs() < 2e-3, "{x2k}");
        assert!((x10k - 0.2807).abs() < 2e-3, "{x10k}");
    }
}
