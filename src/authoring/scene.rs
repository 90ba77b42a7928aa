//! The generator's scenes are [`SceneDesc`]s, the description the loaders fill: this
//! module places geometry and cameras in one ([`placed`], [`look_at`]) and checks one for
//! the GLB writer ([`validate`]).
//!
//! Same conventions as the rest of Iris: world space is metres, right-handed, +Y up;
//! meshes wind counter-clockwise seen from outside; colours are **linear** RGB; point and
//! spot intensities are in candela, directional ones in lux (KHR_lights_punctual).
//!
//! What the writer writes: the scene's name, its meshes (world-space positions, normals,
//! TEXCOORD_0, a material or none), materials (glTF names, no textures, no `conductor`,
//! Iris's keys in `extras`: [`super::material`]), punctual lights, cameras, the environment
//! and the fog. What loaders and preparation add for the renderer (the source path,
//! warnings, decoded images, the resolved environment light, added lights, subject bounds)
//! is not part of a file and is ignored; mesh data a file could hold but the writer does
//! not (TEXCOORD_1, tangents, a mesh frame other than world space) is refused.
//!
//! [`validate`] rejects anything that would give an invalid or lossy file (non-finite
//! numbers, out-of-range indices, degenerate cameras) with [`crate::error::Error::Usage`],
//! naming the element.

use super::invalid::bad;
use super::material::check_material;
use super::shapes::TriMesh;
use crate::error::Result;
use crate::scene::desc::{CameraDesc, EnvironmentDesc, LightDesc, MeshDesc, Projection, SceneDesc};
use glam::{Mat3, Mat4, Vec3};

/// A mesh `name` of `geometry` with material `material`, shifted by `at` into world space
/// (`None`: the geometry is in world space already). Positions are `p + at` in `f32`,
/// which is what the loader computes for a node translated by `at`.
pub fn placed(name: &str, geometry: TriMesh, material: usize, at: Option<Vec3>) -> MeshDesc {
    let TriMesh {
        mut positions,
        normals,
        indices,
    } = geometry;
    if let Some(at) = at {
        positions.iter_mut().for_each(|p| *p += at);
    }
    MeshDesc {
        name: name.into(),
        positions,
        normals,
        indices,
        material: Some(material),
        ..MeshDesc::default()
    }
}

/// A perspective camera `name` at `eye` looking at `target`, rolled so that `up` points
/// up, with vertical field of view `yfov` (radians) and `aspect` (width / height) if fixed.
///
/// The rotation is found in `f64` and rounded once to a quaternion
/// ([`super::gltf_json::look_rotation`]); `world_from_camera` is that quaternion and `eye`
/// as the glTF loader turns a node's translation and rotation into a matrix, so a node
/// holding this matrix loads exactly as a node holding that translation and rotation
/// would (the loader then makes the axes orthonormal in `f64`). A degenerate frame (eye at
/// the target, `up` along the view, non-finite values) gives a non-finite matrix, which
/// [`validate`] refuses naming the camera.
pub fn look_at(
    name: &str,
    eye: Vec3,
    target: Vec3,
    up: Vec3,
    yfov: f32,
    aspect: Option<f32>,
) -> CameraDesc {
    let forward = target.as_dvec3() - eye.as_dvec3();
    let world_from_camera = match super::gltf_json::look_rotation(forward, up.as_dvec3()) {
        Some(rotation) if eye.is_finite() => {
            let trs = gltf::scene::Transform::Decomposed {
                translation: eye.to_array(),
                rotation,
                scale: [1.0; 3],
            };
            Mat4::from_cols_array_2d(&trs.matrix())
        }
        _ => Mat4::NAN,
    };
    CameraDesc {
        name: name.into(),
        projection: Projection::Perspective { yfov, aspect },
        world_from_camera,
    }
}

/// Checks every value the GLB writer relies on; the error names the element. Elements
/// are checked in file order: meshes, materials, lights, cameras, environment, fog.
pub fn validate(scene: &SceneDesc) -> Result<()> {
    for (i, m) in scene.meshes.iter().enumerate() {
        check_mesh(i, m, scene.materials.len())?;
    }
    for (i, m) in scene.materials.iter().enumerate() {
        check_material(i, m)?;
    }
    for (i, l) in scene.lights.iter().enumerate() {
        check_light(i, l)?;
    }
    for c in &scene.cameras {
        check_camera(c)?;
    }
    if let Some(env) = &scene.environment {
        check_environment(env)?;
    }
    if let Some(fog) = &scene.fog {
        if crate::volume::fog::spec(fog).is_none() {
            return Err(bad("fog", "no fog specification gives this medium"));
        }
    }
    Ok(())
}

/// Mesh `i`: triangles present and within u32 counts, per-vertex arrays matching
/// positions, finite values, indices in range, material `< materials`, nothing the writer
/// leaves out.
fn check_mesh(i: usize, m: &MeshDesc, materials: usize) -> Result<()> {
    let el = format!("mesh {i} \"{}\"", m.name);
    if m.positions.is_empty() || m.indices.is_empty() {
        return Err(bad(&el, "no triangles"));
    }
    if u32::try_from(m.positions.len()).is_err() || m.indices.len() > (u32::MAX / 3) as usize {
        return Err(bad(&el, "too many vertices or triangles"));
    }
    if !m.normals.is_empty() && m.normals.len() != m.positions.len() {
        return Err(bad(&el, "normals and positions differ in length"));
    }
    if !m.uvs.is_empty() && m.uvs.len() != m.positions.len() {
        return Err(bad(&el, "texture coordinates are not one per position"));
    }
    if !m.positions.iter().chain(&m.normals).all(|p| p.is_finite()) {
        return Err(bad(&el, "non-finite position or normal"));
    }
    if !m.uvs.iter().all(|uv| uv.is_finite()) {
        return Err(bad(&el, "non-finite texture coordinate"));
    }
    let n = m.positions.len() as u64;
    if m.indices.iter().flatten().any(|&k| u64::from(k) >= n) {
        return Err(bad(&el, "vertex index out of range"));
    }
    if let Some(k) = m.material.filter(|&k| k >= materials) {
        return Err(bad(&el, format!("material {k} out of range")));
    }
    if !m.uvs1.is_empty() || !m.tangents.is_empty() {
        return Err(bad(&el, "TEXCOORD_1 and tangents are not written"));
    }
    if m.orientation != Mat3::IDENTITY {
        return Err(bad(
            &el,
            "the writer places meshes in world space (orientation must be the identity)",
        ));
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
    if position.is_some_and(|p| !p.is_finite()) {
        return Err(bad(&el, "non-finite position"));
    }
    if direction.is_some_and(|d| !(d.is_finite() && d.length_squared() > 0.0)) {
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

/// A camera: a finite rigid frame (unit, orthogonal, right-handed axes to 1e-4, so the
/// loader keeps it), `yfov` in (0, π) and a finite positive aspect, or positive finite
/// orthographic half-extents.
fn check_camera(c: &CameraDesc) -> Result<()> {
    let el = format!("camera \"{}\"", c.name);
    let m = c.world_from_camera;
    if !m.is_finite() {
        return Err(bad(
            &el,
            "degenerate frame: eye at the target, up along the view, or a non-finite value",
        ));
    }
    let linear = Mat3::from_mat4(m);
    let rigid = (linear.transpose() * linear).abs_diff_eq(Mat3::IDENTITY, 1e-4)
        && (linear.determinant() - 1.0).abs() < 1e-4
        && m.row(3) == glam::Vec4::W;
    if !rigid {
        return Err(bad(
            &el,
            "world_from_camera is not a rotation and a translation",
        ));
    }
    match c.projection {
        Projection::Perspective { yfov, aspect } => {
            if !(yfov.is_finite() && yfov > 0.0 && yfov < std::f32::consts::PI) {
                return Err(bad(&el, "yfov must be in (0, π)"));
            }
            if !aspect.is_none_or(|a| a.is_finite() && a > 0.0) {
                return Err(bad(&el, "aspect must be finite and > 0"));
            }
        }
        Projection::Orthographic { xmag, ymag } => {
            if ![xmag, ymag].iter().all(|v| v.is_finite() && *v > 0.0) {
                return Err(bad(&el, "xmag and ymag must be finite and > 0"));
            }
        }
    }
    Ok(())
}

/// The environment: a finite non-negative radiance, a sky in range, or a relative UTF-8
/// path to an `.exr`/`.hdr` map (written as given, read against the file's directory).
fn check_environment(env: &EnvironmentDesc) -> Result<()> {
    let el = "environment";
    match env {
        EnvironmentDesc::Uniform(rgb) => {
            if !(rgb.is_finite() && rgb.min_element() >= 0.0) {
                return Err(bad(el, "radiance must be finite and ≥ 0"));
            }
        }
        EnvironmentDesc::Sky(p) => {
            let text = super::gltf_json::sky_text(p);
            crate::light::sky::SkyParams::parse(&text["sky:".len()..])
                .map_err(|why| bad(el, format!("{text}: {why}")))?;
        }
        EnvironmentDesc::Map(path) => {
            let ok = path.is_relative()
                && path.to_str().is_some()
                && path
                    .extension()
                    .and_then(|e| e.to_str())
                    .is_some_and(|e| matches!(e.to_ascii_lowercase().as_str(), "exr" | "hdr"));
            if !ok {
                return Err(bad(
                    el,
                    format!(
                        "{}: a map is a relative UTF-8 path to an .exr or .hdr file",
                        path.display()
                    ),
                ));
            }
        }
    }
    Ok(())
}
