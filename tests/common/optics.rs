//! Scene pieces and renders shared by the polarization tests (`tests/optics/polarization.rs`,
//! `tests/photon/polarized_photons.rs`): polarizer sheets, emitters, glass and crystal materials,
//! orthographic cameras, the polarized path tracer at a fixed seed.

use glam::Vec3;
use iris::accel::Backend;
use iris::authoring::shapes::{ground_plane, quarter_turn_x};
use iris::camera::{look_at, Camera};
use iris::image::ImageRgb;
use iris::integrator::path::polarized::Polarization;
use iris::integrator::Integrator;
use iris::light::env::Environment;
use iris::material::{CrystalDesc, CrystalOptics, MaterialDesc};
use iris::render::RenderSettings;
use iris::scene::desc::{CameraDesc, Projection, SceneDesc};
use iris::scene::Scene;

/// Spectral render settings at `size`² and `spp`, seed 11, all threads.
pub fn settings(size: u32, spp: u32) -> RenderSettings {
    RenderSettings {
        spectral: true,
        ..super::render_settings((size, size), spp, 11, 0)
    }
}

pub fn polarized(
    scene: &Scene,
    cam: &CameraDesc,
    polarizer: Option<f32>,
    size: u32,
    spp: u32,
) -> ImageRgb {
    let integrator = Integrator::Path {
        max_depth: 32,
        dispersion: iris::integrator::path::Dispersion::ALL,
        polarization: Some(Polarization {
            polarizer: polarizer.map(f32::to_radians),
        }),
    };
    integrator
        .render(scene, &Camera::new(cam, size, size), &settings(size, spp))
        .expect("render")
        .0
}

pub fn ortho(eye: Vec3, target: Vec3, up: Vec3, half: f32) -> CameraDesc {
    CameraDesc {
        name: "ortho".into(),
        projection: Projection::Orthographic {
            xmag: half,
            ymag: half,
        },
        world_from_camera: look_at(eye, target, up),
    }
}

/// A 4×4 wall at depth `z` facing the camera on +z.
pub fn wall(z: f32) -> iris::authoring::shapes::TriMesh {
    ground_plane(2.0, 2.0).transformed(quarter_turn_x(), Vec3::new(0.0, 0.0, z))
}

/// An ideal polarizer sheet with its transmission axis along `axis`.
pub fn sheet(axis: Vec3) -> MaterialDesc {
    MaterialDesc {
        name: "sheet".into(),
        metallic: 0.0,
        transmission: 1.0,
        ior: 1.0,
        polarizer: Some(axis),
        ..Default::default()
    }
}

pub fn emitter() -> MaterialDesc {
    MaterialDesc {
        name: "light".into(),
        base_color: glam::Vec4::new(0.0, 0.0, 0.0, 1.0),
        metallic: 0.0,
        emissive: Vec3::ONE,
        double_sided: true,
        ..Default::default()
    }
}

pub fn glass(ior: f32) -> MaterialDesc {
    super::clear_glass("glass", ior)
}

pub fn crystal(name: &str, optics: CrystalOptics, axis: Vec3) -> MaterialDesc {
    MaterialDesc {
        name: name.into(),
        crystal: Some(CrystalDesc::oriented(optics, axis, None).expect("axis")),
        ..glass(1.6)
    }
}

pub fn build(desc: SceneDesc, env: Option<f32>) -> Scene {
    let desc = SceneDesc {
        environment_light: env.map(|r| Environment::Uniform {
            radiance: Vec3::splat(r),
        }),
        ..iris::scene::validate::validate(desc).expect("valid scene")
    };
    Scene::build(desc, Backend::Auto).expect("build")
}

pub fn mean(img: &ImageRgb) -> Vec3 {
    img.data.iter().copied().sum::<Vec3>() / img.data.len() as f32
}

pub fn luminance(v: Vec3) -> f32 {
    0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z
}
