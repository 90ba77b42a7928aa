//! Self-intersection: rays spawned from hits on a tessellated sphere (a convex polyhedron)
//! scaled to 1e4 and to 1e-4, leaving to the outside and to the inside, never re-hit their
//! own triangle, on every backend. On a convex polyhedron the expected answers are exact:
//! a ray leaving a face outward (dot(dir, ng) > 0) can hit nothing at all, and a ray
//! leaving inward must hit a *different* face from inside (front_face = false).

use crate::common;

use glam::Vec3;
use iris::accel::Backend;
use iris::math::{Ray, Rng};
use iris::scene::desc::{MeshDesc, SceneDesc};
use iris::scene::Scene;

use common::backends;

fn sphere_scene(scale: f32, backend: Backend) -> (Scene, Vec3, f32) {
    let iris::authoring::shapes::TriMesh {
        positions, indices, ..
    } = iris::authoring::shapes::icosphere(1.0, 3);
    let center = Vec3::new(0.3, -0.2, 0.1) * scale;
    let desc = SceneDesc {
        source: "reintersect-test".into(),
        meshes: vec![MeshDesc {
            name: "sphere".into(),
            positions: positions.iter().map(|p| *p * scale + center).collect(),
            indices,
            ..Default::default()
        }],
        ..Default::default()
    };
    let desc = iris::scene::validate::validate(desc).expect("valid");
    (Scene::build(desc, backend).expect("build"), center, scale)
}

/// A unit direction with dot(d, n) = cos_theta exactly-ish, random azimuth.
fn dir_around(n: Vec3, cos_theta: f32, rng: &mut Rng) -> Vec3 {
    let f = iris::math::Frame::from_normal(n);
    let phi = rng.next_f32() * std::f32::consts::TAU;
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    f.to_world(Vec3::new(s * phi.cos(), s * phi.sin(), cos_theta))
        .normalize()
}

fn check(scale: f32, backend: Backend) {
    let (scene, center, r) = sphere_scene(scale, backend);
    let mut rng = Rng::new(&[scale.to_bits() as u64, backend as u64]);
    let mut failures = Vec::new();
    let n_rays = 20_000;
    for i in 0..n_rays {
        // Camera-like ray from outside toward a random interior point.
        let from = center + dir_around(Vec3::Y, rng.next_f32() * 2.0 - 1.0, &mut rng) * (3.0 * r);
        let to = center
            + dir_around(Vec3::Z, rng.next_f32() * 2.0 - 1.0, &mut rng)
                * (0.5 * r * rng.next_f32());
        let ray = Ray::new(from, (to - from).normalize());
        let Some(hit) = scene.intersect(&ray) else {
            failures.push(format!("ray {i}: primary ray missed"));
            continue;
        };
        assert!(hit.front_face, "primary ray must arrive from outside");
        // Cosines down to grazing (1e-3) on both sides.
        let cos = [1.0, 0.5, 0.1, 0.01, 0.001][i % 5];
        let out = dir_around(hit.ng, cos, &mut rng);
        if let Some(h) = scene.intersect(&hit.spawn_ray(out)) {
            failures.push(format!(
                "ray {i}: outward ray (cos {cos}) hit prim {} (own {}) at t={}",
                h.prim, hit.prim, h.t
            ));
        }
        let inward = dir_around(-hit.ng, cos, &mut rng);
        match scene.intersect(&hit.spawn_ray(inward)) {
            None => failures.push(format!(
                "ray {i}: inward ray (cos {cos}) escaped the closed sphere"
            )),
            Some(h) if h.prim == hit.prim => failures.push(format!(
                "ray {i}: inward ray re-hit its own triangle at t={}",
                h.t
            )),
            Some(h) => {
                if h.front_face {
                    failures.push(format!("ray {i}: inward ray hit a face from outside"));
                }
                // From the inside hit, go back inward again (internal reflection).
                let back = dir_around(-h.ng, [1.0, 0.3, 0.01][i % 3], &mut rng);
                match scene.intersect(&h.spawn_ray(back)) {
                    Some(h2) if h2.prim == h.prim => failures.push(format!(
                        "ray {i}: internal reflection re-hit its own triangle"
                    )),
                    None => failures.push(format!("ray {i}: internal reflection escaped")),
                    _ => {}
                }
                // Shadow ray from the inside hit to the sphere centre: unoccluded.
                if scene.occluded(&h.spawn_ray_to(center)) {
                    failures.push(format!("ray {i}: shadow ray to the centre occluded"));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "scale {scale}, backend {backend:?}: {} failures of {n_rays}, first: {:?}",
        failures.len(),
        &failures[..failures.len().min(5)]
    );
}

#[test]
fn no_self_intersection_at_scale_1e4() {
    for b in backends() {
        check(1e4, b);
    }
}

#[test]
fn no_self_intersection_at_scale_1e_minus_4() {
    for b in backends() {
        check(1e-4, b);
    }
}

#[test]
fn no_self_intersection_at_unit_scale() {
    for b in backends() {
        check(1.0, b);
    }
}
