//! Texture decoding shared by the glTF and OBJ/MTL loaders: PNG, JPEG, WebP (and Radiance HDR,
//! which the `image` crate also recognises) → row-major RGBA8, top row first, **as
//! stored** (no sRGB decoding; see [`crate::material::texture`]).
//!
//! Sizes are checked from the header before any pixel is decoded: at most
//! [`MAX_TEXTURE_TEXELS`] texels, and the decoder's own allocation limit
//! [`MAX_DECODE_BYTES`] (which covers its intermediate buffers, e.g. 16-bit or float
//! samples), so a header claiming 10⁵ × 10⁵ pixels is an error, not an allocation.

use super::panic_net;
use crate::error::LoadErrorKind;
use crate::material::ImageDesc;
use image::ImageDecoder;
use std::io::Cursor;
use std::sync::Arc;

/// Largest texture accepted, in texels (8192 × 8192: 256 MiB as RGBA8).
pub const MAX_TEXTURE_TEXELS: u64 = 1 << 26;

/// Most bytes the image decoder may allocate for one texture.
pub const MAX_DECODE_BYTES: u64 = 512 << 20;

/// Decodes `bytes` (format recognised from its magic bytes) into RGBA8 named `name`.
/// The error is a kind ([`LoadErrorKind::TooLarge`] for the size limits,
/// [`LoadErrorKind::MissingBuffer`] for unreadable data) and a sentence for the caller to
/// wrap with the file and the element.
pub fn decode_rgba8(bytes: &[u8], name: String) -> Result<ImageDesc, (LoadErrorKind, String)> {
    let bad = |detail: String| (LoadErrorKind::MissingBuffer, detail);
    check_png_palette(bytes).map_err(bad)?;
    let mut reader = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| bad(format!("cannot read image data: {e}")))?;
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(MAX_DECODE_BYTES);
    reader.limits(limits);
    let decoder = reader.into_decoder().map_err(unsupported)?;
    let (w, h) = decoder.dimensions();
    let texels = u64::from(w) * u64::from(h);
    if texels > MAX_TEXTURE_TEXELS {
        return Err(too_large(format!(
            "the image header declares {w}×{h} pixels, over the limit of {MAX_TEXTURE_TEXELS} texels"
        )));
    }
    if decoder.total_bytes() > MAX_DECODE_BYTES {
        return Err(too_large(format!(
            "decoding the {w}×{h} image needs {} bytes, over the limit of {MAX_DECODE_BYTES}",
            decoder.total_bytes()
        )));
    }
    if texels == 0 {
        return Err(bad(format!(
            "the image header declares {w}×{h} pixels (empty)"
        )));
    }
    // A decoder bug must not take Iris down: png 0.18.1 panics on a PLTE chunk whose length
    // is not a multiple of 3 (`range end index 3 out of range`,
    // fuzz/regressions/image/png-palette-panic.png). `check_png_palette` rejects those
    // first; the panic net (which keeps a panic's message off the terminal) stays for bugs
    // not yet known.
    let decoded = panic_net::catch(std::panic::AssertUnwindSafe(|| {
        image::DynamicImage::from_decoder(decoder)
    }))
    .map_err(|caught| {
        bad(caught.describe("the image decoder failed on this data (internal error)"))
    })?
    .map_err(unsupported)?;
    let rgba = decoded.into_rgba8();
    Ok(ImageDesc {
        name,
        width: rgba.width(),
        height: rgba.height(),
        rgba8: Arc::new(rgba.into_raw()),
    })
}

/// PNG only: every PLTE chunk must hold 1–256 RGB entries (length a multiple of 3, at most
/// 768 bytes; PNG spec §11.2.3). Other data passes.
fn check_png_palette(bytes: &[u8]) -> Result<(), String> {
    const SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";
    let Some(mut rest) = bytes.strip_prefix(SIGNATURE) else {
        return Ok(());
    };
    // Chunks: length (4 bytes, big-endian), type (4), data, CRC (4).
    while rest.len() >= 8 {
        let len = u32::from_be_bytes([rest[0], rest[1], rest[2], rest[3]]) as usize;
        let kind = &rest[4..8];
        if kind == b"PLTE" && (len == 0 || !len.is_multiple_of(3) || len > 768) {
            return Err(format!(
                "invalid PNG: its PLTE chunk is {len} bytes (1 to 256 RGB entries of 3 bytes)"
            ));
        }
        if kind == b"IDAT" || kind == b"IEND" {
            break; // PLTE must come before the image data
        }
        rest = rest.get(12usize.saturating_add(len)..).unwrap_or(&[]);
    }
    Ok(())
}

fn too_large(detail: String) -> (LoadErrorKind, String) {
    (LoadErrorKind::TooLarge, detail)
}

/// A decoder error; a limit the `image` crate enforces itself is still `TooLarge`.
fn unsupported(e: image::ImageError) -> (LoadErrorKind, String) {
    match e {
        image::ImageError::Limits(_) => too_large(format!("image too large: {e}")),
        e => (
            LoadErrorKind::MissingBuffer,
            format!("cannot decode image (PNG and JPEG are supported): {e}"),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(rel: &str) -> Vec<u8> {
        std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)).unwrap()
    }

    #[test]
    fn a_bad_palette_is_an_error_before_the_decoder_sees_it() {
        // PLTE of 38 bytes: png 0.18.1 panics on it.
        let bad = read("fuzz/regressions/image/png-palette-panic.png");
        let err = decode_rgba8(&bad, "t".into()).unwrap_err();
        assert!(err.1.contains("PLTE chunk is 38 bytes"), "{}", err.1);
        // A valid palette image still decodes.
        let ok = read("fuzz/seeds/image/seed_P.png");
        let img = decode_rgba8(&ok, "t".into()).expect("valid palette PNG");
        assert!(img.width > 0 && img.height > 0);
    }
}
