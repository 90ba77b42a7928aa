//! Bounds-checked accessor reads (glTF 2.0 §3.6.2 "Accessors", §3.6.2.3 sparse accessors,
//! §3.6.2.4 data alignment).
//!
//! Every byte range is computed with checked arithmetic against the loaded buffer, so
//! a hostile `count`, `byteOffset` or `byteStride` yields an error, never a panic or a
//! huge allocation (dense reads allocate at most one element per buffer byte).
//! Integer components are converted to `f32`; normalized ones with the spec's table
//! (§3.11 "Animations", also used by KHR_mesh_quantization):
//! `i8: max(c/127, -1)`, `u8: c/255`, `i16: max(c/32767, -1)`, `u16: c/65535`.

use super::source::view_bytes;
use super::Ctx;
use crate::error::LoadErrorKind;
use gltf::accessor::{DataType, Dimensions};

/// Largest element count of an accessor that has no buffer view (all zeros + sparse):
/// 4 Mi elements (48 MiB of VEC3). Such an accessor costs a few bytes of JSON, so the
/// bound keeps a tiny file from allocating gigabytes; real files store big meshes densely.
const MAX_ZERO_FILLED: usize = 1 << 22;

/// Why an accessor could not be read; the caller names the element.
#[derive(Debug)]
pub(super) struct AccessorError {
    /// Class of problem.
    pub kind: LoadErrorKind,
    /// Details, starting with `accessor N`.
    pub detail: String,
}

fn fail(
    acc: &gltf::Accessor<'_>,
    kind: LoadErrorKind,
    detail: impl std::fmt::Display,
) -> AccessorError {
    AccessorError {
        kind,
        detail: format!("accessor {}: {detail}", acc.index()),
    }
}

/// Reads an accessor of `N` components per element (SCALAR, VEC2, VEC3 or VEC4) as `f32`.
pub(super) fn read_floats<const N: usize>(
    ctx: &Ctx<'_>,
    acc: &gltf::Accessor<'_>,
) -> Result<Vec<[f32; N]>, AccessorError> {
    let dims = acc.dimensions();
    if multiplicity(dims) != Some(N) {
        return Err(fail(
            acc,
            LoadErrorKind::Parse,
            format!("has type {dims:?}, expected {N} components"),
        ));
    }
    let ty = acc.data_type();
    let size = ty.size();
    let normalized = acc.normalized();
    let decode = |bytes: &[u8]| -> [f32; N] {
        std::array::from_fn(|k| component(bytes.get(k * size..).unwrap_or(&[]), ty, normalized))
    };
    read_elements(ctx, acc, size * N, decode, [0.0; N])
}

/// Reads an index accessor (SCALAR of unsigned bytes, shorts or ints) as `u32`.
pub(super) fn read_indices(
    ctx: &Ctx<'_>,
    acc: &gltf::Accessor<'_>,
) -> Result<Vec<u32>, AccessorError> {
    let dims = acc.dimensions();
    if dims != Dimensions::Scalar {
        return Err(fail(
            acc,
            LoadErrorKind::Parse,
            format!("indices have type {dims:?}, expected SCALAR"),
        ));
    }
    let ty = acc.data_type();
    if !matches!(ty, DataType::U8 | DataType::U16 | DataType::U32) {
        return Err(fail(
            acc,
            LoadErrorKind::Parse,
            format!("indices have component type {ty:?}, expected an unsigned integer"),
        ));
    }
    read_elements(ctx, acc, ty.size(), |b| unsigned(b, ty), 0)
}

/// Components per element for the vector types this loader reads.
fn multiplicity(dims: Dimensions) -> Option<usize> {
    match dims {
        Dimensions::Scalar => Some(1),
        Dimensions::Vec2 => Some(2),
        Dimensions::Vec3 => Some(3),
        Dimensions::Vec4 => Some(4),
        Dimensions::Mat2 | Dimensions::Mat3 | Dimensions::Mat4 => None,
    }
}

/// Dense elements (from the buffer view, or zeros), then the sparse substitutions.
fn read_elements<T: Copy>(
    ctx: &Ctx<'_>,
    acc: &gltf::Accessor<'_>,
    elem_size: usize,
    decode: impl Fn(&[u8]) -> T,
    zero: T,
) -> Result<Vec<T>, AccessorError> {
    let count = acc.count();
    let mut out = match acc.view() {
        Some(view) => {
            let data =
                view_bytes(ctx, &view).map_err(|e| fail(acc, LoadErrorKind::MissingBuffer, e))?;
            let stride = view.stride().unwrap_or(elem_size);
            if stride < elem_size {
                return Err(fail(
                    acc,
                    LoadErrorKind::Parse,
                    format!("byteStride {stride} of buffer view {} is smaller than the element size {elem_size}", view.index()),
                ));
            }
            let region = strided_region(data, acc.offset(), count, stride, elem_size).ok_or_else(|| {
                fail(
                    acc,
                    LoadErrorKind::MissingBuffer,
                    format!(
                        "{count} elements of {elem_size} bytes (stride {stride}) from byte {} do not fit in buffer view {} ({} bytes)",
                        acc.offset(),
                        view.index(),
                        data.len()
                    ),
                )
            })?;
            (0..count)
                .map(|i| decode(region.get(i * stride..).unwrap_or(&[])))
                .collect::<Vec<T>>()
        }
        None => {
            if count > MAX_ZERO_FILLED {
                return Err(fail(
                    acc,
                    LoadErrorKind::TooLarge,
                    format!("{count} zero-filled elements"),
                ));
            }
            vec![zero; count]
        }
    };
    if let Some(sparse) = acc.sparse() {
        apply_sparse(ctx, acc, &sparse, &mut out, elem_size, &decode)?;
    }
    Ok(out)
}

/// The bytes `offset .. offset + stride*(count-1) + elem_size` of `data`, if they exist.
fn strided_region(
    data: &[u8],
    offset: usize,
    count: usize,
    stride: usize,
    elem_size: usize,
) -> Option<&[u8]> {
    if count == 0 {
        return Some(&[]);
    }
    let len = stride.checked_mul(count - 1)?.checked_add(elem_size)?;
    data.get(offset..offset.checked_add(len)?)
}

/// Overwrites the elements listed by a sparse accessor (§3.6.2.3): tightly packed indices
/// (strictly increasing per spec, not relied on) and values.
fn apply_sparse<T>(
    ctx: &Ctx<'_>,
    acc: &gltf::Accessor<'_>,
    sparse: &gltf::accessor::sparse::Sparse<'_>,
    out: &mut [T],
    elem_size: usize,
    decode: &impl Fn(&[u8]) -> T,
) -> Result<(), AccessorError> {
    let n = sparse.count();
    let indices = sparse.indices();
    let index_type = match indices.index_type() {
        gltf::accessor::sparse::IndexType::U8 => DataType::U8,
        gltf::accessor::sparse::IndexType::U16 => DataType::U16,
        gltf::accessor::sparse::IndexType::U32 => DataType::U32,
    };
    let index_size = index_type.size();
    let missing = |what: &str, e: String| {
        fail(
            acc,
            LoadErrorKind::MissingBuffer,
            format!("sparse {what}: {e}"),
        )
    };
    let index_bytes = view_bytes(ctx, &indices.view()).map_err(|e| missing("indices", e))?;
    let index_bytes = strided_region(index_bytes, indices.offset(), n, index_size, index_size)
        .ok_or_else(|| {
            missing(
                "indices",
                format!("{n} indices do not fit in their buffer view"),
            )
        })?;
    let values = sparse.values();
    let value_bytes = view_bytes(ctx, &values.view()).map_err(|e| missing("values", e))?;
    let value_bytes = strided_region(value_bytes, values.offset(), n, elem_size, elem_size)
        .ok_or_else(|| {
            missing(
                "values",
                format!("{n} values do not fit in their buffer view"),
            )
        })?;
    let len = out.len();
    for k in 0..n {
        let target =
            unsigned(index_bytes.get(k * index_size..).unwrap_or(&[]), index_type) as usize;
        let slot = out.get_mut(target).ok_or_else(|| {
            fail(
                acc,
                LoadErrorKind::IndexOutOfRange,
                format!("sparse index {target} is not below the accessor count {len}"),
            )
        })?;
        *slot = decode(value_bytes.get(k * elem_size..).unwrap_or(&[]));
    }
    Ok(())
}

/// The first `K` bytes of `bytes`, zero-padded (callers pass ranges already checked).
fn le<const K: usize>(bytes: &[u8]) -> [u8; K] {
    let mut out = [0u8; K];
    for (o, b) in out.iter_mut().zip(bytes) {
        *o = *b;
    }
    out
}

/// An unsigned integer component (anything else reads as 0; callers check the type).
fn unsigned(bytes: &[u8], ty: DataType) -> u32 {
    match ty {
        DataType::U8 => u32::from(le::<1>(bytes)[0]),
        DataType::U16 => u32::from(u16::from_le_bytes(le(bytes))),
        DataType::U32 => u32::from_le_bytes(le(bytes)),
        DataType::I8 | DataType::I16 | DataType::F32 => 0,
    }
}

/// One component as `f32`, applying the normalization table in the module docs.
pub(super) fn component(bytes: &[u8], ty: DataType, normalized: bool) -> f32 {
    match (ty, normalized) {
        (DataType::F32, _) => f32::from_le_bytes(le(bytes)),
        (DataType::I8, false) => f32::from(i8::from_le_bytes(le(bytes))),
        (DataType::I8, true) => (f32::from(i8::from_le_bytes(le(bytes))) / 127.0).max(-1.0),
        (DataType::U8, false) => f32::from(le::<1>(bytes)[0]),
        (DataType::U8, true) => f32::from(le::<1>(bytes)[0]) / 255.0,
        (DataType::I16, false) => f32::from(i16::from_le_bytes(le(bytes))),
        (DataType::I16, true) => (f32::from(i16::from_le_bytes(le(bytes))) / 32767.0).max(-1.0),
        (DataType::U16, false) => f32::from(u16::from_le_bytes(le(bytes))),
        (DataType::U16, true) => f32::from(u16::from_le_bytes(le(bytes))) / 65535.0,
        (DataType::U32, false) => u32::from_le_bytes(le(bytes)) as f32,
        (DataType::U32, true) => {
            (f64::from(u32::from_le_bytes(le(bytes))) / f64::from(u32::MAX)) as f32
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalization_table() {
        assert_eq!(component(&[255], DataType::U8, true), 1.0);
        assert_eq!(component(&[0x80], DataType::I8, true), -1.0);
        assert_eq!(component(&[0x81], DataType::I8, true), -1.0);
        assert_eq!(component(&[0xff, 0x7f], DataType::I16, true), 1.0);
        assert_eq!(component(&[0x00, 0x80], DataType::U16, false), 32768.0);
        assert_eq!(component(&1.5f32.to_le_bytes(), DataType::F32, true), 1.5);
        assert_eq!(unsigned(&[1, 2, 3, 4], DataType::U32), 0x0403_0201);
    }

    #[test]
    fn regions_are_checked() {
        let data = [0u8; 16];
        assert_eq!(strided_region(&data, 0, 4, 4, 4).map(<[u8]>::len), Some(16));
        assert!(strided_region(&data, 1, 4, 4, 4).is_none());
        assert!(strided_region(&data, 0, usize::MAX, 4, 4).is_none());
        assert!(strided_region(&data, usize::MAX, 1, 4, 4).is_none());
        assert_eq!(strided_region(&data, 99, 0, 4, 4).map(<[u8]>::len), Some(0));
    }
}
