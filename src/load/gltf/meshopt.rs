//! EXT_meshopt_compression (and its successor KHR_meshopt_compression, same layout):
//! buffer views whose bytes are stored compressed by meshoptimizer's codecs.
//!
//! Spec: <https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/EXT_meshopt_compression>.
//! A buffer view carries `extensions.EXT_meshopt_compression {buffer, byteOffset,
//! byteLength, byteStride, count, mode, filter}`: the compressed bytes are
//! `buffers[buffer][byteOffset .. byteOffset+byteLength]`, and decoding yields `count`
//! elements of `byteStride` bytes, which replace the view's own bytes (the view's
//! `buffer` is then usually a *fallback* buffer, `extensions.EXT_meshopt_compression
//! .fallback: true`, often without a `uri`: Iris never loads fallback buffers).
//!
//! Decoder: the `meshopt` crate, i.e. meshoptimizer's own C++ decoders built by `cc`
//! (the reference implementation of the bitstream, vertex codec versions 0 and 1, index
//! codec versions 0 and 1, all filters). Chosen over a Rust port of the codec because
//! the codec is subtle (SIMD and scalar paths, two versions) and the reference decoder
//! is documented as safe on untrusted *data*. It is not safe on bad *parameters*: its
//! `assert`s abort the process (vertex size not a multiple of 4 or above 256, index
//! count not a multiple of 3, filter strides). So every parameter is checked against
//! the spec here, before any call: a hostile file is a [`LoadError`], never an abort.
//! The safe wrapper API needs the element type at compile time, so strides are
//! dispatched to `[u8; N]` by a macro (N = 4, 8, …, 256).
//!
//! Allocation bound: the decoded size `count·byteStride` must equal the view's
//! `byteLength` and may be at most [`MAX_EXPANSION`] times the compressed size (plus
//! 64 KiB), so a tiny file cannot make the loader allocate gigabytes.

use super::label;
use crate::error::{LoadError, LoadErrorKind};
use serde_json::Value;
use std::collections::{BTreeSet, HashMap};
use std::path::Path;

/// The extension names read here (same JSON layout).
pub(super) const NAMES: [&str; 2] = ["EXT_meshopt_compression", "KHR_meshopt_compression"];

/// Largest ratio of decoded to compressed bytes accepted. The vertex codec v1 can store a
/// block's byte lane of zeros in 2 bits (1024:1 on 256-vertex blocks); real files are
/// 2:1 to 10:1.
const MAX_EXPANSION: usize = 1024;

/// How a compressed view is encoded (`mode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Attributes,
    Triangles,
    Indices,
}

/// The post-decode filter (`filter`), attributes only.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Filter {
    None,
    Octahedral,
    Quaternion,
    Exponential,
    /// KHR_meshopt_compression only (YCoCg colours).
    Color,
}

/// A validated `EXT_meshopt_compression` object of one buffer view.
#[derive(Debug)]
struct Compressed {
    buffer: usize,
    offset: usize,
    length: usize,
    stride: usize,
    count: usize,
    mode: Mode,
    filter: Filter,
}

/// What the meshopt pass found: decoded bytes per buffer view index, and the buffers
/// that are fallbacks (not loaded).
#[derive(Debug, Default)]
pub(super) struct DecodedViews {
    /// Decoded bytes, keyed by buffer view index.
    pub views: HashMap<usize, Vec<u8>>,
    /// Indices of fallback buffers (their bytes are never read).
    pub fallback: BTreeSet<usize>,
}

/// Whether `buffer` is declared a meshopt fallback buffer.
pub(super) fn is_fallback(buffer: &gltf::Buffer<'_>) -> bool {
    NAMES.iter().any(|name| {
        buffer
            .extension_value(name)
            .and_then(|v| v.get("fallback"))
            .and_then(Value::as_bool)
            == Some(true)
    })
}

/// Decodes every compressed buffer view of `doc`; `buffers` are the loaded buffers
/// (fallback buffers empty). Errors name `buffer view N "name"`.
pub(super) fn decode_views(
    path: &Path,
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    views: &mut DecodedViews,
) -> Result<(), LoadError> {
    for view in doc.views() {
        let Some((name, ext)) = NAMES
            .iter()
            .find_map(|n| view.extension_value(n).map(|v| (*n, v)))
        else {
            continue;
        };
        let element = label("buffer view", view.index(), view.name());
        let fail = |kind, detail: String| {
            LoadError::new(path, element.clone(), kind, format!("{name}: {detail}"))
        };
        let c = parse(ext, name).map_err(|d| fail(LoadErrorKind::Parse, d))?;
        let decoded_len = c.count.checked_mul(c.stride);
        if decoded_len != Some(view.length()) {
            return Err(fail(
                LoadErrorKind::Parse,
                format!(
                    "count {} × byteStride {} does not equal the view's byteLength {}",
                    c.count,
                    c.stride,
                    view.length()
                ),
            ));
        }
        if view.length()
            > c.length
                .saturating_mul(MAX_EXPANSION)
                .saturating_add(1 << 16)
        {
            return Err(fail(
                LoadErrorKind::TooLarge,
                format!(
                    "{} decoded bytes from {} compressed bytes exceed the {MAX_EXPANSION}:1 bound",
                    view.length(),
                    c.length
                ),
            ));
        }
        if views.fallback.contains(&c.buffer) {
            return Err(fail(
                LoadErrorKind::MissingBuffer,
                format!(
                    "compressed data is in buffer {}, a fallback buffer without data",
                    c.buffer
                ),
            ));
        }
        let source = buffers
            .get(c.buffer)
            .and_then(|b| b.get(c.offset..c.offset.checked_add(c.length)?))
            .ok_or_else(|| {
                fail(
                    LoadErrorKind::MissingBuffer,
                    format!(
                        "bytes {}..{} of buffer {} do not exist",
                        c.offset,
                        c.offset.saturating_add(c.length),
                        c.buffer
                    ),
                )
            })?;
        let bytes = decode(&c, source).map_err(|d| fail(LoadErrorKind::Parse, d))?;
        views.views.insert(view.index(), bytes);
    }
    Ok(())
}

/// Reads and validates the extension object against the spec's constraints (the
/// parameters meshoptimizer would otherwise `assert` on).
fn parse(ext: &Value, name: &str) -> Result<Compressed, String> {
    let uint = |key: &str, default: Option<usize>| -> Result<usize, String> {
        match ext.get(key) {
            None => default.ok_or_else(|| format!("{key} is missing")),
            Some(v) => v
                .as_u64()
                .and_then(|n| usize::try_from(n).ok())
                .ok_or_else(|| format!("{key} is not a non-negative integer: {v}")),
        }
    };
    let text = |key: &str, default: &'static str| -> Result<String, String> {
        match ext.get(key) {
            None => Ok(default.to_string()),
            Some(Value::String(s)) => Ok(s.clone()),
            Some(v) => Err(format!("{key} is not a string: {v}")),
        }
    };
    let mode = match text("mode", "")?.as_str() {
        "ATTRIBUTES" => Mode::Attributes,
        "TRIANGLES" => Mode::Triangles,
        "INDICES" => Mode::Indices,
        "" => return Err("mode is missing".into()),
        other => return Err(format!("unknown mode {other:?}")),
    };
    let filter = match text("filter", "NONE")?.as_str() {
        "NONE" => Filter::None,
        "OCTAHEDRAL" => Filter::Octahedral,
        "QUATERNION" => Filter::Quaternion,
        "EXPONENTIAL" => Filter::Exponential,
        "COLOR" if name.starts_with("KHR") => Filter::Color,
        other => return Err(format!("unknown filter {other:?}")),
    };
    let c = Compressed {
        buffer: uint("buffer", None)?,
        offset: uint("byteOffset", Some(0))?,
        length: uint("byteLength", None)?,
        stride: uint("byteStride", None)?,
        count: uint("count", None)?,
        mode,
        filter,
    };
    let s = c.stride;
    match mode {
        Mode::Attributes if s == 0 || !s.is_multiple_of(4) || s > 256 => Err(format!(
            "byteStride {s} is invalid for ATTRIBUTES (a multiple of 4 from 4 to 256)"
        )),
        Mode::Triangles | Mode::Indices if s != 2 && s != 4 => {
            Err(format!("byteStride {s} is invalid for {mode:?} (2 or 4)"))
        }
        Mode::Triangles if !c.count.is_multiple_of(3) => Err(format!(
            "count {} is not a multiple of 3 for TRIANGLES",
            c.count
        )),
        Mode::Triangles | Mode::Indices if filter != Filter::None => {
            Err(format!("filter {filter:?} is only allowed with ATTRIBUTES"))
        }
        _ => match filter {
            Filter::Octahedral | Filter::Color if s != 4 && s != 8 => {
                Err(format!("byteStride {s} is invalid for {filter:?} (4 or 8)"))
            }
            Filter::Quaternion if s != 8 => {
                Err(format!("byteStride {s} is invalid for QUATERNION (8)"))
            }
            _ => Ok(c),
        },
    }
}

/// Decodes a validated view (parameters already checked by [`parse`]).
fn decode(c: &Compressed, source: &[u8]) -> Result<Vec<u8>, String> {
    if c.count == 0 {
        return Ok(Vec::new());
    }
    let err = |e: meshopt::Error| format!("corrupt {:?} data: {e}", c.mode);
    let mut bytes = match (c.mode, c.stride) {
        (Mode::Attributes, _) => decode_vertices(source, c.count, c.stride).map_err(err)?,
        (mode, 2) => decode_indices(mode, source, c.count, u16::to_le_bytes).map_err(err)?,
        (mode, _) => decode_indices(mode, source, c.count, u32::to_le_bytes).map_err(err)?,
    };
    apply_filter(c.filter, c.stride, &mut bytes);
    Ok(bytes)
}

/// The index codec of `mode` (TRIANGLES: `decode_index_buffer`, INDICES:
/// `decode_index_sequence`) for indices of type `T`, as little-endian bytes.
fn decode_indices<T: meshopt::IndexType, const K: usize>(
    mode: Mode,
    source: &[u8],
    count: usize,
    to_le: fn(T) -> [u8; K],
) -> Result<Vec<u8>, meshopt::Error> {
    let values = match mode {
        Mode::Triangles => meshopt::decode_index_buffer::<T>(source, count)?,
        _ => meshopt::decode_index_sequence::<T>(source, count)?,
    };
    Ok(values.into_iter().flat_map(to_le).collect())
}

/// One decoded vertex of `N` bytes (`[u8; N]` has no `Default` above 32 bytes, which the
/// decoder's output buffer needs).
#[derive(Clone, Copy)]
#[repr(transparent)]
struct Vertex<const N: usize>([u8; N]);

impl<const N: usize> Default for Vertex<N> {
    fn default() -> Self {
        Self([0; N])
    }
}

/// The vertex codec for a runtime stride: one [`Vertex<N>`] instantiation per valid stride.
fn decode_vertices(source: &[u8], count: usize, stride: usize) -> Result<Vec<u8>, meshopt::Error> {
    macro_rules! strides {
        ($($n:literal)*) => {
            match stride {
                $($n => meshopt::decode_vertex_buffer::<Vertex<$n>>(source, count)
                    .map(|v| v.iter().flat_map(|e| e.0).collect()),)*
                // Unreachable after `parse`; an error rather than a call that would abort.
                _ => Err(meshopt::Error::Memory(format!("invalid vertex size {stride}").into())),
            }
        };
    }
    strides!(4 8 12 16 20 24 28 32 36 40 44 48 52 56 60 64 68 72 76 80 84 88 92 96 100
        104 108 112 116 120 124 128 132 136 140 144 148 152 156 160 164 168 172 176 180 184
        188 192 196 200 204 208 212 216 220 224 228 232 236 240 244 248 252 256)
}

/// Applies a filter in place on `bytes` (whole elements of `stride` bytes).
fn apply_filter(filter: Filter, stride: usize, bytes: &mut [u8]) {
    match (filter, stride) {
        (Filter::None, _) => {}
        (Filter::Octahedral | Filter::Color, 4) => {
            let mut v: Vec<[i8; 4]> = bytes
                .chunks_exact(4)
                .map(|c| std::array::from_fn(|k| c[k] as i8))
                .collect();
            if filter == Filter::Octahedral {
                meshopt::decode_filter_oct(&mut v);
            } else {
                meshopt::decode_filter_color(&mut v);
            }
            for (out, e) in bytes.chunks_exact_mut(4).zip(&v) {
                for (o, c) in out.iter_mut().zip(e) {
                    *o = *c as u8;
                }
            }
        }
        (Filter::Octahedral | Filter::Color | Filter::Quaternion, _) => {
            let mut v: Vec<[i16; 4]> = bytes
                .chunks_exact(8)
                .map(|c| std::array::from_fn(|k| i16::from_le_bytes([c[2 * k], c[2 * k + 1]])))
                .collect();
            match filter {
                Filter::Octahedral => meshopt::decode_filter_oct(&mut v),
                Filter::Color => meshopt::decode_filter_color(&mut v),
                _ => meshopt::decode_filter_quat(&mut v),
            }
            for (out, e) in bytes.chunks_exact_mut(8).zip(&v) {
                out.copy_from_slice(&e.iter().flat_map(|c| c.to_le_bytes()).collect::<Vec<_>>());
            }
        }
        (Filter::Exponential, _) => {
            // Each 32-bit word decodes on its own (2^E·M), so the stride does not matter.
            let mut v: Vec<[u32; 1]> = bytes
                .chunks_exact(4)
                .map(|c| [u32::from_le_bytes([c[0], c[1], c[2], c[3]])])
                .collect();
            meshopt::decode_filter_exp(&mut v);
            for (out, e) in bytes.chunks_exact_mut(4).zip(&v) {
                out.copy_from_slice(&e[0].to_le_bytes());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn ext(stride: usize, count: usize, mode: &str, filter: &str) -> Value {
        json!({"buffer": 0, "byteLength": 100, "byteStride": stride, "count": count,
               "mode": mode, "filter": filter})
    }

    #[test]
    fn parameters_meshoptimizer_would_assert_on_are_errors() {
        let name = NAMES[0];
        assert!(parse(&ext(12, 5, "ATTRIBUTES", "NONE"), name).is_ok());
        for (stride, count, mode, filter) in [
            (3, 5, "ATTRIBUTES", "NONE"),
            (0, 5, "ATTRIBUTES", "NONE"),
            (260, 5, "ATTRIBUTES", "NONE"),
            (4, 4, "TRIANGLES", "NONE"),
            (8, 3, "TRIANGLES", "NONE"),
            (1, 3, "INDICES", "NONE"),
            (4, 3, "INDICES", "OCTAHEDRAL"),
            (12, 3, "ATTRIBUTES", "OCTAHEDRAL"),
            (4, 3, "ATTRIBUTES", "QUATERNION"),
            (4, 3, "ATTRIBUTES", "COLOR"),
            (4, 3, "POINTS", "NONE"),
            (4, 3, "ATTRIBUTES", "SQUARE"),
        ] {
            let e = parse(&ext(stride, count, mode, filter), name);
            assert!(e.is_err(), "{stride} {count} {mode} {filter} accepted");
        }
        assert!(parse(&ext(4, 3, "ATTRIBUTES", "COLOR"), NAMES[1]).is_ok());
        assert!(parse(
            &json!({"buffer": 0, "byteLength": 1, "byteStride": 4}),
            name
        )
        .is_err());
        assert!(parse(
            &json!({"buffer": -1, "byteLength": 1, "byteStride": 4, "count": 1,
                              "mode": "ATTRIBUTES"}),
            name
        )
        .is_err());
    }

    #[test]
    fn round_trips_through_the_reference_encoder() {
        let verts: Vec<[u8; 12]> = (0..100u8)
            .map(|i| std::array::from_fn(|k| i.wrapping_mul(k as u8 + 1)))
            .collect();
        let encoded = meshopt::encode_vertex_buffer(&verts).expect("encode");
        let c = Compressed {
            buffer: 0,
            offset: 0,
            length: encoded.len(),
            stride: 12,
            count: 100,
            mode: Mode::Attributes,
            filter: Filter::None,
        };
        assert_eq!(decode(&c, &encoded).expect("decode"), verts.concat());
        // Truncated data is an error from the decoder, not a crash.
        assert!(decode(&c, &encoded[..encoded.len() / 2]).is_err());

        let indices: Vec<u32> = vec![0, 1, 2, 2, 1, 3, 3, 4, 0];
        let encoded = meshopt::encode_index_buffer(&indices, 5).expect("encode");
        let c = Compressed {
            stride: 4,
            count: 9,
            length: encoded.len(),
            mode: Mode::Triangles,
            ..c
        };
        let bytes = decode(&c, &encoded).expect("decode");
        let back: Vec<u32> = bytes
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        // The triangle codec may rotate a triangle's indices; it keeps each triangle.
        for (t, u) in back.chunks(3).zip(indices.chunks(3)) {
            let rotations = [[u[0], u[1], u[2]], [u[1], u[2], u[0]], [u[2], u[0], u[1]]];
            assert!(rotations.iter().any(|r| r == t), "{t:?} vs {u:?}");
        }
    }

    #[test]
    fn exponential_filter_is_two_to_the_e_times_m() {
        // E = -2, M = 3 → 0.75.
        let word = ((-2i32 as u32) << 24) | 3;
        let mut bytes = word.to_le_bytes().to_vec();
        apply_filter(Filter::Exponential, 4, &mut bytes);
        let value = f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
        assert_eq!(value, 0.75);
    }
}
