//! Small helpers the generated scenes share (`paper`, `demos`, `caustic`,
//! `spectral`, `focus_bench`, `rainbow`): a material slot and a look-at camera. They
//! live here, below every scene module, so that no scene module imports another's helpers
//! (which made `paper` ↔ `caustic` ↔ `spectral` an import cycle). Units:
//! metres; frames: world space, +Y up.

use crate::model::scene::{GenCamera, GenMaterial, GenScene};
use glam::Vec3;

/// Appends `m` to the scene's materials and returns its index.
pub(super) fn push_material(s: &mut GenScene, m: GenMaterial) -> usize {
    s.materials.push(m);
    s.materials.len() - 1
}

/// A camera named "Camera" at `eye` looking at `target`, +Y up, with a vertical field of
/// view of `yfov_degrees` and the given aspect ratio (width / height).
pub(super) fn camera(eye: Vec3, target: Vec3, yfov_degrees: f64, aspect: f32) -> GenCamera {
    GenCamera {
        name: "Camera".into(),
        eye,
        target,
        up: Vec3::Y,
        yfov: yfov_degrees.to_radians() as f32,
        aspect: Some(aspect),
    }
}
