//! Environment lighting: radiance arriving from infinitely far away (the `--env` flag).
//!
//! ## Frames and units
//! - Directions are unit vectors in Iris's world frame (right-handed, +Y up, glTF).
//!   [`Environment::eval`]`(dir)` is the radiance arriving **from** `dir`, i.e. `dir` points
//!   away from the scene towards the sky. Maps use the equirectangular convention of
//!   [`mapping`]: `u = 0.5 + atan2(dir.x, −dir.z)/(2π)`, `v = acos(dir.y)/π`, top row
//!   (v = 0) = +Y, image centre = −Z.
//! - Radiance is linear RGB (Rec.709 primaries) in the scene's radiometric unit
//!   (W·sr⁻¹·m⁻², or whatever unit the punctual lights of [`crate::light::punctual`] imply); map
//!   texels are used as stored, without exposure.
//! - Every pdf is with respect to **solid angle** (sr⁻¹).
//!
//! ## Invariants
//! - `sample(u)` returns `wi`, `radiance == eval(wi)` and `pdf == pdf(wi) > 0`; directions
//!   with `pdf(dir) == 0` have `eval(dir) == 0` (black texels, poles aside – see [`map`]).
//! - Uniform: uniform sphere sampling, pdf = 1/(4π).
//! - Map: importance sampling by luminance × solid angle with a piecewise-constant 2D
//!   distribution (pbrt-v4 §12.5.2 `ImageInfiniteLight`, §A.5.2 `PiecewiseConstant2D`);
//!   nearest-texel lookup, so sampling and evaluation describe the same function exactly.
//! - User input (flag values, files) never panics: errors name the flag or the file.

pub mod distribution;
pub mod map;
pub mod mapping;

#[cfg(test)]
mod tests;

pub use map::{luminance, EnvMap, MAX_TEXELS};
pub use mapping::{dir_to_uv, uv_to_dir};

use crate::error::{Error, LoadError, LoadErrorKind, Result};
use crate::fileio::{input, Input};
use crate::image::ImageRgb;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;
use std::path::Path;

/// Light arriving from infinitely far away.
#[derive(Debug, Clone)]
pub enum Environment {
    /// The same radiance from every direction.
    Uniform {
        /// Linear RGB radiance (finite, ≥ 0).
        radiance: Vec3,
    },
    /// An equirectangular radiance map.
    Map(EnvMap),
    /// A computed sky (`--env sky:…`): its map; its sun is a directional light of the
    /// scene ([`crate::light::sky`]).
    Sky(Box<crate::light::sky::Sky>),
}

/// An [`Environment`] as its light functions see it.
enum View<'a> {
    Uniform(Vec3),
    Map(&'a EnvMap),
}

/// A direction sampled from an [`Environment`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvSample {
    /// Unit world direction towards the environment (the radiance arrives from here).
    pub wi: Vec3,
    /// Radiance arriving from `wi` (equals `eval(wi)`).
    pub radiance: Vec3,
    /// Solid-angle density of `wi` (equals `pdf(wi)`, > 0).
    pub pdf: f32,
}

impl Environment {
    /// Parses an `--env` value: `none` → `None`; `R,G,B` or a single grey value → uniform
    /// radiance (finite, ≥ 0, else [`Error::Usage`] naming `--env`); anything else is a
    /// path to a `.exr` or `.hdr` equirectangular map (errors name the file). A value made
    /// only of numbers is always a colour, never a file name. `sky:KEY=VALUE,…` is a
    /// computed sky ([`crate::light::sky::SkyParams::parse`]).
    pub fn parse_arg(s: &str) -> Result<Option<Environment>> {
        let t = s.trim();
        if t.eq_ignore_ascii_case("none") {
            return Ok(None);
        }
        if let Some(rest) = t.strip_prefix("sky:") {
            let params = crate::light::sky::SkyParams::parse(rest)
                .map_err(|why| Error::Usage(format!("--env {s:?}: {why}")))?;
            return Ok(Some(Environment::Sky(Box::new(
                crate::light::sky::Sky::new(params)?,
            ))));
        }
        let parts: Vec<&str> = t.split(',').map(str::trim).collect();
        let nums: Option<Vec<f32>> = parts.iter().map(|p| p.parse::<f32>().ok()).collect();
        if let Some(nums) = nums {
            let radiance = match nums.as_slice() {
                [g] => Vec3::splat(*g),
                [r, g, b] => Vec3::new(*r, *g, *b),
                _ => {
                    return Err(Error::Usage(format!(
                        "--env {s:?}: expected none, one grey value, R,G,B or a .exr/.hdr file"
                    )))
                }
            };
            if !radiance.is_finite() || radiance.min_element() < 0.0 {
                return Err(Error::Usage(format!(
                    "--env {s:?}: radiance must be finite and ≥ 0"
                )));
            }
            return Ok(Some(Environment::Uniform { radiance }));
        }
        Ok(Some(Environment::Map(load(Path::new(s))?)))
    }

    /// What the light functions read: a uniform radiance or a map (a sky is its map).
    fn view(&self) -> View<'_> {
        match self {
            Environment::Uniform { radiance } => View::Uniform(*radiance),
            Environment::Map(m) => View::Map(m),
            Environment::Sky(s) => View::Map(&s.map),
        }
    }

    /// Radiance arriving from world direction `dir` (unit, pointing towards the sky).
    pub fn eval(&self, dir: Vec3) -> Vec3 {
        match self.view() {
            View::Uniform(radiance) => radiance,
            View::Map(m) => m.eval(dir),
        }
    }

    /// Samples a direction for `u` ∈ [0, 1)²; `None` if nothing can be sampled there
    /// (black map, pole).
    pub fn sample(&self, u: Vec2) -> Option<EnvSample> {
        match self.view() {
            View::Uniform(radiance) => Some(EnvSample {
                wi: uniform_sphere(u),
                radiance,
                pdf: 1.0 / (4.0 * PI),
            }),
            View::Map(m) => m
                .sample(u)
                .map(|(wi, radiance, pdf)| EnvSample { wi, radiance, pdf }),
        }
    }

    /// Solid-angle density with which [`Environment::sample`] returns `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        match self.view() {
            View::Uniform(_) => 1.0 / (4.0 * PI),
            View::Map(m) => m.pdf(dir),
        }
    }

    /// ∫ Y(L(ω)) dω = mean luminance × 4π (sr × radiance unit), for light selection.
    pub fn power_proxy(&self) -> f32 {
        match self.view() {
            View::Uniform(radiance) => luminance(radiance) * 4.0 * PI,
            View::Map(m) => m.luminance_integral(),
        }
    }

    /// Warnings produced while loading (clamped texels); empty for uniform light.
    pub fn warnings(&self) -> &[String] {
        match self.view() {
            View::Uniform(_) => &[],
            View::Map(m) => m.warnings(),
        }
    }
}

/// Uniform direction on the unit sphere (y = 1 − 2u.x, φ = 2π u.y).
fn uniform_sphere(u: Vec2) -> Vec3 {
    let y = 1.0 - 2.0 * u.x;
    let r = (1.0 - y * y).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(r * c, y, r * s)
}

/// Loads an equirectangular map from a `.exr` or `.hdr` file (extension, case-insensitive).
pub fn load(path: &Path) -> Result<EnvMap> {
    // A directory, FIFO or device is named as such before its name is judged.
    input::refuse_special(path).map_err(|e| e.at(path, ""))?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let img = match ext.as_deref() {
        Some("exr") => {
            check_exr_size(path)?;
            crate::output::read_exr(path)?
        }
        Some("hdr") => read_hdr(path)?,
        _ => {
            return Err(LoadError::new(
                path,
                "",
                LoadErrorKind::Unsupported,
                "environment maps must be .exr or .hdr (equirectangular)",
            )
            .into())
        }
    };
    EnvMap::from_image(img, path)
}

/// Rejects EXR files whose layers exceed [`MAX_TEXELS`] before decoding the pixels.
fn check_exr_size(path: &Path) -> Result<()> {
    let file = input::open(path, Input::Exr).map_err(|e| e.at(path, ""))?;
    let file_len = file.len();
    let meta = exr::meta::MetaData::read_from_buffered(std::io::BufReader::new(file), false)
        .map_err(|e| LoadError::new(path, "", LoadErrorKind::Parse, e.to_string()))?;
    for (i, h) in meta.headers.iter().enumerate() {
        let n = h.layer_size.width() as u64 * h.layer_size.height() as u64;
        if n > MAX_TEXELS {
            return Err(LoadError::new(
                path,
                format!("layer {i}"),
                LoadErrorKind::TooLarge,
                format!("{n} texels exceeds the limit of {MAX_TEXELS}"),
            )
            .into());
        }
        check_plausible(path, &format!("layer {i}"), n, file_len)?;
    }
    Ok(())
}

/// Most texels a map may declare per byte of its file. Decoders allocate the whole image
/// (and Iris its sampling tables, ~40 bytes a texel in all) from the header before reading
/// any pixel, so without this a 1.5 KB EXR claiming 2^25 texels cost 2.6 GB (found by
/// `cargo fuzz run image`). 64 texels a byte is a compression ratio of 384:1 for half RGB
/// and 256:1 for RGBE, beyond RGBE run-length coding (at most ~64:1); only near-constant
/// synthetic EXRs compress further, and they get this error instead of an allocation.
const MAX_TEXELS_PER_FILE_BYTE: u64 = 64;

/// Rejects a map whose file is too short to hold the `texels` its header declares.
fn check_plausible(path: &Path, element: &str, texels: u64, file_len: u64) -> Result<()> {
    if texels > file_len.saturating_mul(MAX_TEXELS_PER_FILE_BYTE) {
        return Err(LoadError::new(
            path,
            element,
            LoadErrorKind::MissingBuffer,
            format!(
                "declares {texels} texels but the file has only {file_len} bytes (at most \
                 {MAX_TEXELS_PER_FILE_BYTE} texels per byte)"
            ),
        )
        .into());
    }
    Ok(())
}

/// Reads a Radiance RGBE (.hdr) file as linear RGB, checking its size before decoding.
fn read_hdr(path: &Path) -> Result<ImageRgb> {
    use image::ImageDecoder;
    let parse =
        |e: image::ImageError| LoadError::new(path, "", LoadErrorKind::Parse, e.to_string());
    let file = input::open(path, Input::Image).map_err(|e| e.at(path, ""))?;
    let file_len = file.len();
    let decoder =
        image::codecs::hdr::HdrDecoder::new(std::io::BufReader::new(file)).map_err(parse)?;
    let (w, h) = decoder.dimensions();
    if w as u64 * h as u64 > MAX_TEXELS || w == 0 || h == 0 {
        return Err(LoadError::new(
            path,
            "header",
            if w == 0 || h == 0 {
                LoadErrorKind::InvalidValue
            } else {
                LoadErrorKind::TooLarge
            },
            format!("environment map {w}×{h} must have 1 … {MAX_TEXELS} texels"),
        )
        .into());
    }
    check_plausible(path, "header", u64::from(w) * u64::from(h), file_len)?;
    let rgb = image::DynamicImage::from_decoder(decoder)
        .map_err(parse)?
        .into_rgb32f();
    let data = rgb
        .pixels()
        .map(|p| Vec3::new(p.0[0], p.0[1], p.0[2]))
        .collect();
    Ok(ImageRgb {
        width: w,
        height: h,
        data,
    })
}
