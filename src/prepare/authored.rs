//! Whether a scene file is **authored**: it brings its own light. The one place
//! this is decided; [`super::prepare`] uses it to keep such a file's scene as it is.
//!
//! A file is authored when it has a punctual light (KHR_lights_punctual), an emitting
//! triangle (an emissive material on a mesh, by the area lights' own test,
//! [`crate::scene::lighting::has_emitter`]) or an environment it names itself (glTF scene
//! `extras.iris_environment`). What `--env` gives does not count: it is the user's, not the
//! file's. For an authored file:
//! - `--ground auto` adds no floor (a floor under a lit scene changes its light: under the
//!   peers' prism seen against an emissive slit, `tests/load/authored.rs`, it made the image
//!   3.5 % brighter (path tracer, 256 spp, 160×120) and moved `--method auto` from the path
//!   tracer to the hybrid);
//! - the default `--studio` adds no studio (the file is lit);
//! - flags that ask explicitly still apply: `--ground on`, `--studio NAME`, `--env`,
//!   `--view`.
//!
//! The file's own camera is a separate matter: framing applies only when the file has none
//! (or with `--view`), authored or not ([`crate::prepare::camera_choice::choose_camera_in`]).

use crate::scene::desc::SceneDesc;
use crate::scene::lighting;

/// The evidence that a file is authored: what light it brings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Authored {
    /// Punctual lights in the file.
    pub punctual: usize,
    /// Whether a mesh emits (an emissive material on triangles).
    pub emissive: bool,
    /// Whether the file names its own environment (`iris_environment`).
    pub environment: bool,
}

impl Authored {
    /// The evidence for `desc` as loaded (before `--env` is resolved), or `None` when the
    /// file brings no light of its own.
    pub fn of(desc: &SceneDesc) -> Option<Authored> {
        let a = Authored {
            punctual: desc.lights.len(),
            emissive: lighting::has_emitter(desc),
            environment: desc.environment.is_some(),
        };
        (a.punctual > 0 || a.emissive || a.environment).then_some(a)
    }

    /// "2 punctual lights, emissive surfaces, its own environment".
    pub fn evidence(&self) -> String {
        let mut parts = Vec::new();
        match self.punctual {
            0 => {}
            1 => parts.push("1 punctual light".to_string()),
            n => parts.push(format!("{n} punctual lights")),
        }
        if self.emissive {
            parts.push("emissive surfaces".into());
        }
        if self.environment {
            parts.push("its own environment".into());
        }
        parts.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::MaterialDesc;
    use crate::scene::desc::{EnvironmentDesc, MeshDesc};
    use glam::Vec3;

    fn quad(material: Option<usize>) -> MeshDesc {
        MeshDesc {
            name: "quad".into(),
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z],
            indices: vec![[0, 2, 1], [0, 3, 2]],
            material,
            ..Default::default()
        }
    }

    #[test]
    fn light_of_its_own_makes_a_file_authored() {
        let bare = SceneDesc {
            meshes: vec![quad(None)],
            ..Default::default()
        };
        assert_eq!(Authored::of(&bare), None);
        let lamp = SceneDesc {
            materials: vec![MaterialDesc {
                emissive: Vec3::ONE,
                ..Default::default()
            }],
            meshes: vec![quad(Some(0))],
            ..Default::default()
        };
        let a = Authored::of(&lamp).expect("an emitter");
        assert!(a.emissive && a.punctual == 0 && !a.environment);
        assert_eq!(a.evidence(), "emissive surfaces");
        // A black emissive factor emits nothing: not a light.
        let dark = SceneDesc {
            materials: vec![MaterialDesc {
                emissive: Vec3::ZERO,
                ..Default::default()
            }],
            ..lamp.clone()
        };
        assert_eq!(Authored::of(&dark), None);
        let sky = SceneDesc {
            environment: Some(EnvironmentDesc::Uniform(Vec3::splat(0.2))),
            ..bare.clone()
        };
        assert_eq!(
            Authored::of(&sky).unwrap().evidence(),
            "its own environment"
        );
    }
}
