//! `--background`: what the image shows where camera rays escape, and alpha.
//!
//! **Coverage (alpha).** A pixel's alpha α is the fraction of its camera samples whose
//! *primary* ray hits a surface (alpha-mask cut-outs do not count as hits). A ray that hits
//! glass counts as covered even when it is refracted out into the environment: glass is
//! part of the model, and what is seen through it (the lit environment, the floor) stays
//! in the pixel. Only rays that see no surface at all are background.
//!
//! **Escaped radiance.** [`Coverage::escaped`] is each pixel's mean over the same samples of
//! the environment radiance of the escaped primary rays (each miss contributes `L_env(d)`,
//! each hit 0), i.e. exactly what the renderer's per-sample methods add for those rays.
//! Replacing the background subtracts it: the model's part of a pixel is
//! `M = max(I − E, 0)` (linear, premultiplied by α), so the environment still lights the
//! model but is no longer seen behind it. (Spectral renders convert `L_env` through the
//! wavelengths, so `E` matches up to colour noise; SPPM jitters its own camera rays, so
//! `E` matches in expectation.)
//!
//! **Outputs** (linear values are Rec.709 radiance, display values sRGB-encoded in [0, 1]):
//! - [`Background::Environment`] (no flag): the image as rendered.
//! - [`Background::Color`] `c` (display sRGB): PNG pixels are `α·T(M/α) + (1−α)·c`, blended
//!   in display values (as viewers composite PNG alpha), so the background is exactly `c`;
//!   EXR pixels are `M + (1−α)·c_lin` with `c_lin` the sRGB-decoded colour.
//! - [`Background::Transparent`]: PNG is RGBA8 with straight (unassociated) alpha, colour
//!   `T(M/α)` and alpha `round(255 α)`; EXR is RGBA with premultiplied (associated) colour
//!   `M` and A = α, as the OpenEXR convention requires.
//!
//! `T` is the display transform ([`super::tonemap`]); with automatic exposure the key is
//! taken over the covered pixels only (`M/α` where α > 0), so the background never changes
//! the model's exposure.

use super::tonemap::{exposure_scale, to_srgb8, to_u8};
use super::{DisplayOptions, Exposure};
use crate::error::{Error, Result};
use crate::image::srgb::srgb_eotf;
use crate::image::{Coverage, ImageRgb};
use glam::Vec3;

/// What escaped camera rays show.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Background {
    /// The environment (or black without one), as rendered: the default.
    #[default]
    Environment,
    /// A flat colour, display (sRGB-encoded) values in [0, 1].
    Color(Vec3),
    /// Alpha 0: PNG RGBA, EXR with an A channel.
    Transparent,
}

impl Background {
    /// Parses `--background`: `transparent`, `env` (the default: the environment), a name
    /// (`white`, `black`, `grey`/`gray`), `#rrggbb`, or `R,G,B` sRGB values in [0, 1]. The
    /// error says what is accepted.
    pub fn parse(s: &str) -> Result<Background> {
        let key = s.trim().to_ascii_lowercase();
        let bad = || {
            Error::Usage(format!(
                "--background {s:?}: expected `transparent`, `env`, white, black, grey, \
                 #rrggbb, or R,G,B sRGB values in [0, 1] (e.g. 0.9,0.9,0.9)"
            ))
        };
        let color = match key.as_str() {
            "transparent" | "none" => return Ok(Background::Transparent),
            "env" | "environment" => return Ok(Background::Environment),
            "white" => Vec3::ONE,
            "black" => Vec3::ZERO,
            "grey" | "gray" => Vec3::splat(0.5),
            hex if hex.starts_with('#') => {
                let h = &hex[1..];
                if h.len() != 6 || !h.chars().all(|c| c.is_ascii_hexdigit()) {
                    return Err(bad());
                }
                let byte = |i: usize| u8::from_str_radix(&h[i..i + 2], 16).map_err(|_| bad());
                Vec3::new(
                    f32::from(byte(0)?),
                    f32::from(byte(2)?),
                    f32::from(byte(4)?),
                ) / 255.0
            }
            list => {
                let v: Vec<f32> = list
                    .split(',')
                    .map(|p| p.trim().parse::<f32>().map_err(|_| bad()))
                    .collect::<Result<_>>()?;
                if v.len() != 3 || v.iter().any(|x| !(0.0..=1.0).contains(x)) {
                    return Err(bad());
                }
                Vec3::new(v[0], v[1], v[2])
            }
        };
        Ok(Background::Color(color))
    }
}

/// `M`, the model's premultiplied part of each pixel, `max(I − E, 0)` (0 where α = 0).
fn model_part(img: &ImageRgb, cov: &Coverage) -> Vec<Vec3> {
    img.data
        .iter()
        .zip(&cov.alpha)
        .zip(&cov.escaped)
        .map(|((&i, &a), &e)| {
            if a > 0.0 && i.is_finite() {
                (i - e).max(Vec3::ZERO)
            } else {
                Vec3::ZERO
            }
        })
        .collect()
}

/// The linear image for EXR and its alpha channel (`Some` only for transparent).
pub fn composite_linear(
    img: &ImageRgb,
    cov: &Coverage,
    bg: Background,
) -> (ImageRgb, Option<Vec<f32>>) {
    let model = model_part(img, cov);
    let data = match bg {
        Background::Environment => return (img.clone(), None),
        Background::Transparent => model,
        Background::Color(c) => {
            let lin = Vec3::new(srgb_eotf(c.x), srgb_eotf(c.y), srgb_eotf(c.z));
            model
                .iter()
                .zip(&cov.alpha)
                .map(|(&m, &a)| m + (1.0 - a) * lin)
                .collect()
        }
    };
    let alpha = (bg == Background::Transparent).then(|| cov.alpha.clone());
    (
        ImageRgb {
            width: img.width,
            height: img.height,
            data,
        },
        alpha,
    )
}

/// The straight colours of the covered pixels (α > 0), from per-pixel straight colours.
fn covered_straight(straight: &[Vec3], cov: &Coverage) -> Vec<Vec3> {
    straight
        .iter()
        .zip(&cov.alpha)
        .filter(|(_, &a)| a > 0.0)
        .map(|(&c, _)| c)
        .collect()
}

/// The pixels `--exposure auto` measures for the background `bg`: the whole image for
/// [`Background::Environment`] (or without coverage), else the straight colour M/α of the
/// covered pixels, the model alone (as [`display_bytes`] does).
pub fn exposure_pixels(img: &ImageRgb, cov: Option<&Coverage>, bg: Background) -> Vec<Vec3> {
    match (bg, cov) {
        (Background::Environment, _) | (_, None) => img.data.clone(),
        (_, Some(cov)) => {
            covered_straight(&straight_exposed(img, cov, Exposure::Ev(0.0)).0.data, cov)
        }
    }
}

/// The straight colour `M/α` of every pixel (0 where α = 0) and the exposure a display
/// output gives it: `exposure` itself, or for [`Exposure::Auto`] the key of the covered
/// pixels alone (the module docs), resolved to an EV.
pub fn straight_exposed(
    img: &ImageRgb,
    cov: &Coverage,
    exposure: Exposure,
) -> (ImageRgb, Exposure) {
    let straight: Vec<Vec3> = model_part(img, cov)
        .iter()
        .zip(&cov.alpha)
        .map(|(&m, &a)| if a > 0.0 { m / a } else { Vec3::ZERO })
        .collect();
    let exposure = match exposure {
        Exposure::Ev(e) => Exposure::Ev(e),
        Exposure::Auto => {
            let covered = covered_straight(&straight, cov);
            let probe = ImageRgb {
                width: covered.len() as u32,
                height: 1,
                data: covered,
            };
            Exposure::Ev(exposure_scale(&probe, Exposure::Auto).log2())
        }
    };
    let straight = ImageRgb {
        width: img.width,
        height: img.height,
        data: straight,
    };
    (straight, exposure)
}

/// 8-bit display bytes: RGB8 for a colour background, RGBA8 (straight alpha) for
/// transparent. Returns `(bytes, has_alpha)`.
pub fn display_bytes(
    img: &ImageRgb,
    cov: &Coverage,
    bg: Background,
    opts: &DisplayOptions,
) -> (Vec<u8>, bool) {
    if bg == Background::Environment {
        return (to_srgb8(img, opts.exposure, opts.tonemap), false);
    }
    let (straight, exposure) = straight_exposed(img, cov, opts.exposure);
    let rgb = to_srgb8(&straight, exposure, opts.tonemap);
    match bg {
        Background::Transparent => {
            let mut out = Vec::with_capacity(cov.alpha.len() * 4);
            for (px, &a) in rgb.chunks_exact(3).zip(&cov.alpha) {
                out.extend_from_slice(px);
                out.push(to_u8(a));
            }
            (out, true)
        }
        Background::Color(c) => {
            let bg8 = [c.x, c.y, c.z];
            let mut out = Vec::with_capacity(rgb.len());
            for (px, &a) in rgb.chunks_exact(3).zip(&cov.alpha) {
                for k in 0..3 {
                    let v = a * f32::from(px[k]) / 255.0 + (1.0 - a) * bg8[k];
                    out.push(to_u8(v));
                }
            }
            (out, false)
        }
        Background::Environment => (rgb, false),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_documented_forms_and_rejects_others() {
        assert_eq!(
            Background::parse("Transparent").unwrap(),
            Background::Transparent
        );
        assert_eq!(Background::parse("env").unwrap(), Background::Environment);
        assert_eq!(
            Background::parse("#ff8000").unwrap(),
            Background::Color(Vec3::new(1.0, 128.0 / 255.0, 0.0))
        );
        assert_eq!(
            Background::parse("0.1, 0.2,0.3").unwrap(),
            Background::Color(Vec3::new(0.1, 0.2, 0.3))
        );
        for bad in [
            "",
            "#12345",
            "#gggggg",
            "1,2",
            "0.5,0.5,1.5",
            "blue-ish",
            "nan,0,0",
        ] {
            let e = Background::parse(bad).expect_err(bad);
            assert!(e.to_string().contains("--background"), "{e}");
        }
    }

    fn two_pixels() -> (ImageRgb, Coverage) {
        // Pixel 0 escaped entirely (showing env 0.5); pixel 1 half covered: model 0.8·½,
        // env 0.5·½.
        let img = ImageRgb {
            width: 2,
            height: 1,
            data: vec![Vec3::splat(0.5), Vec3::splat(0.4 + 0.25)],
        };
        let cov = Coverage {
            width: 2,
            height: 1,
            alpha: vec![0.0, 0.5],
            escaped: vec![Vec3::splat(0.5), Vec3::splat(0.25)],
        };
        (img, cov)
    }

    #[test]
    fn linear_composite_removes_the_seen_environment() {
        let (img, cov) = two_pixels();
        let (t, a) = composite_linear(&img, &cov, Background::Transparent);
        assert_eq!(a.unwrap(), vec![0.0, 0.5]);
        assert_eq!(t.data[0], Vec3::ZERO);
        assert!((t.data[1] - Vec3::splat(0.4)).abs().max_element() < 1e-6);
        let (c, a) = composite_linear(&img, &cov, Background::Color(Vec3::ONE));
        assert!(a.is_none());
        assert_eq!(c.data[0], Vec3::ONE);
        assert!((c.data[1] - Vec3::splat(0.9)).abs().max_element() < 1e-6);
    }

    #[test]
    fn display_bytes_keep_the_exact_background() {
        let (img, cov) = two_pixels();
        let opts = DisplayOptions {
            exposure: Exposure::Ev(0.0),
            tonemap: crate::output::ToneMap::Clamp,
        };
        let (rgba, alpha) = display_bytes(&img, &cov, Background::Transparent, &opts);
        assert!(alpha);
        assert_eq!(&rgba[..4], &[0, 0, 0, 0]);
        // Straight colour 0.8 → sRGB 231; alpha 128.
        assert_eq!(&rgba[4..], &[231, 231, 231, 128]);
        let (rgb, alpha) = display_bytes(
            &img,
            &cov,
            Background::Color(Vec3::new(1.0, 0.0, 0.0)),
            &opts,
        );
        assert!(!alpha);
        assert_eq!(&rgb[..3], &[255, 0, 0]);
        // ½·231/255 + ½·(1, 0, 0).
        assert_eq!(&rgb[3..], &[243, 116, 116]);
    }
}
