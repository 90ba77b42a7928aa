//! The packed triangle record the intersection layer reads at a hit ([`TriangleData`]):
//! world-space vertex positions (the scene file's units) and the material index with three
//! flags in one `u32`. A module of its own, below both [`crate::scene`] and
//! [`crate::light::area`], which build and read it (it sat in `scene/mod.rs`, which made
//! `scene` ↔ `light::area` an import cycle).

use glam::Vec3;

/// What the intersection layer reads for a hit triangle, packed so that one fetch brings
/// the vertex positions and the material (the hot path on large meshes is memory-bound).
/// Aligned to a 64-byte cache line so a fetch never straddles two lines.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct TriangleData {
    /// World-space vertex positions.
    pub p: [Vec3; 3],
    /// Material index in the low 29 bits; [`TriangleData::HAS_NORMALS`] and
    /// [`TriangleData::HAS_UVS`] say whether to interpolate vertex attributes,
    /// [`TriangleData::TOUCHES`] whether another object's face may lie on it.
    pub info: u32,
}

impl TriangleData {
    /// The triangle's mesh has per-vertex shading normals.
    pub const HAS_NORMALS: u32 = 1 << 30;
    /// The triangle's mesh has texture coordinates.
    pub const HAS_UVS: u32 = 1 << 31;
    /// A face of another mesh lies on this triangle (within the merge distance) somewhere:
    /// only such hits are probed for coincident surfaces (see [`super::contact`]).
    pub const TOUCHES: u32 = 1 << 29;
    /// Mask of the material index bits.
    pub const MATERIAL_MASK: u32 = (1 << 29) - 1;

    /// The material index.
    #[inline]
    pub fn material(&self) -> u32 {
        self.info & Self::MATERIAL_MASK
    }
}
