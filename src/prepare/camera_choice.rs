//! The camera a render looks through ([`choose_camera_in`]): the file's camera (by name or
//! index, `--camera`), or the model framed automatically from a [`View`] when the file has
//! none or `--view` asks for one ([`AutoCamera`] says which and why).
//!
//! [`crate::prepare::prepare`] (the one scene preparation every command uses) runs the
//! steps on the scene description, in order: ground decision, environment, camera (the
//! file's, or framed by [`crate::framing`] on the file's own vertices, never the floor),
//! studio ([`crate::studio`]) or default lights, floor ([`crate::studio::ground`]), build.
//! Units: the file's (metres for glTF); frames: world space, +Y up.

use crate::error::{Error, Result};
use crate::framing::{frame_points, View};
use crate::scene::desc::CameraDesc;
use crate::scene::Scene;
use crate::studio::ground;
use glam::Vec3;
use std::path::Path;

/// The vertices automatic framing fits in a built scene: the file's own, without a
/// `--ground` floor ([`crate::studio::ground::GROUND_MESH`]).
fn subject_points(scene: &Scene) -> Vec<Vec3> {
    let ground = scene
        .meshes()
        .iter()
        .position(|m| m.name == ground::GROUND_MESH);
    match ground {
        None => scene.positions().to_vec(),
        Some(g) => scene
            .triangles()
            .iter()
            .filter(|t| t.mesh as usize != g)
            .flat_map(|t| t.vertices.map(|i| scene.positions()[i as usize]))
            .collect(),
    }
}

/// How Iris chose the camera when the file's was not used as it is (the render notes say
/// it, [`crate::prepare::Note`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AutoCamera {
    /// `--view`: the model framed from `view`, over the file's camera when it has one.
    View {
        /// The view asked for.
        view: View,
        /// Whether the file has a camera (that the view replaces).
        over_file_camera: bool,
    },
    /// The file has no camera: the model framed from the default view.
    NoCamera,
}

/// Picks the camera of a built scene by name or index, or frames it when the file has
/// none.
pub fn choose_camera(
    scene: &Scene,
    choice: Option<&str>,
    aspect: f32,
) -> Result<(CameraDesc, Option<AutoCamera>)> {
    choose_camera_view(scene, choice, None, aspect)
}

/// [`choose_camera`] with `--view` ([`choose_camera_in`] on a built scene, framing the
/// file's own vertices).
pub fn choose_camera_view(
    scene: &Scene,
    choice: Option<&str>,
    view: Option<View>,
    aspect: f32,
) -> Result<(CameraDesc, Option<AutoCamera>)> {
    choose_camera_in(
        scene.cameras(),
        scene.source(),
        || subject_points(scene),
        choice,
        view,
        aspect,
    )
}

/// Picks one of `cameras` (of the file `source`) by name or index, or frames the points
/// `subject()` returns (the model's own vertices; gathered only when framing) when there is
/// none. With `--view` the model is
/// framed automatically ([`crate::framing`]) even when the file has cameras; it cannot be
/// combined with `--camera`.
pub fn choose_camera_in(
    cameras: &[CameraDesc],
    source: &Path,
    subject: impl FnOnce() -> Vec<Vec3>,
    choice: Option<&str>,
    view: Option<View>,
    aspect: f32,
) -> Result<(CameraDesc, Option<AutoCamera>)> {
    if let (Some(v), Some(c)) = (view, choice) {
        return Err(Error::Usage(format!(
            "--view {} and --camera {c}: choose one (--view frames the model automatically)",
            v.name()
        )));
    }
    if let Some(v) = view {
        let note = AutoCamera::View {
            view: v,
            over_file_camera: !cameras.is_empty(),
        };
        return Ok((frame_points(&subject(), v, aspect), Some(note)));
    }
    let Some(c) = choice else {
        return Ok(match cameras.first() {
            Some(cam) => (cam.clone(), None),
            None => (
                frame_points(&subject(), View::default(), aspect),
                Some(AutoCamera::NoCamera),
            ),
        });
    };
    let found = cameras
        .iter()
        .find(|cam| cam.name == c)
        .or_else(|| c.parse::<usize>().ok().and_then(|i| cameras.get(i)));
    match found {
        Some(cam) => Ok((cam.clone(), None)),
        None => {
            let names: Vec<String> = cameras
                .iter()
                .enumerate()
                .map(|(i, c)| format!("{i} \"{}\"", c.name))
                .collect();
            Err(Error::Usage(format!(
                "--camera {c}: no such camera in {} (available: {})",
                source.display(),
                if names.is_empty() {
                    "none".into()
                } else {
                    names.join(", ")
                }
            )))
        }
    }
}
