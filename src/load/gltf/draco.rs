//! KHR_draco_mesh_compression: primitives whose indices and (some) attributes are one
//! Draco-compressed mesh in a buffer view.
//!
//! Spec: <https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_draco_mesh_compression>.
//! The primitive carries `extensions.KHR_draco_mesh_compression {bufferView, attributes
//! {SEMANTIC: draco attribute unique id}}`. The primitive's accessors keep `count`,
//! `componentType`, `type` and `normalized` but no `bufferView`; the indices come from the
//! Draco mesh's faces; attributes not listed in the extension are read as usual. The
//! decoded index count must equal the indices accessor's count, every listed attribute
//! must decode to the same number of points, and that number may not be below the
//! accessors' count (else an error naming the primitive). It may be *above* it: Google's
//! decoder merges a few points that `draco-oxide-decoder` keeps apart (Blender's glass
//! of water, tests/data/compressed: 1446 decoded points for 1442 declared, same
//! triangles), so the decoded mesh is used and the loader warns once, as Blender's own
//! importer does ("Vertex count of accessor and decoded vertex count does not match").
//! Values come out of the decoder dequantized (Draco's quantization is undone by the
//! decoder: positions to within `extent / 2^bits`); integer attributes are converted
//! with the accessor's `normalized` flag exactly as dense accessors are.
//!
//! Decoder: `draco-oxide-decoder` (pure Rust, Draco bitstream 2.2 meshes, sequential
//! and Edgebreaker connectivity, the prediction schemes Google's encoder emits).
//! Evaluated against `draco_decoder` (Google's C++ through cxx + cmake; writes its build
//! cache into its own source directory, marked work in progress) and `draco-rs`
//! (autocxx + cmake, needs libclang and cmake at build time): the pure-Rust decoder needs
//! no C++ toolchain or cmake in CI, adds no `unsafe` to Iris, and decodes Blender's
//! exports (tests/load/load_compressed.rs compares them with their uncompressed twins). Its
//! caveats: it is an alpha, and it does use `unsafe` internally (unchecked indexing in
//! its attribute traversal). Iris builds a patched copy (`vendor/draco-oxide-decoder`,
//! wired by `[patch.crates-io]`; the changes are listed in its `IRIS-PATCHES.md`): fuzzing
//! through Iris's glTF target found stream-declared sizes the decoder allocated unchecked
//! (up to 1.8 GB, and one allocation failure that aborted the process), and the patch
//! bounds each such count by the remaining stream, the declared faces or values, or an
//! absolute cap; mutations of exporter-made files found three panics (a wrap transform
//! with inverted bounds, an octahedral transform on a 3-component attribute, a symbol
//! stream shorter than its symbols), which the patch refuses as Google's decoder does.
//! Those inputs (fuzz/regressions/gltf/draco_*.glb) end in clean errors.
//!
//! Hostile input: the decoder's own errors become [`LoadError`]s; a panic inside it is
//! caught by the panic net ([`crate::load::panic_net`], which keeps its message off the
//! terminal unless `--verbose`) and reported the same way. Before decoding, the
//! stream's header counts (faces, vertices; `draco_header`, which refuses a stream whose
//! counts it cannot read) must agree with the accessors, and the accessors' counts (or,
//! without indices, the corners) may be at most [`MAX_EXPANSION`] elements per
//! compressed byte, so a small file cannot ask the decoder for gigabytes.

use super::accessor::component;
use super::draco_header::header_counts;
use super::source::view_bytes;
use super::Ctx;
use crate::error::{LoadError, LoadErrorKind};
use crate::load::panic_net;
use draco_oxide_core::attribute::{Attribute, ComponentDataType};
use draco_oxide_core::mesh::Mesh;
use gltf::accessor::DataType;
use serde_json::Value;
use std::collections::BTreeMap;

/// The extension name.
pub(super) const NAME: &str = "KHR_draco_mesh_compression";

/// Most decoded elements (vertices or indices) per compressed byte: 1/8 bit each, far
/// below any real Draco stream (Edgebreaker spends about 2 bits per triangle).
const MAX_EXPANSION: usize = 64;

/// A decoded Draco primitive: attribute values per glTF semantic (as `f32` components,
/// one `Vec` per point) and the triangle indices.
#[derive(Debug, Default)]
pub(super) struct DracoPrimitive {
    /// Values per semantic name (`POSITION`, `NORMAL`, `TEXCOORD_0`, …).
    pub attributes: BTreeMap<String, Vec<Vec<f32>>>,
    /// Triangle-list indices into the points.
    pub indices: Vec<u32>,
    /// `(decoded, declared)` when the decoder produced more points than the accessors say.
    pub extra_points: Option<(usize, usize)>,
}

impl DracoPrimitive {
    /// The values of `semantic` as `N`-component vectors, if Draco holds that attribute.
    pub(super) fn get<const N: usize>(&self, semantic: &str) -> Option<Vec<[f32; N]>> {
        self.attributes.get(semantic).map(|values| {
            values
                .iter()
                .map(|v| std::array::from_fn(|k| v.get(k).copied().unwrap_or(0.0)))
                .collect()
        })
    }
}

/// A reason to refuse the primitive: the error kind and the sentence after the extension's
/// name.
type Failure = (LoadErrorKind, String);

/// An accessor the Draco stream fills: its semantic, the Draco attribute id the extension
/// maps it to, and the accessor (declared count, type, `normalized`).
struct Wanted<'a> {
    semantic: String,
    id: usize,
    acc: gltf::Accessor<'a>,
}

/// The error sentence for a decoder panic (the panic net's; `--verbose` adds the message).
pub(super) const DECODER_PANICKED: &str = "the Draco decoder panicked on this data";

/// Decodes the Draco mesh of `prim` if it has the extension; `element` names the
/// primitive in errors.
pub(super) fn read_draco(
    ctx: &Ctx<'_>,
    prim: &gltf::Primitive<'_>,
    element: &str,
) -> Result<Option<DracoPrimitive>, LoadError> {
    let Some(ext) = prim.extension_value(NAME) else {
        return Ok(None);
    };
    let fail = |(kind, detail): Failure| ctx.error(element, kind, format!("{NAME}: {detail}"));
    let bytes = stream_bytes(ctx, ext).map_err(fail)?;
    let wanted = wanted_accessors(prim, ext).map_err(fail)?;
    let index_count = prim.indices().map(|acc| acc.count());
    check_counts(bytes, &wanted, index_count).map_err(fail)?;
    let mesh = decode(bytes).map_err(fail)?;
    to_primitive(&mesh, &wanted, index_count)
        .map(Some)
        .map_err(fail)
}

/// The compressed bytes: the buffer view the extension names.
fn stream_bytes<'c>(ctx: &'c Ctx<'_>, ext: &Value) -> Result<&'c [u8], Failure> {
    let view_index = ext
        .get("bufferView")
        .and_then(Value::as_u64)
        .and_then(|v| usize::try_from(v).ok())
        .ok_or_else(|| {
            (
                LoadErrorKind::Parse,
                "bufferView is missing or not an index".to_string(),
            )
        })?;
    let view = ctx.doc.views().nth(view_index).ok_or_else(|| {
        (
            LoadErrorKind::IndexOutOfRange,
            format!("bufferView {view_index} does not exist"),
        )
    })?;
    view_bytes(ctx, &view).map_err(|e| (LoadErrorKind::MissingBuffer, e))
}

/// The accessors this stream must fill, in the extension's `attributes` order; each named
/// semantic must be an attribute of the primitive.
fn wanted_accessors<'a>(
    prim: &gltf::Primitive<'a>,
    ext: &Value,
) -> Result<Vec<Wanted<'a>>, Failure> {
    let ids = attribute_ids(ext).map_err(|d| (LoadErrorKind::Parse, d))?;
    ids.into_iter()
        .map(|(semantic, id)| {
            let acc = prim
                .attributes()
                .find(|(s, _)| s.to_string() == semantic)
                .map(|(_, acc)| acc)
                .ok_or_else(|| {
                    (
                        LoadErrorKind::Parse,
                        format!("attribute {semantic} is not an attribute of the primitive"),
                    )
                })?;
            Ok(Wanted { semantic, id, acc })
        })
        .collect()
}

/// The bounds checked before decoding: the accessors' counts (or, without indices, the
/// corners) at most [`MAX_EXPANSION`] per compressed byte, and the stream's header counts
/// in agreement with them.
fn check_counts(
    bytes: &[u8],
    wanted: &[Wanted<'_>],
    index_count: Option<usize>,
) -> Result<(), Failure> {
    let budget = bytes.len().saturating_mul(MAX_EXPANSION);
    let largest = wanted
        .iter()
        .map(|w| w.acc.count())
        .chain(index_count)
        .max()
        .unwrap_or(0);
    if largest > budget {
        return Err((
            LoadErrorKind::TooLarge,
            format!(
                "the accessors declare {largest} elements for {} compressed bytes (at most {MAX_EXPANSION} per byte)",
                bytes.len()
            ),
        ));
    }
    let header = header_counts(bytes).map_err(|d| (LoadErrorKind::Parse, d))?;
    // Without an indices accessor the faces are bounded by the byte budget instead.
    let corners = header.faces.checked_mul(3);
    let faces_ok = match index_count {
        Some(n) => corners == Some(n),
        None => corners.is_some_and(|c| c <= budget),
    };
    let points_ok = wanted.iter().all(|w| header.vertices <= w.acc.count());
    if !faces_ok || !points_ok {
        return Err((
            LoadErrorKind::Parse,
            format!(
                "the Draco stream has {} faces and {} vertices, which disagree with the accessors ({} indices, {} points)",
                header.faces,
                header.vertices,
                index_count.map_or("no".to_string(), |n| n.to_string()),
                wanted.first().map_or(0, |w| w.acc.count())
            ),
        ));
    }
    Ok(())
}

/// Runs the decoder under the panic net ([`panic_net::catch`]): a panic is an error, and
/// its message stays off the terminal unless `--verbose`.
fn decode(bytes: &[u8]) -> Result<Mesh, Failure> {
    panic_net::catch(|| draco_oxide_decoder::decode_mesh(bytes))
        .map_err(|caught| (LoadErrorKind::Parse, caught.describe(DECODER_PANICKED)))?
        .map_err(|e| (LoadErrorKind::Parse, format!("invalid Draco data: {e}")))
}

/// The decoded mesh as the primitive's attributes and indices, after checking it against
/// the accessors: every listed attribute present with the same number of points, at least
/// the declared count (more is tolerated, see the module doc), indices below the point
/// count and as many as the indices accessor declares.
fn to_primitive(
    mesh: &Mesh,
    wanted: &[Wanted<'_>],
    index_count: Option<usize>,
) -> Result<DracoPrimitive, Failure> {
    let parse = |detail: String| (LoadErrorKind::Parse, detail);
    let mut out = DracoPrimitive::default();
    for Wanted { semantic, id, acc } in wanted {
        let attribute = mesh
            .attributes
            .iter()
            .find(|a| a.get_id().as_usize() == *id)
            .ok_or_else(|| {
                parse(format!(
                    "{semantic} refers to Draco attribute {id}, which the stream does not have"
                ))
            })?;
        let values =
            attribute_values(attribute, acc).map_err(|d| parse(format!("{semantic}: {d}")))?;
        out.attributes.insert(semantic.clone(), values);
    }
    out.indices = face_indices(mesh)?;
    let decoded = out.attributes.values().map(Vec::len).max().unwrap_or(0);
    let declared = wanted.first().map_or(0, |w| w.acc.count());
    for Wanted { semantic, acc, .. } in wanted {
        let len = out.attributes.get(semantic).map_or(0, Vec::len);
        // More points than declared is tolerated (see the module doc), fewer is not.
        if len != decoded || len < acc.count() {
            return Err(parse(format!(
                "{semantic} decodes to {len} values but accessor {} has count {}",
                acc.index(),
                acc.count()
            )));
        }
    }
    if decoded > declared {
        out.extra_points = Some((decoded, declared));
    }
    if let Some((i, &p)) = out
        .indices
        .iter()
        .enumerate()
        .find(|(_, &p)| p as usize >= decoded)
    {
        return Err((
            LoadErrorKind::IndexOutOfRange,
            format!("decoded index {p} (position {i}) is not below the point count {decoded}"),
        ));
    }
    if let Some(n) = index_count.filter(|&n| n != out.indices.len()) {
        return Err(parse(format!(
            "the Draco mesh has {} indices but the indices accessor has count {n}",
            out.indices.len()
        )));
    }
    Ok(out)
}

/// The decoded faces as a triangle list of 32-bit indices.
fn face_indices(mesh: &Mesh) -> Result<Vec<u32>, Failure> {
    let mut faces: Vec<u32> = Vec::with_capacity(mesh.faces.len().saturating_mul(3));
    for &p in mesh.faces.iter().flatten() {
        let p = u32::try_from(usize::from(p)).map_err(|_| {
            (
                LoadErrorKind::TooLarge,
                "a decoded face index exceeds 32 bits".to_string(),
            )
        })?;
        faces.push(p);
    }
    Ok(faces)
}

/// How many primitives of the file carry the extension.
pub(super) fn compressed_primitives(root: &gltf::json::Root) -> usize {
    root.meshes
        .iter()
        .flat_map(|m| &m.primitives)
        .filter(|p| {
            p.extensions
                .as_ref()
                .is_some_and(|e| e.others.contains_key(NAME))
        })
        .count()
}

/// Accessors used by primitives that carry the extension (their attributes and indices):
/// the spec lets these have no `bufferView`.
pub(super) fn accessors_without_views(root: &gltf::json::Root) -> Vec<usize> {
    let mut out = Vec::new();
    for prim in root.meshes.iter().flat_map(|m| &m.primitives) {
        let has_ext = prim
            .extensions
            .as_ref()
            .is_some_and(|e| e.others.contains_key(NAME));
        if has_ext {
            out.extend(prim.attributes.values().map(|a| a.value()));
            out.extend(prim.indices.map(|a| a.value()));
        }
    }
    out
}

/// The extension's `attributes` map: semantic name → Draco attribute unique id.
fn attribute_ids(ext: &Value) -> Result<Vec<(String, usize)>, String> {
    let map = ext
        .get("attributes")
        .and_then(Value::as_object)
        .ok_or("attributes is missing or not an object")?;
    map.iter()
        .map(|(name, id)| {
            id.as_u64()
                .and_then(|v| usize::try_from(v).ok())
                .map(|id| (name.clone(), id))
                .ok_or_else(|| {
                    format!("attribute id of {name} is not a non-negative integer: {id}")
                })
        })
        .collect()
}

/// One Draco attribute as `f32` vectors per point, converted like the accessor's own
/// component type would be (normalized integers with the glTF table).
fn attribute_values(
    attribute: &Attribute,
    acc: &gltf::Accessor<'_>,
) -> Result<Vec<Vec<f32>>, String> {
    let n = attribute.get_num_components();
    let expected = acc.dimensions().multiplicity();
    if n != expected {
        return Err(format!(
            "Draco attribute has {n} components but accessor {} is {:?}",
            acc.index(),
            acc.dimensions()
        ));
    }
    let ty = match attribute.get_component_type() {
        ComponentDataType::F32 => DataType::F32,
        ComponentDataType::I8 => DataType::I8,
        ComponentDataType::U8 => DataType::U8,
        ComponentDataType::I16 => DataType::I16,
        ComponentDataType::U16 => DataType::U16,
        ComponentDataType::U32 => DataType::U32,
        other => return Err(format!("unsupported Draco component type {other:?}")),
    };
    let size = ty.size();
    let data = attribute.get_data_as_bytes();
    let normalized = acc.normalized();
    let value = |v: usize| -> Option<Vec<f32>> {
        let bytes = data.get(v.checked_mul(n * size)?..)?.get(..n * size)?;
        Some(
            (0..n)
                .map(|k| component(&bytes[k * size..], ty, normalized))
                .collect(),
        )
    };
    let missing = |v: usize| format!("point refers to value {v}, which the attribute lacks");
    match attribute.point_map_as_slice() {
        Some(map) => map
            .iter()
            .map(|&v| {
                let v = usize::from(v);
                value(v).ok_or_else(|| missing(v))
            })
            .collect(),
        None => (0..attribute.num_unique_values())
            .map(|v| value(v).ok_or_else(|| missing(v)))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn garbage_is_an_error_not_a_panic() {
        for data in [
            &b""[..],
            b"DRACO",
            b"DRACO\x02\x02\x01\x01\x00\x00\xff\xff\xff\xff",
        ] {
            let r = std::panic::catch_unwind(|| draco_oxide_decoder::decode_mesh(data));
            assert!(matches!(r, Ok(Err(_))), "{data:?}");
        }
    }
}
