//! Buffer and image bytes of a glTF file (glTF 2.0 §3.6.1 "Buffers and Buffer Views",
//! §3.8.4 "Images"; GLB binary chunk §4.4.3.3).
//!
//! Buffers are loaded one by one so that a missing or short buffer is reported as
//! `buffer N "name"` with the file it should have come from. A buffer keeps exactly
//! `byteLength` bytes. Images are decoded lazily (only those a material uses) with the
//! `image` crate (PNG, JPEG, WebP) into RGBA8, **as stored** (no sRGB decoding here), with the
//! size limits of [`crate::load::decode`]. External files are read through
//! [`Files`] (regular files only).

use super::uri::{self, UriSource};
use super::{label, Ctx};
use crate::error::{LoadError, LoadErrorKind};
use crate::load::decode::decode_rgba8;
use crate::load::files::Files;
use crate::material::ImageDesc;
use gltf::buffer::Source;
use std::collections::{BTreeSet, HashMap};
use std::path::Path;

/// Loads every buffer of `doc`; index `i` of the result is glTF buffer `i`. Meshopt
/// fallback buffers (see [`super::meshopt`]) are not loaded: they stay empty and their
/// indices are added to `fallback`.
pub(super) fn load_buffers(
    path: &Path,
    base_dir: &Path,
    files: Files<'_>,
    doc: &gltf::Document,
    mut blob: Option<Vec<u8>>,
    fallback: &mut BTreeSet<usize>,
) -> Result<Vec<Vec<u8>>, LoadError> {
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        if super::meshopt::is_fallback(&buffer) {
            fallback.insert(buffer.index());
            out.push(Vec::new());
            continue;
        }
        let element = label("buffer", buffer.index(), buffer.name());
        let missing = |detail: String| {
            LoadError::new(path, element.clone(), LoadErrorKind::MissingBuffer, detail)
        };
        let (mut data, origin) = match buffer.source() {
            Source::Bin => {
                let data = blob.take().ok_or_else(|| {
                    missing(
                        "has no uri, so it must be the GLB binary chunk, which is absent".into(),
                    )
                })?;
                (data, "the GLB binary chunk".to_string())
            }
            Source::Uri(text) => match uri::resolve(text, base_dir).map_err(missing)? {
                UriSource::Embedded(bytes) => (bytes, "its data URI".to_string()),
                UriSource::File(file) => {
                    let data = files
                        .read(&file, crate::fileio::Input::Scene)
                        .map_err(|e| missing(format!("cannot read {}: {e}", file.display())))?;
                    (data, file.display().to_string())
                }
            },
        };
        let declared = buffer.length();
        if data.len() < declared {
            return Err(missing(format!(
                "byteLength is {declared} but {origin} holds only {} bytes",
                data.len()
            )));
        }
        data.truncate(declared);
        out.push(data);
    }
    Ok(out)
}

/// The bytes of buffer view `view` (decoded, for a meshopt-compressed view), or why they
/// are not there.
pub(super) fn view_bytes<'c>(
    ctx: &'c Ctx<'_>,
    view: &gltf::buffer::View<'_>,
) -> Result<&'c [u8], String> {
    if let Some(decoded) = ctx.decoded.views.get(&view.index()) {
        return Ok(decoded);
    }
    let buffer = view.buffer().index();
    if ctx.decoded.fallback.contains(&buffer) {
        return Err(format!(
            "buffer view {} refers to buffer {buffer}, a meshopt fallback buffer without data, and has no EXT_meshopt_compression data of its own",
            view.index()
        ));
    }
    let data = ctx.buffers.get(buffer).ok_or_else(|| {
        format!(
            "buffer view {} refers to missing buffer {buffer}",
            view.index()
        )
    })?;
    let start = view.offset();
    start
        .checked_add(view.length())
        .and_then(|end| data.get(start..end))
        .ok_or_else(|| {
            format!(
                "buffer view {} spans bytes {start}..{} of buffer {buffer}, which has {} bytes",
                view.index(),
                start.saturating_add(view.length()),
                data.len()
            )
        })
}

/// Images decoded so far, keyed by glTF image index.
#[derive(Default)]
pub(super) struct ImageCache {
    index_of: HashMap<usize, usize>,
    images: Vec<ImageDesc>,
}

impl ImageCache {
    /// Index into the decoded image list of glTF image `image`, decoding it on first use.
    pub(super) fn get(&mut self, ctx: &Ctx<'_>, image: usize) -> Result<usize, LoadError> {
        if let Some(&i) = self.index_of.get(&image) {
            return Ok(i);
        }
        let desc = decode_image(ctx, image)?;
        let i = self.images.len();
        self.images.push(desc);
        self.index_of.insert(image, i);
        Ok(i)
    }

    /// The decoded images, in first-use order.
    pub(super) fn into_images(self) -> Vec<ImageDesc> {
        self.images
    }
}

/// Reads and decodes glTF image `index` into RGBA8.
fn decode_image(ctx: &Ctx<'_>, index: usize) -> Result<ImageDesc, LoadError> {
    let json = ctx.doc.as_json().images.get(index).ok_or_else(|| {
        ctx.error(
            format!("image {index}"),
            LoadErrorKind::IndexOutOfRange,
            "no such image",
        )
    })?;
    let display_name = json
        .name
        .as_deref()
        .or_else(|| json.uri.as_deref().filter(|u| !u.starts_with("data:")));
    let element = label("image", index, display_name);
    let missing = |detail: String| ctx.error(element.clone(), LoadErrorKind::MissingBuffer, detail);

    let owned;
    let bytes: &[u8] = if let Some(view_index) = json.buffer_view {
        let view =
            ctx.doc.views().nth(view_index.value()).ok_or_else(|| {
                missing(format!("buffer view {} does not exist", view_index.value()))
            })?;
        view_bytes(ctx, &view).map_err(missing)?
    } else if let Some(text) = json.uri.as_deref() {
        owned = match uri::resolve(text, &ctx.base_dir).map_err(missing)? {
            UriSource::Embedded(bytes) => bytes,
            UriSource::File(file) => ctx
                .files
                .read(&file, crate::fileio::Input::Image)
                .map_err(|e| missing(format!("cannot read {}: {e}", file.display())))?,
        };
        &owned
    } else {
        return Err(missing("has neither a uri nor a bufferView".into()));
    };

    decode_rgba8(bytes, element.clone())
        .map_err(|(kind, detail)| ctx.error(element.clone(), kind, detail))
}
