//! Image output: the rendered linear image → a PNG for people or an EXR for tools.
//!
//! - The input is an [`ImageRgb`] ([`crate::image`]): **linear** RGB with Rec.709/sRGB
//!   primaries (scene-referred, any scale), row-major, top row first.
//! - `.png`: 8-bit sRGB after exposure and tone mapping ([`tonemap`] documents the formulas).
//! - `.exr`: 32-bit float linear RGB, the numbers as rendered (no exposure, no tone map).
//!
//! - With `--background` ([`background`]): a flat colour or alpha (PNG RGBA8 with straight
//!   alpha, EXR RGBA with premultiplied colour) from the image's coverage.
//! - Frame sequences (`iris turntable`) become an animated APNG or GIF ([`animation`]).
//!
//! The format is chosen by the extension (case-insensitive). Every file is written
//! atomically ([`atomic`]): temporary file in the same directory, fsync, rename; a failed
//! write leaves neither a partial output nor a temporary file. Errors name the path.

pub mod animation;
pub mod atomic;
pub mod background;
pub mod display;
pub mod exr_io;
pub mod partial;
pub mod tonemap;

use crate::error::{Error, Result};
use crate::image::{Coverage, ImageRgb};
pub use background::Background;
use std::io::Cursor;
use std::path::Path;

/// The tone curve used for 8-bit output (formulas in [`tonemap`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ToneMap {
    /// Per-channel `min(x, 1)`.
    Clamp,
    /// Reinhard et al. 2002 `L/(1+L)` on luminance.
    Reinhard,
    /// Narkowicz's ACES filmic fit (the default).
    #[default]
    Aces,
}

impl ToneMap {
    /// Parses `--tonemap aces|reinhard|clamp` ([`crate::error::parse_name`]).
    pub fn parse(s: &str) -> Result<ToneMap> {
        let names = [
            ("aces", ToneMap::Aces),
            ("reinhard", ToneMap::Reinhard),
            ("clamp", ToneMap::Clamp),
        ];
        crate::error::parse_name("--tonemap", s, &names)
    }
}

/// How the linear values are scaled before tone mapping.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Exposure {
    /// Map the log-average luminance (Reinhard's key) to 0.18 (the default).
    #[default]
    Auto,
    /// Multiply by `2^ev`; `ev` must be finite.
    Ev(f32),
}

/// Exposure and tone map for 8-bit output; ignored for EXR.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DisplayOptions {
    /// Exposure (default [`Exposure::Auto`]).
    pub exposure: Exposure,
    /// Tone map (default [`ToneMap::Aces`]).
    pub tonemap: ToneMap,
}

/// The output formats, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Png,
    Exr,
}

fn format_of(path: &Path) -> Result<Format> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(Format::Png),
        Some("exr") => Ok(Format::Exr),
        _ => Err(Error::Usage(format!(
            "{}: unknown output format (accepted extensions: .png, .exr)",
            path.display()
        ))),
    }
}

/// Whether `path` is a display-referred output (a PNG: exposure, tone map and 8-bit
/// sRGB, [`display`]) rather than a scene-referred one (an EXR's linear numbers).
pub fn is_display_referred(path: &Path) -> bool {
    format_of(path).is_ok_and(|f| f == Format::Png)
}

/// Checks that `path` has a supported image extension (`.png`, `.exr`), so a render can
/// fail before it starts rather than after.
pub fn check_extension(path: &Path) -> Result<()> {
    format_of(path).map(|_| ())
}

/// Writes `img` to `path` as PNG (8-bit sRGB, via `opts`) or EXR (linear f32), atomically.
///
/// Errors: [`Error::Usage`] for an unknown extension or a non-finite `Ev`;
/// [`Error::Output`] for an inconsistent or empty image and for any encoding or I/O failure.
pub fn write_image(path: &Path, img: &ImageRgb, opts: &DisplayOptions) -> Result<()> {
    write_image_with_background(path, img, None, Background::Environment, opts)
}

/// [`write_image`] with a background ([`background`] documents the compositing). `coverage`
/// is required for any background but [`Background::Environment`] and must match the
/// image's size ([`Error::Output`] otherwise).
pub fn write_image_with_background(
    path: &Path,
    img: &ImageRgb,
    coverage: Option<&Coverage>,
    bg: Background,
    opts: &DisplayOptions,
) -> Result<()> {
    write_image_with_layer(path, img, None, coverage, bg, opts)
}

/// [`write_image_with_background`] with, for EXR, an extra image `layer` = (name, image)
/// written as the channels `name.R`, `name.G`, `name.B` ([`exr_io::encode_with_layer`];
/// composited with the same background). The extra image must have the main image's size
/// ([`Error::Output`] otherwise); a PNG cannot hold it ([`Error::Usage`]).
pub fn write_image_with_layer(
    path: &Path,
    img: &ImageRgb,
    layer: Option<(&str, &ImageRgb)>,
    coverage: Option<&Coverage>,
    bg: Background,
    opts: &DisplayOptions,
) -> Result<()> {
    let format = format_of(path)?;
    let output_err = |reason: String| Error::Output {
        path: path.to_path_buf(),
        reason,
    };
    if let Exposure::Ev(e) = opts.exposure {
        if !e.is_finite() {
            return Err(Error::Usage(format!(
                "exposure must be a finite EV, got {e}"
            )));
        }
    }
    let expected = u64::from(img.width) * u64::from(img.height);
    if expected == 0 {
        return Err(output_err(format!(
            "empty image ({}×{})",
            img.width, img.height
        )));
    }
    if img.data.len() as u64 != expected {
        return Err(output_err(format!(
            "image is {}×{} but holds {} pixels",
            img.width,
            img.height,
            img.data.len()
        )));
    }
    let cov = match (bg, coverage) {
        (Background::Environment, _) => None,
        (_, Some(c))
            if (c.width, c.height) == (img.width, img.height)
                && c.alpha.len() as u64 == expected
                && c.escaped.len() as u64 == expected =>
        {
            Some(c)
        }
        _ => {
            return Err(output_err(
                "a background needs the image's coverage at the image's size".into(),
            ))
        }
    };
    if let Some((name, extra)) = layer {
        if format == Format::Png {
            return Err(Error::Usage(format!(
                "{}: a PNG cannot hold the extra layer `{name}` (write .exr)",
                path.display()
            )));
        }
        if (extra.width, extra.height) != (img.width, img.height)
            || extra.data.len() != img.data.len()
        {
            return Err(output_err(format!(
                "layer `{name}` is {}x{} but the image is {}x{}",
                extra.width, extra.height, img.width, img.height
            )));
        }
        let bytes = match cov {
            None => exr_io::encode_with_layer(img, None, (name, extra)),
            Some(c) => {
                let (out, alpha) = background::composite_linear(img, c, bg);
                let (extra, _) = background::composite_linear(extra, c, bg);
                exr_io::encode_with_layer(&out, alpha.as_deref(), (name, &extra))
            }
        }
        .map_err(output_err)?;
        return atomic::write_file_atomic(path, &bytes);
    }
    let bytes = match (format, cov) {
        (Format::Png, None) => encode_png(img, opts).map_err(output_err)?,
        (Format::Exr, None) => exr_io::encode(img).map_err(output_err)?,
        (Format::Png, Some(c)) => {
            let (bytes, rgba) = background::display_bytes(img, c, bg, opts);
            png_bytes(&bytes, img.width, img.height, rgba).map_err(output_err)?
        }
        (Format::Exr, Some(c)) => match background::composite_linear(img, c, bg) {
            (out, Some(alpha)) => exr_io::encode_rgba(&out, &alpha).map_err(output_err)?,
            (out, None) => exr_io::encode(&out).map_err(output_err)?,
        },
    };
    atomic::write_file_atomic(path, &bytes)
}

/// Reads an EXR file written by [`write_image`] (or any EXR with R, G, B channels; the
/// first such layer at full resolution).
///
/// Errors are [`Error::Load`] naming the file: `Io` if it cannot be read, `Parse` if it is
/// not a valid EXR with RGB channels, `TooLarge` beyond [`exr_io::MAX_PIXELS`].
pub fn read_exr(path: &Path) -> Result<ImageRgb> {
    Ok(exr_io::decode(path)?)
}

/// Reads the extra layer `name` of an EXR file ([`write_image_with_layer`]): the channels
/// `name.R`, `name.G`, `name.B`. Errors as [`read_exr`]; `Parse` when the layer is missing.
pub fn read_exr_layer(path: &Path, name: &str) -> Result<ImageRgb> {
    Ok(exr_io::decode_layer(path, name)?)
}

/// Display-transforms and PNG-encodes the image in memory.
fn encode_png(img: &ImageRgb, opts: &DisplayOptions) -> std::result::Result<Vec<u8>, String> {
    let rgb8 = tonemap::to_srgb8(img, opts.exposure, opts.tonemap);
    png_bytes(&rgb8, img.width, img.height, false)
}

/// PNG-encodes 8-bit RGB (or RGBA with `alpha`) bytes in memory.
fn png_bytes(px: &[u8], w: u32, h: u32, alpha: bool) -> std::result::Result<Vec<u8>, String> {
    use image::ImageEncoder;
    let color = if alpha {
        image::ExtendedColorType::Rgba8
    } else {
        image::ExtendedColorType::Rgb8
    };
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(Cursor::new(&mut bytes))
        .write_image(px, w, h, color)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use std::fs;
    use std::path::PathBuf;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("iris-output-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("scratch dir");
        dir
    }

    fn gradient(w: u32, h: u32) -> ImageRgb {
        let mut img = ImageRgb::new(w, h);
        for (i, p) in img.data.iter_mut().enumerate() {
            let t = i as f32 * 0.37;
            *p = Vec3::new(t, t.sin() * 3.0, 1.0 / (1.0 + t));
        }
        img
    }

    #[test]
    fn exr_round_trip_is_exact() {
        let dir = scratch("exr");
        let path = dir.join("img.EXR");
        let mut img = gradient(7, 5);
        img.data[3] = Vec3::new(f32::INFINITY, -2.5, 1e-30);
        write_image(&path, &img, &DisplayOptions::default()).expect("write exr");
        let back = read_exr(&path).expect("read exr");
        assert_eq!((back.width, back.height), (7, 5));
        for (a, b) in img.data.iter().zip(&back.data) {
            for k in 0..3 {
                assert_eq!(a[k].to_bits(), b[k].to_bits());
            }
        }
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn png_has_the_right_size() {
        let dir = scratch("png");
        let path = dir.join("img.png");
        let mut img = gradient(9, 4);
        img.data[0] = Vec3::splat(f32::NAN);
        let opts = DisplayOptions {
            exposure: Exposure::Ev(-1.0),
            tonemap: ToneMap::Reinhard,
        };
        write_image(&path, &img, &opts).expect("write png");
        let back = image::open(&path).expect("decode png").to_rgb8();
        assert_eq!(back.dimensions(), (9, 4));
        assert_eq!(back.get_pixel(0, 0).0, [0, 0, 0]);
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn unknown_extension_is_a_usage_error() {
        let img = ImageRgb::new(2, 2);
        for name in ["out.jpg", "out", "out.png.bak"] {
            let err = write_image(Path::new(name), &img, &DisplayOptions::default())
                .expect_err("must reject");
            match err {
                Error::Usage(msg) => {
                    assert!(msg.contains(name) && msg.contains(".png") && msg.contains(".exr"))
                }
                other => panic!("expected Usage, got {other:?}"),
            }
        }
    }

    #[test]
    fn missing_directory_is_an_output_error_without_temp_files() {
        let dir = scratch("missing");
        for name in ["img.png", "img.exr"] {
            let path = dir.join("no-such-dir").join(name);
            let err = write_image(&path, &gradient(3, 3), &DisplayOptions::default())
                .expect_err("must fail");
            assert!(
                matches!(&err, Error::Output { path: p, .. } if *p == path),
                "{err:?}"
            );
        }
        assert_eq!(
            fs::read_dir(&dir).expect("ls").count(),
            0,
            "nothing left behind"
        );
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn inconsistent_images_and_bad_exposure_are_errors() {
        let dir = scratch("bad");
        let path = dir.join("x.png");
        let bad = ImageRgb {
            width: 3,
            height: 3,
            data: vec![Vec3::ZERO; 8],
        };
        let opts = DisplayOptions::default();
        assert!(matches!(
            write_image(&path, &bad, &opts),
            Err(Error::Output { .. })
        ));
        assert!(matches!(
            write_image(&path, &ImageRgb::new(0, 4), &opts),
            Err(Error::Output { .. })
        ));
        let nan_ev = DisplayOptions {
            exposure: Exposure::Ev(f32::NAN),
            tonemap: ToneMap::Aces,
        };
        assert!(matches!(
            write_image(&path, &ImageRgb::new(1, 1), &nan_ev),
            Err(Error::Usage(_))
        ));
        assert_eq!(fs::read_dir(&dir).expect("ls").count(), 0);
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn read_exr_reports_missing_and_garbage_files() {
        let dir = scratch("readerr");
        let missing = dir.join("none.exr");
        assert!(matches!(
            read_exr(&missing),
            Err(Error::Load(e)) if e.kind == crate::LoadErrorKind::Io
        ));
        let garbage = dir.join("garbage.exr");
        fs::write(&garbage, b"not an exr file at all").expect("write");
        assert!(matches!(
            read_exr(&garbage),
            Err(Error::Load(e)) if e.kind == crate::LoadErrorKind::Parse
        ));
        let _ = fs::remove_dir_all(&dir);
    }
}
