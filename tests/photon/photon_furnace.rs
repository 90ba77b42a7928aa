//! A furnace for photons: a closed white diffuse room — the inside of a sphere of radius R
//! and albedo ρ — lit by an isotropic point light of intensity I at its centre. By
//! symmetry the radiance leaving the wall is the same everywhere and in every direction:
//! direct irradiance E₀ = I/R², and each bounce multiplies the irradiance by ρ, so
//! E = E₀/(1 − ρ) and L = ρE/π = ρ I / (π R² (1 − ρ)). With ρ = 0.5, I = 1, R = 1: L = 1/π.
//! The room is an icosphere (20480 faces; its faces lie ≤ 0.03 % inside the sphere, so
//! the flat-face error is far below the tolerances).
//!
//! Direct light is the camera path's (shadow rays), the rest comes from photons (SPPM) or
//! from the global map through final gathering (photon); the path tracer is the check of
//! the scene itself.

use crate::common;

use glam::{Vec2, Vec3};
use iris::camera::{look_at, Camera};
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::material::MaterialDesc;
use iris::photon::emit::PhotonEmitter;
use iris::render::RenderSettings;
use iris::scene::desc::{CameraDesc, MeshDesc, Projection, SceneDesc};
use iris::scene::Scene;

const RHO: f32 = 0.5;

fn room() -> Scene {
    let sphere = iris::authoring::shapes::icosphere(1.0, 5);
    let white = MaterialDesc {
        base_color: glam::Vec4::new(RHO, RHO, RHO, 1.0),
        ..common::white_lambert()
    };
    let desc = SceneDesc {
        source: "photon furnace".into(),
        meshes: vec![MeshDesc {
            name: "room".into(),
            positions: sphere.positions,
            normals: sphere.normals,
            indices: sphere.indices,
            material: Some(0),
            ..Default::default()
        }],
        materials: vec![white],
        lights: vec![common::white_point_light(Vec3::ZERO)],
        ..Default::default()
    };
    common::build_scene(desc)
}

fn mean_radiance(scene: &Scene, method: Method, photon: PhotonSettings, spp: u32) -> f64 {
    let (w, h) = (24, 18);
    let cam = CameraDesc {
        name: "inside".into(),
        projection: Projection::Perspective {
            yfov: 1.2,
            aspect: None,
        },
        world_from_camera: look_at(
            Vec3::new(0.0, 0.0, 0.4),
            Vec3::new(0.3, -0.2, -1.0),
            Vec3::Y,
        ),
    };
    let settings = RenderSettings::quiet_rgb((w, h), spp, 3, 2);
    let integrator = Integrator::new(method, 64, &photon).expect("a resolved method");
    let (img, _) = integrator
        .render(scene, &Camera::new(&cam, w, h), &settings)
        .unwrap();
    assert!(img.data.iter().all(|p| p.is_finite()));
    img.data.iter().map(|p| p.y as f64).sum::<f64>() / img.data.len() as f64
}

fn expected() -> f64 {
    (RHO / (std::f32::consts::PI * (1.0 - RHO))) as f64
}

#[test]
fn emitted_photon_power_equals_the_light_power() {
    let scene = room();
    let e = PhotonEmitter::new(&scene);
    // Φ = 4π I for an isotropic point light.
    let phi = 4.0 * std::f32::consts::PI;
    assert!((e.total_power() - Vec3::splat(phi)).abs().max_element() < 1e-4 * phi);
    let n = 20_000;
    let mut sum = Vec3::ZERO;
    for i in 0..n {
        let u = |k: u32| ((i * 7 + k) % n) as f32 / n as f32;
        let p = e
            .emit(&scene, u(0), Vec2::new(u(1), u(2)), Vec2::new(u(3), u(5)))
            .expect("photon");
        sum += p.power;
    }
    let mean = sum / n as f32;
    // A single point light: every photon carries exactly Φ.
    assert!(
        (mean - Vec3::splat(phi)).abs().max_element() < 1e-3 * phi,
        "{mean}"
    );
}

#[test]
fn path_tracer_matches_the_analytic_room() {
    let l = mean_radiance(&room(), Method::Path, PhotonSettings::default(), 64);
    // 24×18×64 samples of a quantity with relative s.d. ≲ 1: standard error ≲ 0.2 %.
    assert!(
        (l / expected() - 1.0).abs() < 0.01,
        "path {l} vs {}",
        expected()
    );
}

#[test]
fn sppm_matches_the_analytic_room() {
    let photon = PhotonSettings {
        photons: 20_000,
        passes: 24,
        ..PhotonSettings::default()
    };
    let l = mean_radiance(&room(), Method::Sppm, photon, 1);
    // The photon half (ρ/(1−ρ) − ρ = 0.5 of L... i.e. half of L) comes from 480k photons
    // gathered over 432 pixels; Monte Carlo error ≈ 0.5 %, kernel bias 0 (uniform density).
    assert!(
        (l / expected() - 1.0).abs() < 0.02,
        "sppm {l} vs {}",
        expected()
    );
}

#[test]
fn photon_map_with_final_gather_matches_the_analytic_room() {
    let photon = PhotonSettings {
        photons: 200_000,
        ..PhotonSettings::default()
    };
    let l = mean_radiance(&room(), Method::Photon, photon, 16);
    assert!(
        (l / expected() - 1.0).abs() < 0.03,
        "photon {l} vs {}",
        expected()
    );
}

/// A closed white box (a cube seen from inside, albedo ρ) around a point light: every photon
/// stays inside until absorbed, so the flux arriving at the walls summed over all bounces is
/// Φ (1 + ρ + ρ² + …) = Φ/(1 − ρ), whatever the box's shape. The photons stored by the
/// tracer (one per wall hit) must carry exactly that on average: this checks emission,
/// the Lambertian bounce and Russian roulette together.
#[test]
fn photons_in_a_closed_white_box_carry_the_geometric_series_of_the_light_power() {
    use iris::photon::trace::{trace, Roulette, TraceSettings};
    let cube = iris::authoring::shapes::cuboid(Vec3::new(1.0, 0.7, 0.5));
    let white = MaterialDesc {
        base_color: glam::Vec4::new(RHO, RHO, RHO, 1.0),
        ..common::white_lambert()
    };
    let desc = SceneDesc {
        source: "white box".into(),
        meshes: vec![MeshDesc {
            name: "box".into(),
            positions: cube.positions,
            normals: cube.normals,
            indices: cube.indices,
            material: Some(0),
            ..Default::default()
        }],
        materials: vec![white],
        lights: vec![common::white_point_light(Vec3::new(0.3, -0.2, 0.1))],
        ..Default::default()
    };
    let desc = iris::scene::validate::validate(desc).expect("valid scene");
    let scene = Scene::build(desc, iris::accel::Backend::Auto).expect("build");
    let emitter = PhotonEmitter::new(&scene);
    let settings = TraceSettings {
        max_depth: 1000,
        roulette: Roulette::Throughput,
    };
    let n = 200_000u64;
    let mut per_photon = Vec::with_capacity(n as usize);
    for i in 0..n {
        let mut rng = iris::math::Rng::new(&[11, i]);
        let ph = emitter.emit_from(&scene, &mut rng).expect("photon");
        let mut sum = 0.0f64;
        trace::<Vec3>(&scene, &ph, (), &settings, &mut rng, |v, _| {
            sum += v.power.y as f64
        });
        per_photon.push(sum);
    }
    let mean = per_photon.iter().sum::<f64>() / n as f64;
    let var = per_photon.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let se = (var / n as f64).sqrt();
    let phi = 4.0 * std::f64::consts::PI;
    let expected = phi / (1.0 - RHO as f64);
    eprintln!("stored flux per photon {mean:.4} ± {se:.4}, expected Φ/(1−ρ) = {expected:.4}");
    // 5 standard errors (≈ 0.3 % here) plus f32 accumulation.
    assert!(
        (mean - expected).abs() < 5.0 * se + 1e-4 * expected,
        "{mean} vs {expected}"
    );
}
