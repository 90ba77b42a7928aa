//! `--ground auto|on|off`: a white diffuse floor under the model, added to the scene
//! description **before** the acceleration structure is built.
//!
//! ## The floor
//! A square quad in the plane y = the model's lowest point (it touches the model; a flat
//! base lying on it is merged as one interface by [`crate::scene::contact`]), centred
//! under the model's bounding-box centre, [`HALF_SIZE`] bounding radii from centre to
//! edge, facing +Y (counter-clockwise from above), material [`ALBEDO`] white Lambertian
//! (metallic 0, roughness 1), named [`GROUND_MESH`].
//!
//! ## `auto`
//! On when the model has a transmissive material (`transmission > 0`) and **no floor of
//! its own under it**. "Floor" is tested on a 5×5 grid of points spread over the
//! horizontal footprint of the transmissive meshes' bounding box (inset 10 % from its
//! edges): a point is supported when an opaque (`transmission == 0`) triangle that faces up
//! (geometric normal within 45° of +Y) covers it in plan view and lies entirely below the
//! transmissive part's lowest point + 5 % of its height. The model has a floor when at
//! least 13 of the 25 points are supported, so a ring's band or a thin stand under part
//! of a gem does not count, while a table, a plate or a preview floor does.

use crate::error::{Error, Result};
use crate::material::MaterialDesc;
use crate::scene::desc::{MeshDesc, SceneDesc};
use glam::{Vec2, Vec3, Vec4};

/// The floor reaches this many bounding radii from the model's centre (half side).
pub const HALF_SIZE: f32 = 12.0;
/// The floor's albedo (a white card).
pub const ALBEDO: f32 = 0.8;
/// Name of the added mesh (and material).
pub const GROUND_MESH: &str = "iris ground";
/// Grid points per side of the footprint test.
const GRID: usize = 5;
/// Supported grid points needed for "has a floor" (a majority of 25).
const MAJORITY: usize = 13;
/// cos 45°: the largest tilt of a floor triangle.
const UP_COS: f32 = std::f32::consts::FRAC_1_SQRT_2;

/// `--ground`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GroundMode {
    /// A floor when the model is transmissive and has none (see the module docs).
    #[default]
    Auto,
    /// Always add a floor.
    On,
    /// Never add one.
    Off,
}

impl GroundMode {
    /// Parses `--ground auto|on|off` (case-insensitive).
    pub fn parse(s: &str) -> Result<GroundMode> {
        match s.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(GroundMode::Auto),
            "on" => Ok(GroundMode::On),
            "off" => Ok(GroundMode::Off),
            _ => Err(Error::Usage(format!(
                "--ground {s:?}: expected auto, on or off"
            ))),
        }
    }
}

/// World bounds of all meshes of `desc` (min, max); infinite when it has no vertex.
pub fn desc_bounds(desc: &SceneDesc) -> (Vec3, Vec3) {
    bounds_of(desc.meshes.iter())
}

fn bounds_of<'a>(meshes: impl Iterator<Item = &'a MeshDesc>) -> (Vec3, Vec3) {
    meshes.flat_map(|m| m.positions.iter()).fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

fn transmissive(desc: &SceneDesc, m: &MeshDesc) -> bool {
    m.material
        .and_then(|i| desc.materials.get(i))
        .is_some_and(|mat| mat.transmission > 0.0)
}

/// Why a floor was or was not added (the render notes say it, [`crate::prepare::Note`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Floor {
    /// `--ground on`: a floor.
    On,
    /// `--ground off`: none.
    Off,
    /// `auto`: no transmissive material, no floor (the common case, not worth a note).
    NotTransmissive,
    /// `auto`: the model stands on a surface of its own, no floor.
    OwnSurface,
    /// `auto`: a transmissive model with nothing under it gets a floor for its caustics.
    UnderGlass,
    /// `auto` with a `--background` other than the environment: no floor, which would
    /// cover it ([`crate::prepare::drop_in::PreviewOptions::ground_mode`]).
    CoversBackground,
    /// `auto` on a file that brings its own light ([`crate::prepare::Authored`]): its scene
    /// is kept as authored, no floor (the preparation's authored note says so).
    Authored,
}

impl Floor {
    /// Whether a floor is added.
    pub fn adds(self) -> bool {
        matches!(self, Floor::On | Floor::UnderGlass)
    }
}

/// Whether to add a floor ([`Floor::adds`]), and why.
pub fn decide(desc: &SceneDesc, mode: GroundMode) -> (bool, Floor) {
    let floor = match mode {
        GroundMode::On => Floor::On,
        GroundMode::Off => Floor::Off,
        GroundMode::Auto => {
            let glass: Vec<&MeshDesc> = desc
                .meshes
                .iter()
                .filter(|m| transmissive(desc, m))
                .collect();
            if glass.is_empty() {
                Floor::NotTransmissive
            } else if has_floor(desc, bounds_of(glass.into_iter())) {
                Floor::OwnSurface
            } else {
                Floor::UnderGlass
            }
        }
    };
    (floor.adds(), floor)
}

/// Whether opaque up-facing triangles lie under most of the footprint of `glass` (the
/// transmissive part's bounds), as described in the module docs.
pub fn has_floor(desc: &SceneDesc, glass: (Vec3, Vec3)) -> bool {
    let (lo, hi) = glass;
    if !lo.is_finite() || !hi.is_finite() {
        return false;
    }
    let top = lo.y + 0.05 * (hi.y - lo.y);
    let points: Vec<Vec2> = (0..GRID * GRID)
        .map(|i| {
            let f = |k: usize| 0.1 + 0.8 * k as f32 / (GRID - 1) as f32;
            Vec2::new(
                lo.x + (hi.x - lo.x) * f(i % GRID),
                lo.z + (hi.z - lo.z) * f(i / GRID),
            )
        })
        .collect();
    let mut supported = vec![false; points.len()];
    for m in desc.meshes.iter().filter(|m| !transmissive(desc, m)) {
        for t in &m.indices {
            let Some(p) = t
                .map(|i| m.positions.get(i as usize).copied())
                .into_iter()
                .collect::<Option<Vec<Vec3>>>()
            else {
                continue;
            };
            if p.iter().any(|q| q.y > top) {
                continue;
            }
            let n = (p[1] - p[0]).cross(p[2] - p[0]);
            let len = n.length();
            if len.is_nan() || len <= 0.0 || n.y < UP_COS * len {
                continue;
            }
            let xz = |v: Vec3| Vec2::new(v.x, v.z);
            let tri = [xz(p[0]), xz(p[1]), xz(p[2])];
            for (s, q) in supported.iter_mut().zip(&points) {
                if !*s && in_triangle(*q, tri) {
                    *s = true;
                }
            }
        }
    }
    supported.iter().filter(|s| **s).count() >= MAJORITY
}

/// Whether `q` lies in the plan-view triangle `t` (either winding, edges included).
fn in_triangle(q: Vec2, t: [Vec2; 3]) -> bool {
    let e = |a: Vec2, b: Vec2| (b - a).perp_dot(q - a);
    let (d0, d1, d2) = (e(t[0], t[1]), e(t[1], t[2]), e(t[2], t[0]));
    (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0)
}

/// Adds the floor under the model (the file's own geometry, whose bounds it records as
/// `desc.subject_bounds`) to `desc`: a new material and a two-triangle mesh, valid by
/// construction (so validation need not run again).
pub fn add_ground(desc: &mut SceneDesc) {
    let model = desc.subject_bounds.unwrap_or_else(|| desc_bounds(desc));
    desc.subject_bounds = Some(model);
    let (centre, radius) = super::bounding_sphere(model);
    let y = if model.0.y.is_finite() {
        model.0.y
    } else {
        0.0
    };
    let h = HALF_SIZE * radius;
    let (cx, cz) = (centre.x, centre.z);
    desc.materials.push(MaterialDesc {
        name: format!("{GROUND_MESH} (white diffuse)"),
        base_color: Vec4::new(ALBEDO, ALBEDO, ALBEDO, 1.0),
        metallic: 0.0,
        roughness: 1.0,
        ..MaterialDesc::default()
    });
    // Counter-clockwise seen from +Y: (p1 − p0) × (p2 − p0) points up.
    let positions = vec![
        Vec3::new(cx - h, y, cz - h),
        Vec3::new(cx - h, y, cz + h),
        Vec3::new(cx + h, y, cz + h),
        Vec3::new(cx + h, y, cz - h),
    ];
    desc.meshes.push(MeshDesc {
        name: GROUND_MESH.into(),
        normals: vec![Vec3::Y; 4],
        positions,
        uvs: Vec::new(),
        uvs1: Vec::new(),
        tangents: Vec::new(),
        indices: vec![[0, 1, 2], [0, 2, 3]],
        material: Some(desc.materials.len() - 1),
        orientation: glam::Mat3::IDENTITY,
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(y: f32, h: f32, up: bool, material: Option<usize>) -> MeshDesc {
        let mut indices = vec![[0, 1, 2], [0, 2, 3]];
        if !up {
            indices = vec![[0, 2, 1], [0, 3, 2]];
        }
        MeshDesc {
            name: "quad".into(),
            positions: vec![
                Vec3::new(-h, y, -h),
                Vec3::new(-h, y, h),
                Vec3::new(h, y, h),
                Vec3::new(h, y, -h),
            ],
            indices,
            material,
            ..MeshDesc::default()
        }
    }

    fn glass_scene() -> SceneDesc {
        let glass = MaterialDesc {
            transmission: 1.0,
            ..MaterialDesc::default()
        };
        let mut box_ = quad(1.0, 0.5, true, Some(0));
        box_.positions.push(Vec3::new(0.0, 0.5, 0.0));
        SceneDesc {
            meshes: vec![box_],
            materials: vec![glass],
            ..SceneDesc::default()
        }
    }

    #[test]
    fn auto_floor_for_glass_alone_not_on_a_table() {
        let mut d = glass_scene();
        assert!(decide(&d, GroundMode::Auto).0);
        // A table under it: no floor added.
        d.meshes.push(quad(0.4, 3.0, true, None));
        assert!(!decide(&d, GroundMode::Auto).0);
        // A downward-facing sheet is a ceiling, not a floor.
        d.meshes.pop();
        d.meshes.push(quad(0.4, 3.0, false, None));
        assert!(decide(&d, GroundMode::Auto).0);
        // Too small a stand (covers only the centre point) does not count.
        d.meshes.pop();
        d.meshes.push(quad(0.4, 0.1, true, None));
        assert!(decide(&d, GroundMode::Auto).0);
        assert!(decide(&d, GroundMode::On).0);
        assert!(!decide(&glass_scene(), GroundMode::Off).0);
    }

    #[test]
    fn opaque_model_gets_no_auto_floor() {
        let d = SceneDesc {
            meshes: vec![quad(1.0, 0.5, true, None)],
            ..SceneDesc::default()
        };
        assert!(!decide(&d, GroundMode::Auto).0);
    }

    #[test]
    fn ground_touches_the_lowest_point_and_faces_up() {
        let mut d = glass_scene();
        let b = desc_bounds(&d);
        add_ground(&mut d);
        assert_eq!(d.subject_bounds, Some(b));
        let g = d.meshes.last().unwrap();
        assert!(g.positions.iter().all(|p| p.y == 0.5));
        let p = &g.positions;
        for t in &g.indices {
            let n =
                (p[t[1] as usize] - p[t[0] as usize]).cross(p[t[2] as usize] - p[t[0] as usize]);
            assert!(n.y > 0.0 && n.x == 0.0 && n.z == 0.0);
        }
        assert_eq!(g.material, Some(d.materials.len() - 1));
        assert!(crate::scene::validate::validate(d).is_ok());
        assert!(GroundMode::parse("maybe").is_err());
        assert_eq!(GroundMode::parse(" ON ").unwrap(), GroundMode::On);
    }
}
