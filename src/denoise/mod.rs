//! Denoising rendered images with Intel Open Image Denoise (OIDN 2, its `RT` filter; feature
//! `denoise`, on by default; `build.rs` provides the library), fed with auxiliary buffers.
//!
//! - [`aux`]: the auxiliary pass — per pixel, the albedo and shading normal of the first
//!   non-specular surface seen through glass and mirrors (as Cycles does), from jittered
//!   camera rays like the render's.
//! - [`denoise`]: the filter on an HDR linear image, before any exposure or tone map, with
//!   or without the auxiliary images; [`denoised_estimate`]: the half-buffer error estimate
//!   of the denoised image.
//! - [`mode`]: `--denoise auto|on|off` and what a render denoises (PNG previews by
//!   default, EXR left raw), with the reason the plan prints.
//! - `oidn` (private): the C FFI layer, the only `unsafe` here.
//!
//! Input guards, applied here, before OIDN sees a value (OIDN's domains: colour HDR in
//! [0, ∞), albedo in [0, 1], normals in [−1, 1]): a non-finite value (NaN, ±∞; the render's
//! film guard normally keeps them out, but an image may come from elsewhere) becomes 0 and
//! the pixel is counted in [`Denoised::non_finite`]; then colour channels below 0 (slightly
//! negative linear sRGB of saturated spectral colours) become 0, albedo is clamped to
//! [0, 1] and normals to [−1, 1], uncounted. Sizes are checked first: every buffer must have
//! the colour image's width × height, and the error names the buffer and both sizes.
//!
//! Without the `denoise` feature everything but the checks is there and [`denoise`] returns
//! [`Error::Denoise`] saying how to get the feature; [`available`] tells callers beforehand.
//!
//! Units: images are linear RGB (Rec.709 primaries, radiance in W·sr⁻¹·m⁻² per channel);
//! normals are world-space unit vectors (averaged per pixel, so shorter at edges).

pub mod aux;
pub mod mode;
// The Open Image Denoise FFI layer: with `accel::embree`, the one module allowed `unsafe`
// (lib.rs).
#[cfg(feature = "denoise")]
#[allow(unsafe_code)]
mod oidn;

pub use mode::{DenoiseChoice, DenoiseMode, EXR_LAYER};

use crate::error::{Error, Result};
use crate::image::ImageRgb;
use glam::Vec3;
use std::time::{Duration, Instant};

/// The auxiliary images of a render ([`aux::aux_pass`]), at its size.
#[derive(Debug, Clone, PartialEq)]
pub struct AuxImages {
    /// Albedo in [0, 1] of the first non-specular surface, times the tint of the specular
    /// surfaces on the way (the environment's colour, clamped, where the rays escape).
    pub albedo: ImageRgb,
    /// World-space shading normal of that surface, facing the ray (0 where rays escape).
    pub normal: ImageRgb,
}

/// A denoised image and what the input guard did.
#[derive(Debug, Clone, PartialEq)]
pub struct Denoised {
    /// The denoised linear RGB image (same size as the input).
    pub image: ImageRgb,
    /// Pixels holding a non-finite value in the colour or an auxiliary image, replaced by
    /// 0 before filtering.
    pub non_finite: u64,
    /// Wall time of the filter (guards included).
    pub time: Duration,
}

/// What [`denoise`] says in a build without the `denoise` feature.
pub const UNAVAILABLE: &str = "this build of Iris has no denoiser (it was built without the \
     `denoise` cargo feature; rebuild with the default features, or with --features denoise)";

/// Whether this build can denoise (the `denoise` feature, which links OIDN).
pub fn available() -> bool {
    cfg!(feature = "denoise")
}

/// `name` is `width × height` like the colour image, or an error naming both sizes.
fn check_size(name: &str, img: &ImageRgb, (w, h): (u32, u32)) -> Result<()> {
    if (img.width, img.height) != (w, h) {
        return Err(Error::Denoise(format!(
            "the {name} buffer is {}x{} but the colour image is {w}x{h}",
            img.width, img.height
        )));
    }
    if img.data.len() as u64 != u64::from(w) * u64::from(h) {
        return Err(Error::Denoise(format!(
            "the {name} buffer is {w}x{h} but holds {} pixels",
            img.data.len()
        )));
    }
    if w == 0 || h == 0 {
        return Err(Error::Denoise(format!(
            "the {name} buffer is empty ({w}x{h})"
        )));
    }
    Ok(())
}

/// `img`'s pixels with non-finite channels set to 0 and the rest clamped to `[lo, hi]`,
/// adding to `bad` the pixels that had a non-finite channel.
fn guarded(img: &ImageRgb, lo: f32, hi: f32, bad: &mut u64) -> Vec<Vec3> {
    img.data
        .iter()
        .map(|p| {
            if !p.is_finite() {
                *bad += 1;
            }
            let finite = Vec3::select(p.is_finite_mask(), *p, Vec3::ZERO);
            finite.clamp(Vec3::splat(lo), Vec3::splat(hi))
        })
        .collect()
}

/// Denoises the HDR linear image `color` with OIDN's RT filter, using `aux` (albedo and
/// normals, noisy: `cleanAux` off) when given. Sizes are checked and values guarded as the
/// module docs say. Errors: [`Error::Denoise`] for a size mismatch (naming the buffer), a
/// build without the feature ([`UNAVAILABLE`]) or OIDN's own error message.
pub fn denoise(color: &ImageRgb, aux: Option<&AuxImages>) -> Result<Denoised> {
    let start = Instant::now();
    let size = (color.width, color.height);
    check_size("colour", color, size)?;
    if let Some(a) = aux {
        check_size("albedo", &a.albedo, size)?;
        check_size("normal", &a.normal, size)?;
    }
    let mut non_finite = 0u64;
    let c = guarded(color, 0.0, f32::INFINITY, &mut non_finite);
    let aux = aux.map(|a| {
        // A pixel counts once even when both auxiliary values are bad.
        let (mut ba, mut bn) = (0u64, 0u64);
        let albedo = guarded(&a.albedo, 0.0, 1.0, &mut ba);
        let normal = guarded(&a.normal, -1.0, 1.0, &mut bn);
        non_finite += ba.max(bn);
        (albedo, normal)
    });
    let data = run_filter(size, &c, aux.as_ref().map(|(a, n)| (&a[..], &n[..])))?;
    Ok(Denoised {
        image: ImageRgb {
            width: color.width,
            height: color.height,
            data,
        },
        non_finite,
        time: start.elapsed(),
    })
}

#[cfg(feature = "denoise")]
fn run_filter(
    (w, h): (u32, u32),
    color: &[Vec3],
    aux: Option<(&[Vec3], &[Vec3])>,
) -> Result<Vec<Vec3>> {
    oidn::rt_filter(&oidn::RtInputs {
        width: w as usize,
        height: h as usize,
        color,
        aux,
        clean_aux: false,
    })
    .map_err(Error::Denoise)
}

#[cfg(not(feature = "denoise"))]
fn run_filter(_: (u32, u32), _: &[Vec3], _: Option<(&[Vec3], &[Vec3])>) -> Result<Vec<Vec3>> {
    Err(Error::Denoise(UNAVAILABLE.into()))
}

/// The relative error estimate of the denoised image, from the render's two half images
/// (even and odd samples): both are denoised with `aux` and compared as
/// [`crate::render::relative_error_estimate`] compares raw halves (√ of the half-buffer
/// relative MSE). It measures how much the denoised result still depends on the noise, not
/// the denoiser's bias (blur), so it is a lower bound on the denoised image's error against
/// the truth. `None` when the halves cannot be compared (different sizes).
pub fn denoised_estimate(
    halves: (&ImageRgb, &ImageRgb),
    aux: Option<&AuxImages>,
) -> Result<Option<f64>> {
    let (a, b) = denoised_halves(halves, aux)?;
    Ok(crate::render::relative_error_estimate(&a, &b))
}

/// Both half images denoised with `aux` ([`denoised_estimate`] compares them).
pub fn denoised_halves(
    halves: (&ImageRgb, &ImageRgb),
    aux: Option<&AuxImages>,
) -> Result<(ImageRgb, ImageRgb)> {
    Ok((denoise(halves.0, aux)?.image, denoise(halves.1, aux)?.image))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn img(w: u32, h: u32, v: Vec3) -> ImageRgb {
        ImageRgb {
            width: w,
            height: h,
            data: vec![v; (w * h) as usize],
        }
    }

    #[test]
    fn wrong_sized_aux_buffers_are_named() {
        let color = img(8, 6, Vec3::splat(0.5));
        let aux = AuxImages {
            albedo: img(4, 3, Vec3::ONE),
            normal: img(8, 6, Vec3::Z),
        };
        let e = denoise(&color, Some(&aux))
            .expect_err("albedo is 4x3")
            .to_string();
        assert!(
            e.contains("albedo") && e.contains("4x3") && e.contains("8x6"),
            "{e}"
        );
        let aux = AuxImages {
            albedo: img(8, 6, Vec3::ONE),
            normal: img(8, 5, Vec3::Z),
        };
        let e = denoise(&color, Some(&aux))
            .expect_err("normal is 8x5")
            .to_string();
        assert!(
            e.contains("normal") && e.contains("8x5") && e.contains("8x6"),
            "{e}"
        );
        // A size that lies about its data is caught too.
        let mut liar = img(8, 6, Vec3::ONE);
        liar.data.pop();
        let aux = AuxImages {
            albedo: liar,
            normal: img(8, 6, Vec3::Z),
        };
        let e = denoise(&color, Some(&aux))
            .expect_err("47 pixels")
            .to_string();
        assert!(e.contains("albedo") && e.contains("47"), "{e}");
    }

    #[test]
    fn guard_zeroes_and_counts_non_finite_pixels() {
        let mut c = img(3, 1, Vec3::splat(2.0));
        c.data[0] = Vec3::new(f32::NAN, 1.0, 1.0);
        c.data[1] = Vec3::new(-0.25, f32::INFINITY, 3.0);
        let mut bad = 0;
        let g = guarded(&c, 0.0, f32::INFINITY, &mut bad);
        assert_eq!(bad, 2);
        assert_eq!(
            g,
            vec![
                Vec3::new(0.0, 1.0, 1.0),
                Vec3::new(0.0, 0.0, 3.0),
                Vec3::splat(2.0)
            ]
        );
    }

    #[cfg(not(feature = "denoise"))]
    #[test]
    fn without_the_feature_denoise_says_how_to_get_it() {
        assert!(!available());
        let e = denoise(&img(2, 2, Vec3::ONE), None)
            .expect_err("no feature")
            .to_string();
        assert!(e.contains("--features denoise"), "{e}");
    }
}
