//! Triangle-mesh builders for generated scenes, in the mesh's local frame (metres, +Y up).
//!
//! Invariants of every builder:
//! - triangles wind **counter-clockwise seen from outside**, so `(p1-p0)×(p2-p0)` points
//!   out of the solid (for the open plane and checkerboard: towards +Y);
//! - `normals` has one unit normal per vertex: smooth (radial) on the sphere, flat on the
//!   box and prism, whose faces each own their vertices;
//! - closed shapes (sphere, box, prism) are watertight: every edge, after welding equal
//!   positions, is shared by exactly two triangles.
//!
//! Geometry is computed in `f64` using only `+ − × ÷ √` (all correctly rounded in IEEE 754)
//! and rounded to `f32` once, so the output is bit-identical on every platform; this keeps
//! the committed assets reproducible.

use glam::{DVec3, Mat3, Vec3};
use std::collections::BTreeMap;

/// Most subdivisions [`icosphere`] performs (20·4⁷ ≈ 330 k triangles); more are clamped.
pub const MAX_SUBDIVISIONS: u32 = 7;

/// An indexed triangle mesh.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriMesh {
    /// Vertex positions, metres.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position.
    pub normals: Vec<Vec3>,
    /// Triangles, counter-clockwise seen from outside.
    pub indices: Vec<[u32; 3]>,
}

impl TriMesh {
    /// The mesh as a scene description's mesh named `name` with material `material` (no
    /// texture coordinates or tangents): for scenes built in memory instead of written.
    pub fn into_mesh_desc(self, name: &str, material: usize) -> crate::scene::desc::MeshDesc {
        crate::scene::desc::MeshDesc {
            name: name.into(),
            positions: self.positions,
            normals: self.normals,
            indices: self.indices,
            material: Some(material),
            ..Default::default()
        }
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// Appends a vertex in f64, rounding once to f32; returns its index.
    fn push(&mut self, p: DVec3, n: DVec3) -> u32 {
        self.positions.push(p.as_vec3());
        self.normals.push(n.as_vec3());
        (self.positions.len() - 1) as u32
    }

    /// Appends a planar quad with corners `c` counter-clockwise around `n` (flat normal).
    fn push_quad(&mut self, c: [DVec3; 4], n: DVec3) {
        let i = c.map(|p| self.push(p, n));
        self.indices.push([i[0], i[1], i[2]]);
        self.indices.push([i[0], i[2], i[3]]);
    }

    /// This mesh mapped by `p ↦ m·p + offset` (normals by `m`). `m` should be a rotation
    /// or an axis permutation; if its determinant is negative the winding is flipped so
    /// triangles stay counter-clockwise seen from outside.
    pub fn transformed(&self, m: Mat3, offset: Vec3) -> TriMesh {
        let flip = m.determinant() < 0.0;
        TriMesh {
            positions: self.positions.iter().map(|&p| m * p + offset).collect(),
            normals: self
                .normals
                .iter()
                .map(|&n| (m * n).normalize_or_zero())
                .collect(),
            indices: self
                .indices
                .iter()
                .map(|&[a, b, c]| if flip { [a, c, b] } else { [a, b, c] })
                .collect(),
        }
    }
}

/// Pushes the planar convex polygon `pts` (any winding) with the unit normal `n` of its
/// plane (either sign), turned to face away from the point `inside`: the polygon gets its
/// own vertices with that flat normal and is fanned from its first vertex.
pub fn push_flat_facing_away(mesh: &mut TriMesh, mut pts: Vec<DVec3>, mut n: DVec3, inside: DVec3) {
    let centre = pts.iter().sum::<DVec3>() / pts.len() as f64;
    if n.dot(centre - inside) < 0.0 {
        pts.reverse();
        n = -n;
    }
    let base = mesh.positions.len() as u32;
    for p in &pts {
        mesh.positions.push(p.as_vec3());
        mesh.normals.push(n.as_vec3());
    }
    for i in 1..pts.len() as u32 - 1 {
        mesh.indices.push([base, base + i, base + i + 1]);
    }
}

/// The regular icosahedron: 12 unit vertices (0, ±1, ±φ) and cyclic permutations,
/// φ = (1+√5)/2, and 20 faces counter-clockwise seen from outside (A. Kahler, "Creating an
/// icosphere mesh in code", 2009). Orientation is asserted by the unit tests below.
pub fn icosahedron() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let t = (1.0 + 5.0f64.sqrt()) / 2.0;
    let verts: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let faces = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    (verts, faces)
}

/// A geodesic sphere centred at the origin: a regular icosahedron whose triangles are split
/// in four `subdivisions` times, new vertices pushed onto the sphere; smooth normals.
/// 20·4ˢ triangles and 10·4ˢ + 2 vertices (s = 5: 20 480 and 10 242).
/// `subdivisions` is clamped to [`MAX_SUBDIVISIONS`].
pub fn icosphere(radius: f32, subdivisions: u32) -> TriMesh {
    let (mut verts, mut faces) = icosahedron();
    for _ in 0..subdivisions.min(MAX_SUBDIVISIONS) {
        let mut midpoints: BTreeMap<(u32, u32), u32> = BTreeMap::new();
        let mut mid = |a: u32, b: u32, verts: &mut Vec<DVec3>| -> u32 {
            let key = (a.min(b), a.max(b));
            *midpoints.entry(key).or_insert_with(|| {
                let m = (verts[a as usize] + verts[b as usize]).normalize();
                verts.push(m);
                (verts.len() - 1) as u32
            })
        };
        let mut next = Vec::with_capacity(faces.len() * 4);
        for &[a, b, c] in &faces {
            let ab = mid(a, b, &mut verts);
            let bc = mid(b, c, &mut verts);
            let ca = mid(c, a, &mut verts);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    let r = f64::from(radius);
    let mut mesh = TriMesh::default();
    for &v in &verts {
        mesh.push(v * r, v);
    }
    mesh.indices = faces;
    mesh
}

/// An axis-aligned box centred at the origin with the given half extents; flat normals.
pub fn cuboid(half: Vec3) -> TriMesh {
    let h = half.as_dvec3();
    let (x, y, z) = (DVec3::X * h.x, DVec3::Y * h.y, DVec3::Z * h.z);
    // (normal, u, v) with u × v = normal, so −u−v, +u−v, +u+v, −u+v is counter-clockwise.
    let faces = [
        (DVec3::X, y, z, x),
        (DVec3::NEG_X, z, y, -x),
        (DVec3::Y, z, x, y),
        (DVec3::NEG_Y, x, z, -y),
        (DVec3::Z, x, y, z),
        (DVec3::NEG_Z, y, x, -z),
    ];
    let mut mesh = TriMesh::default();
    for (n, u, v, c) in faces {
        mesh.push_quad([c - u - v, c + u - v, c + u + v, c - u + v], n);
    }
    mesh
}

/// A straight prism with an equilateral triangular cross-section (all angles 60°, apex at
/// +Y, base face at `y = −h/3` facing −Y, h = side·√3/2), axis along Z from −length/2 to
/// +length/2, centroid at the origin. Flat normals; 8 triangles, 18 vertices.
pub fn prism(side: f32, length: f32) -> TriMesh {
    let s = f64::from(side);
    let half_len = f64::from(length) / 2.0;
    let h = s * 3.0f64.sqrt() / 2.0;
    // Cross-section corners, counter-clockwise seen from +Z.
    let corners = [
        DVec3::new(-s / 2.0, -h / 3.0, 0.0),
        DVec3::new(s / 2.0, -h / 3.0, 0.0),
        DVec3::new(0.0, 2.0 * h / 3.0, 0.0),
    ];
    let front = DVec3::Z * half_len;
    let mut mesh = TriMesh::default();
    let f = corners.map(|c| mesh.push(c + front, DVec3::Z));
    mesh.indices.push([f[0], f[1], f[2]]);
    let b = corners.map(|c| mesh.push(c - front, DVec3::NEG_Z));
    mesh.indices.push([b[0], b[2], b[1]]);
    for k in 0..3 {
        let (a, c) = (corners[k], corners[(k + 1) % 3]);
        let d = c - a;
        let n = DVec3::new(d.y, -d.x, 0.0).normalize();
        mesh.push_quad([a + front, a - front, c - front, c + front], n);
    }
    mesh
}

/// A rectangle in the plane y = 0 facing +Y, centred at the origin, `2·half_x × 2·half_z`.
pub fn ground_plane(half_x: f32, half_z: f32) -> TriMesh {
    let (x, z) = (f64::from(half_x), f64::from(half_z));
    let mut mesh = TriMesh::default();
    push_tile(&mut mesh, -x, x, -z, z);
    mesh
}

/// Pushes the tile `[x0,x1]×[z0,z1]` in the plane y = 0, facing +Y.
fn push_tile(mesh: &mut TriMesh, x0: f64, x1: f64, z0: f64, z1: f64) {
    mesh.push_quad(
        [
            DVec3::new(x0, 0.0, z0),
            DVec3::new(x0, 0.0, z1),
            DVec3::new(x1, 0.0, z1),
            DVec3::new(x1, 0.0, z0),
        ],
        DVec3::Y,
    );
}

/// A checkerboard of `nx × nz` square tiles of side `tile` in the plane y = 0 facing +Y,
/// centred at the origin, as two meshes: `[0]` holds tiles with even `i + j` (tile (0, 0) is
/// at −X, −Z), `[1]` the odd ones. Each tile has its own four vertices.
pub fn checkerboard(nx: u32, nz: u32, tile: f32) -> [TriMesh; 2] {
    let t = f64::from(tile);
    let x_start = -f64::from(nx) * t / 2.0;
    let z_start = -f64::from(nz) * t / 2.0;
    let mut meshes = [TriMesh::default(), TriMesh::default()];
    for j in 0..nz {
        for i in 0..nx {
            let x0 = x_start + f64::from(i) * t;
            let z0 = z_start + f64::from(j) * t;
            push_tile(&mut meshes[((i + j) % 2) as usize], x0, x0 + t, z0, z0 + t);
        }
    }
    meshes
}

/// Rotation by +90° about X: `(x, y, z) ↦ (x, −z, y)`; turns a +Y-facing plane into a
/// +Z-facing wall (a backdrop facing a camera on the +Z side). Exact (entries 0, ±1).
pub fn quarter_turn_x() -> Mat3 {
    Mat3::from_cols(Vec3::X, Vec3::Z, Vec3::NEG_Y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// Edge use counts after welding equal positions.
    fn welded_edges(m: &TriMesh) -> HashMap<([u32; 3], [u32; 3]), u32> {
        let key = |i: u32| m.positions[i as usize].to_array().map(f32::to_bits);
        let mut edges = HashMap::new();
        for t in &m.indices {
            for k in 0..3 {
                let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        edges
    }

    fn check_closed_outward(m: &TriMesh) {
        assert!(welded_edges(m).values().all(|&c| c == 2), "not watertight");
        let mut volume = 0.0f64;
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
            volume += a.dot(b.cross(c)) / 6.0;
            let n = (b - a).cross(c - a);
            let centre = (a + b + c) / 3.0;
            assert!(n.dot(centre) > 0.0, "face points inwards");
            for i in t {
                assert!(
                    m.normals[*i as usize].as_dvec3().dot(n) > 0.0,
                    "normal disagrees"
                );
            }
        }
        assert!(volume > 0.0);
    }

    #[test]
    fn icosphere_counts_and_orientation() {
        for s in 0..=3 {
            let m = icosphere(0.5, s);
            assert_eq!(m.indices.len(), 20 * 4usize.pow(s));
            assert_eq!(m.positions.len(), 10 * 4usize.pow(s) + 2);
            check_closed_outward(&m);
        }
    }

    #[test]
    fn box_and_prism_are_closed_and_outward() {
        check_closed_outward(&cuboid(Vec3::new(0.5, 0.25, 1.0)));
        let p = prism(0.5, 1.0);
        assert_eq!((p.indices.len(), p.positions.len()), (8, 18));
        check_closed_outward(&p);
        // 60° between the two upper faces' inward directions: normals at 120°.
        let n1 = p.normals[12].as_dvec3();
        let n2 = p.normals[16].as_dvec3();
        assert!((n1.dot(n2) + 0.5).abs() < 1e-6, "{n1} {n2}");
    }

    #[test]
    fn planes_face_up_and_walls_face_camera() {
        let [even, odd] = checkerboard(3, 2, 0.5);
        assert_eq!((even.indices.len(), odd.indices.len()), (6, 6));
        for m in [&even, &odd, &ground_plane(1.0, 2.0)] {
            for t in &m.indices {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                assert!((b - a).cross(c - a).normalize().dot(Vec3::Y) > 0.999);
            }
        }
        let wall = ground_plane(1.0, 1.0).transformed(quarter_turn_x(), Vec3::ZERO);
        let [a, b, c] = wall.indices[0].map(|i| wall.positions[i as usize]);
        assert!((b - a).cross(c - a).normalize().dot(Vec3::Z) > 0.999);
        assert!(wall.normals.iter().all(|n| *n == Vec3::Z));
    }
}
