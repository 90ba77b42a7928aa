//! Turntables: frame `F` of `N` turns the model by θ = 360°·F/N about the
//! vertical axis, under fixed lights and a fixed camera, as one step of the one preparation
//! ([`super::prepare`], `PrepareOptions::spin`).
//!
//! **Why the model turns and the camera does not.** Gem videos are shot on a rotating stage
//! inside a fixed light box: the fire and scintillation a viewer sees come from the facets
//! moving against fixed lights. Orbiting the camera would carry the studio round with it
//! (its lights are placed relative to the camera, [`crate::studio`]) and swing the floor
//! and the background through the frame.
//!
//! **What turns.** Every mesh of the file that does not emit light (by the area lights' own
//! test, [`crate::scene::lighting::mesh_emits`]): an emissive mesh is a light, and lights
//! stay. Nothing else moves: the file's punctual lights and cameras, the environment, the
//! `--ground` floor and the studio.
//!
//! **Axis and sense.** +Y (glTF up) through the centre of the turning meshes' bounding box
//! (its x and z; heights are not touched, so the floor keeps touching the model's lowest
//! point). The rotation is right-handed about +Y (counter-clockwise seen from above):
//! `x' = cx + (x − cx) cos θ + (z − cz) sin θ`, `z' = cz − (x − cx) sin θ + (z − cz) cos θ`,
//! computed in f64 and rounded to f32 once; shading normals turn by the same rotation
//! (det = +1, so the winding stays outward).
//!
//! **Exactness.** A frame at a multiple of 360° (F ≡ 0 mod N) changes nothing, bit for bit:
//! frame 0 is the still `iris render` gives. Quarter turns use the exact cos and sin (0,
//! ±1); other angles [`crate::authoring::lathe::sin_cos`] (`+ − × ÷` only: the same bits on
//! every platform).
//!
//! **What is decided on the unturned model**, so it is the same in every frame: the floor
//! decision and the floor (centred under the bounding-box centre, sized by its bounding
//! sphere, which contains the model at every angle: turning about an axis through the
//! centre keeps every distance to it), the studio (placed round the same centre and sphere,
//! relative to the camera), and the automatic camera. A file without a camera (or with
//! `--view`) is framed on the **bounding cylinder** of the turn, not on the vertices, so
//! the framing does not jump between frames and no frame leaves the picture: two rings of
//! [`RING`] points round the axis at the model's lowest and highest points, on the
//! circumscribed polygon of the circle of radius r = the largest distance of a turning
//! vertex from the axis (so every vertex at every angle lies inside), plus the vertices
//! of the meshes that stay. That shot is wider than the still's (which fits the vertices
//! as they are), so only a file's own camera makes frame 0 equal to the still.
//!
//! Units: the file's (metres for glTF); angles in degrees in messages, radians inside.

use super::Note;
use crate::authoring::lathe::sin_cos;
use crate::error::{Error, Result};
use crate::scene::desc::{MeshDesc, SceneDesc};
use crate::scene::lighting::mesh_emits;
use glam::Vec3;

/// Points per ring of the bounding cylinder the automatic camera frames.
pub const RING: u32 = 64;

/// Largest frame count of a turntable (frame files are numbered with 4 digits).
pub const MAX_FRAMES: u32 = 10_000;

/// Frame `frame` of a turntable of `frames` frames: the model turned by 360°·frame/frames.
/// Frames are numbered from 0; a frame at or past `frames` is the same turn as
/// `frame mod frames` (the CLI accepts only 0 to frames − 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Spin {
    frame: u32,
    frames: u32,
}

impl Spin {
    /// The spin of frame `frame` of `frames`; `frames` must be 1 to [`MAX_FRAMES`].
    pub fn new(frame: u32, frames: u32) -> Result<Spin> {
        if frames == 0 || frames > MAX_FRAMES {
            return Err(Error::Usage(format!(
                "--frames {frames}: a turntable has 1 to {MAX_FRAMES} frames"
            )));
        }
        Ok(Spin { frame, frames })
    }

    /// The frame number.
    pub fn frame(self) -> u32 {
        self.frame
    }

    /// The number of frames in the whole turn.
    pub fn frames(self) -> u32 {
        self.frames
    }

    /// The turn in degrees, in [0, 360).
    pub fn degrees(self) -> f64 {
        360.0 * f64::from(self.frame % self.frames) / f64::from(self.frames)
    }

    /// (sin θ, cos θ): exact at quarter turns (θ = 0 included), else [`sin_cos`].
    fn sin_cos(self) -> (f64, f64) {
        let (f, n) = (u64::from(self.frame % self.frames), u64::from(self.frames));
        if (4 * f) % n == 0 {
            return [(0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0)][(4 * f / n) as usize];
        }
        sin_cos(std::f64::consts::TAU * f as f64 / n as f64)
    }
}

/// A turntable frame's turn of one scene description: which meshes turn, about which axis,
/// and the cylinder they sweep.
#[derive(Debug, Clone)]
pub(super) struct Turn {
    spin: Spin,
    /// Per file mesh (the description's meshes before the floor is added): whether it turns.
    turning: Vec<bool>,
    /// The axis: (x, z) of the turning meshes' bounding-box centre.
    axis: (f64, f64),
    /// Largest distance of a turning vertex from the axis.
    radius: f64,
    /// Lowest and highest turning vertex.
    heights: (f32, f32),
}

impl Turn {
    /// The turn of `desc` (as loaded, looks applied, before anything is added) for `spin`.
    /// Errors when no mesh would turn (every mesh emits light).
    pub(super) fn new(desc: &SceneDesc, spin: Spin) -> Result<Turn> {
        let turning: Vec<bool> = desc.meshes.iter().map(|m| !mesh_emits(desc, m)).collect();
        let points = || {
            desc.meshes
                .iter()
                .zip(&turning)
                .filter(|(_, &t)| t)
                .flat_map(|(m, _)| m.positions.iter().copied())
        };
        let (lo, hi) = points().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p), hi.max(p)),
        );
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(Error::Usage(format!(
                "{}: nothing to turn: a turntable turns the file's meshes that do not emit \
                 light, and this file has none",
                desc.source.display()
            )));
        }
        let axis = (
            0.5 * (f64::from(lo.x) + f64::from(hi.x)),
            0.5 * (f64::from(lo.z) + f64::from(hi.z)),
        );
        let radius = points()
            .map(|p| (f64::from(p.x) - axis.0).hypot(f64::from(p.z) - axis.1))
            .fold(0.0, f64::max);
        Ok(Turn {
            spin,
            turning,
            axis,
            radius,
            heights: (lo.y, hi.y),
        })
    }

    /// The points the automatic camera frames in every frame: the bounding cylinder's two
    /// rings (see the module docs) and the vertices of the file's meshes that stay.
    pub(super) fn framing_points(&self, meshes: &[MeshDesc]) -> Vec<Vec3> {
        let half = std::f64::consts::PI / f64::from(RING);
        // The circumscribed polygon: its edges' midpoints lie on the circle.
        let r = self.radius / sin_cos(half).1;
        let ring = (0..RING).flat_map(|k| {
            let (s, c) = sin_cos(2.0 * half * f64::from(k));
            let (x, z) = ((self.axis.0 + r * c) as f32, (self.axis.1 + r * s) as f32);
            [
                Vec3::new(x, self.heights.0, z),
                Vec3::new(x, self.heights.1, z),
            ]
        });
        let fixed = meshes
            .iter()
            .zip(&self.turning)
            .filter(|(_, &t)| !t)
            .flat_map(|(m, _)| m.positions.iter().copied());
        ring.chain(fixed).collect()
    }

    /// Turns the file's meshes of `desc` (the first ones, before any added floor) and
    /// updates `subject_bounds` when a floor was added. Frame 0 (and every multiple of
    /// 360°) leaves `desc` untouched.
    pub(super) fn apply(&self, desc: &mut SceneDesc) {
        if self.spin.frame.is_multiple_of(self.spin.frames) {
            return;
        }
        let (s, c) = self.spin.sin_cos();
        let (cx, cz) = self.axis;
        let turn = |x: f64, z: f64| (x * c + z * s, -x * s + z * c);
        let n = self.turning.len();
        for (m, _) in desc.meshes[..n]
            .iter_mut()
            .zip(&self.turning)
            .filter(|(_, &t)| t)
        {
            for p in &mut m.positions {
                let (x, z) = turn(f64::from(p.x) - cx, f64::from(p.z) - cz);
                *p = Vec3::new((cx + x) as f32, p.y, (cz + z) as f32);
            }
            for v in &mut m.normals {
                let (x, z) = turn(f64::from(v.x), f64::from(v.z));
                *v = Vec3::new(x as f32, v.y, z as f32);
            }
            let (s, c) = (s as f32, c as f32);
            let rotation =
                glam::Mat3::from_cols(Vec3::new(c, 0.0, -s), Vec3::Y, Vec3::new(s, 0.0, c));
            m.orientation = rotation * m.orientation;
        }
        if desc.subject_bounds.is_some() {
            desc.subject_bounds = Some(desc.meshes[..n].iter().flat_map(|m| &m.positions).fold(
                (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
                |(lo, hi), p| (lo.min(*p), hi.max(*p)),
            ));
        }
    }

    /// What the preparation says about this frame; `framed`: the automatic camera framed
    /// the bounding cylinder.
    pub(super) fn note(&self, framed: bool) -> Note {
        let turned = self.turning.iter().filter(|&&t| t).count();
        Note::Turntable {
            frame: self.spin.frame,
            frames: self.spin.frames,
            turned,
            fixed: self.turning.len() - turned,
            framed,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::MaterialDesc;

    fn mesh(positions: Vec<Vec3>, material: Option<usize>) -> MeshDesc {
        MeshDesc {
            name: "m".into(),
            normals: positions.iter().map(|_| Vec3::X).collect(),
            indices: vec![[0, 1, 2]],
            positions,
            material,
            ..Default::default()
        }
    }

    /// An L-shaped, off-origin point set (no symmetry) and an emissive triangle above it.
    fn scene() -> SceneDesc {
        let l = vec![
            Vec3::new(1.0, 0.0, 2.0),
            Vec3::new(4.0, 0.0, 2.0),
            Vec3::new(1.0, 1.0, 3.0),
            Vec3::new(1.5, 2.0, 2.5),
        ];
        let lamp = vec![
            Vec3::new(0.0, 5.0, 0.0),
            Vec3::new(1.0, 5.0, 0.0),
            Vec3::new(0.0, 5.0, 1.0),
        ];
        SceneDesc {
            meshes: vec![mesh(l, None), mesh(lamp, Some(0))],
            materials: vec![MaterialDesc {
                emissive: Vec3::ONE,
                double_sided: true,
                ..Default::default()
            }],
            ..Default::default()
        }
    }

    fn turned(frame: u32, frames: u32) -> SceneDesc {
        let mut d = scene();
        Turn::new(&d, Spin::new(frame, frames).unwrap())
            .unwrap()
            .apply(&mut d);
        d
    }

    #[test]
    fn frame_zero_and_full_turns_are_the_identity_bit_for_bit() {
        let d = scene();
        for (f, n) in [(0, 36), (36, 36), (72, 36), (0, 1), (5, 1)] {
            let t = turned(f, n);
            assert_eq!(t.meshes[0].positions, d.meshes[0].positions, "{f}/{n}");
            assert_eq!(t.meshes[0].normals, d.meshes[0].normals);
        }
    }

    #[test]
    fn a_turn_keeps_heights_and_axis_distances_and_moves_no_light() {
        let d = scene();
        let turn = Turn::new(&d, Spin::new(5, 36).unwrap()).unwrap();
        assert_eq!(turn.axis, (2.5, 2.5));
        let t = turned(5, 36);
        // The emissive mesh is a light: it stays where it was.
        assert_eq!(t.meshes[1].positions, d.meshes[1].positions);
        for (a, b) in d.meshes[0].positions.iter().zip(&t.meshes[0].positions) {
            assert_eq!(a.y, b.y);
            let r = |p: &Vec3| f64::from(p.x - 2.5).hypot(f64::from(p.z - 2.5));
            assert!((r(a) - r(b)).abs() < 1e-6, "{a} → {b}");
            assert_ne!(a, b);
        }
        // 50° counter-clockwise seen from above: +X goes towards −Z.
        let q = t.meshes[0].positions[1]; // was (4, 0, 2): 1.5 right of the axis, 0.5 behind it
        let (s, c) = (50f64.to_radians().sin(), 50f64.to_radians().cos());
        let want = (2.5 + 1.5 * c - 0.5 * s, 2.5 - 1.5 * s - 0.5 * c);
        assert!((f64::from(q.x) - want.0).abs() < 1e-6 && (f64::from(q.z) - want.1).abs() < 1e-6);
        // Normals turn too: +X at 50°.
        let n = t.meshes[0].normals[0];
        assert!((f64::from(n.x) - c).abs() < 1e-6 && (f64::from(n.z) + s).abs() < 1e-6);
    }

    #[test]
    fn turning_back_restores_the_model_and_quarter_turns_are_exact() {
        let d = scene();
        // 130° then 230° = 360°: back within f32 rounding of each step.
        let first = Turn::new(&d, Spin::new(13, 36).unwrap()).unwrap();
        let back = Turn {
            spin: Spin::new(23, 36).unwrap(),
            ..first.clone()
        };
        let mut t = d.clone();
        first.apply(&mut t);
        back.apply(&mut t);
        for (a, b) in d.meshes[0].positions.iter().zip(&t.meshes[0].positions) {
            assert!((*a - *b).abs().max_element() < 2e-6, "{a} vs {b}");
        }
        // A quarter turn of a point on the axis' grid stays on the grid exactly.
        let q = turned(9, 36).meshes[0].positions[1];
        assert_eq!(q, Vec3::new(2.0, 0.0, 1.0));
        assert_eq!(Spin::new(9, 36).unwrap().degrees(), 90.0);
    }

    #[test]
    fn the_framing_cylinder_contains_every_frame() {
        let d = scene();
        let turn = Turn::new(&d, Spin::new(0, 7).unwrap()).unwrap();
        let ring = turn.framing_points(&d.meshes);
        // Two rings plus the lamp's three vertices.
        assert_eq!(ring.len(), 2 * RING as usize + 3);
        let (lo, hi) = ring.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        for f in 0..7 {
            for p in &turned(f, 7).meshes[0].positions {
                assert!(p.cmpge(lo).all() && p.cmple(hi).all(), "frame {f}: {p}");
            }
        }
    }

    #[test]
    fn bad_turntables_are_errors() {
        assert!(Spin::new(0, 0).is_err());
        assert!(Spin::new(0, MAX_FRAMES + 1).is_err());
        let mut d = scene();
        d.meshes.remove(0);
        d.source = "lamp.glb".into();
        let e = Turn::new(&d, Spin::new(1, 4).unwrap()).unwrap_err();
        assert!(e.to_string().contains("lamp.glb: nothing to turn"), "{e}");
    }
}
