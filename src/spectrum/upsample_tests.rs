//! Tests of [`super`]: basis fit, exact grey, round trips through the CIE tables.

use super::super::cie::{spectrum_to_xyz, xyz_to_linear_srgb};
use super::*;

/// ColorChecker Classic patches, 8-bit sRGB (X-Rite / BabelColor averages), decoded with the
/// sRGB transfer curve to linear sRGB.
fn macbeth_linear() -> Vec<[f32; 3]> {
    const PATCHES: [[u8; 3]; 24] = [
        [115, 82, 68],
        [194, 150, 130],
        [98, 122, 157],
        [87, 108, 67],
        [133, 128, 177],
        [103, 189, 170],
        [214, 126, 44],
        [80, 91, 166],
        [193, 90, 99],
        [94, 60, 108],
        [157, 188, 64],
        [224, 163, 46],
        [56, 61, 150],
        [70, 148, 73],
        [175, 54, 60],
        [231, 199, 31],
        [187, 86, 149],
        [8, 133, 161],
        [243, 243, 242],
        [200, 200, 200],
        [160, 160, 160],
        [122, 122, 121],
        [85, 85, 85],
        [52, 52, 52],
    ];
    let decode = |c: u8| {
        let v = c as f32 / 255.0;
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    let mut v: Vec<[f32; 3]> = PATCHES.iter().map(|p| p.map(decode)).collect();
    // The basis colours themselves and a few greys.
    v.extend(TARGETS.iter().map(|t| t.map(|x| x as f32)));
    v.extend([[0.0; 3], [1.0; 3], [0.5; 3]]);
    v
}

/// Reflectance round trip: linear sRGB of (spectrum × D65 with Y = 1).
fn reflectance_rgb(s: &RgbReflectance) -> [f32; 3] {
    xyz_to_linear_srgb(spectrum_to_xyz(|l| s.eval(l) * d65_normalized(l)))
}

fn max_abs_diff(a: [f32; 3], b: [f32; 3]) -> f32 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f32::max)
}

#[test]
fn basis_meets_targets_and_bounds() {
    let r = rgb_weights();
    for (k, nodes) in basis().iter().enumerate() {
        for c in 0..3 {
            let got: f64 = (0..NODES).map(|j| r[c][j] * nodes[j] as f64).sum();
            // Solver precision ~1e-12; f32 node storage adds ~1e-7 per node.
            assert!(
                (got - TARGETS[k][c]).abs() < 1e-5,
                "basis {k} channel {c}: {got}"
            );
        }
        assert!(nodes.iter().all(|&v| (0.0..=1.0).contains(&v)), "{nodes:?}");
    }
}

#[test]
fn grey_is_exactly_constant() {
    for g in [0.0, 0.18, 0.5, 1.0] {
        let s = RgbReflectance::new([g, g, g]);
        for l in [360.0, 400.5, 555.0, 700.0, 830.0] {
            assert_eq!(s.eval(l), g, "g = {g} at {l} nm");
        }
    }
    let w = RgbIlluminant::new([1.0, 1.0, 1.0]);
    for l in [380.0, 512.3, 640.0] {
        assert_eq!(w.eval(l), d65_normalized(l));
    }
}

#[test]
fn reflectance_round_trip() {
    let mut worst = 0.0f32;
    for rgb in macbeth_linear() {
        let s = RgbReflectance::new(rgb);
        worst = worst.max(max_abs_diff(reflectance_rgb(&s), rgb));
    }
    // Measured 1.7e-4 (the white patch): the 4-digit IEC matrix maps D65 to
    // (1.00001, 1.00008, 0.99983); the basis colours themselves are met to 1e-7.
    assert!(worst < 5e-4, "worst round-trip error {worst}");
}

#[test]
fn reflectance_stays_in_unit_interval() {
    let mut state = 12_345u32;
    let mut next = || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    for _ in 0..2000 {
        let rgb = [next() * 1.4 - 0.2, next() * 1.4 - 0.2, next() * 1.4 - 0.2];
        let s = RgbReflectance::new(rgb);
        for k in 0..48 {
            let v = s.eval(360.0 + 10.0 * k as f32 + 3.3);
            assert!((0.0..=1.0).contains(&v), "{rgb:?}: {v}");
        }
    }
    assert_eq!(RgbReflectance::new([f32::NAN; 3]).eval(500.0), 0.0);
}

#[test]
fn illuminant_white_and_round_trip() {
    let white = xyz_to_linear_srgb(spectrum_to_xyz(|l| RgbIlluminant::new([1.0; 3]).eval(l)));
    // D65 through the tables and the IEC matrix: (1,1,1) to ~2e-4.
    assert!(max_abs_diff(white, [1.0; 3]) < 1e-3, "{white:?}");
    for rgb in [
        [5.0, 2.0, 0.5],
        [0.0, 0.3, 3.0],
        [1.0, 0.0, 0.0],
        [0.2, 0.2, 0.2],
    ] {
        let e = RgbIlluminant::new(rgb);
        let got = xyz_to_linear_srgb(spectrum_to_xyz(|l| e.eval(l)));
        let m = rgb[0].max(rgb[1]).max(rgb[2]);
        // Relative to the brightest channel, same bound as the reflectance round trip.
        assert!(max_abs_diff(got, rgb) < 1e-3 * m, "{rgb:?} → {got:?}");
    }
    assert_eq!(
        RgbIlluminant::new([f32::INFINITY, 0.0, 0.0]).eval(600.0),
        0.0
    );
    assert_eq!(RgbIlluminant::new([-1.0, f32::NAN, 0.0]).eval(600.0), 0.0);
}

#[test]
fn white_light_through_monte_carlo_is_white() {
    // White light × white reflector estimated with hero wavelengths: the estimator must
    // converge to sRGB (1,1,1). 4000 golden-ratio samples: standard error ≲ 3e-3 per channel.
    let (light, refl) = (RgbIlluminant::new([1.0; 3]), RgbReflectance::new([1.0; 3]));
    let n = 4000;
    let mut acc = [0.0f64; 3];
    for k in 0..n {
        let u = (0.5 + k as f64 * 0.618_033_988_749_895).fract() as f32;
        let w = SampledWavelengths::sample_visible(u);
        let xyz = (light.sample(&w) * refl.sample(&w)).to_xyz(&w);
        for (a, v) in acc.iter_mut().zip(xyz) {
            *a += v as f64 / n as f64;
        }
    }
    let rgb = xyz_to_linear_srgb(acc.map(|v| v as f32));
    assert!(max_abs_diff(rgb, [1.0; 3]) < 1e-2, "{rgb:?}");
}

/// The upsampling as written per wavelength, without the shared grid point or the grey
/// shortcut: every λ located afresh for every term.
fn reflectance_reference(s: &RgbReflectance, lambda: f32) -> f32 {
    let nodes_at = |nodes: &[f32; NODES]| {
        if lambda.is_nan() || !(LAMBDA_MIN..=super::super::LAMBDA_MAX).contains(&lambda) {
            return 0.0;
        }
        let x = (lambda - LAMBDA_MIN) / STEP;
        let j = (x as usize).min(NODES - 2);
        let t = x - j as f32;
        nodes[j] * (1.0 - t) + nodes[j + 1] * t
    };
    let mut v = s.white;
    for (b, w) in s.terms {
        if w != 0.0 {
            v += w * nodes_at(&basis()[b as usize]);
        }
    }
    v.clamp(0.0, 1.0)
}

/// `sample` and `eval` (grid point shared by both terms, greys without a lookup) give the
/// per-wavelength reference bit for bit: ColorChecker colours, greys, signed zeros, NaN and
/// out-of-range components, illuminants of them (also through the grey shortcut of
/// `sample_rgb`, at scales down to subnormal and up to infinite), at visible and uniform
/// wavelengths.
#[test]
fn sample_equals_reference_bit_for_bit() {
    let mut colours = macbeth_linear();
    colours.extend([
        [-0.0, -0.0, -0.0],
        [-0.0, 0.3, 0.3],
        [0.25, 0.25, 0.25],
        [f32::NAN, 0.5, 0.2],
        [1.5, -0.2, 0.4],
        [0.8, 0.8, 0.1],
        [3.0, 2.0, 0.5],
    ]);
    let bits = |s: SampledSpectrum| s.values().map(f32::to_bits);
    for k in 0..257 {
        let u = k as f32 / 257.0;
        for w in [
            SampledWavelengths::sample_visible(u),
            SampledWavelengths::sample_uniform(u),
        ] {
            for &rgb in &colours {
                let r = RgbReflectance::new(rgb);
                let want = w.lambdas().map(|l| reflectance_reference(&r, l).to_bits());
                assert_eq!(bits(r.sample(&w)), want, "{rgb:?} at {:?}", w.lambdas());
                assert_eq!(w.lambdas().map(|l| r.eval(l).to_bits()), want);
                let e = RgbIlluminant::new(rgb);
                let d65 = SampledSpectrum::from_fn(&w, d65_normalized);
                let want = std::array::from_fn(|i| {
                    let l = w.lambda(i);
                    if e.scale == 0.0 {
                        0.0f32.to_bits()
                    } else {
                        (reflectance_reference(&e.shape, l) * d65[i] * e.scale).to_bits()
                    }
                });
                assert_eq!(bits(e.sample(&w)), want, "illuminant {rgb:?}");
                for scale in [1.0, 80.0, 1e-40, 0.0, -1.0, f32::INFINITY, f32::NAN] {
                    let c = rgb.map(|v| v * scale);
                    let want = bits(RgbIlluminant::new(c).sample_with_d65(&w, d65));
                    let got = bits(RgbIlluminant::sample_rgb(c, &w, d65));
                    assert_eq!(got, want, "illuminant {c:?}");
                }
            }
        }
    }
}
