//! White furnace for the path tracer: inside a uniform white environment (radiance 1),
//! a non-absorbing object must vanish — every pixel renders 1.
//! - A smooth glass sphere (IOR 1.5): every path is a chain of delta bounces weighted
//!   exactly (Fresnel choice, 1/η² in and η² out), so each pixel is 1 up to rounding;
//!   tolerance 1 % per pixel and on the mean.
//! - A white Lambertian sphere (albedo 1, no specular layer): the estimate is noisy but
//!   unbiased; with 64 spp at 24×24 the image mean is within 1 % (σ of the mean ≈ 0.2 %).

mod common;

use glam::Vec3;
use iris::camera::{look_at, Camera};
use iris::integrator::{Integrator, Method};
use iris::render::{render, RenderSettings};
use iris::scene::desc::{CameraDesc, MaterialDesc, Projection};

fn furnace(material: MaterialDesc, spp: u32) -> Vec<Vec3> {
    let scene = common::sphere_in_white_environment(material);
    let cam = CameraDesc {
        name: "c".into(),
        projection: Projection::Perspective {
            yfov: 0.5,
            aspect: None,
        },
        world_from_camera: look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y),
    };
    let settings = RenderSettings {
        width: 24,
        height: 24,
        spp,
        seed: 11,
        threads: 2,
        quiet: true,
    };
    let integrator = Integrator {
        method: Method::Path,
        max_depth: 64,
    };
    render(&scene, &Camera::new(&cam, 24, 24), &integrator, &settings)
        .unwrap()
        .0
        .data
}

#[test]
fn smooth_glass_sphere_vanishes_in_a_white_furnace() {
    let glass = MaterialDesc {
        name: "glass".into(),
        metallic: 0.0,
        roughness: 0.0,
        transmission: 1.0,
        thickness: 1.0,
        ior: 1.5,
        ..Default::default()
    };
    let px = furnace(glass, 16);
    let mean = px.iter().map(|p| p.x as f64).sum::<f64>() / px.len() as f64;
    assert!((mean - 1.0).abs() < 0.01, "mean {mean}");
    for (i, p) in px.iter().enumerate() {
        assert!(
            (p.max_element() - 1.0).abs() < 0.01 && (p.min_element() - 1.0).abs() < 0.01,
            "pixel {i}: {p}"
        );
    }
}

#[test]
fn white_lambertian_sphere_vanishes_in_a_white_furnace() {
    let white = MaterialDesc {
        name: "white".into(),
        metallic: 0.0,
        specular: 0.0,
        ..Default::default()
    };
    let px = furnace(white, 64);
    let mean = px.iter().map(|p| p.x as f64).sum::<f64>() / px.len() as f64;
    assert!((mean - 1.0).abs() < 0.01, "mean {mean}");
    assert!(px.iter().all(|p| p.is_finite()));
}
