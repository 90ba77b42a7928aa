//! The meshes of a description gathered into the render scene's arrays ([`Geometry`]):
//! per-vertex attributes concatenated mesh after mesh (a mesh without an attribute gets
//! zeros, so every array is as long as the positions), and one [`Triangle`] record per
//! triangle, sorted by the Morton code of the centroids so that nearby hits read nearby
//! memory. Units: world space, the file's units.

use super::desc::SceneDesc;
use super::triangle::Triangle;
use super::MeshInfo;
use glam::{Vec2, Vec3, Vec4};

/// Per-vertex attributes of every mesh, indexed by [`Triangle::vertices`].
#[derive(Debug, Clone, Default)]
pub struct Vertices {
    /// World-space positions.
    pub positions: Vec<Vec3>,
    /// Unit shading normals (zero where the mesh has none).
    pub normals: Vec<Vec3>,
    /// Texture coordinates TEXCOORD_0 (zero where the mesh has none).
    pub uvs: Vec<Vec2>,
    /// TEXCOORD_1 (a mesh without them repeats its TEXCOORD_0), or empty when no mesh has
    /// any.
    pub uvs1: Vec<Vec2>,
    /// glTF tangents (xyz, w = bitangent sign ±1; zero where the mesh has none), or empty
    /// when no mesh has any.
    pub tangents: Vec<Vec4>,
}

/// The gathered geometry.
pub(super) struct Geometry {
    pub vertices: Vertices,
    pub triangles: Vec<Triangle>,
    pub meshes: Vec<MeshInfo>,
}

/// Whether a per-vertex array belongs to a mesh of `n` vertices.
fn full<T>(attribute: &[T], n: usize) -> bool {
    !attribute.is_empty() && attribute.len() == n
}

impl Geometry {
    /// Concatenates the meshes of `desc` (a mesh without a material gets the default one,
    /// index `desc.materials.len()`), then sorts the triangles spatially.
    pub fn gather(desc: &SceneDesc) -> Geometry {
        let total_v: usize = desc.meshes.iter().map(|m| m.positions.len()).sum();
        let total_t: usize = desc.meshes.iter().map(|m| m.indices.len()).sum();
        let any_tangents = desc
            .meshes
            .iter()
            .any(|m| full(&m.tangents, m.positions.len()));
        let any_uvs1 = desc.meshes.iter().any(|m| full(&m.uvs1, m.positions.len()));
        let mut v = Vertices {
            positions: Vec::with_capacity(total_v),
            normals: Vec::with_capacity(total_v),
            uvs: Vec::with_capacity(total_v),
            uvs1: Vec::with_capacity(if any_uvs1 { total_v } else { 0 }),
            tangents: Vec::with_capacity(if any_tangents { total_v } else { 0 }),
        };
        let mut triangles = Vec::with_capacity(total_t);
        let mut meshes = Vec::with_capacity(desc.meshes.len());
        let default_material = desc.materials.len() as u32;
        for (mi, m) in desc.meshes.iter().enumerate() {
            let n = m.positions.len();
            let base = v.positions.len() as u32;
            v.positions.extend_from_slice(&m.positions);
            let has_normals = full(&m.normals, n);
            if has_normals {
                v.normals
                    .extend(m.normals.iter().map(|n| n.normalize_or_zero()));
            } else {
                v.normals.extend(std::iter::repeat_n(Vec3::ZERO, n));
            }
            let base_uv = v.uvs.len();
            if m.uvs.len() == n {
                v.uvs.extend_from_slice(&m.uvs);
            } else {
                v.uvs.extend(std::iter::repeat_n(Vec2::ZERO, n));
            }
            if any_uvs1 {
                if full(&m.uvs1, n) {
                    v.uvs1.extend_from_slice(&m.uvs1);
                } else {
                    v.uvs1.extend_from_slice(&v.uvs[base_uv..]);
                }
            }
            if any_tangents {
                if m.tangents.len() == n {
                    v.tangents.extend_from_slice(&m.tangents);
                } else {
                    v.tangents.extend(std::iter::repeat_n(Vec4::ZERO, n));
                }
            }
            meshes.push(MeshInfo {
                name: m.name.clone(),
                triangle_count: m.indices.len() as u32,
                has_normals,
            });
            let mat = m.material.map_or(default_material, |i| i as u32);
            let mut flags = 0;
            if has_normals {
                flags |= Triangle::HAS_NORMALS;
            }
            if full(&m.uvs, n) {
                flags |= Triangle::HAS_UVS;
            }
            for t in &m.indices {
                triangles.push(Triangle {
                    p: t.map(|i| m.positions[i as usize]),
                    info: (mat & Triangle::MATERIAL_MASK) | flags,
                    vertices: t.map(|i| i + base),
                    mesh: mi as u32,
                });
            }
        }
        // Spatial order: hits of neighbouring rays then touch neighbouring memory.
        let triangles = morton_order(&triangles)
            .into_iter()
            .map(|i| triangles[i])
            .collect();
        Geometry {
            vertices: v,
            triangles,
            meshes,
        }
    }

    /// The bounding box (min, max) of every vertex.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.vertices.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        )
    }
}

/// Spreads the low 10 bits of `v` to every third bit (for a 30-bit 3D Morton code).
fn spread_bits(v: u32) -> u32 {
    let mut x = v & 0x3ff;
    x = (x | (x << 16)) & 0x0300_00ff;
    x = (x | (x << 8)) & 0x0300_f00f;
    x = (x | (x << 4)) & 0x030c_30c3;
    x = (x | (x << 2)) & 0x0924_9249;
    x
}

/// Triangle indices sorted by the Morton code of their centroids (ties by index, so the
/// order is deterministic). Both backends are built over this order.
fn morton_order(tris: &[Triangle]) -> Vec<usize> {
    let (lo, hi) = tris.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), t| {
            let c = (t.p[0] + t.p[1] + t.p[2]) / 3.0;
            (lo.min(c), hi.max(c))
        },
    );
    let ext = (hi - lo).max(Vec3::splat(f32::MIN_POSITIVE));
    let mut keyed: Vec<(u32, usize)> = tris
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let c = ((t.p[0] + t.p[1] + t.p[2]) / 3.0 - lo) / ext * 1023.0;
            let q = c.clamp(Vec3::ZERO, Vec3::splat(1023.0)).as_uvec3();
            let code = spread_bits(q.x) | (spread_bits(q.y) << 1) | (spread_bits(q.z) << 2);
            (code, i)
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// The range of scene scales ([`scale`]) in which f32 geometry renders as at unit scale
/// (`tests/accel/stiff_geometry.rs` renders one diamond across it); outside it the scene is
/// rendered with a warning.
pub const SCALE_RANGE: (f32, f32) = (1e-6, 1e10);

/// A scene's scale in scene units: the larger of its bounding box's diagonal and the
/// largest coordinate magnitude of its corners (a small scene far from the origin has
/// coarse coordinates); 0 for empty or non-finite bounds.
pub fn scale((lo, hi): (Vec3, Vec3)) -> f32 {
    let diagonal = (hi - lo).length();
    let far = lo.abs().max(hi.abs()).max_element();
    if diagonal.is_finite() && far.is_finite() {
        diagonal.max(far)
    } else {
        0.0
    }
}

/// The warning for a scene whose scale lies outside [`SCALE_RANGE`], naming the file.
pub fn scale_warning(source: &std::path::Path, bounds: (Vec3, Vec3)) -> Option<String> {
    let s = scale(bounds);
    let (lo, hi) = SCALE_RANGE;
    (s > 0.0 && !(lo..=hi).contains(&s)).then(|| {
        format!(
            "{}: the scene's scale is {s:.3e} scene units, outside {lo:e}..{hi:e} where its \
             f32 geometry renders as at unit scale: the image may be wrong; scale the model \
             (a node's scale) into that range",
            source.display()
        )
    })
}
