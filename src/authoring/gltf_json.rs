//! glTF JSON for the lights, the cameras and the environment of a generated scene
//! (KHR_lights_punctual; a light's spectral shape as its `extras.iris_spectrum`), numbers
//! written by [`super::json_number`].
//!
//! Frames: lights and cameras look down their node's local −Z with +Y up (glTF 2.0 §3.10
//! "Cameras", KHR_lights_punctual "Adding Light Instances to Nodes"). A light's node
//! carries the rotation taking −Z to its direction, and [`super::scene::look_at`] a
//! camera's: computed in `f64` with `+ − × ÷ √` only and rounded once, so files are
//! bit-identical on every platform. A camera's node carries its description's
//! `world_from_camera` as its `matrix`.

use super::json_number::{num, vec3};
use crate::error::{Error, Result};
use crate::light::sky::SkyParams;
use crate::scene::desc::{CameraDesc, EnvironmentDesc, LightDesc, Projection};
use crate::spectrum::EmissionSpectrum;
use glam::{DMat3, DQuat, DVec3, Vec3};
use serde_json::{json, Map, Value};

/// Near clipping distance written for cameras (metres); Iris does not clip.
pub const ZNEAR: f32 = 0.01;

/// Far clipping distance written for orthographic cameras, which glTF requires (metres);
/// Iris does not clip.
pub const ZFAR_ORTHOGRAPHIC: f32 = 1.0e4;

/// The unit quaternion (x, y, z, w) rotating −Z to `forward` and +Y towards `up`, or
/// `None` if `forward` is zero or parallel to `up`. Columns of the rotation are
/// (right, up', −forward) with right = forward × up (right-handed).
pub(super) fn look_rotation(forward: DVec3, up: DVec3) -> Option<[f32; 4]> {
    let f = forward.try_normalize()?;
    let r = f.cross(up);
    if r.length_squared() < 1e-18 {
        return None;
    }
    let r = r.normalize();
    let u = r.cross(f);
    let q = DQuat::from_mat3(&DMat3::from_cols(r, u, -f)).normalize();
    Some([q.x as f32, q.y as f32, q.z as f32, q.w as f32])
}

/// Rotation for a light travelling along `dir`: up is +Y unless `dir` is nearly vertical.
fn light_rotation(dir: Vec3) -> Option<[f32; 4]> {
    let d = dir.as_dvec3().try_normalize()?;
    let up = if d.dot(DVec3::Y).abs() > 0.999 {
        DVec3::Z
    } else {
        DVec3::Y
    };
    look_rotation(d, up)
}

/// `extras.iris_spectrum` as the loader reads it (`load::gltf::material::iris_spectrum`).
fn spectrum_json(s: EmissionSpectrum) -> Value {
    match s {
        EmissionSpectrum::D65 => json!("D65"),
        EmissionSpectrum::Sun => json!("sun"),
        EmissionSpectrum::Blackbody { kelvin } => json!({"blackbody": num(kelvin)}),
    }
}

/// Light `index`'s KHR_lights_punctual JSON and its node.
pub(super) fn light(l: &LightDesc, index: usize) -> Result<(Value, Value)> {
    let node_ext = json!({"KHR_lights_punctual": {"light": index}});
    let name = l.name();
    let degenerate = || {
        Error::Usage(format!(
            "scene generator: light {index} \"{name}\": zero direction"
        ))
    };
    let mut light = Map::new();
    light.insert("name".into(), json!(name));
    light.insert("color".into(), vec3(l.color()));
    light.insert("intensity".into(), num(l.intensity()));
    let (kind, node, range) = match l {
        LightDesc::Point {
            position, range, ..
        } => (
            "point",
            json!({"name": name, "translation": vec3(*position), "extensions": node_ext}),
            *range,
        ),
        LightDesc::Spot {
            position,
            direction,
            inner_cone,
            outer_cone,
            range,
            ..
        } => {
            let q = light_rotation(*direction).ok_or_else(degenerate)?;
            light.insert(
                "spot".into(),
                json!({"innerConeAngle": num(*inner_cone), "outerConeAngle": num(*outer_cone)}),
            );
            (
                "spot",
                json!({"name": name, "translation": vec3(*position), "rotation": q.map(num),
                       "extensions": node_ext}),
                *range,
            )
        }
        LightDesc::Directional { direction, .. } => {
            let q = light_rotation(*direction).ok_or_else(degenerate)?;
            (
                "directional",
                json!({"name": name, "rotation": q.map(num), "extensions": node_ext}),
                None,
            )
        }
    };
    light.insert("type".into(), json!(kind));
    if let Some(r) = range {
        light.insert("range".into(), num(r));
    }
    if let Some(s) = l.spectrum() {
        light.insert("extras".into(), json!({"iris_spectrum": spectrum_json(s)}));
    }
    Ok((Value::Object(light), node))
}

/// Camera `index`'s glTF JSON and its node, which holds `world_from_camera` as its
/// `matrix` (column-major, each number the shortest decimal of its `f32`), so the loader
/// reads the description's matrix exactly.
pub(super) fn camera(c: &CameraDesc, index: usize) -> (Value, Value) {
    let mut cam = Map::new();
    cam.insert("name".into(), json!(c.name));
    match c.projection {
        Projection::Perspective { yfov, aspect } => {
            let mut persp = Map::new();
            persp.insert("yfov".into(), num(yfov));
            persp.insert("znear".into(), num(ZNEAR));
            if let Some(a) = aspect {
                persp.insert("aspectRatio".into(), num(a));
            }
            cam.insert("type".into(), json!("perspective"));
            cam.insert("perspective".into(), Value::Object(persp));
        }
        Projection::Orthographic { xmag, ymag } => {
            cam.insert("type".into(), json!("orthographic"));
            cam.insert(
                "orthographic".into(),
                json!({"xmag": num(xmag), "ymag": num(ymag), "znear": num(ZNEAR),
                       "zfar": num(ZFAR_ORTHOGRAPHIC)}),
            );
        }
    }
    let matrix: Vec<Value> = c
        .world_from_camera
        .to_cols_array()
        .into_iter()
        .map(num)
        .collect();
    (
        Value::Object(cam),
        json!({"name": c.name, "camera": index, "matrix": matrix}),
    )
}

/// The environment as `extras.iris_environment` holds it: a grey radiance as one number,
/// a coloured one as `[r, g, b]`, a sky as its `sky:` text, a map as its relative path.
pub(super) fn environment(env: &EnvironmentDesc) -> Value {
    match env {
        EnvironmentDesc::Uniform(rgb) if rgb.x == rgb.y && rgb.y == rgb.z => num(rgb.x),
        EnvironmentDesc::Uniform(rgb) => vec3(*rgb),
        EnvironmentDesc::Sky(p) => json!(sky_text(p)),
        EnvironmentDesc::Map(path) => json!(path.to_string_lossy()),
    }
}

/// A sky as `--env` and `extras.iris_environment` take it, every parameter written.
pub(super) fn sky_text(p: &SkyParams) -> String {
    format!(
        "sky:elevation={},azimuth={},turbidity={}",
        p.elevation, p.azimuth, p.turbidity
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    fn quat(q: [f32; 4]) -> Quat {
        Quat::from_array(q)
    }

    #[test]
    fn look_rotation_maps_minus_z_to_forward_and_y_to_up() {
        let forward = DVec3::new(-1.4, -0.85, -1.8);
        let q = quat(look_rotation(forward, DVec3::Y).expect("rotation"));
        let f = forward.normalize().as_vec3();
        assert!((q * Vec3::NEG_Z - f).length() < 1e-6);
        let up = q * Vec3::Y;
        assert!(up.dot(f).abs() < 1e-6 && up.y > 0.0);
        assert!(
            (q * Vec3::X).y.abs() < 1e-6,
            "no roll: right stays horizontal"
        );
        assert!(look_rotation(DVec3::ZERO, DVec3::Y).is_none());
        assert!(look_rotation(DVec3::Y, DVec3::Y).is_none());
    }

    #[test]
    fn light_rotation_handles_vertical_directions() {
        for d in [Vec3::NEG_Y, Vec3::Y, Vec3::new(0.5, -0.7, -0.4)] {
            let q = quat(light_rotation(d).expect("rotation"));
            assert!((q * Vec3::NEG_Z - d.normalize()).length() < 1e-6, "{d}");
        }
        assert!(light_rotation(Vec3::ZERO).is_none());
    }

    #[test]
    fn numbers_print_shortest() {
        assert_eq!(num(0.8).to_string(), "0.8");
        assert_eq!(
            num(1.0 / 3.0).to_string().parse::<f32>().ok(),
            Some(1.0 / 3.0)
        );
        assert_eq!(num(16.0 / 9.0).to_string(), "1.7777778");
    }
}
