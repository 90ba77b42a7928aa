//! Display transform for 8-bit output: exposure → tone map → sRGB OETF → 8-bit quantisation.
//!
//! Input values are **linear** Rec.709/sRGB-primary radiometric RGB (any scale); output is
//! sRGB-encoded bytes. Non-finite or negative components never panic: a pixel with any
//! non-finite component is written black, negative components are clamped to 0.
//!
//! ## Luminance
//! `Y = 0.2126 R + 0.7152 G + 0.0722 B` (ITU-R BT.709-6, item 3.2; the coefficients sum to 1).
//!
//! ## Exposure
//! - `Ev(e)`: scale `2^e`.
//! - `Auto`: Reinhard's *key* (Reinhard et al. 2002, "Photographic Tone Reproduction for
//!   Digital Images", SIGGRAPH, eq. 1), the log-average luminance
//!   `L̄ = exp( Σ n_b ln(δ + Y_b) / Σ n_b )`, δ = 1e-6, over runs of [`KEY_BLOCK`] pixels
//!   rather than single pixels: `Y_b` is the mean luminance of a run of consecutive finite
//!   pixels (row-major; `n_b` of them, the last run shorter), and only runs with `Y_b > 0`
//!   count. The scale `0.18 / L̄` maps the key to middle grey 0.18 (the paper's `a`). An
//!   image with no such run (all black) gets scale 1. Runs keep a noisy image's exposure
//!   near the converged one's: a pixel-wise log-average over the lit pixels reads a
//!   few-sample image's dim regions (black pixels and some bright samples) as brighter than
//!   their mean (Jensen's inequality), so the picture would darken as samples accumulate
//!   (BENCHMARKS.md, "Judging the picture written"); four pixels average that away and
//!   move a converged picture's exposure by at most about a tenth of a stop (a high-contrast
//!   checkerboard; gems: under 0.01 EV).
//! ## Tone maps (applied after exposure)
//! - `Clamp`: `min(x, 1)` per channel.
//! - `Reinhard`: on luminance, `L_d = L / (1 + L)` (Reinhard et al. 2002, eq. 3); RGB is
//!   scaled by `L_d / L`, then clamped to 1 (saturated colours can exceed 1 per channel).
//! - `Aces`: Narkowicz's fit of the ACES RRT+ODT, per channel,
//!   `f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)`, clamped to [0, 1]
//!   (K. Narkowicz, "ACES Filmic Tone Mapping Curve", blog post, 2016-01-06,
//!   <https://knarkowicz.wordpress.com/2016/01/06/aces-filmic-tone-mapping-curve/>).
//!   The fit is pre-exposed (1 → ≈0.8); f is monotone for x ≥ 0 because the numerator of f′,
//!   `1.408x² + 0.7028x + 0.0042`, is positive.
//!
//! ## Encoding
//! The sRGB OETF ([`crate::image::srgb::srgb_oetf`], IEC 61966-2-1:1999, §5.2); bytes are
//! `round(255 V)`.

use super::{Exposure, ToneMap};
use crate::image::srgb::srgb_oetf;
use crate::image::ImageRgb;
use glam::Vec3;

/// Reinhard's δ in the log-average, avoiding `ln 0`.
const KEY_DELTA: f64 = 1e-6;
/// Middle grey the key is mapped to (Reinhard et al. 2002, `a = 0.18`).
const MIDDLE_GREY: f64 = 0.18;

/// Relative luminance of a linear Rec.709 colour (BT.709 coefficients).
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// The multiplier applied to every pixel before tone mapping.
///
/// `Ev(e)` must be finite (checked by the caller); `Auto` follows the module doc.
pub fn exposure_scale(img: &ImageRgb, exposure: Exposure) -> f32 {
    match exposure {
        Exposure::Ev(e) => e.exp2(),
        Exposure::Auto => auto_scale(&img.data),
    }
}

/// Pixels per block of the automatic exposure's key (module docs).
pub const KEY_BLOCK: usize = 4;

/// `0.18 / key` over the runs of [`KEY_BLOCK`] finite pixels with positive mean luminance
/// (module docs); 1 if there are none.
fn auto_scale(data: &[Vec3]) -> f32 {
    let (mut sum, mut weight) = (0.0f64, 0.0f64);
    let (mut run, mut n) = (0.0f64, 0usize);
    let mut close = |run: f64, n: usize| {
        let y = run / n.max(1) as f64;
        if n > 0 && y.is_finite() && y > 0.0 {
            sum += n as f64 * (KEY_DELTA + y).ln();
            weight += n as f64;
        }
    };
    for &c in data {
        let y = f64::from(luminance(c));
        if !c.is_finite() || !y.is_finite() {
            continue;
        }
        run += y.max(0.0);
        n += 1;
        if n == KEY_BLOCK {
            close(run, n);
            (run, n) = (0.0, 0);
        }
    }
    close(run, n);
    if weight == 0.0 {
        return 1.0;
    }
    let key = (sum / weight).exp();
    let scale = MIDDLE_GREY / key;
    if scale.is_finite() && scale > 0.0 {
        scale as f32
    } else {
        1.0
    }
}

/// Narkowicz's ACES fit for one channel, clamped to [0, 1]; negative input gives 0.
pub fn aces_fit(x: f32) -> f32 {
    let x = x.max(0.0);
    let y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    if y.is_nan() {
        // x = +∞ gives ∞/∞; the curve's limit is saturated white.
        1.0
    } else {
        y.clamp(0.0, 1.0)
    }
}

/// Applies a tone map to an exposed, finite, non-negative colour; the result is in [0, 1].
pub fn apply_tonemap(c: Vec3, tonemap: ToneMap) -> Vec3 {
    let c = c.max(Vec3::ZERO);
    match tonemap {
        ToneMap::Clamp => c.min(Vec3::ONE),
        ToneMap::Reinhard => {
            let l = luminance(c);
            if l > 0.0 && l.is_finite() {
                let ld = l / (1.0 + l);
                (c * (ld / l)).min(Vec3::ONE)
            } else if l > 0.0 {
                Vec3::ONE
            } else {
                Vec3::ZERO
            }
        }
        ToneMap::Aces => Vec3::new(aces_fit(c.x), aces_fit(c.y), aces_fit(c.z)),
    }
}

/// Quantises an encoded value in [0, 1] to a byte, rounding to nearest.
pub fn to_u8(v: f32) -> u8 {
    // In range by the clamp, so the cast cannot truncate meaningfully.
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// One pixel's display value: `c` exposed by `scale`, tone mapped and sRGB-encoded, each
/// channel in [0, 1] (what a byte holds before rounding); a non-finite pixel is black.
pub fn encode(c: Vec3, scale: f32, tonemap: ToneMap) -> Vec3 {
    let mapped = if c.is_finite() {
        let exposed = c * scale;
        if exposed.is_nan() {
            Vec3::ZERO
        } else {
            apply_tonemap(exposed, tonemap)
        }
    } else {
        Vec3::ZERO
    };
    Vec3::new(
        srgb_oetf(mapped.x),
        srgb_oetf(mapped.y),
        srgb_oetf(mapped.z),
    )
}

/// The full display transform: row-major RGB8 bytes, `3 * width * height` long.
pub fn to_srgb8(img: &ImageRgb, exposure: Exposure, tonemap: ToneMap) -> Vec<u8> {
    let scale = exposure_scale(img, exposure);
    let mut out = Vec::with_capacity(img.data.len() * 3);
    for &c in &img.data {
        let v = encode(c, scale, tonemap);
        out.extend([v.x, v.y, v.z].map(to_u8));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_oetf_known_values() {
        assert_eq!(to_u8(srgb_oetf(0.0)), 0);
        assert_eq!(to_u8(srgb_oetf(1.0)), 255);
        assert_eq!(to_u8(srgb_oetf(0.5)), 188);
        // Both branches meet at the boundary: 12.92 · 0.0031308 = 0.040450 ≈ 1.055·b^(1/2.4) − 0.055.
        let b = 0.003_130_8f32;
        let linear = 12.92 * b;
        let power = 1.055 * b.powf(1.0 / 2.4) - 0.055;
        assert!((srgb_oetf(b) - 0.040_45).abs() < 1e-5);
        assert!((linear - power).abs() < 1e-5, "{linear} vs {power}");
        assert!((srgb_oetf(b * 1.0001) - srgb_oetf(b)).abs() < 1e-5);
    }

    #[test]
    fn aces_is_monotone_and_zero_at_zero() {
        assert_eq!(aces_fit(0.0), 0.0);
        let mut prev = 0.0;
        for i in 1..=20_000 {
            let y = aces_fit(i as f32 * 1e-3);
            assert!(y >= prev, "not monotone at {}", i as f32 * 1e-3);
            prev = y;
        }
        assert_eq!(aces_fit(f32::INFINITY), 1.0);
        assert_eq!(aces_fit(-1.0), 0.0);
    }

    #[test]
    fn auto_exposure_maps_uniform_to_key() {
        let img = ImageRgb {
            width: 4,
            height: 3,
            data: vec![Vec3::splat(2.0); 12],
        };
        let s = exposure_scale(&img, Exposure::Auto);
        assert!((2.0 * s - 0.18).abs() < 1e-6, "scale {s}");
    }

    #[test]
    fn auto_exposure_ignores_non_finite_and_averages_runs() {
        // Runs of four: [2, 2, 2, 2] ×2, then [2, 2, NaN skipped, ∞ skipped, 0, ...]: the
        // black pixel counts in its run's mean.
        let mut data = vec![Vec3::splat(2.0); 10];
        data.push(Vec3::new(f32::NAN, 1.0, 1.0));
        data.push(Vec3::splat(f32::INFINITY));
        data.push(Vec3::ZERO);
        data.push(Vec3::splat(2.0));
        let img = ImageRgb {
            width: 14,
            height: 1,
            data,
        };
        // Runs 2, 2, (2 + 2 + 0 + 2)/4 = 1.5: key exp((8 ln 2 + 4 ln 1.5)/12).
        let key = ((8.0 * 2.0f64.ln() + 4.0 * 1.5f64.ln()) / 12.0).exp();
        let s = exposure_scale(&img, Exposure::Auto);
        assert!((f64::from(s) * key - 0.18).abs() < 1e-5, "scale {s}");
        let black = ImageRgb {
            width: 2,
            height: 1,
            data: vec![Vec3::ZERO; 2],
        };
        assert_eq!(exposure_scale(&black, Exposure::Auto), 1.0);
        assert_eq!(exposure_scale(&black, Exposure::Ev(2.0)), 4.0);
        // A noisy run exposes as its mean: one lit sample in four pixels at 4× the value
        // reads as the run's mean, where a pixel-wise key over lit pixels reads it 4×.
        let sparse = ImageRgb {
            width: 8,
            height: 1,
            data: (0..8)
                .map(|i| {
                    if i % 4 == 0 {
                        Vec3::splat(4.0)
                    } else {
                        Vec3::ZERO
                    }
                })
                .collect(),
        };
        let s = exposure_scale(&sparse, Exposure::Auto);
        assert!((s - 0.18).abs() < 1e-6, "scale {s}");
        // A shorter last run weighs by its length: [1, 1, 1, 1], [4, 4].
        let mut data = vec![Vec3::ONE; 4];
        data.extend([Vec3::splat(4.0); 2]);
        let img = ImageRgb {
            width: 6,
            height: 1,
            data,
        };
        let key = (2.0 * 4.0f64.ln() / 6.0).exp();
        let s = exposure_scale(&img, Exposure::Auto);
        assert!((f64::from(s) * key - 0.18).abs() < 1e-5, "scale {s}");
    }

    #[test]
    fn tone_maps_stay_in_unit_range() {
        for tm in [ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Aces] {
            for c in [
                Vec3::ZERO,
                Vec3::new(100.0, 0.0, 0.0),
                Vec3::splat(1e30),
                Vec3::splat(f32::MAX),
                Vec3::new(-1.0, 0.5, 2.0),
            ] {
                let m = apply_tonemap(c, tm);
                assert!(m.is_finite() && m.min_element() >= 0.0 && m.max_element() <= 1.0);
            }
        }
        // Reinhard keeps hue for in-range colours: L/(1+L) on Y = 1 gives 0.5.
        let m = apply_tonemap(Vec3::ONE, ToneMap::Reinhard);
        assert!((m - Vec3::splat(0.5)).abs().max_element() < 1e-6);
    }

    #[test]
    fn non_finite_pixels_become_black() {
        let img = ImageRgb {
            width: 3,
            height: 1,
            data: vec![
                Vec3::new(f32::NAN, 0.0, 0.0),
                Vec3::splat(f32::NEG_INFINITY),
                Vec3::ONE,
            ],
        };
        let bytes = to_srgb8(&img, Exposure::Ev(0.0), ToneMap::Clamp);
        assert_eq!(bytes, vec![0, 0, 0, 0, 0, 0, 255, 255, 255]);
    }
}
