//! Validation of a [`SceneDesc`]: format-agnostic checks run on every loader's output
//! (see the invariants in [`crate::scene::desc`]). Positions, directions and distances are
//! in world units (metres), angles in radians.
//!
//! Every error names `desc.source` and the element by the name the loader stored
//! (`MeshDesc::name`, `MaterialDesc::name`, light/camera names; `mesh 3` etc. when empty).
//! Harmless problems are repaired and reported in `desc.warnings`:
//! non-finite UVs become (0, 0); out-of-range unit-interval material factors are clamped;
//! a spot light with `inner ≥ outer` gets a hard edge; and each mesh is cleaned by
//! `repair` (triangles on non-finite positions and degenerate triangles dropped, winding
//! made consistent and outward per connected component, bad or inward shading normals
//! replaced or reversed), one warning per kind of repair naming the file and the mesh. A
//! mesh left without triangles is removed with a warning.
//!
//! Order: sizes ([`MAX_ELEMENTS`], before anything else allocates) → mesh structure →
//! images and materials (`material`) → lights and cameras (`light`) → mesh repair →
//! media and crystals (`closed`: closed surfaces, one weld rule; a medium no path can
//! enter is dropped with a warning) → polarizer sheets (`sheets`: the axis not along the
//! sheet's normal) → `NoTriangles` if nothing is left.

mod closed;
mod light;
mod material;
mod repair;
mod sheets;
#[cfg(test)]
mod tests;

use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::{MeshDesc, SceneDesc};
use glam::Vec2;
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
    repair_meshes(&src, &mut desc.meshes, &mut warnings);
    closed::check_media(&mut desc, &mut warnings)?;
    closed::check_crystals(&desc)?;
    sheets::check_sheets(&desc)?;
    warnings.extend(material::extension_warnings(&desc));
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

/// Checks that every crystal material of an already validated `desc` has a closed
/// surface (the rule media and `extras.iris_crystal` are held to in [`validate`]); for
/// materials made crystals after validation (`--stone`).
pub fn check_crystals_closed(desc: &SceneDesc) -> Result<(), LoadError> {
    closed::check_crystals(desc)
}

/// Whether the triangles of material `material` in `desc` form closed surfaces, by the
/// rule media and crystals are held to (welded within [`crate::scene::weld`]'s tolerance).
pub fn is_closed(desc: &SceneDesc, material: usize) -> bool {
    closed::is_closed(desc, material)
}

/// Whether one mesh's triangles form closed surfaces, by the same rule.
pub fn mesh_is_closed(mesh: &crate::scene::desc::MeshDesc) -> bool {
    closed::mesh_is_closed(mesh)
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

fn repair_meshes(src: &Path, meshes: &mut Vec<MeshDesc>, warnings: &mut Vec<String>) {
    for (i, mesh) in meshes.iter_mut().enumerate() {
        let name = element(&mesh.name, "mesh", i);
        repair::repair_mesh(src, &name, mesh, warnings);
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
    if !removed.is_empty() {
        warnings.push(format!(
            "{}: {} mesh(es) left without triangles removed: {}",
            src.display(),
            removed.len(),
            removed.join(", ")
        ));
    }
}
