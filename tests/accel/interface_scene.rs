//! The η vs 1/η choice made from `front_face`, through the real intersection layer: a beam
//! crosses a glass slab (IOR 1.5, thickness d). On entry the hit must be a front face with
//! η = 1.5, on exit a back face with η = 1/1.5; the beam leaves parallel to its entry
//! direction, displaced sideways by d·sin(θi − θt)/cos θt (plane-parallel plate), and a
//! beam inside steeper than the critical angle is totally internally reflected.

use crate::common;

use glam::{Mat3, Vec3};
use iris::accel::Backend;
use iris::math::Ray;
use iris::optics::{critical_angle, orient_interface, refract};
use iris::scene::desc::{MeshDesc, SceneDesc};
use iris::scene::Scene;

const IOR: f32 = 1.5;
const THICKNESS: f32 = 0.2;

fn slab(backend: Backend) -> Scene {
    // A wide slab: |x|,|z| < 5, 0 < y < THICKNESS.
    let m = iris::authoring::shapes::cuboid(Vec3::new(5.0, THICKNESS / 2.0, 5.0))
        .transformed(Mat3::IDENTITY, Vec3::new(0.0, THICKNESS / 2.0, 0.0));
    let desc = SceneDesc {
        source: "slab".into(),
        meshes: vec![MeshDesc {
            name: "slab".into(),
            positions: m.positions,
            indices: m.indices,
            ..Default::default()
        }],
        ..Default::default()
    };
    Scene::build(iris::scene::validate::validate(desc).unwrap(), backend).unwrap()
}

use common::backends;

#[test]
fn beam_through_slab_obeys_snell_on_entry_and_exit() {
    for backend in backends() {
        let scene = slab(backend);
        for deg in [0.0f32, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0] {
            let ti = deg.to_radians();
            // Incoming from above, travelling down and to +x.
            let dir = Vec3::new(ti.sin(), -ti.cos(), 0.0);
            let origin = Vec3::new(0.0, THICKNESS, 0.0) - dir * 2.0;
            let hit = scene
                .intersect(&Ray::new(origin, dir))
                .expect("hits the top face");
            assert!(hit.front_face, "{deg}°: entering must be a front face");
            let (n, eta) = orient_interface(hit.front_face, hit.ng, IOR);
            assert_eq!(eta, IOR);
            let inside = refract(hit.wo, n, eta).expect("no TIR entering a denser medium");
            let exit = scene
                .intersect(&hit.spawn_ray(inside))
                .expect("hits the bottom face");
            assert!(!exit.front_face, "{deg}°: leaving must be a back face");
            let (n2, eta2) = orient_interface(exit.front_face, exit.ng, IOR);
            assert!((eta2 - 1.0 / IOR).abs() < 1e-7);
            let out = refract(exit.wo, n2, eta2).expect("symmetric: no TIR on exit");
            // Leaves parallel to the incoming beam.
            assert!(
                (out - dir).length() < 2e-5,
                "{deg}°: out {out:?} vs in {dir:?}"
            );
            // Lateral displacement of a plane-parallel plate.
            let tt = (ti.sin() / IOR).asin();
            let expect = THICKNESS * (ti - tt).sin() / tt.cos();
            // Perpendicular distance between the incoming line and the outgoing line.
            let shift = (exit.p - hit.p).cross(dir).length();
            let shift_in = (exit.p - hit.p) - dir * (exit.p - hit.p).dot(dir);
            assert!(
                (shift - expect).abs() < 1e-4 * (1.0 + expect),
                "{deg}°: shift {shift} vs {expect} ({shift_in:?})"
            );
            // The path inside has the length d / cos θt.
            assert!(
                (exit.t - THICKNESS / tt.cos()).abs() < 1e-4,
                "{deg}°: inside length {}",
                exit.t
            );
        }
    }
}

#[test]
fn beam_inside_beyond_critical_angle_is_totally_reflected() {
    let tc = critical_angle(1.0 / IOR).unwrap();
    for backend in backends() {
        let scene = slab(backend);
        for (deg, tir) in [
            (tc.to_degrees() - 1.0, false),
            (tc.to_degrees() + 1.0, true),
        ] {
            let t = deg.to_radians();
            // From inside the slab, travelling up toward the top face.
            let dir = Vec3::new(t.sin(), t.cos(), 0.0);
            let origin = Vec3::new(0.0, THICKNESS / 2.0, 0.0);
            let hit = scene
                .intersect(&Ray::new(origin, dir))
                .expect("hits the top face from inside");
            assert!(!hit.front_face);
            let (n, eta) = orient_interface(hit.front_face, hit.ng, IOR);
            assert_eq!(refract(hit.wo, n, eta).is_none(), tir, "{deg}°");
        }
    }
}
