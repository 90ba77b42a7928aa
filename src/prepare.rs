//! One scene preparation for every command (issue 16): what `iris render`, `iris converge`,
//! `iris info` and the benches render or describe for a scene file and its flags.
//!
//! Order: load and validate the file; add the `--ground` floor before the acceleration
//! build ([`crate::preview::load_for_preview`]); set the environment (`--env`, else the
//! file's `iris_environment`); fix the image size (the flag, else the reference's, else
//! [`crate::app::default_size`]); pick the file's camera or frame the model
//! ([`crate::preview::choose_camera_view`], never fitting the floor); then, when the file
//! has no light and no `--env` is given, light it with the studio ([`crate::studio`]),
//! placed relative to that camera. Units: the file's (metres for glTF); frames: world
//! space, +Y up. Two calls with the same file and options give the same scene and camera.

use crate::accel::Backend;
use crate::app::{check_size, default_size, resolve_environment};
use crate::error::Result;
use crate::light::env::Environment;
use crate::preview::{choose_camera_view, load_for_preview, PreviewOptions};
use crate::scene::desc::CameraDesc;
use crate::scene::Scene;
use std::path::Path;
use std::time::Duration;

/// The flags that decide the scene a command sees.
#[derive(Debug, Clone, Default)]
pub struct PrepareOptions {
    /// Intersection backend.
    pub accel: Backend,
    /// `--env`: `Some(choice)` overrides the file's environment (and turns the studio off).
    pub env: Option<Option<Environment>>,
    /// `--camera` name or index.
    pub camera: Option<String>,
    /// Image size: `--size`, else a reference image's size; `None` = the default size.
    pub size: Option<(u32, u32)>,
    /// Studio, ground, view and background choices.
    pub preview: PreviewOptions,
}

/// A scene ready to render: built, lit, with its camera and image size.
pub struct Prepared {
    /// The render scene (floor, environment and studio lights included).
    pub scene: Scene,
    /// The camera: the file's, or the automatic framing.
    pub camera: CameraDesc,
    /// Image width and height in pixels (checked by [`check_size`]).
    pub size: (u32, u32),
    /// Load, validation and build time.
    pub load_time: Duration,
    /// Whether a floor was added, and why (empty when there is nothing to say).
    pub ground_note: String,
    /// How the camera was chosen, when Iris chose it.
    pub camera_note: Option<String>,
}

impl Prepared {
    /// What was decided for the user while preparing, in order: the scene's notes (default
    /// or studio lights, environment), the floor, the camera.
    pub fn notes(&self) -> Vec<String> {
        let mut notes = self.scene.notes.clone();
        if !self.ground_note.is_empty() {
            notes.push(self.ground_note.clone());
        }
        notes.extend(self.camera_note.clone());
        notes
    }
}

/// Loads `path` and prepares it as described in the module docs.
pub fn prepare(path: &Path, opts: &PrepareOptions) -> Result<Prepared> {
    let preview = &opts.preview;
    let (scene, file_env, load_time, mut ground_note) =
        load_for_preview(path, opts.accel, preview.ground_mode())?;
    if preview.ground_mode() != preview.ground {
        ground_note = "--ground auto: no floor, since it would cover the --background \
                       (--ground on to add it)"
            .into();
    }
    let mut scene = scene.with_environment(resolve_environment(opts.env.clone(), file_env)?);
    let (w, h) = opts.size.unwrap_or_else(|| default_size(&scene));
    check_size(w, h)?;
    let (camera, camera_note) = choose_camera_view(
        &scene,
        opts.camera.as_deref(),
        preview.view,
        w as f32 / h as f32,
    )?;
    if opts.env.is_none() {
        let bounds = scene.subject_bounds;
        crate::studio::apply(&mut scene, preview.studio, bounds, &camera);
    }
    Ok(Prepared {
        scene,
        camera,
        size: (w, h),
        load_time,
        ground_note,
        camera_note,
    })
}
