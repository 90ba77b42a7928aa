//! The per-triangle record of the render scene ([`Triangle`]) and the geometry every
//! consumer of a triangle agrees on: its outward geometric normal ([`geometric_normal`]),
//! its coordinate magnitude, and the two distances scaled by it — the ray offset
//! ([`OFFSET_SCALE`], which the intersection layer applies) and the merge distance
//! ([`MERGE_SCALE`], within which faces of touching objects are one interface).
//!
//! Units: world space, the scene file's units (metres for glTF). Invariant: the normal
//! `normalize((p1−p0)×(p2−p0))` points out of the object (counter-clockwise winding seen
//! from outside) and is never flipped; validation drops triangles without one.

use glam::Vec3;

/// Offset distance per unit of coordinate magnitude: 2^-18 ≈ 3.8e-6, i.e. 32 ulps of f32.
/// A point computed from barycentrics errs by a few ulps of the triangle's coordinate
/// magnitude, so an offset scaled by it is scale-free (Wächter & Binder 2019, "A Fast and
/// Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6).
pub const OFFSET_SCALE: f32 = 1.0 / 262_144.0;

/// Half-length of the coincidence probe per unit of coordinate magnitude: 16 offsets
/// (2^-14 ≈ 6.1e-5). Faces closer than this along the normal are one interface; a real gap
/// that thin is below what the offset rule can resolve anyway.
pub const MERGE_SCALE: f32 = 16.0 * OFFSET_SCALE;

/// One triangle of the render scene, packed so that one fetch at a hit brings the vertex
/// positions, the material and the vertex indices (the hot path on large meshes is
/// memory-bound). Aligned to a 64-byte cache line so a fetch never straddles two lines.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct Triangle {
    /// World-space vertex positions.
    pub p: [Vec3; 3],
    /// Material index in the low 29 bits; [`Triangle::HAS_NORMALS`] and
    /// [`Triangle::HAS_UVS`] say whether to interpolate vertex attributes,
    /// [`Triangle::TOUCHES`] whether another object's face may lie on it.
    pub info: u32,
    /// Indices of its vertices in the scene's per-vertex arrays.
    pub vertices: [u32; 3],
    /// Index of the mesh it came from.
    pub mesh: u32,
}

impl Triangle {
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

    /// Whether `flag` (one of the associated constants) is set.
    #[inline]
    pub fn has(&self, flag: u32) -> bool {
        self.info & flag != 0
    }

    /// The largest coordinate magnitude of the vertices (bounds that of any point on it).
    #[inline]
    pub fn magnitude(&self) -> f32 {
        let [p0, p1, p2] = self.p;
        p0.abs().max(p1.abs()).max(p2.abs()).max_element()
    }

    /// How far rays leaving the triangle start from it ([`OFFSET_SCALE`] × magnitude).
    #[inline]
    pub fn offset(&self) -> f32 {
        self.magnitude() * OFFSET_SCALE
    }

    /// Within how far of the triangle, along its normal, another face is the same
    /// interface ([`MERGE_SCALE`] × magnitude).
    #[inline]
    pub fn merge_distance(&self) -> f32 {
        self.magnitude() * MERGE_SCALE
    }

    /// Its area.
    pub fn area(&self) -> f32 {
        0.5 * (self.p[1] - self.p[0])
            .cross(self.p[2] - self.p[0])
            .length()
    }
}

/// The unit geometric normal `normalize((p1−p0)×(p2−p0))` of a triangle, or `None` when it
/// has none (zero area, or non-finite corners). Tiny triangles whose f32 cross product
/// underflows (edges below ~1e-10 of any unit: |e|⁴ < f32::MIN_POSITIVE) are rescaled by
/// their longest edge component first, so the normal is scale-free like the offset rule.
/// Validation drops every triangle for which this is `None`, so hits never see one.
#[inline(always)]
pub fn geometric_normal([p0, p1, p2]: [Vec3; 3]) -> Option<Vec3> {
    let (e1, e2) = (p1 - p0, p2 - p0);
    let n = e1.cross(e2);
    let rcp = n.length_recip();
    if rcp.is_finite() && rcp > 0.0 {
        return Some(n * rcp);
    }
    rescaled_normal(e1, e2)
}

/// [`geometric_normal`]'s rare path: the edges rescaled (exactly, by a power of two) so
/// that their cross product does not underflow, then normalised.
#[cold]
#[inline(never)]
fn rescaled_normal(e1: Vec3, e2: Vec3) -> Option<Vec3> {
    let m = e1.abs().max(e2.abs()).max_element();
    if m.is_nan() || m <= 0.0 || m.is_infinite() {
        return None;
    }
    let s = 2f32.powi(-m.log2().floor() as i32);
    let n = (e1 * s).cross(e2 * s);
    let rcp = n.length_recip();
    (rcp.is_finite() && rcp > 0.0).then(|| n * rcp)
}
