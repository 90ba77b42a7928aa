//! `--method auto`'s enclosure probe and the bidirectional methods it picks
//! ([`iris::plan::resolve_method`], [`iris::photon::probe::kept_share`]):
//! - in a closed diffuse room of albedo ρ every photon a wall reflects meets a wall again,
//!   so the kept share is ρ (within the probe's binomial noise); a bare floor under a
//!   light never sends light back to itself (exactly 0);
//! - the closed room picks BPT under a perspective camera and the path tracer under an
//!   orthographic one (BPT needs a pinhole); the bare floor picks the path tracer;
//! - the room with a small glass ball in it (a caustic path, a small caustic share) picks
//!   VCM, where the same ball on an open floor picks the hybrid;
//! - the McGuire Cornell boxes (shared assets): BPT for the plain box, VCM for the boxes
//!   with spheres and with water, each reason naming the share kept.

use crate::common;

use glam::Vec3;
use iris::integrator::Method;
use iris::photon::emit::PhotonEmitter;
use iris::photon::probe::kept_share;
use iris::plan::{resolve_method, AUTO_ENCLOSED_FROM, CAUSTIC_PROBE_PHOTONS};
use iris::scene::desc::{Projection, SceneDesc};
use iris::scene::Scene;

fn grey(rho: f32) -> iris::material::MaterialDesc {
    iris::material::MaterialDesc {
        base_color: glam::Vec4::new(rho, rho, rho, 1.0),
        ..common::white_lambert()
    }
}

/// A sphere room (R = 1) of albedo `rho` around a point light at its centre, with a glass
/// ball (radius 0.15) off the light if `ball`.
fn room(rho: f32, ball: bool) -> Scene {
    let mut meshes = vec![common::sphere_mesh("room", 1.0, 4, Vec3::ZERO, 0)];
    if ball {
        meshes.push(common::sphere_mesh(
            "ball",
            0.15,
            4,
            Vec3::new(0.0, -0.7, 0.0),
            1,
        ));
    }
    common::build_scene(SceneDesc {
        source: "sphere room".into(),
        meshes,
        materials: vec![grey(rho), common::clear_glass("glass", 1.5)],
        lights: vec![common::white_point_light(Vec3::ZERO)],
        ..Default::default()
    })
}

/// A 2 × 2 m floor of albedo ½ under a point light, with the same glass ball if `ball`.
fn open_floor(ball: bool) -> Scene {
    let floor = iris::authoring::shapes::ground_plane(1.0, 1.0).into_mesh_desc("floor", 0);
    let mut meshes = vec![floor];
    if ball {
        meshes.push(common::sphere_mesh(
            "ball",
            0.15,
            4,
            Vec3::new(0.0, 0.15, 0.0),
            1,
        ));
    }
    common::build_scene(SceneDesc {
        source: "open floor".into(),
        meshes,
        materials: vec![grey(0.5), common::clear_glass("glass", 1.5)],
        lights: vec![common::white_point_light(Vec3::new(0.3, 1.0, 0.0))],
        ..Default::default()
    })
}

fn kept(scene: &Scene) -> f64 {
    kept_share(scene, &PhotonEmitter::new(scene), CAUSTIC_PROBE_PHOTONS)
}

const ORTHO: Projection = Projection::Orthographic {
    xmag: 1.0,
    ymag: 1.0,
};

/// Bound: the probe's estimate is a mean over 4096 photons of a Bernoulli-like variable
/// (Russian roulette with survival ρ, survivors keeping their power): σ = √(ρ(1 − ρ)/4096)
/// ≤ 0.008; 0.04 is 5σ, and a probe that counted the first hit twice (1) or lost the
/// second (0) fails by far.
#[test]
fn the_kept_share_is_the_albedo_of_a_closed_room_and_zero_on_a_bare_floor() {
    for rho in [0.5f32, 0.8] {
        let k = kept(&room(rho, false));
        eprintln!("room of albedo {rho}: kept {k:.4}");
        assert!((k - f64::from(rho)).abs() < 0.04, "albedo {rho}: kept {k}");
    }
    let k = kept(&open_floor(false));
    assert_eq!(k, 0.0, "a plane cannot light itself");
    // The threshold lies between the two: a room of albedo ½ counts as enclosed.
    assert!(kept(&room(0.5, false)) > AUTO_ENCLOSED_FROM && k < AUTO_ENCLOSED_FROM);
}

#[test]
fn auto_picks_the_bidirectional_methods_where_the_scene_is_enclosed() {
    let pick = |scene: &Scene, p: &Projection| {
        let (m, why) = resolve_method(Method::Auto, scene, p);
        (m, why.unwrap())
    };
    let closed = room(0.5, false);
    let (m, why) = pick(&closed, &common::PINHOLE);
    assert_eq!(m, Method::Bpt, "{why}");
    assert!(why.contains("enclosed"), "{why}");
    let (m, why) = pick(&closed, &ORTHO);
    assert_eq!(m, Method::Path, "{why}");
    assert!(why.contains("orthographic"), "{why}");
    let (m, why) = pick(&open_floor(false), &common::PINHOLE);
    assert_eq!(m, Method::Path, "{why}");
    assert!(why.contains("open"), "{why}");
    let (m, why) = pick(&room(0.5, true), &common::PINHOLE);
    assert_eq!(m, Method::Vcm, "{why}");
    assert!(
        why.contains("enclosed") && why.contains("caustics carry"),
        "{why}"
    );
    let (m, why) = pick(&open_floor(true), &common::PINHOLE);
    assert_eq!(m, Method::Hybrid, "{why}");
}

#[test]
fn auto_picks_bpt_and_vcm_for_the_cornell_boxes() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let dir = shared.join("obj/CornellBox-McGuire");
    for (file, expected) in [
        ("CornellBox-Original.obj", Method::Bpt),
        ("CornellBox-Sphere.obj", Method::Vcm),
        ("CornellBox-Water.obj", Method::Vcm),
    ] {
        // OBJ files have no camera: Iris frames them with a perspective one.
        let (scene, _) =
            iris::app::load(&dir.join(file), iris::accel::Backend::Auto).expect("load");
        let (m, why) = resolve_method(Method::Auto, &scene, &common::PINHOLE);
        let why = why.unwrap();
        assert_eq!(m, expected, "{file}: {why}");
        assert!(
            why.contains("keeps") || why.contains("caustics carry"),
            "{file}: {why}"
        );
    }
}
