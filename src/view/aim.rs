//! Where the live view looks, always about the scene's subject
//! ([`crate::prepare::subject`]: the stones, else the file's own meshes; never an added floor
//! or the studio's lights):
//!
//! - [`home`]: the first camera, which **Reset** restores: the file's camera when the
//!   subject's centre is in its frame (its target moved to the subject's depth), else the
//!   subject framed from the three-quarter view; the pivot is the subject's centre.
//! - [`preset`]: the subject framed from a named view (front, top, side, three-quarter).
//! - [`pick`]: the surface point under a pixel of the live image (a double-click's pivot),
//!   by one ray through the scene.
//!
//! Each prepares the scene the view renders (the same `iris render` arguments, so the turn
//! and the looks are those on screen). Units: scene units, degrees; pixel positions as
//! fractions of the image's width and height from its top-left corner.

use super::controls::{Controls, TURN_FRAMES};
use crate::error::{Error, Result};
use crate::framing::View;
use crate::prepare::look_at::{LookAt, FOV_RANGE};
use crate::prepare::subject::{Subject, SubjectKind};
use crate::prepare::Prepared;
use crate::scene::desc::{CameraDesc, Projection};
use glam::Vec3;
use serde_json::{json, Value};

/// A camera and the point the page orbits it about.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aim {
    /// The camera.
    pub camera: LookAt,
    /// The orbit's pivot (the subject's centre, or a picked point).
    pub pivot: Vec3,
}

/// `scene` prepared by `iris render` with `extra` arguments (after the scene), with its
/// subject.
pub fn prepared(scene: &str, extra: &[String]) -> Result<Prepared> {
    let mut args = vec![scene.to_string(), "--quiet".into()];
    args.extend(extra.iter().cloned());
    let opts = crate::cli::parse_render(&args)?;
    let mut prepare = opts.prepare_options(None);
    prepare.subject = true;
    crate::prepare::prepare(&opts.scene, &prepare)
}

/// The `--turn` arguments of a turn in whole degrees (none for 0).
fn turn_args(turn: u32) -> Vec<String> {
    match turn {
        0 => Vec::new(),
        t => vec!["--turn".into(), format!("{t}/{TURN_FRAMES}")],
    }
}

fn subject_of(p: &Prepared) -> Result<&Subject> {
    p.subject
        .as_ref()
        .ok_or_else(|| Error::Usage("the scene's subject was not found".into()))
}

/// The look-at of `camera` with its target at the depth of `pivot` along its axis.
fn look_at(camera: &CameraDesc, pivot: Vec3, radius: f32) -> LookAt {
    let m = camera.world_from_camera;
    let eye = m.w_axis.truncate();
    let forward = (-m.z_axis.truncate()).normalize_or(Vec3::NEG_Z);
    let depth = (pivot - eye).dot(forward).max(0.05 * radius);
    let fov = match camera.projection {
        Projection::Perspective { yfov, .. } => yfov.to_degrees(),
        Projection::Orthographic { .. } => crate::framing::AUTO_YFOV_DEG,
    };
    LookAt {
        eye,
        target: eye + forward * depth,
        fov_deg: fov.clamp(FOV_RANGE.0, FOV_RANGE.1),
    }
}

fn aspect(p: &Prepared) -> f32 {
    p.size.0 as f32 / p.size.1 as f32
}

/// The home aim of a prepared scene (module docs).
fn home_of(p: &Prepared) -> Result<Aim> {
    let subject = subject_of(p)?;
    let pivot = subject.centre();
    let in_frame = p.camera_note.is_none()
        && crate::framing::projected_box(&[pivot], &p.camera, aspect(p))
            .is_some_and(|(lo, hi)| lo.x.max(lo.y) >= -1.0 && hi.x.min(hi.y) <= 1.0);
    let camera = if in_frame {
        p.camera.clone()
    } else {
        subject.frame(View::ThreeQuarter, aspect(p))
    };
    let aim = Aim {
        camera: look_at(&camera, pivot, subject.radius()),
        pivot,
    };
    aim.camera
        .check()
        .map_err(|e| Error::Usage(format!("{}: the camera: {e}", p.scene.source().display())))?;
    Ok(aim)
}

/// The first camera of `scene` turned by `turn` degrees (module docs), the live image's
/// size (`width` at the scene's aspect) and the subject as the page reads it.
pub fn home(scene: &str, turn: u32, width: u32) -> Result<(Aim, (u32, u32), Value)> {
    let p = prepared(scene, &turn_args(turn))?;
    let (w, h) = p.size;
    let height = ((u64::from(width) * u64::from(h) + u64::from(w) / 2) / u64::from(w)).max(16);
    let subject = subject_of(&p)?;
    let about = json!({
        "kind": match subject.kind { SubjectKind::Stones => "stones", SubjectKind::Model => "model" },
        "names": subject.names,
        "centre": subject.centre().to_array(),
        "radius": subject.radius(),
    });
    Ok((home_of(&p)?, (width, height as u32), about))
}

/// The subject framed from view `name` (module docs), the model turned by `turn` degrees.
pub fn preset(scene: &str, name: &str, turn: u32) -> std::result::Result<Aim, String> {
    let view = View::parse(name).map_err(|e| e.to_string())?;
    let p = prepared(scene, &turn_args(turn)).map_err(|e| e.to_string())?;
    let subject = subject_of(&p).map_err(|e| e.to_string())?;
    let pivot = subject.centre();
    let camera = subject.frame(view, aspect(&p));
    Ok(Aim {
        camera: look_at(&camera, pivot, subject.radius()),
        pivot,
    })
}

/// The surface point seen through `(x, y)` (fractions of the image from its top-left) by
/// `controls`' camera, or the error saying nothing is there.
pub fn pick(
    scene: &str,
    controls: &Controls,
    (x, y): (f64, f64),
) -> std::result::Result<Vec3, String> {
    if !((0.0..=1.0).contains(&x) && (0.0..=1.0).contains(&y)) {
        return Err("pick: expected [x, y], fractions of the image from 0 to 1".into());
    }
    let p = prepared(scene, &controls.args(scene, &[])[1..]).map_err(|e| e.to_string())?;
    let (w, h) = p.size;
    let camera = crate::camera::Camera::new(&p.camera, w, h);
    let px = glam::Vec2::new((x * f64::from(w)) as f32, (y * f64::from(h)) as f32);
    let ray = camera.generate_ray(px);
    p.scene
        .intersect(&ray)
        .map(|hit| hit.p)
        .filter(|p| p.is_finite())
        .ok_or_else(|| "double-click: no surface there to orbit about".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_target_sits_at_the_pivots_depth() {
        let camera = CameraDesc {
            name: "c".into(),
            projection: Projection::Perspective {
                yfov: 30f32.to_radians(),
                aspect: None,
            },
            world_from_camera: crate::camera::look_at(
                Vec3::new(0.0, 0.0, 5.0),
                Vec3::ZERO,
                Vec3::Y,
            ),
        };
        let look = look_at(&camera, Vec3::new(0.3, 0.0, 1.0), 0.1);
        assert!((look.target - Vec3::new(0.0, 0.0, 1.0)).length() < 1e-5);
        assert!((look.fov_deg - 30.0).abs() < 1e-4);
        // A pivot behind the camera keeps the target in front.
        let behind = look_at(&camera, Vec3::new(0.0, 0.0, 9.0), 1.0);
        assert!(behind.target.z < 5.0);
    }
}
