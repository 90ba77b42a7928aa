//! Nested media through coincident faces: a beam crosses glass (n = 1.5) directly into
//! water (n = 1.33) where the two objects share a face, the way artists model a glass of
//! water. The square [-1,1]² (extruded along z) is split on its diagonal x + y = 0: the
//! lower-left half is a glass prism, the upper-right half a water prism, each a closed mesh
//! of its own whose diagonal faces coincide exactly (or within a sliver, see below).
//!
//! The beam enters the glass through the face x = −1, meets the diagonal, and leaves the
//! water through x = +1 or y = +1. The expected exit direction is computed here with the
//! textbook scalar form of Snell's law, n₁ sin θ₁ = n₂ sin θ₂, face by face (air → glass →
//! water → air), independently of `iris::optics`. Had the renderer treated the shared face
//! as glass → air → water (the bug this guards against) the exit would differ by
//! degrees (asserted too), so the 1e-4 tolerance (f32 rounding over three refractions of
//! unit vectors, ~1e-6) separates the two hypotheses by orders of magnitude.
//!
//! The integrators' own step is exercised: `shading::meet` (the intersection layer's
//! coincidence probe) and `shading::interface` give the indices, refraction uses
//! `η = n_t / n_i` about the incident-side normal exactly as `--method whitted` does, and the
//! next ray leaves from the merged hit. A last test puts the water against an opaque block
//! instead: the path must meet the block, not leave the water through it.

use crate::common;

use glam::{Vec2, Vec3};
use iris::accel::Backend;
use iris::material::MaterialDesc;
use iris::math::Ray;
use iris::medium_stack::MediumStack;
use iris::optics::refract;
use iris::scene::desc::{MeshDesc, SceneDesc};
use iris::scene::Scene;
use iris::shading;

const N_GLASS: f32 = 1.5;
const N_WATER: f32 = 1.33;
const HALF_Z: f32 = 5.0;

/// A closed prism over the CCW 2D polygon `poly`, from z = −HALF_Z to +HALF_Z, outward
/// winding.
fn prism(name: &str, poly: &[Vec2], material: usize) -> MeshDesc {
    let k = poly.len() as u32;
    let mut positions = Vec::new();
    for z in [-HALF_Z, HALF_Z] {
        positions.extend(poly.iter().map(|p| Vec3::new(p.x, p.y, z)));
    }
    let mut indices = Vec::new();
    // Caps: back (z−) seen from −z is clockwise in xy, front (z+) counter-clockwise.
    for i in 1..k - 1 {
        indices.push([0, i + 1, i]);
        indices.push([k, k + i, k + i + 1]);
    }
    // Sides: edge (i, j) of a CCW polygon has its outward normal on the right.
    for i in 0..k {
        let j = (i + 1) % k;
        indices.push([i, j, k + j]);
        indices.push([i, k + j, k + i]);
    }
    MeshDesc {
        name: name.into(),
        positions,
        indices,
        material: Some(material),
        ..Default::default()
    }
}

/// Glass (lower-left) and water (upper-right) halves of the square. `water_shift` moves the
/// water's diagonal face along (1,1)/√2: 0 = exactly coincident, > 0 a gap, < 0 an overlap.
fn scene(backend: Backend, water_shift: f32, second_material_is_glass: bool) -> Scene {
    scene_with(backend, water_shift, second_material_is_glass, false, 0)
}

/// As [`scene`]; `opaque_first` makes the lower-left prism an opaque diffuse block, and the
/// glass gets nested-media priority `glass_priority` (the water has 0).
fn scene_with(
    backend: Backend,
    water_shift: f32,
    second_material_is_glass: bool,
    opaque_first: bool,
    glass_priority: i32,
) -> Scene {
    let s = Vec2::splat(water_shift / 2f32.sqrt());
    let glass = prism(
        "glass",
        &[
            Vec2::new(-1.0, -1.0),
            Vec2::new(1.0, -1.0),
            Vec2::new(-1.0, 1.0),
        ],
        0,
    );
    let water = prism(
        "water",
        &[
            Vec2::new(1.0, -1.0) + s,
            Vec2::new(1.0, 1.0),
            Vec2::new(-1.0, 1.0) + s,
        ],
        1,
    );
    let second = if second_material_is_glass {
        common::clear_glass("glass 2", N_GLASS)
    } else {
        common::clear_glass("water", N_WATER)
    };
    let desc = SceneDesc {
        source: "nested".into(),
        meshes: vec![glass, water],
        materials: vec![
            if opaque_first {
                MaterialDesc {
                    name: "block".into(),
                    ..Default::default()
                }
            } else {
                MaterialDesc {
                    priority: glass_priority,
                    ..common::clear_glass("glass", N_GLASS)
                }
            },
            second,
        ],
        ..Default::default()
    };
    Scene::build(iris::scene::validate::validate(desc).unwrap(), backend).unwrap()
}

use common::backends;

/// Textbook vector form of Snell's law for unit `d` hitting a surface with unit normal `n`
/// facing the incoming side (d·n < 0), from index `n1` into `n2`; `None` beyond the
/// critical angle.
fn snell(d: Vec3, n: Vec3, n1: f32, n2: f32) -> Option<Vec3> {
    let r = n1 / n2;
    let cos_i = -d.dot(n);
    let sin2_t = r * r * (1.0 - cos_i * cos_i);
    (sin2_t < 1.0).then(|| (d * r + n * (r * cos_i - (1.0 - sin2_t).sqrt())).normalize())
}

/// The expected exit direction for a beam entering x = −1 with direction `d0`, given the
/// index pair used at the diagonal, and the face it leaves by (x = +1 or y = +1); `None`
/// if that pair reflects the beam totally.
fn expected_exit(d0: Vec3, y0: f32, diag: (f32, f32)) -> Option<Vec3> {
    let d1 = snell(d0, Vec3::NEG_X, 1.0, N_GLASS)?;
    let diag_n = Vec3::new(-1.0, -1.0, 0.0).normalize(); // facing the glass side
    let d2 = snell(d1, diag_n, diag.0, diag.1)?;
    // Where on the diagonal, then which outer face of the water it reaches first.
    let p0 = Vec3::new(-1.0, y0, 0.0);
    let t1 = -(p0.x + p0.y) / (d1.x + d1.y);
    let p1 = p0 + d1 * t1;
    let tx = (1.0 - p1.x) / d2.x;
    let ty = if d2.y > 0.0 {
        (1.0 - p1.y) / d2.y
    } else {
        f32::INFINITY
    };
    let n_out = if tx < ty { Vec3::X } else { Vec3::Y };
    snell(d2, -n_out, N_WATER, 1.0)
}

/// Follows the beam with the integrators' interface step; returns the exit direction and
/// the (n_i, n_t) pairs met.
fn trace(scene: &Scene, origin: Vec3, dir: Vec3) -> (Vec3, Vec<(f32, f32)>) {
    let mut ray = Ray::new(origin, dir);
    let mut media = MediumStack::new();
    let mut pairs = Vec::new();
    for _ in 0..16 {
        let Some(hit) = scene.intersect(&ray) else {
            assert_eq!(
                media,
                MediumStack::new(),
                "left the objects still inside a medium"
            );
            return (ray.dir.normalize(), pairs);
        };
        let (merged, coincident) = shading::meet(scene, hit);
        let (n_i, n_t, after, _) =
            shading::interface::<glam::Vec3>(scene, &merged, &coincident, media, &());
        pairs.push((n_i, n_t));
        let n = if merged.front_face {
            merged.ns
        } else {
            -merged.ns
        };
        let eta = if n_i == n_t { 1.0 } else { n_t / n_i };
        let out = refract(merged.wo, n, eta).expect("no TIR on this path");
        media = after;
        ray = merged.spawn_ray(out);
    }
    panic!("beam did not leave: {pairs:?}");
}

fn beams() -> impl Iterator<Item = (Vec3, f32)> {
    // Entry heights below the diagonal's reach and angles up to 40° from +x, upward.
    [
        (-0.8f32, 0.0f32),
        (-0.5, 10.0),
        (-0.3, 25.0),
        (-0.6, 40.0),
        (-0.2, -5.0),
    ]
    .into_iter()
    .map(|(y, deg)| {
        let a = deg.to_radians();
        (Vec3::new(a.cos(), a.sin(), 0.0), y)
    })
}

#[test]
fn glass_to_water_through_coincident_faces_bends_by_their_index_ratio() {
    for backend in backends() {
        let scene = scene(backend, 0.0, false);
        for (dir, y) in beams() {
            let origin = Vec3::new(-3.0, y - dir.y / dir.x * 2.0, 0.3);
            let (out, pairs) = trace(&scene, origin, dir);
            let want = expected_exit(dir, y, (N_GLASS, N_WATER)).unwrap();
            // Glass → air at the shared face (the bug guarded against): total internal
            // reflection for the steeper beams, a different exit for the others.
            if let Some(wrong) = expected_exit(dir, y, (N_GLASS, 1.0)) {
                assert!(
                    (want - wrong).length() > 1e-2,
                    "test geometry does not separate the hypotheses"
                );
            }
            assert!(
                (out - want).length() < 1e-4,
                "{backend:?} dir {dir}: exit {out} vs Snell {want} (pairs {pairs:?})"
            );
            assert_eq!(
                pairs,
                vec![(1.0, N_GLASS), (N_GLASS, N_WATER), (N_WATER, 1.0)],
                "{backend:?} dir {dir}: three interfaces, the shared face crossed once"
            );
        }
    }
}

#[test]
fn nearly_coincident_faces_are_one_interface_and_real_gaps_are_not() {
    for backend in backends() {
        for shift in [1e-6f32, -1e-6, 2e-5, -2e-5] {
            let scene = scene(backend, shift, false);
            for (dir, y) in beams() {
                let origin = Vec3::new(-3.0, y - dir.y / dir.x * 2.0, 0.3);
                let (out, pairs) = trace(&scene, origin, dir);
                let want = expected_exit(dir, y, (N_GLASS, N_WATER)).unwrap();
                // A sliver of |shift| shifts the beam by ~|shift|, not its direction.
                assert!(
                    (out - want).length() < 1e-4,
                    "{backend:?} shift {shift}: exit {out} vs {want} ({pairs:?})"
                );
                assert_eq!(pairs.len(), 3, "{backend:?} shift {shift}: {pairs:?}");
            }
        }
        // A visible air gap (1e-3, far beyond the merge distance) is two interfaces.
        let scene = scene(backend, 1e-3, false);
        let (dir, y) = beams().nth(1).unwrap();
        let origin = Vec3::new(-3.0, y - dir.y / dir.x * 2.0, 0.3);
        let (_, pairs) = trace(&scene, origin, dir);
        assert_eq!(
            pairs,
            vec![
                (1.0, N_GLASS),
                (N_GLASS, 1.0),
                (1.0, N_WATER),
                (N_WATER, 1.0)
            ],
            "{backend:?}"
        );
    }
}

#[test]
fn touching_prisms_of_one_glass_are_no_interface() {
    for backend in backends() {
        let scene = scene(backend, 0.0, true);
        for (dir, y) in beams() {
            let origin = Vec3::new(-3.0, y - dir.y / dir.x * 2.0, 0.3);
            let (_, pairs) = trace(&scene, origin, dir);
            assert_eq!(
                pairs,
                vec![(1.0, N_GLASS), (N_GLASS, N_GLASS), (N_GLASS, 1.0)],
                "{backend:?} dir {dir}"
            );
        }
    }
}

#[test]
fn water_against_an_opaque_wall_meets_the_wall() {
    for backend in backends() {
        let scene = scene_with(backend, 0.0, false, true, 0);
        let (mut met_block, mut n) = (0, 0);
        // From inside the water, toward the shared diagonal at many angles.
        for i in 0..200 {
            let a = (200.0 + 50.0 * (i as f32 / 199.0)).to_radians();
            let origin = Vec3::new(0.5, 0.5, 0.1 + 0.01 * i as f32);
            let dir = Vec3::new(a.cos(), a.sin(), 0.0);
            let hit = scene
                .intersect(&Ray::new(origin, dir))
                .expect("hits the diagonal");
            let (met, co) = shading::meet(&scene, hit);
            assert!(co.is_empty(), "{backend:?}: no volume interface to cross");
            n += 1;
            met_block += (met.material == 0) as usize;
            // Reflected back into the water, the next ray must not meet the water's
            // coincident face (it would leave a water it is still inside).
            let n_in = if met.front_face { met.ng } else { -met.ng };
            let back = met.spawn_ray(dir - 2.0 * dir.dot(n_in) * n_in);
            let next = scene.intersect(&back).expect("hits the water's far side");
            assert!(
                next.t > 0.1,
                "{backend:?}: re-hit the shared face at t = {}",
                next.t
            );
        }
        assert_eq!(
            met_block, n,
            "{backend:?}: the wall must win over the water's face"
        );
    }
}

#[test]
fn only_the_shared_faces_are_marked_as_touching() {
    use iris::scene::Triangle;
    for backend in backends() {
        for (shift, want) in [(0.0f32, 4usize), (1e-6, 4), (1e-3, 0)] {
            let scene = scene(backend, shift, false);
            let marked = scene
                .triangles()
                .iter()
                .filter(|t| t.has(Triangle::TOUCHES))
                .count();
            // The diagonal is two triangles in each prism.
            assert_eq!(marked, want, "{backend:?} shift {shift}");
        }
    }
}

/// Water modelled overlapping its glass by 0.02 (far beyond the merge distance): with equal
/// priorities the last medium entered wins, so the beam refracts glass→water at the water's
/// face inside the glass and the glass face inside the water is false; with the glass at
/// priority 1 (Schmidt & Budge) the overlap is glass: the water's face is false and the real
/// 1.5→1.33 interface is the glass's own face. Either way the beam leaves in the same
/// direction (the two candidate faces are parallel, so only a sideways shift differs).
#[test]
fn overlapping_volumes_follow_their_priorities() {
    for backend in backends() {
        let mut exits: Vec<Vec3> = Vec::new();
        for (priority, want) in [
            (
                0,
                [
                    (1.0, N_GLASS),
                    (N_GLASS, N_WATER),
                    (N_WATER, N_WATER),
                    (N_WATER, 1.0),
                ],
            ),
            (
                1,
                [
                    (1.0, N_GLASS),
                    (N_GLASS, N_GLASS),
                    (N_GLASS, N_WATER),
                    (N_WATER, 1.0),
                ],
            ),
        ] {
            let scene = scene_with(backend, -0.02, false, false, priority);
            let (dir, y) = beams().nth(1).unwrap();
            let origin = Vec3::new(-3.0, y - dir.y / dir.x * 2.0, 0.3);
            let (out, pairs) = trace(&scene, origin, dir);
            assert_eq!(pairs, want.to_vec(), "{backend:?} priority {priority}");
            exits.push(out);
        }
        assert!(
            (exits[0] - exits[1]).length() < 1e-5,
            "{backend:?}: {exits:?}"
        );
    }
}

/// The test case, McGuire's CornellBox-Water (shared assets): beams from the room
/// enter the open water surface (IOR 1.33, `illum 7`), bend by Snell's law about the
/// surface's shading normal (n sin θ conserved to 1e-4), and reach the floor or a sphere
/// while the path's medium stack holds the water.
#[test]
fn cornell_water_beams_refract_into_the_water_and_reach_the_floor() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let path = shared.join("obj/CornellBox-McGuire/CornellBox-Water.obj");
    for backend in backends() {
        let (scene, _) = iris::app::load(&path, backend).unwrap();
        let water = scene
            .materials()
            .iter()
            .position(|m| m.desc.name.contains("water"))
            .expect("a water material") as u32;
        let (mut checked, mut on_floor) = (0, 0);
        for i in 0..100 {
            let (x, z) = (-0.6 + 0.012 * i as f32, -0.5 + 0.009 * i as f32);
            let dir = Vec3::new(0.3, -1.0, 0.2).normalize();
            let Some(hit) = scene.intersect(&Ray::new(Vec3::new(x, 1.2, z), dir)) else {
                continue;
            };
            if hit.material != water {
                continue; // a sphere above the waterline
            }
            let (hit, co) = shading::meet(&scene, hit);
            let (n_i, n_t, media, _) =
                shading::interface::<Vec3>(&scene, &hit, &co, MediumStack::new(), &());
            assert!(
                hit.front_face,
                "{backend:?}: the surface is entered from above"
            );
            assert_eq!((n_i, n_t), (1.0, 1.33), "{backend:?}");
            assert_eq!(media.current(), Some(water));
            let n = hit.ns;
            let out = refract(hit.wo, n, n_t / n_i).expect("no TIR entering water");
            let sin_i = hit.wo.cross(n).length();
            let sin_t = out.cross(-n).length();
            assert!(
                (sin_i - 1.33 * sin_t).abs() < 1e-4,
                "{backend:?}: {sin_i} vs {sin_t}"
            );
            let next = scene
                .intersect(&hit.spawn_ray(out))
                .expect("something below");
            let name = &scene.materials()[next.material as usize].desc.name;
            assert_ne!(
                next.material, water,
                "{backend:?}: re-hit the water surface"
            );
            // Material names carry their source: `material 2 "floor" (… line 28)`.
            on_floor += name.contains("\"floor\"") as usize;
            checked += 1;
        }
        assert!(
            checked > 30 && on_floor > 20,
            "{backend:?}: {checked} beams, {on_floor} floor"
        );
    }
}
