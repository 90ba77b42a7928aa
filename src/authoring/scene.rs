//! The file the generator writes ([`super::glb`]): the scene description's own materials
//! and lights ([`MaterialDesc`], [`LightDesc`], the types the loaders fill), placed
//! geometry ([`GenMesh`]: a mesh in its node's frame and the node's translation, which the
//! world-space [`crate::scene::desc::MeshDesc`] has no place for), a look-at camera
//! ([`GenCamera`]) and the scene's `extras` (Iris's keys as written, e.g.
//! `iris_environment`).
//!
//! Same conventions as the rest of Iris: world space is metres, right-handed, +Y up;
//! meshes wind counter-clockwise seen from outside; colours are **linear** RGB; point and
//! spot intensities are in candela, directional ones in lux (KHR_lights_punctual).
//! A mesh is placed by an optional node translation (no rotation or scale), so its
//! world-space geometry is its local geometry shifted.
//!
//! [`GenScene::validate`] rejects anything that would give an invalid or lossy file
//! (non-finite numbers, out-of-range indices, degenerate cameras) with [`crate::error::Error::Usage`].

use super::invalid::bad;
use super::material::check_material;
use super::shapes::TriMesh;
use crate::error::Result;
use crate::material::MaterialDesc;
use crate::scene::desc::LightDesc;
use glam::{Vec2, Vec3};

/// A whole generated scene.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GenScene {
    /// Scene name (glTF `scenes[0].name`).
    pub name: String,
    /// Meshes, one glTF node each.
    pub meshes: Vec<GenMesh>,
    /// Materials referenced by `GenMesh::material`: glTF names, no textures, no `conductor`
    /// (a render-time override), Iris's keys in `extras` ([`super::material`]).
    pub materials: Vec<MaterialDesc>,
    /// Punctual lights; a spot's or directional light's direction need not be unit (the
    /// writer normalises it).
    pub lights: Vec<LightDesc>,
    /// The camera, if any.
    pub camera: Option<GenCamera>,
    /// Scene `extras` (glTF `scenes[0].extras`), e.g. `{"iris_environment": "sky.hdr"}`.
    pub extras: Option<serde_json::Value>,
    /// TEXCOORD_0 of `meshes[i]` (one per position; glTF's v-down convention); missing
    /// entries = none. Must not be longer than `meshes`.
    pub mesh_uvs: Vec<Option<Vec<Vec2>>>,
}

/// A mesh instance: geometry, material and placement.
#[derive(Debug, Clone, PartialEq)]
pub struct GenMesh {
    /// Name of the mesh and its node.
    pub name: String,
    /// Geometry in the node's frame.
    pub geometry: TriMesh,
    /// Index into `GenScene::materials`.
    pub material: usize,
    /// Node translation (metres), if any.
    pub translation: Option<Vec3>,
}

/// A perspective camera given by a look-at frame. It stays a look-at rather than a
/// [`crate::scene::desc::CameraDesc`]: the writer computes the node rotation from it in
/// `f64`, which the description's `f32` world matrix would round differently.
#[derive(Debug, Clone, PartialEq)]
pub struct GenCamera {
    /// Name.
    pub name: String,
    /// Eye position, metres.
    pub eye: Vec3,
    /// The point looked at.
    pub target: Vec3,
    /// Approximate up direction (not parallel to `target − eye`).
    pub up: Vec3,
    /// Vertical field of view, radians, in (0, π).
    pub yfov: f32,
    /// Width / height, if fixed.
    pub aspect: Option<f32>,
}

fn finite3(v: Vec3) -> bool {
    v.is_finite()
}

impl GenScene {
    /// Checks every value the GLB writer relies on; the error names the element. Elements
    /// are checked in file order: meshes, materials, lights, camera.
    pub fn validate(&self) -> Result<()> {
        for (i, m) in self.meshes.iter().enumerate() {
            check_mesh(i, m, self.materials.len())?;
        }
        for (i, m) in self.materials.iter().enumerate() {
            check_material(i, m)?;
        }
        for (i, l) in self.lights.iter().enumerate() {
            check_light(i, l)?;
        }
        if self.mesh_uvs.len() > self.meshes.len() {
            return Err(bad("mesh uvs", "more entries than meshes"));
        }
        for (i, uvs) in self.mesh_uvs.iter().enumerate() {
            let Some(uvs) = uvs else { continue };
            let el = format!("mesh {i} uvs");
            if uvs.len() != self.meshes[i].geometry.positions.len() {
                return Err(bad(&el, "not one per position"));
            }
            if !uvs.iter().all(|uv| uv.is_finite()) {
                return Err(bad(&el, "non-finite texture coordinate"));
            }
        }
        if let Some(c) = &self.camera {
            check_camera(c)?;
        }
        Ok(())
    }
}

/// Mesh `i`: triangles present and within u32 counts, normals matching positions, finite
/// values, indices in range, material `< materials`, finite translation.
fn check_mesh(i: usize, m: &GenMesh, materials: usize) -> Result<()> {
    let el = format!("mesh {i} \"{}\"", m.name);
    let g = &m.geometry;
    if g.positions.is_empty() || g.indices.is_empty() {
        return Err(bad(&el, "no triangles"));
    }
    if u32::try_from(g.positions.len()).is_err() || g.indices.len() > (u32::MAX / 3) as usize {
        return Err(bad(&el, "too many vertices or triangles"));
    }
    if !g.normals.is_empty() && g.normals.len() != g.positions.len() {
        return Err(bad(&el, "normals and positions differ in length"));
    }
    if !g.positions.iter().chain(&g.normals).all(|&p| finite3(p)) {
        return Err(bad(&el, "non-finite position or normal"));
    }
    let n = g.positions.len() as u64;
    if g.indices.iter().flatten().any(|&k| u64::from(k) >= n) {
        return Err(bad(&el, "vertex index out of range"));
    }
    if m.material >= materials {
        return Err(bad(&el, format!("material {} out of range", m.material)));
    }
    if m.translation.is_some_and(|t| !finite3(t)) {
        return Err(bad(&el, "non-finite translation"));
    }
    Ok(())
}

/// Light `i`: finite non-negative colour and intensity, finite position, finite non-zero
/// direction, for a spot `0 ≤ inner < outer ≤ π/2`, a finite positive range and a spectrum
/// in range.
fn check_light(i: usize, l: &LightDesc) -> Result<()> {
    let el = format!("light {i} \"{}\"", l.name());
    let (position, direction, range) = match l {
        LightDesc::Point {
            position, range, ..
        } => (Some(position), None, *range),
        LightDesc::Spot {
            position,
            direction,
            inner_cone,
            outer_cone,
            range,
            ..
        } => {
            let ok = inner_cone.is_finite()
                && outer_cone.is_finite()
                && *inner_cone >= 0.0
                && inner_cone < outer_cone
                && *outer_cone <= std::f32::consts::FRAC_PI_2;
            if !ok {
                return Err(bad(&el, "need 0 ≤ inner < outer ≤ π/2"));
            }
            (Some(position), Some(direction), *range)
        }
        LightDesc::Directional { direction, .. } => (None, Some(direction), None),
    };
    let (color, intensity) = (l.color(), l.intensity());
    if !(color.is_finite() && color.min_element() >= 0.0) {
        return Err(bad(&el, "colour must be finite and ≥ 0"));
    }
    if !(intensity.is_finite() && intensity >= 0.0) {
        return Err(bad(&el, "intensity must be finite and ≥ 0"));
    }
    if position.is_some_and(|p| !finite3(*p)) {
        return Err(bad(&el, "non-finite position"));
    }
    if direction.is_some_and(|d| !(finite3(*d) && d.length_squared() > 0.0)) {
        return Err(bad(&el, "direction must be finite and non-zero"));
    }
    if !range.is_none_or(|r| r.is_finite() && r > 0.0) {
        return Err(bad(&el, "range must be finite and > 0"));
    }
    if let Some(spectrum) = l.spectrum() {
        spectrum.check().map_err(|e| bad(&el, e))?;
    }
    Ok(())
}

/// The camera: finite look-at frame, `yfov` in (0, π), finite positive aspect.
fn check_camera(c: &GenCamera) -> Result<()> {
    let el = format!("camera \"{}\"", c.name);
    if !(finite3(c.eye) && finite3(c.target) && finite3(c.up)) {
        return Err(bad(&el, "non-finite eye, target or up"));
    }
    if !(c.yfov.is_finite() && c.yfov > 0.0 && c.yfov < std::f32::consts::PI) {
        return Err(bad(&el, "yfov must be in (0, π)"));
    }
    if !c.aspect.is_none_or(|a| a.is_finite() && a > 0.0) {
        return Err(bad(&el, "aspect must be finite and > 0"));
    }
    Ok(())
}
