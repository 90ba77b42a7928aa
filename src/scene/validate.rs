//! Validation of a [`SceneDesc`]: format-agnostic checks run on every loader's output
//! (see the invariants in [`crate::scene::desc`]). Positions, directions and distances are
//! in world units (metres), angles in radians.
//!
//! Every error names `desc.source` and the element by the name the loader stored
//! (`MeshDesc::name`, `MaterialDesc::name`, light/camera names; `mesh 3` etc. when empty).
//! Harmless problems are repaired and reported in `desc.warnings`:
//! non-finite or zero-length shading normals are dropped (geometric normals are used),
//! non-finite UVs become (0, 0), degenerate triangles (repeated vertex or zero area) are
//! dropped and a mesh left without triangles is removed, out-of-range unit-interval
//! material factors are clamped, and a spot light with `inner ≥ outer` gets a hard edge.
//!
//! Order: sizes ([`MAX_ELEMENTS`], before anything else allocates) → meshes → images and
//! materials (`material`) → lights and cameras (`light`) → degenerate triangles →
//! `NoTriangles` if nothing is left.

mod light;
mod material;
#[cfg(test)]
mod tests;

use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::{MeshDesc, SceneDesc};
use glam::{DVec3, Vec2};
use std::path::Path;

/// Most triangles, and most vertices, a scene may have (2^28 each).
pub const MAX_ELEMENTS: usize = 1 << 28;

/// Checks every invariant of the description, repairs what is harmless (with warnings) and
/// returns it, or the first error found.
pub fn validate(mut desc: SceneDesc) -> Result<SceneDesc, LoadError> {
    let src = desc.source.clone();
    check_sizes(&src, &desc.meshes)?;
    let mut warnings = Vec::new();
    let material_count = desc.materials.len();
    for (i, mesh) in desc.meshes.iter_mut().enumerate() {
        check_mesh(&src, i, mesh, material_count, &mut warnings)?;
    }
    material::check_images(&src, &desc.images)?;
    let image_count = desc.images.len();
    for (i, m) in desc.materials.iter_mut().enumerate() {
        material::check_material(&src, i, m, image_count, &mut warnings)?;
    }
    for (i, l) in desc.lights.iter_mut().enumerate() {
        light::check_light(&src, i, l, &mut warnings)?;
    }
    for (i, c) in desc.cameras.iter().enumerate() {
        light::check_camera(&src, i, c)?;
    }
    drop_degenerate(&mut desc.meshes, &mut warnings);
    if desc.meshes.is_empty() {
        return Err(LoadError::new(
            &src,
            "",
            LoadErrorKind::NoTriangles,
            "the scene contains no (non-degenerate) triangles",
        ));
    }
    desc.warnings.extend(warnings);
    Ok(desc)
}

/// The element name for messages: the stored name, or `{kind} {index}` when it is empty.
fn element(name: &str, kind: &str, index: usize) -> String {
    if name.is_empty() {
        format!("{kind} {index}")
    } else {
        name.to_string()
    }
}

fn fail(src: &Path, element: &str, kind: LoadErrorKind, detail: String) -> LoadError {
    LoadError::new(src, element, kind, detail)
}

fn check_sizes(src: &Path, meshes: &[MeshDesc]) -> Result<(), LoadError> {
    let (mut tris, mut verts) = (0usize, 0usize);
    for mesh in meshes {
        tris = tris.saturating_add(mesh.indices.len());
        verts = verts.saturating_add(mesh.positions.len());
    }
    check_counts(src, tris, verts)
}

fn check_counts(src: &Path, tris: usize, verts: usize) -> Result<(), LoadError> {
    for (count, what) in [(tris, "triangles"), (verts, "vertices")] {
        if count > MAX_ELEMENTS {
            return Err(fail(
                src,
                "",
                LoadErrorKind::TooLarge,
                format!("{count} {what}; at most {MAX_ELEMENTS} are supported"),
            ));
        }
    }
    Ok(())
}

fn check_mesh(
    src: &Path,
    index: usize,
    mesh: &mut MeshDesc,
    material_count: usize,
    warnings: &mut Vec<String>,
) -> Result<(), LoadError> {
    let name = element(&mesh.name, "mesh", index);
    let n = mesh.positions.len();
    for (len, what) in [
        (mesh.normals.len(), "normals"),
        (mesh.uvs.len(), "texture coordinates"),
    ] {
        if len != 0 && len != n {
            return Err(fail(
                src,
                &name,
                LoadErrorKind::Parse,
                format!("{len} {what} for {n} vertices (must be none or one per vertex)"),
            ));
        }
    }
    if let Some(m) = mesh.material.filter(|&m| m >= material_count) {
        return Err(fail(
            src,
            &name,
            LoadErrorKind::IndexOutOfRange,
            format!("material {m} does not exist ({material_count} materials)"),
        ));
    }
    for (t, tri) in mesh.indices.iter().enumerate() {
        if let Some(&bad) = tri.iter().find(|&&v| v as usize >= n) {
            return Err(fail(
                src,
                &format!("{name} triangle {t}"),
                LoadErrorKind::IndexOutOfRange,
                format!("vertex index {bad} out of range ({n} vertices)"),
            ));
        }
    }
    if let Some((v, p)) = mesh
        .positions
        .iter()
        .enumerate()
        .find(|(_, p)| !p.is_finite())
    {
        return Err(fail(
            src,
            &format!("{name} vertex {v}"),
            LoadErrorKind::NonFinite,
            format!("position {p} is not finite"),
        ));
    }
    let unusable = |v: &glam::Vec3| !v.is_finite() || v.length_squared() == 0.0;
    if mesh.normals.iter().any(unusable) {
        mesh.normals.clear();
        warnings.push(format!(
            "{name}: non-finite or zero-length shading normals; normals dropped (geometric normals used)"
        ));
    }
    let mut bad_uvs = 0usize;
    for uv in mesh.uvs.iter_mut().filter(|uv| !uv.is_finite()) {
        *uv = Vec2::ZERO;
        bad_uvs += 1;
    }
    if bad_uvs > 0 {
        warnings.push(format!(
            "{name}: {bad_uvs} non-finite texture coordinate(s) replaced by (0, 0)"
        ));
    }
    Ok(())
}

/// True when the triangle repeats a vertex or has zero area (computed in f64 so tiny but
/// valid triangles do not underflow).
fn degenerate(positions: &[glam::Vec3], [a, b, c]: [u32; 3]) -> bool {
    if a == b || b == c || a == c {
        return true;
    }
    let p = |i: u32| positions.get(i as usize).map(|v| v.as_dvec3());
    match (p(a), p(b), p(c)) {
        (Some(p0), Some(p1), Some(p2)) => (p1 - p0).cross(p2 - p0) == DVec3::ZERO,
        _ => true,
    }
}

fn drop_degenerate(meshes: &mut Vec<MeshDesc>, warnings: &mut Vec<String>) {
    let mut dropped = 0usize;
    for mesh in meshes.iter_mut() {
        let before = mesh.indices.len();
        let positions = &mesh.positions;
        mesh.indices.retain(|&tri| !degenerate(positions, tri));
        dropped += before - mesh.indices.len();
    }
    let mut removed = Vec::new();
    meshes.retain(|m| {
        if m.indices.is_empty() {
            removed.push(if m.name.is_empty() {
                "(unnamed)".to_string()
            } else {
                m.name.clone()
            });
        }
        !m.indices.is_empty()
    });
    if dropped > 0 || !removed.is_empty() {
        let mut note =
            format!("dropped {dropped} degenerate triangle(s) (repeated vertex or zero area)");
        if !removed.is_empty() {
            note.push_str(&format!(
                "; {} mesh(es) without triangles removed: {}",
                removed.len(),
                removed.join(", ")
            ));
        }
        warnings.push(note);
    }
}
