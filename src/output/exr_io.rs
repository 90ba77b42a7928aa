//! OpenEXR encoding and decoding of [`ImageRgb`] via the `exr` crate.
//!
//! Files hold three 32-bit float channels `R`, `G`, `B` with linear Rec.709/sRGB-primary
//! values exactly as rendered (no exposure, no tone map), ZIP-compressed (lossless), so a
//! write → read round trip is bit-exact, including non-finite values. An extra image (the
//! denoised one, `--denoise on`) goes into the same part as the channels `NAME.R`,
//! `NAME.G`, `NAME.B` (OpenEXR's layer naming); readers that look for `R`, `G`, `B` (this
//! module's [`decode`] too) see the main image.
//! Pixel (x, y) is row-major with y = 0 the top row, matching the EXR data window.

use crate::error::{LoadError, LoadErrorKind};
use crate::fileio::input::Reader;
use crate::fileio::Input;
use crate::image::ImageRgb;
use exr::image::write::channels::WritableChannels;
use exr::image::write::layers::WritableLayers;
use exr::prelude::*;
use std::io::{BufReader, Cursor, Seek, SeekFrom};
use std::path::Path;

/// Largest image [`decode`] accepts (pixels): 2^28 ≈ 268 M, i.e. 3 GiB of f32 RGB.
pub const MAX_PIXELS: u64 = 1 << 28;

/// Encodes an image (whose `data` length was already checked) as EXR bytes.
pub fn encode(img: &ImageRgb) -> std::result::Result<Vec<u8>, String> {
    let w = img.width as usize;
    let data = &img.data;
    let channels = SpecificChannels::rgb(|pos: Vec2<usize>| {
        let c = data.get(pos.y() * w + pos.x()).copied().unwrap_or_default();
        (c.x, c.y, c.z)
    });
    to_bytes(&lossless(
        size_of(img),
        LayerAttributes::named("rgb"),
        channels,
    ))
}

/// Encodes an image with an alpha channel (`alpha[i]` for pixel i; colour premultiplied,
/// as OpenEXR's associated alpha requires) as RGBA EXR bytes. Lengths were checked.
pub fn encode_rgba(img: &ImageRgb, alpha: &[f32]) -> std::result::Result<Vec<u8>, String> {
    let w = img.width as usize;
    let data = &img.data;
    let channels = SpecificChannels::rgba(|pos: Vec2<usize>| {
        let i = pos.y() * w + pos.x();
        let c = data.get(i).copied().unwrap_or_default();
        (c.x, c.y, c.z, alpha.get(i).copied().unwrap_or(0.0))
    });
    to_bytes(&lossless(
        size_of(img),
        LayerAttributes::named("rgba"),
        channels,
    ))
}

/// Encodes `img` (with `alpha` when given, colour premultiplied) plus the extra image
/// `layer` = (name, image of the same size) as channels `name.R`, `name.G`, `name.B`.
/// Lengths were checked.
pub fn encode_with_layer(
    img: &ImageRgb,
    alpha: Option<&[f32]>,
    (name, extra): (&str, &ImageRgb),
) -> std::result::Result<Vec<u8>, String> {
    let mut list = Vec::with_capacity(7);
    for (k, c) in ["R", "G", "B"].into_iter().enumerate() {
        list.push(AnyChannel::new(c, FlatSamples::F32(plane(img, k))));
        list.push(AnyChannel::new(
            format!("{name}.{c}").as_str(),
            FlatSamples::F32(plane(extra, k)),
        ));
    }
    if let Some(a) = alpha {
        list.push(AnyChannel::new("A", FlatSamples::F32(a.to_vec())));
    }
    encode_channels(
        size_of(img),
        LayerAttributes::named(if alpha.is_some() { "rgba" } else { "rgb" }),
        list,
    )
}

/// Channel `k` (0 = R, 1 = G, 2 = B) of `img`, row-major.
pub(super) fn plane(img: &ImageRgb, k: usize) -> Vec<f32> {
    img.data.iter().map(|p| p[k]).collect()
}

/// One lossless layer of `size` with `attributes` and the channels `list` (sorted by name,
/// as EXR stores them), encoded to bytes: the one writer of flat-channel EXRs (images with
/// extra layers, partial images).
pub(super) fn encode_channels(
    size: (usize, usize),
    attributes: LayerAttributes,
    list: Vec<AnyChannel<FlatSamples>>,
) -> std::result::Result<Vec<u8>, String> {
    let channels = AnyChannels::sort(SmallVec::from_vec(list));
    to_bytes(&lossless(size, attributes, channels))
}

/// The image's size as the `exr` crate takes it.
fn size_of(img: &ImageRgb) -> (usize, usize) {
    (img.width as usize, img.height as usize)
}

/// A one-layer image of `size` holding `channels`, ZIP-compressed (lossless): the layout of
/// every EXR Iris writes.
fn lossless<'c, C: WritableChannels<'c> + 'c>(
    size: (usize, usize),
    attributes: LayerAttributes,
    channels: C,
) -> Image<Layer<C>> {
    Image::from_layer(Layer::new(
        size,
        attributes,
        Encoding::SMALL_LOSSLESS,
        channels,
    ))
}

/// The bytes of an EXR file holding `image`, written in memory.
fn to_bytes<'i, L: WritableLayers<'i>>(
    image: &'i Image<L>,
) -> std::result::Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    image
        .write()
        .to_buffered(Cursor::new(&mut bytes))
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// The file opened for decoding ([`crate::fileio::input`]: a regular file within
/// [`crate::fileio::input::EXR_BYTES`]), at its start, once the header parses and every
/// layer's size is within [`MAX_PIXELS`]; errors name the file and the element: `parsed`
/// for a header that does not parse, `sized(i)` for layer `i` that is too large. Only the
/// header is read here; the decoder reads the pixels from the file.
pub(super) fn open_checked(
    path: &Path,
    parsed: &str,
    sized: impl Fn(usize) -> String,
) -> std::result::Result<BufReader<Reader>, LoadError> {
    let file = crate::fileio::input::open(path, Input::Exr).map_err(|e| e.at(path, ""))?;
    let mut reader = BufReader::new(file);
    let meta = MetaData::read_from_buffered(&mut reader, false)
        .map_err(|e| parse_error(path, parsed.to_string(), e))?;
    for (i, header) in meta.headers.iter().enumerate() {
        let size = header.layer_size;
        if size.width() as u64 * size.height() as u64 > MAX_PIXELS {
            return Err(LoadError::new(
                path,
                sized(i),
                LoadErrorKind::TooLarge,
                format!(
                    "{}×{} pixels exceeds the limit of {MAX_PIXELS}",
                    size.width(),
                    size.height()
                ),
            ));
        }
    }
    reader
        .seek(SeekFrom::Start(0))
        .map_err(|e| LoadError::new(path, "", LoadErrorKind::Io, e.to_string()))?;
    Ok(reader)
}

/// A parse error of the EXR reader, naming the file and `element`.
fn parse_error(path: &Path, element: String, e: exr::error::Error) -> LoadError {
    LoadError::new(path, element, LoadErrorKind::Parse, e.to_string())
}

/// An all-black image of the layer's resolution, for the reader to fill.
fn new_image(res: Vec2<usize>) -> ImageRgb {
    ImageRgb {
        width: res.width() as u32,
        height: res.height() as u32,
        data: vec![glam::Vec3::ZERO; res.area()],
    }
}

/// Stores one pixel the reader decoded (positions outside the image are ignored).
fn set_pixel(img: &mut ImageRgb, pos: Vec2<usize>, (r, g, b): (f32, f32, f32)) {
    let i = pos.y() * img.width as usize + pos.x();
    if let Some(p) = img.data.get_mut(i) {
        *p = glam::Vec3::new(r, g, b);
    }
}

/// Reads the channels `name.R`, `name.G`, `name.B` of the first layer holding them (the
/// extra image [`encode_with_layer`] writes) at full resolution.
pub fn decode_layer(path: &Path, name: &str) -> std::result::Result<ImageRgb, LoadError> {
    let element = format!("layer {name}");
    let file = open_checked(path, &element, |_| element.clone())?;
    let channel = |c: &str| format!("{name}.{c}");
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .specific_channels()
        .required(channel("R").as_str())
        .required(channel("G").as_str())
        .required(channel("B").as_str())
        .collect_pixels(|res: Vec2<usize>, _| new_image(res), set_pixel)
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(file)
        .map_err(|e| parse_error(path, element.clone(), e))?;
    Ok(image.layer_data.channel_data.pixels)
}

/// Reads the first RGB layer of an EXR file at its full resolution.
pub fn decode(path: &Path) -> std::result::Result<ImageRgb, LoadError> {
    let file = open_checked(path, "", |i| format!("layer {i}"))?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |res: Vec2<usize>, _: &RgbChannels| new_image(res),
            set_pixel,
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(file)
        .map_err(|e| parse_error(path, String::new(), e))?;
    Ok(image.layer_data.channel_data.pixels)
}
