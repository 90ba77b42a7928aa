//! What a person chose in the live view, and the `iris render` command line it means.
//!
//! [`Controls`] hold the choices (camera and the pivot it orbits about, turn, stone, metal,
//! studio, environment, exposure, method, spectral mode); [`Controls::merge`] applies a JSON change from the page
//! (unknown keys and wrong types are refused, naming the key); [`Controls::args`] writes
//! the `iris render` arguments, which the view parses with the command line's own parser
//! ([`crate::cli::parse_render`]) so that every value is checked by the same rules and the
//! printed command reproduces the render. [`choices`] lists the values the page offers,
//! from the same tables the flags accept.
//!
//! Units: the camera's eye and target in scene units (world space), its field of view and
//! the turn in degrees; exposure in stops (or `auto`).

use crate::prepare::look_at::LookAt;
use serde_json::{json, Map, Value};

/// Frames in the view's turn: `--turn F/360`, one per degree.
pub const TURN_FRAMES: u32 = 360;

/// The view's choices; strings are the flags' own values, empty for "the default".
#[derive(Debug, Clone, PartialEq)]
pub struct Controls {
    /// The camera (always explicit: the page orbits it).
    pub camera: LookAt,
    /// The point the page orbits the camera about and zooms towards (not a render flag).
    pub pivot: glam::Vec3,
    /// The model's turn, whole degrees in [0, 360).
    pub turn: u32,
    /// `--stone NAME` for the stones (no selector: the transmissive volumes), or empty.
    pub stone: String,
    /// `--metal NAME` for every material no stone names, or empty.
    pub metal: String,
    /// `--studio`, or empty (the file's lights, or the default studio).
    pub studio: String,
    /// `--env`, or empty (the file's environment).
    pub env: String,
    /// `--exposure`: `auto` or stops.
    pub exposure: String,
    /// `--method`.
    pub method: String,
    /// `--spectral`.
    pub spectral: String,
}

impl Controls {
    /// The defaults for a scene whose camera is `camera`, orbiting about `pivot`.
    pub fn new(camera: LookAt, pivot: glam::Vec3) -> Controls {
        Controls {
            camera,
            pivot,
            turn: 0,
            stone: String::new(),
            metal: String::new(),
            studio: String::new(),
            env: String::new(),
            exposure: "auto".into(),
            method: "auto".into(),
            spectral: "auto".into(),
        }
    }

    /// Applies the keys of `change` (a JSON object with any of the fields, the camera as
    /// `{"eye": [x, y, z], "target": [x, y, z], "fov": deg}`, the pivot as `[x, y, z]`); an
    /// error names the key.
    /// Values are checked later, by the command line's parser.
    pub fn merge(&mut self, change: &Value) -> Result<(), String> {
        let Some(map) = change.as_object() else {
            return Err("expected a JSON object of controls".into());
        };
        for (key, value) in map {
            match key.as_str() {
                "camera" => self.camera = camera_of(value)?,
                "pivot" => self.pivot = point(value, "pivot")?,
                "turn" => {
                    let t = value
                        .as_f64()
                        .filter(|t| t.is_finite())
                        .ok_or("turn: expected degrees")?;
                    self.turn = t.round().rem_euclid(f64::from(TURN_FRAMES)) as u32 % TURN_FRAMES;
                }
                "stone" | "metal" | "studio" | "env" | "exposure" | "method" | "spectral" => {
                    let text = match value {
                        Value::String(s) => s.trim().to_string(),
                        Value::Number(n) => n.to_string(),
                        _ => return Err(format!("{key}: expected a string")),
                    };
                    *self.text_mut(key) = text;
                }
                other => return Err(format!("unknown control {other:?}")),
            }
        }
        Ok(())
    }

    fn text_mut(&mut self, key: &str) -> &mut String {
        match key {
            "stone" => &mut self.stone,
            "metal" => &mut self.metal,
            "studio" => &mut self.studio,
            "env" => &mut self.env,
            "exposure" => &mut self.exposure,
            "method" => &mut self.method,
            _ => &mut self.spectral,
        }
    }

    /// The `iris render` arguments after `iris render` for `scene` (as given to the view):
    /// the choices, then `extra` (size, budget, output).
    pub fn args(&self, scene: &str, extra: &[String]) -> Vec<String> {
        let mut a = vec![scene.to_string()];
        let mut flag = |name: &str, value: &str| {
            if !value.is_empty() {
                a.push(format!("--{name}"));
                a.push(value.to_string());
            }
        };
        flag("camera-look-at", &self.camera.to_string());
        if self.turn != 0 {
            flag("turn", &format!("{}/{TURN_FRAMES}", self.turn));
        }
        flag("stone", &self.stone);
        flag("metal", &self.metal);
        flag("studio", &self.studio);
        flag("env", &self.env);
        if self.exposure != "auto" {
            flag("exposure", &self.exposure);
        }
        if self.method != "auto" {
            flag("method", &self.method);
        }
        if self.spectral != "auto" {
            flag("spectral", &self.spectral);
        }
        a.extend(extra.iter().cloned());
        a
    }

    /// The choices as the page reads them.
    pub fn to_json(&self) -> Value {
        let c = self.camera;
        json!({
            "camera": {"eye": c.eye.to_array(), "target": c.target.to_array(), "fov": c.fov_deg},
            "pivot": self.pivot.to_array(),
            "turn": self.turn,
            "stone": self.stone, "metal": self.metal, "studio": self.studio, "env": self.env,
            "exposure": self.exposure, "method": self.method, "spectral": self.spectral,
        })
    }
}

/// `[x, y, z]` (finite numbers) as a point; an error names `key`.
fn point(value: &Value, key: &str) -> Result<glam::Vec3, String> {
    let v = value
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| format!("{key}: expected [x, y, z]"))?;
    let c: Vec<f32> = v
        .iter()
        .map(|x| x.as_f64().map(|x| x as f32).filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("{key}: expected finite numbers"))?;
    Ok(glam::Vec3::new(c[0], c[1], c[2]))
}

/// `{"eye": [x, y, z], "target": [x, y, z], "fov": deg}` as a checked camera.
fn camera_of(value: &Value) -> Result<LookAt, String> {
    let at = |key: &str| {
        point(
            value.get(key).unwrap_or(&Value::Null),
            &format!("camera.{key}"),
        )
    };
    let look = LookAt {
        eye: at("eye")?,
        target: at("target")?,
        fov_deg: value
            .get("fov")
            .and_then(Value::as_f64)
            .ok_or("camera.fov: expected degrees")? as f32,
    };
    look.check().map_err(|e| format!("camera: {e}"))?;
    Ok(look)
}

/// The values the page offers for each control, from the tables the flags accept.
pub fn choices() -> Value {
    use crate::integrator::Method;
    let stones: Vec<&str> = crate::authoring::stones::STONES
        .iter()
        .map(|s| s.name())
        .collect();
    let metals: Vec<&str> = crate::spectrum::metals::METALS
        .iter()
        .map(|m| m.name())
        .collect();
    let studios: Vec<&str> = [
        crate::studio::Studio::Soft,
        crate::studio::Studio::Jeweller,
        crate::studio::Studio::Bright,
        crate::studio::Studio::Tent,
        crate::studio::Studio::None,
    ]
    .iter()
    .map(|s| s.name())
    .collect();
    let views: Vec<&str> = crate::framing::VIEWS.iter().map(|v| v.name()).collect();
    let mut methods: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
    methods.rotate_right(1); // auto first
    let mut map = Map::new();
    map.insert("stone".into(), json!(stones));
    map.insert("metal".into(), json!(metals));
    map.insert("studio".into(), json!(studios));
    map.insert(
        "env".into(),
        json!(["none", "0.5", "1", "sky:elevation=60", "sky:elevation=5"]),
    );
    map.insert("view".into(), json!(views));
    map.insert("method".into(), json!(methods));
    map.insert("spectral".into(), json!(["auto", "on", "off"]));
    map.insert("turn_frames".into(), json!(TURN_FRAMES));
    Value::Object(map)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn controls() -> Controls {
        Controls::new(
            LookAt {
                eye: Vec3::new(0.0, 1.0, 3.0),
                target: Vec3::ZERO,
                fov_deg: 35.0,
            },
            Vec3::ZERO,
        )
    }

    #[test]
    fn merge_applies_known_keys_and_names_bad_ones() {
        let mut c = controls();
        c.merge(&json!({"stone": "diamond", "turn": 370, "exposure": -1.5}))
            .unwrap();
        assert_eq!(
            (c.stone.as_str(), c.turn, c.exposure.as_str()),
            ("diamond", 10, "-1.5")
        );
        let e = c.merge(&json!({"colour": "red"})).unwrap_err();
        assert!(e.contains("colour"), "{e}");
        let e = c.merge(&json!({"camera": {"eye": [0, 0], "target": [0, 0, 0], "fov": 30}}));
        assert!(e.unwrap_err().contains("camera.eye"));
        let e = c.merge(&json!({"camera": {"eye": [0, 0, 0], "target": [0, 0, 0], "fov": 30}}));
        assert!(e.unwrap_err().contains("same point"));
        c.merge(&json!({"pivot": [1, 2, 3]})).unwrap();
        assert_eq!(c.pivot, Vec3::new(1.0, 2.0, 3.0));
        let e = c.merge(&json!({"pivot": [1, "x", 3]})).unwrap_err();
        assert!(e.contains("pivot"), "{e}");
    }

    #[test]
    fn args_leave_defaults_out_and_keep_the_camera_exact() {
        let mut c = controls();
        assert_eq!(
            c.args("a.glb", &[]),
            ["a.glb", "--camera-look-at", "0,1,3:0,0,0:35"]
        );
        c.merge(&json!({"stone": "ruby", "turn": 90, "method": "path"}))
            .unwrap();
        let a = c.args("a.glb", &["--spp".into(), "4".into()]);
        assert_eq!(
            a[3..],
            ["--turn", "90/360", "--stone", "ruby", "--method", "path", "--spp", "4"]
        );
    }
}
