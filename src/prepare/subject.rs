//! The subject of a prepared scene ([`Subject`]): what the live view orbits, zooms towards
//! and frames. It is the stones, as `--stone NAME` without a selector picks them
//! ([`super::looks::stone_meshes`]: the transmissive volumes and crystals, else the closed
//! surfaces, else every material but the lights), taken on the file as loaded (before any
//! `--stone` or `--metal` replaces a material) and placed as rendered (after the turntable's
//! turn); a file with none of them has the file's own meshes as its subject, which is what
//! the drop-in framing frames. An added floor and the studio's lights are never part of it.
//!
//! Units: the file's (metres for glTF), world space.

use crate::framing::{frame_points, View};
use crate::scene::desc::{CameraDesc, SceneDesc};
use glam::Vec3;

/// Most vertices a [`Subject`] keeps for framing (a larger subject keeps an even stride of
/// its vertices and the extreme one along each axis).
pub const MAX_POINTS: usize = 1 << 14;

/// Which rule chose the subject's meshes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SubjectKind {
    /// The stones `--stone NAME` changes.
    Stones,
    /// No stone: every mesh of the file.
    Model,
}

/// The subject of a scene (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Subject {
    /// Its meshes, as indices into the scene's meshes (the description's and the built
    /// scene's, which are the same).
    pub meshes: Vec<usize>,
    /// Which rule chose them.
    pub kind: SubjectKind,
    /// What a person calls them: the materials' names (a mesh without a material by the
    /// mesh's name), each once, in mesh order.
    pub names: Vec<String>,
    /// Lower corner of its bounding box.
    pub lo: Vec3,
    /// Upper corner of its bounding box.
    pub hi: Vec3,
    /// Its vertices, at most [`MAX_POINTS`] of them.
    points: Vec<Vec3>,
}

impl Subject {
    /// The subject of `desc` as it is now, where `stones` are the meshes
    /// [`super::looks::stone_meshes`] chose on the file as loaded and `file_meshes` the
    /// number of meshes the file brought (those after it were added).
    pub fn new(desc: &SceneDesc, stones: &[usize], file_meshes: usize) -> Subject {
        let n = file_meshes.min(desc.meshes.len());
        let stones: Vec<usize> = stones.iter().copied().filter(|&i| i < n).collect();
        let has_points = |i: &usize| !desc.meshes[*i].positions.is_empty();
        let (kind, meshes) = if stones.iter().any(has_points) {
            (SubjectKind::Stones, stones)
        } else {
            (SubjectKind::Model, (0..n).collect())
        };
        let mut names: Vec<String> = Vec::new();
        for &i in &meshes {
            let m = &desc.meshes[i];
            let name = match m.material.and_then(|k| desc.materials.get(k)) {
                Some(material) => material.name.clone(),
                None => m.name.clone(),
            };
            if !names.contains(&name) {
                names.push(name);
            }
        }
        let all = || meshes.iter().flat_map(|&i| desc.meshes[i].positions.iter());
        let finite: Vec<Vec3> = all().copied().filter(|p| p.is_finite()).collect();
        let (lo, hi) = if finite.is_empty() {
            (Vec3::splat(-0.5), Vec3::splat(0.5))
        } else {
            finite.iter().fold(
                (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
                |(lo, hi), p| (lo.min(*p), hi.max(*p)),
            )
        };
        Subject {
            meshes,
            kind,
            names,
            lo,
            hi,
            points: thin(finite),
        }
    }

    /// The centre of its bounding box.
    pub fn centre(&self) -> Vec3 {
        0.5 * (self.lo + self.hi)
    }

    /// Half the diagonal of its bounding box (never zero).
    pub fn radius(&self) -> f32 {
        (0.5 * (self.hi - self.lo).length()).max(1e-9)
    }

    /// Whether triangle mesh `mesh` (an index into the scene's meshes) is part of it.
    pub fn holds(&self, mesh: usize) -> bool {
        self.meshes.binary_search(&mesh).is_ok()
    }

    /// The perspective camera that frames it from `view` ([`frame_points`]) for an image
    /// of width/height `aspect`.
    pub fn frame(&self, view: View, aspect: f32) -> CameraDesc {
        frame_points(&self.points, view, aspect)
    }
}

/// `points` thinned to at most [`MAX_POINTS`]: an even stride and the extreme point along
/// each axis, so the bounding box stays the same.
fn thin(points: Vec<Vec3>) -> Vec<Vec3> {
    if points.len() <= MAX_POINTS {
        return points;
    }
    let stride = points.len().div_ceil(MAX_POINTS - 6);
    let mut kept: Vec<Vec3> = points.iter().step_by(stride).copied().collect();
    for axis in 0..3 {
        let by = |a: &&Vec3, b: &&Vec3| a[axis].total_cmp(&b[axis]);
        kept.extend(points.iter().min_by(by));
        kept.extend(points.iter().max_by(by));
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::MaterialDesc;
    use crate::scene::desc::MeshDesc;

    fn mesh(name: &str, lo: Vec3, hi: Vec3, material: Option<usize>) -> MeshDesc {
        MeshDesc {
            name: name.into(),
            positions: vec![lo, hi, Vec3::new(lo.x, hi.y, lo.z)],
            indices: vec![[0, 1, 2]],
            material,
            ..Default::default()
        }
    }

    #[test]
    fn the_stones_not_the_floor_are_the_subject_and_without_stones_the_model_is() {
        let desc = SceneDesc {
            materials: vec![
                MaterialDesc {
                    name: "Gem".into(),
                    ..Default::default()
                },
                MaterialDesc {
                    name: "Floor".into(),
                    ..Default::default()
                },
            ],
            meshes: vec![
                mesh("gem", Vec3::splat(-0.01), Vec3::splat(0.01), Some(0)),
                mesh(
                    "floor",
                    Vec3::splat(-1.0),
                    Vec3::new(1.0, -0.5, 1.0),
                    Some(1),
                ),
                mesh("added", Vec3::splat(-9.0), Vec3::splat(9.0), None),
            ],
            ..Default::default()
        };
        let s = Subject::new(&desc, &[0], 2);
        assert_eq!((s.kind, s.meshes.clone()), (SubjectKind::Stones, vec![0]));
        assert_eq!(s.names, ["Gem"]);
        assert!(s.centre().length() < 1e-6 && (s.radius() - 0.01 * 3f32.sqrt()).abs() < 1e-6);
        assert!(s.holds(0) && !s.holds(1));
        let model = Subject::new(&desc, &[], 2);
        assert_eq!((model.kind, model.meshes), (SubjectKind::Model, vec![0, 1]));
        assert_eq!(model.lo, Vec3::splat(-1.0));
    }

    #[test]
    fn thinning_keeps_the_bounding_box() {
        let points: Vec<Vec3> = (0..100_000)
            .map(|i| {
                let t = i as f32;
                Vec3::new((t * 0.37).sin(), (t * 0.11).cos(), t.sqrt())
            })
            .collect();
        let bounds = |p: &[Vec3]| {
            p.iter()
                .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), q| {
                    (l.min(*q), h.max(*q))
                })
        };
        let kept = thin(points.clone());
        assert!(kept.len() <= MAX_POINTS);
        assert_eq!(bounds(&kept), bounds(&points));
    }
}
