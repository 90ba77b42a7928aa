//! One scene preparation for every command: what `iris render`, `iris converge`,
//! `iris info` and the benches render or describe for a scene file and its flags.
//!
//! Order, all on the scene description ([`crate::scene::desc::SceneDesc`]): load and
//! validate the file; replace materials by `--stone` / `--metal` ([`looks`]); decide
//! whether it is authored ([`Authored`]: it brings its own light, so the defaults add
//! neither floor nor studio); decide the `--ground` floor
//! ([`crate::studio::ground::decide`]); set
//! the environment light (`--env`, else the file's `iris_environment`); fix the image size
//! (the flag, else the reference's, else [`input::default_size`]); pick the file's
//! camera or frame the model's vertices ([`crate::prepare::camera_choice::choose_camera_in`]); when the
//! file has no light (or `--studio NAME` asks) and no `--env` is given, write the studio's
//! lights into the description ([`crate::studio::light`]), placed relative to that camera, else the default
//! key and fill when nothing lights it ([`crate::scene::lighting::light_if_unlit`]); add
//! the floor; for a turntable frame (`spin`), turn the file's meshes ([`turntable`]: every
//! decision above is taken on the unturned model, so it is the same in every frame, and
//! the automatic camera frames the turn's bounding cylinder); then [`Scene::build`], once. Nothing changes the scene after the build, and
//! what was decided is kept as data ([`Note`]). Units: the file's (metres for glTF);
//! frames: world space, +Y up. Two calls with the same file and options give the same
//! scene, camera and notes.

mod authored;
pub mod camera_choice;
pub mod drop_in;
mod note;

pub use authored::Authored;
pub use note::Note;

pub mod input;
pub mod look_at;
pub mod looks;
pub mod select;
pub mod stage;
pub mod subject;
pub mod turntable;

use crate::accel::Backend;
use crate::error::Result;
use crate::light::env::Environment;
use crate::scene::desc::{CameraDesc, SceneDesc};
use crate::scene::{lighting, Scene};
use crate::studio::ground::{self, Floor, GroundMode};
use camera_choice::choose_camera_in;
use drop_in::PreviewOptions;
use input::{check_size, default_size, resolve_environment};
use std::path::Path;
use std::time::{Duration, Instant};

/// The flags that decide the scene a command sees.
#[derive(Debug, Clone, Default)]
pub struct PrepareOptions {
    /// Intersection backend.
    pub accel: Backend,
    /// `--env`: `Some(choice)` overrides the file's environment (and turns the studio off).
    pub env: Option<Option<Environment>>,
    /// `--fog`: `Some(choice)` replaces the file's `iris_fog` ([`crate::volume::fog`]).
    pub fog: Option<Option<crate::volume::Medium>>,
    /// `--camera` name or index.
    pub camera: Option<String>,
    /// `--camera-look-at`: a camera given by eye, target and field of view ([`look_at`]),
    /// replacing the file's (not with `--camera` or `--view`).
    pub look_at: Option<look_at::LookAt>,
    /// Image size: `--size`, else a reference image's size; `None` = the default size.
    pub size: Option<(u32, u32)>,
    /// Studio, ground, view and background choices.
    pub preview: PreviewOptions,
    /// `--stone` and `--metal` flags, in order ([`looks`]).
    pub looks: Vec<looks::LookFlag>,
    /// A turntable frame (`iris turntable`): the model turned about the vertical axis
    /// ([`turntable`]); `None` = as the file has it.
    pub spin: Option<turntable::Spin>,
    /// Whether to find [`Prepared::subject`] (the live view's; the closed-surface rule
    /// reads every triangle).
    pub subject: bool,
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
    /// What was decided about the scene, in order: default lights, touching volumes,
    /// studio, floor, the authored file's note, the turntable frame.
    pub notes: Vec<Note>,
    /// How the camera was chosen, when Iris chose it.
    pub camera_note: Option<Note>,
    /// What each `--stone` / `--metal` flag changed, in flag order (printed before the
    /// notes).
    pub looks: Vec<looks::Applied>,
    /// What the live view orbits and frames: the stones, else the file's meshes
    /// ([`subject`]); found when [`PrepareOptions::subject`] asks.
    pub subject: Option<subject::Subject>,
}

impl Prepared {
    /// Everything decided for the user while preparing, in order: `notes`, then the camera.
    pub fn notes(&self) -> Vec<Note> {
        self.notes
            .iter()
            .chain(&self.camera_note)
            .copied()
            .collect()
    }
}

/// Loads `path` and prepares it as described in the module docs.
pub fn prepare(path: &Path, opts: &PrepareOptions) -> Result<Prepared> {
    let start = Instant::now();
    let desc = crate::load::load_scene(path)?;
    prepare_loaded(desc, start.elapsed(), opts)
}

/// [`prepare`] for a description the caller loaded ([`crate::load::load_scene`], which
/// took `load_time`), so a scene loaded once can be prepared again with other options
/// (the Python module's `Scene`): the same scene, camera and notes as [`prepare`] of its
/// file.
pub fn prepare_loaded(
    mut desc: SceneDesc,
    load_time: Duration,
    opts: &PrepareOptions,
) -> Result<Prepared> {
    let preview = &opts.preview;
    let start = Instant::now();
    let file_meshes = desc.meshes.len();
    let stones = opts.subject.then(|| looks::stone_meshes(&desc));
    let looks = looks::apply(&mut desc, &opts.looks)?;
    let turn = opts
        .spin
        .map(|spin| turntable::Turn::new(&desc, spin))
        .transpose()?;
    let authored = Authored::of(&desc);
    let (add_floor, floor) = if preview.ground_mode() != preview.ground {
        (false, Floor::CoversBackground)
    } else if preview.ground == GroundMode::Auto && authored.is_some() {
        (false, Floor::Authored)
    } else {
        ground::decide(&desc, preview.ground)
    };
    let load_time = load_time + start.elapsed();
    desc.environment_light = resolve_environment(opts.env.clone(), desc.environment.take())?;
    if let Some(fog) = opts.fog {
        desc.fog = fog;
    }
    if let Some(Environment::Sky(sky)) = &desc.environment_light {
        desc.lights.extend(input::sun_light(sky));
    }
    let (w, h) = opts.size.unwrap_or_else(|| default_size(&desc.cameras));
    check_size(w, h)?;
    let meshes = &desc.meshes;
    let (camera, camera_note) = match opts.look_at {
        Some(look) => (given_camera(look, opts)?, None),
        None => choose_camera_in(
            &desc.cameras,
            &desc.source,
            || match &turn {
                Some(t) => t.framing_points(meshes),
                None => meshes
                    .iter()
                    .flat_map(|m| m.positions.iter().copied())
                    .collect(),
            },
            opts.camera.as_deref(),
            preview.view,
            w as f32 / h as f32,
        )?,
    };
    let studio = light(&mut desc, opts, &camera);
    let build_start = Instant::now();
    if add_floor {
        ground::add_ground(&mut desc);
    }
    if let Some(t) = &turn {
        t.apply(&mut desc);
    }
    let subject = stones.map(|s| subject::Subject::new(&desc, &s, file_meshes));
    let scene = Scene::build(desc, opts.accel)?;
    let load_time = load_time + build_start.elapsed();
    let touching = (scene.touching_triangles() > 0).then_some(Note::Touching {
        triangles: scene.touching_triangles(),
    });
    // The authored file's note, when the defaults left something out because of it.
    let (no_floor, no_studio) = (floor == Floor::Authored, preview.studio.is_none());
    let authored_note = authored
        .filter(|_| no_floor || no_studio)
        .map(|evidence| Note::Authored {
            evidence,
            no_floor,
            no_studio,
        });
    let notes = [
        scene.default_lights().then_some(Note::KeyFill),
        touching,
        studio,
        (!matches!(floor, Floor::NotTransmissive | Floor::Authored)).then_some(Note::Floor(floor)),
        authored_note,
        turn.map(|t| t.note(camera_note.is_some())),
    ];
    Ok(Prepared {
        scene,
        camera,
        size: (w, h),
        load_time,
        notes: notes.into_iter().flatten().collect(),
        camera_note: camera_note.map(Note::Camera),
        looks,
        subject,
    })
}

/// The `--camera-look-at` camera; a usage error with `--camera` or `--view`, which choose
/// the camera too.
fn given_camera(look: look_at::LookAt, opts: &PrepareOptions) -> Result<CameraDesc> {
    let other = match (&opts.camera, opts.preview.view) {
        (Some(c), _) => Some(format!("--camera {c}")),
        (None, Some(v)) => Some(format!("--view {}", v.name())),
        (None, None) => None,
    };
    match other {
        Some(flag) => Err(crate::error::Error::Usage(format!(
            "--camera-look-at {look} and {flag}: choose one camera"
        ))),
        None => Ok(look.camera()),
    }
}

/// Lights a description that brings no light: with the studio when no `--env` is given
/// (the returned note), else, or for `--studio none`, with the default key and fill. An
/// explicit `--studio NAME` (not `none`) also adds the studio to a file that is lit.
fn light(desc: &mut SceneDesc, opts: &PrepareOptions, camera: &CameraDesc) -> Option<Note> {
    let explicit = opts.preview.studio;
    let preset = explicit.unwrap_or_else(|| crate::studio::default_for(desc));
    let lit = lighting::is_lit(desc);
    let studio = (opts.env.is_none() && (explicit.is_some() || !lit))
        .then(|| crate::studio::light(desc, preset, camera))
        .flatten()
        .map(|keys| {
            if lit {
                Note::StudioAdded { preset, keys }
            } else {
                Note::Studio { preset, keys }
            }
        });
    lighting::light_if_unlit(desc);
    studio
}

/// The scene and camera `iris render FILE --size WxH` renders with otherwise default flags
/// (the one preparation, [`prepare`], with default options).
pub fn default_preview_scene(
    path: &Path,
    accel: Backend,
    size: (u32, u32),
) -> Result<(Scene, CameraDesc)> {
    let p = prepare(
        path,
        &PrepareOptions {
            accel,
            size: Some(size),
            ..Default::default()
        },
    )?;
    Ok((p.scene, p.camera))
}
