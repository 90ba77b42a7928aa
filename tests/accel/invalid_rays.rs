//! The intersection layer refuses rays it cannot trace (issue 7): a non-finite origin or
//! direction, a zero direction or a NaN `t_max` misses in `intersect` and is blocked in
//! `occluded`, on every backend, instead of reaching a backend (obvhs would visit every node
//! of a NaN ray; Embree's behaviour on NaN input is undefined).

use crate::common;

use glam::Vec3;
use iris::math::Ray;
use iris::scene::desc::{MeshDesc, SceneDesc};
use iris::scene::Scene;

#[test]
fn invalid_rays_miss_and_are_blocked_on_every_backend() {
    let mesh = iris::authoring::shapes::cuboid(Vec3::splat(1.0));
    for backend in common::backends() {
        let desc = SceneDesc {
            source: "cube".into(),
            meshes: vec![MeshDesc {
                name: "cube".into(),
                positions: mesh.positions.clone(),
                indices: mesh.indices.clone(),
                ..Default::default()
            }],
            materials: vec![common::white_lambert()],
            ..Default::default()
        };
        let desc = iris::scene::validate::validate(desc).expect("valid");
        let scene = Scene::build(desc, backend).expect("build");
        let good = Ray::new(Vec3::new(0.1, 0.2, 5.0), Vec3::NEG_Z);
        let hit = scene.intersect(&good).expect("a valid ray hits the cube");
        assert!((hit.t - 4.0).abs() < 1e-5, "{backend:?}: t = {}", hit.t);
        assert!(scene.occluded(&good));
        let mut bad = vec![
            Ray::new(Vec3::new(f32::NAN, 0.0, 5.0), Vec3::NEG_Z),
            Ray::new(Vec3::new(0.0, f32::INFINITY, 5.0), Vec3::NEG_Z),
            Ray::new(Vec3::new(0.1, 0.2, 5.0), Vec3::new(0.0, f32::NAN, -1.0)),
            Ray::new(
                Vec3::new(0.1, 0.2, 5.0),
                Vec3::new(0.0, 0.0, f32::NEG_INFINITY),
            ),
            Ray::new(Vec3::new(0.1, 0.2, 5.0), Vec3::ZERO),
        ];
        let mut nan_tmax = good;
        nan_tmax.t_max = f32::NAN;
        bad.push(nan_tmax);
        for r in bad {
            assert!(scene.intersect(&r).is_none(), "{backend:?}: {r:?} hit");
            assert!(scene.occluded(&r), "{backend:?}: {r:?} not blocked");
            // A ray pointing away from everything is the control: not blocked.
        }
        assert!(!scene.occluded(&Ray::new(Vec3::new(0.1, 0.2, 5.0), Vec3::Z)));
    }
}
