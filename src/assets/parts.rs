//! Small helpers the generated scenes share (`paper`, `demos`, `caustic`,
//! `spectral`, `focus_bench`, `rainbow`, `material_layers`): a material slot, a mesh with
//! its own material, an emitting panel and a look-at camera. They
//! live here, below every scene module, so that no scene module imports another's helpers
//! (which made `paper` ↔ `caustic` ↔ `spectral` an import cycle). Units:
//! metres; frames: world space, +Y up.

use crate::authoring::scene::{look_at, placed};
use crate::authoring::shapes::{ground_plane, TriMesh};
use crate::material::MaterialDesc;
use crate::scene::desc::{CameraDesc, SceneDesc};
use glam::{Mat3, Vec3};

/// Appends `m` to the scene's materials and returns its index.
pub(super) fn push_material(s: &mut SceneDesc, m: MaterialDesc) -> usize {
    s.materials.push(m);
    s.materials.len() - 1
}

/// Adds a mesh `name` of `geometry` with its own material `m`, translated by `at` (`None`:
/// the geometry is in world space).
pub(super) fn add_mesh(
    s: &mut SceneDesc,
    name: &str,
    geometry: TriMesh,
    m: MaterialDesc,
    at: Option<Vec3>,
) {
    let material = push_material(s, m);
    s.meshes.push(placed(name, geometry, material, at));
}

/// Adds a white emitter `name` of radiance `radiance`, a rectangle of half extents `half`
/// (x, z before `rotation`) centred at `at`, emitting from the face that `rotation` turns +Y
/// into.
pub(super) fn add_panel(
    s: &mut SceneDesc,
    name: &str,
    radiance: f32,
    half: (f32, f32),
    rotation: Mat3,
    at: Vec3,
) {
    let geometry = ground_plane(half.0, half.1).transformed(rotation, Vec3::ZERO);
    let m = MaterialDesc::emitter(name, Vec3::splat(radiance));
    add_mesh(s, name, geometry, m, Some(at));
}

/// A camera named "Camera" at `eye` looking at `target`, +Y up, with a vertical field of
/// view of `yfov_degrees` and the given aspect ratio (width / height).
pub(super) fn camera(eye: Vec3, target: Vec3, yfov_degrees: f64, aspect: f32) -> CameraDesc {
    let yfov = yfov_degrees.to_radians() as f32;
    look_at("Camera", eye, target, Vec3::Y, yfov, Some(aspect))
}
