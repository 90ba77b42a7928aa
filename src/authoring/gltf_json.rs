//! glTF JSON for the non-geometry parts of a [`GenScene`](super::scene::GenScene):
//! materials (with their KHR extensions; the layer extensions' JSON is
//! [`super::layers`]'s), KHR_lights_punctual lights and the camera, plus the number
//! formatting shared with [`super::glb`].
//!
//! Frames: lights and cameras look down their node's local −Z with +Y up (glTF 2.0 §3.10
//! "Cameras", KHR_lights_punctual "Adding Light Instances to Nodes"), so their nodes carry
//! the rotation taking −Z to the light/view direction. Rotations are computed in `f64` with
//! `+ − × ÷ √` only and rounded once, so files are bit-identical on every platform.
//! Numbers print as the shortest decimal that reads back as the same `f32`.

use super::scene::{GenCamera, GenLight, GenMaterial};
use crate::error::{Error, Result};
use glam::{DMat3, DQuat, DVec3, Vec3};
use serde_json::{json, Map, Value};
use std::collections::BTreeSet;

/// Near clipping distance written for the perspective camera (metres).
pub const ZNEAR: f32 = 0.01;

/// A JSON number that prints as the shortest decimal reading back as the same `f32`.
pub(super) fn num(x: f32) -> Value {
    let short: f64 = format!("{x}").parse().unwrap_or(f64::from(x));
    // Double rounding (decimal → f64 → f32) could in principle differ; fall back if so.
    let v = if short as f32 == x {
        short
    } else {
        f64::from(x)
    };
    serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number)
}

pub(super) fn vec3(v: Vec3) -> Value {
    Value::Array(v.to_array().map(num).to_vec())
}

pub(super) fn material(m: &GenMaterial, used: &mut BTreeSet<&'static str>) -> Value {
    let mut out = Map::new();
    out.insert("name".into(), json!(m.name));
    out.insert(
        "pbrMetallicRoughness".into(),
        json!({
            "baseColorFactor": m.base_color.to_array().map(num),
            "metallicFactor": num(m.metallic),
            "roughnessFactor": num(m.roughness),
        }),
    );
    let mut ext = Map::new();
    if let Some(e) = m.emissive.filter(|e| e.max_element() > 0.0) {
        // emissiveFactor is limited to [0, 1]; the strength carries the magnitude.
        let strength = e.max_element();
        out.insert("emissiveFactor".into(), vec3(e / strength));
        if strength != 1.0 {
            ext.insert(
                "KHR_materials_emissive_strength".into(),
                json!({"emissiveStrength": num(strength)}),
            );
        }
    }
    if let Some(ior) = m.ior {
        ext.insert("KHR_materials_ior".into(), json!({"ior": num(ior)}));
    }
    if let Some(t) = m.transmission {
        ext.insert(
            "KHR_materials_transmission".into(),
            json!({"transmissionFactor": num(t)}),
        );
    }
    if let Some(v) = m.volume {
        let mut vol = Map::new();
        vol.insert("thicknessFactor".into(), num(v.thickness));
        vol.insert("attenuationColor".into(), vec3(v.attenuation_color));
        if let Some(d) = v.attenuation_distance {
            vol.insert("attenuationDistance".into(), num(d));
        }
        ext.insert("KHR_materials_volume".into(), Value::Object(vol));
        if let Some(sc) = v.scatter {
            ext.insert(
                "KHR_materials_volume_scatter".into(),
                json!({
                    "multiscatterColor": vec3(sc.multiscatter),
                    "scatterAnisotropy": num(sc.anisotropy),
                }),
            );
        }
    }
    if let Some(d) = m.dispersion {
        ext.insert(
            "KHR_materials_dispersion".into(),
            json!({"dispersion": num(d)}),
        );
    }
    if let Some(i) = &m.iridescence {
        ext.insert(
            "KHR_materials_iridescence".into(),
            json!({
                "iridescenceFactor": num(i.factor),
                "iridescenceIor": num(i.ior),
                "iridescenceThicknessMinimum": num(i.thickness_min),
                "iridescenceThicknessMaximum": num(i.thickness_max),
            }),
        );
    }
    if let Some(a) = &m.anisotropy {
        ext.insert(
            "KHR_materials_anisotropy".into(),
            json!({
                "anisotropyStrength": num(a.strength),
                "anisotropyRotation": num(a.rotation),
            }),
        );
    }
    for name in [
        "KHR_materials_iridescence",
        "KHR_materials_anisotropy",
        "KHR_materials_emissive_strength",
        "KHR_materials_ior",
        "KHR_materials_transmission",
        "KHR_materials_volume",
        "KHR_materials_volume_scatter",
        "KHR_materials_dispersion",
    ] {
        if ext.contains_key(name) {
            used.insert(name);
        }
    }
    m.layers.write(&mut ext, used);
    if !ext.is_empty() {
        out.insert("extensions".into(), Value::Object(ext));
    }
    if m.double_sided {
        out.insert("doubleSided".into(), json!(true));
    }
    if let Some(x) = &m.extras {
        out.insert("extras".into(), x.clone());
    }
    Value::Object(out)
}

/// The unit quaternion (x, y, z, w) rotating −Z to `forward` and +Y towards `up`, or
/// `None` if `forward` is zero or parallel to `up`. Columns of the rotation are
/// (right, up', −forward) with right = forward × up (right-handed).
fn look_rotation(forward: DVec3, up: DVec3) -> Option<[f32; 4]> {
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

pub(super) fn light(l: &GenLight, index: usize) -> Result<(Value, Value)> {
    let node_ext = json!({"KHR_lights_punctual": {"light": index}});
    let degenerate = |name: &str| {
        Error::Usage(format!(
            "scene generator: light {index} \"{name}\": zero direction"
        ))
    };
    let (light, node) = match l {
        GenLight::Point {
            name,
            position,
            color,
            intensity,
        } => (
            json!({"name": name, "type": "point", "color": vec3(*color), "intensity": num(*intensity)}),
            json!({"name": name, "translation": vec3(*position), "extensions": node_ext}),
        ),
        GenLight::Spot {
            name,
            position,
            direction,
            color,
            intensity,
            inner_cone,
            outer_cone,
        } => {
            let q = light_rotation(*direction).ok_or_else(|| degenerate(name))?;
            (
                json!({"name": name, "type": "spot", "color": vec3(*color), "intensity": num(*intensity),
                       "spot": {"innerConeAngle": num(*inner_cone), "outerConeAngle": num(*outer_cone)}}),
                json!({"name": name, "translation": vec3(*position), "rotation": q.map(num),
                       "extensions": node_ext}),
            )
        }
        GenLight::Directional {
            name,
            direction,
            color,
            intensity,
        } => {
            let q = light_rotation(*direction).ok_or_else(|| degenerate(name))?;
            (
                json!({"name": name, "type": "directional", "color": vec3(*color), "intensity": num(*intensity)}),
                json!({"name": name, "rotation": q.map(num), "extensions": node_ext}),
            )
        }
    };
    Ok((light, node))
}

pub(super) fn camera(c: &GenCamera) -> Result<(Value, Value)> {
    let forward = c.target.as_dvec3() - c.eye.as_dvec3();
    let q = look_rotation(forward, c.up.as_dvec3()).ok_or_else(|| {
        Error::Usage(format!(
            "scene generator: camera \"{}\": eye equals target or up is parallel to the view",
            c.name
        ))
    })?;
    let mut persp = Map::new();
    persp.insert("yfov".into(), num(c.yfov));
    persp.insert("znear".into(), num(ZNEAR));
    if let Some(a) = c.aspect {
        persp.insert("aspectRatio".into(), num(a));
    }
    Ok((
        json!({"name": c.name, "type": "perspective", "perspective": persp}),
        json!({"name": c.name, "camera": 0, "translation": vec3(c.eye), "rotation": q.map(num)}),
    ))
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
