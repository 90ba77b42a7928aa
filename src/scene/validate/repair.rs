//! Mesh clean-up, run by [`super::validate`] on every mesh of every loader after the
//! structural checks (index ranges, array lengths) have passed. Positions are world-space
//! metres; normals are world-space directions of any length.
//!
//! In order, each step counted per mesh and reported as one warning naming the file and the
//! mesh (the loader's name: `node 3 "Gem" mesh 1 "Cut" primitive 0`, `object "gem"`):
//! 1. **Non-finite positions** (NaN, ±inf): every triangle using one is dropped, and the
//!    vertex is moved onto a finite vertex of the mesh so bounds stay finite.
//! 2. **Degenerate triangles**: a repeated vertex index, zero area in exact arithmetic
//!    (the f64 cross product of f32 inputs, so collinear corners count), or a geometric
//!    normal the intersection layer cannot compute in f32
//!    ([`crate::scene::triangle::geometric_normal`]: an edge overflows): dropped. A mesh left with no triangle is removed by the caller.
//! 3. **Winding** ([`crate::scene::winding`]): made consistent per connected component and
//!    outward on closed ones; flips, open and non-orientable components are reported.
//! 4. **Shading normals**, per vertex: a non-finite or zero-length normal is replaced by the
//!    area-weighted mean of the (repaired) face normals around the vertex; one pointing
//!    against that mean (inward) is reversed. A vertex no kept triangle uses is left alone.
//!
//! Invariants on return: every triangle's corners are finite, distinct and span a
//! non-zero f32 normal; every used vertex normal is finite and non-zero (or the mesh has
//! none).

use crate::scene::desc::MeshDesc;
use crate::scene::triangle::geometric_normal;
use crate::scene::winding;
use glam::{DVec3, Vec3};
use std::path::Path;

/// What was repaired in one mesh.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub(super) struct Repairs {
    /// Vertices with a non-finite position.
    pub bad_positions: usize,
    /// Triangles dropped because they used such a vertex.
    pub non_finite_triangles: usize,
    /// Degenerate triangles dropped.
    pub degenerate: usize,
    /// What the winding pass did.
    pub winding: winding::WindingReport,
    /// Shading normals replaced (non-finite or zero length).
    pub normals_replaced: usize,
    /// Shading normals reversed (pointing inward).
    pub normals_reversed: usize,
}

/// Cleans `mesh` in place and pushes one warning per kind of repair; `name` names the mesh.
pub(super) fn repair_mesh(
    src: &Path,
    name: &str,
    mesh: &mut MeshDesc,
    warnings: &mut Vec<String>,
) -> Repairs {
    let mut r = Repairs::default();
    drop_non_finite(mesh, &mut r);
    let before = mesh.indices.len();
    let positions = &mesh.positions;
    mesh.indices.retain(|&tri| !degenerate(positions, tri));
    r.degenerate = before - mesh.indices.len();
    r.winding = winding::orient(mesh);
    repair_normals(mesh, &mut r);
    let at = format!("{}: {name}", src.display());
    if r.bad_positions > 0 {
        warnings.push(format!(
            "{at}: {} non-finite vertex position(s); {} triangle(s) using them dropped",
            r.bad_positions, r.non_finite_triangles
        ));
    }
    if r.degenerate > 0 {
        warnings.push(format!(
            "{at}: dropped {} degenerate triangle(s) (repeated vertex, zero area or collinear)",
            r.degenerate
        ));
    }
    let w = r.winding;
    if w.flipped > 0 {
        warnings.push(format!(
            "{at}: inconsistent or inside-out winding: flipped {} of {} triangle(s) \
             ({} connected component(s))",
            w.flipped,
            mesh.indices.len(),
            w.components
        ));
    }
    if w.non_orientable > 0 {
        warnings.push(format!(
            "{at}: {} non-orientable component(s) (a Möbius-like surface) kept as authored",
            w.non_orientable
        ));
    }
    if r.normals_replaced + r.normals_reversed > 0 {
        warnings.push(format!(
            "{at}: shading normals: {} non-finite or zero-length replaced by face normals, \
             {} pointing inward reversed",
            r.normals_replaced, r.normals_reversed
        ));
    }
    r
}

/// Step 1 of the module docs.
fn drop_non_finite(mesh: &mut MeshDesc, r: &mut Repairs) {
    let bad: Vec<bool> = mesh.positions.iter().map(|p| !p.is_finite()).collect();
    r.bad_positions = bad.iter().filter(|&&b| b).count();
    if r.bad_positions == 0 {
        return;
    }
    let before = mesh.indices.len();
    mesh.indices
        .retain(|tri| tri.iter().all(|&i| !bad[i as usize]));
    r.non_finite_triangles = before - mesh.indices.len();
    let fill = mesh
        .positions
        .iter()
        .copied()
        .find(|p| p.is_finite())
        .unwrap_or(Vec3::ZERO);
    for (p, _) in mesh.positions.iter_mut().zip(&bad).filter(|(_, &b)| b) {
        *p = fill;
    }
}

/// Step 2 of the module docs (indices are in range: checked before).
fn degenerate(positions: &[Vec3], [a, b, c]: [u32; 3]) -> bool {
    if a == b || b == c || a == c {
        return true;
    }
    let [p0, p1, p2] = [a, b, c].map(|i| positions[i as usize]);
    let exact = (p1.as_dvec3() - p0.as_dvec3()).cross(p2.as_dvec3() - p0.as_dvec3());
    exact == DVec3::ZERO || geometric_normal([p0, p1, p2]).is_none()
}

/// Step 4 of the module docs.
fn repair_normals(mesh: &mut MeshDesc, r: &mut Repairs) {
    if mesh.normals.is_empty() {
        return;
    }
    let mut around = vec![DVec3::ZERO; mesh.positions.len()];
    for tri in &mesh.indices {
        let [p0, p1, p2] = tri.map(|i| mesh.positions[i as usize].as_dvec3());
        let n = (p1 - p0).cross(p2 - p0); // length = 2 × area: area weighting
        for &i in tri {
            around[i as usize] += n;
        }
    }
    for (n, a) in mesh.normals.iter_mut().zip(&around) {
        let bad = !n.is_finite() || n.length_squared() == 0.0;
        if *a == DVec3::ZERO {
            // Unused vertex, or faces that cancel: nothing to compare with.
            if bad {
                *n = Vec3::ZERO; // the intersection layer falls back to ng
            }
            continue;
        }
        if bad {
            *n = a.normalize().as_vec3();
            r.normals_replaced += 1;
        } else if n.as_dvec3().dot(*a) < 0.0 {
            *n = -*n;
            r.normals_reversed += 1;
        }
    }
}
