//! The drop-in preview's set-up, between loading and rendering: what `iris render` does
//! for a file that lacks a camera, lights or a floor ([`PreviewOptions`]: `--view`,
//! `--studio`, `--ground`, `--background`).
//!
//! The steps, in the order [`crate::prepare::prepare`] (the one scene preparation every
//! command uses) runs them: load and validate the file; add the `--ground` floor
//! ([`crate::studio::ground`]) before the acceleration build; pick the file's camera or
//! frame the model ([`crate::framing`], fitting the file's own vertices, never the floor);
//! then, when the file has no light and no environment is given, light it with the studio
//! ([`crate::studio`]), placed relative to that camera. Units: the file's (metres for
//! glTF); frames: world space, +Y up.

use crate::accel::Backend;
use crate::error::{Error, Result};
use crate::framing::{frame_points, View};
use crate::output::Background;
use crate::scene::desc::{CameraDesc, EnvironmentDesc};
use crate::scene::Scene;
use std::path::Path;
use std::time::{Duration, Instant};

/// Like [`load_with_environment`], adding the `--ground` floor between validation and the
/// acceleration build; the scene's `subject_bounds` stay those of the file's geometry.
/// Returns the note saying whether a floor was added.
pub fn load_for_preview(
    path: &Path,
    accel: Backend,
    ground: crate::studio::GroundMode,
) -> Result<(Scene, Option<EnvironmentDesc>, Duration, String)> {
    let start = Instant::now();
    let mut desc = crate::load::load_scene(path)?;
    let env = desc.environment.take();
    let model = crate::studio::ground::desc_bounds(&desc);
    let (add, note) = crate::studio::ground::decide(&desc, ground);
    if add {
        crate::studio::ground::add_ground(&mut desc, model);
    }
    let mut scene = Scene::build(desc, accel)?;
    if add {
        scene.subject_bounds = model;
    }
    Ok((scene, env, start.elapsed(), note))
}

/// The vertices automatic framing fits: the file's own, without a `--ground` floor
/// ([`crate::studio::ground::GROUND_MESH`]).
fn subject_points(scene: &Scene) -> std::borrow::Cow<'_, [glam::Vec3]> {
    let ground = scene
        .meshes
        .iter()
        .position(|m| m.name == crate::studio::ground::GROUND_MESH);
    match ground {
        None => std::borrow::Cow::Borrowed(&scene.positions),
        Some(g) => std::borrow::Cow::Owned(
            scene
                .triangles
                .iter()
                .zip(&scene.triangle_mesh)
                .filter(|(_, &m)| m as usize != g)
                .flat_map(|(t, _)| t.iter().map(|&i| scene.positions[i as usize]))
                .collect(),
        ),
    }
}

/// Picks the camera by name or index, or frames the scene when the file has none.
pub fn choose_camera(
    scene: &Scene,
    choice: Option<&str>,
    aspect: f32,
) -> Result<(CameraDesc, Option<String>)> {
    choose_camera_view(scene, choice, None, aspect)
}

/// [`choose_camera`] with `--view`: a view frames the model automatically
/// ([`crate::framing`]) even when the file has cameras; it cannot be combined with
/// `--camera`.
pub fn choose_camera_view(
    scene: &Scene,
    choice: Option<&str>,
    view: Option<View>,
    aspect: f32,
) -> Result<(CameraDesc, Option<String>)> {
    if let (Some(v), Some(c)) = (view, choice) {
        return Err(Error::Usage(format!(
            "--view {} and --camera {c}: choose one (--view frames the model automatically)",
            v.name()
        )));
    }
    if let Some(v) = view {
        return Ok((
            frame_points(&subject_points(scene), v, aspect),
            Some(format!(
                "--view {}: framing the model automatically{}",
                v.name(),
                if scene.cameras.is_empty() {
                    ""
                } else {
                    " instead of the file's camera"
                }
            )),
        ));
    }
    match choice {
        Some(c) => {
            let found = scene
                .cameras
                .iter()
                .find(|cam| cam.name == c)
                .or_else(|| c.parse::<usize>().ok().and_then(|i| scene.cameras.get(i)));
            match found {
                Some(cam) => Ok((cam.clone(), None)),
                None => {
                    let names: Vec<String> = scene
                        .cameras
                        .iter()
                        .enumerate()
                        .map(|(i, c)| format!("{i} \"{}\"", c.name))
                        .collect();
                    Err(Error::Usage(format!(
                        "--camera {c}: no such camera in {} (available: {})",
                        scene.source.display(),
                        if names.is_empty() {
                            "none".into()
                        } else {
                            names.join(", ")
                        }
                    )))
                }
            }
        }
        None => match scene.cameras.first() {
            Some(cam) => Ok((cam.clone(), None)),
            None => Ok((
                frame_points(&subject_points(scene), View::default(), aspect),
                Some(
                    "no camera in the file: framing the model from the front-right, 35° above \
                     (--view front|top|side|threequarter)"
                        .into(),
                ),
            )),
        },
    }
}

/// `iris render` options for drop-in previews ([`crate::studio`], [`crate::framing`],
/// [`crate::output::background`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PreviewOptions {
    /// Studio preset used when the file has no light and no environment is given.
    pub studio: crate::studio::Studio,
    /// Whether to add a white floor under the model.
    pub ground: crate::studio::GroundMode,
    /// `--view`: frame the model automatically from this view (else the file's first
    /// camera, or the three-quarter view when it has none).
    pub view: Option<View>,
    /// `--background`: what escaped camera rays show ([`crate::output::background`]).
    pub background: Background,
}

impl PreviewOptions {
    /// The floor rule in effect: `--ground auto` adds none when `--background` is not the
    /// environment (a floor filling the frame would hide the background asked for).
    pub fn ground_mode(&self) -> crate::studio::GroundMode {
        use crate::studio::GroundMode;
        match (self.ground, self.background) {
            (GroundMode::Auto, Background::Environment) => GroundMode::Auto,
            (GroundMode::Auto, _) => GroundMode::Off,
            (g, _) => g,
        }
    }
}

/// The scene and camera `iris render FILE --size WxH` renders with otherwise default flags
/// (the one preparation, [`crate::prepare::prepare`], with default options).
pub fn default_preview_scene(
    path: &Path,
    accel: Backend,
    size: (u32, u32),
) -> Result<(Scene, CameraDesc)> {
    let p = crate::prepare::prepare(
        path,
        &crate::prepare::PrepareOptions {
            accel,
            size: Some(size),
            ..Default::default()
        },
    )?;
    Ok((p.scene, p.camera))
}
