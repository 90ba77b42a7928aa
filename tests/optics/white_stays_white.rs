//! White stays white under spectral transport (issue 4): light of D65 colour (an emitter of
//! RGB (1,1,1), which spectral transport upsamples to D65 of luminance 1) passing through
//! non-dispersive glass onto a white diffuser renders with the chromaticity of D65 within
//! 0.002 in x and y — for a plain glass block (IOR 1.5), for a block with
//! KHR_materials_dispersion 0, and for DispersionTest's dispersion-0 column (the shared
//! Khronos sample, with the other columns removed) under a white environment. A dispersive
//! block (dispersion 1) is rendered too, to show the measure reacts: with the path keeping
//! its hero wavelength only past the block (`Dispersion::split` off) its image has
//! per-pixel colour, the non-dispersive ones do not; with the path tracer's default split
//! into the 4 wavelengths that colour falls to the clear glass's (measured: clear 0.279,
//! hero only 2.40, split 0.282).
//!
//! Tolerances: chromaticity of the image mean within 0.002 (the issue's); per-pixel colour is
//! measured as the largest |channel/mean-of-channels − 1| over pixels brighter than 5 % of
//! the mean — for non-dispersive glass only the 4-wavelength sampling noise remains there
//! (stratified over 256 samples), for the dispersive block the fringes dominate.

use crate::common;

use glam::Vec3;
use iris::accel::Backend;
use iris::camera::{look_at, Camera};
use iris::integrator::path::Dispersion;
use iris::integrator::Integrator;
use iris::material::MaterialDesc;
use iris::render::RenderSettings;
use iris::scene::desc::{CameraDesc, MeshDesc, Projection, SceneDesc};
use iris::scene::Scene;
use iris::spectrum::cie::{chromaticity, linear_srgb_to_xyz};

/// CIE 15:2004, D65 white point (2° observer).
const D65_XY: [f32; 2] = [0.3127, 0.3290];

fn mesh(name: &str, m: iris::authoring::shapes::TriMesh, material: usize) -> MeshDesc {
    m.into_mesh_desc(name, material)
}

/// A white floor, a 0.4-thick glass block above it and a white emitter above both; the
/// camera looks down through the block.
fn block_scene(glass: MaterialDesc) -> Scene {
    let floor = iris::authoring::shapes::ground_plane(3.0, 3.0);
    let block = iris::authoring::shapes::cuboid(Vec3::new(1.0, 0.2, 1.0))
        .transformed(glam::Mat3::IDENTITY, Vec3::new(0.0, 0.6, 0.0));
    let lamp = iris::authoring::shapes::ground_plane(0.8, 0.8).transformed(
        glam::Mat3::from_rotation_x(std::f32::consts::PI),
        Vec3::new(0.3, 3.0, 0.2),
    );
    let white = common::white_lambert();
    let lamp_m = MaterialDesc {
        name: "lamp".into(),
        base_color: glam::Vec4::new(0.0, 0.0, 0.0, 1.0),
        emissive: Vec3::splat(5.0),
        ..Default::default()
    };
    let desc = SceneDesc {
        source: "white block".into(),
        meshes: vec![
            mesh("floor", floor, 0),
            mesh("block", block, 1),
            mesh("lamp", lamp, 2),
        ],
        materials: vec![white, glass, lamp_m],
        ..Default::default()
    };
    Scene::build(
        iris::scene::validate::validate(desc).unwrap(),
        Backend::Auto,
    )
    .unwrap()
}

/// The spectral path tracer's image, split into the 4 wavelengths at smooth dispersive
/// interfaces (the default) or keeping the hero only there.
fn render_spectral(scene: &Scene, cam: &CameraDesc, size: u32, spp: u32, split: bool) -> Vec<Vec3> {
    let settings = RenderSettings {
        width: size,
        height: size,
        spp,
        seed: 5,
        threads: 2,
        quiet: true,
        spectral: true,
        time_limit: None,
        sampler: Default::default(),
        adaptive: None,
        cancel: Default::default(),
        kernel: Default::default(),
    };
    let integrator = Integrator::Path {
        max_depth: 16,
        dispersion: Dispersion {
            spectral_mis: true,
            split,
        },
        polarization: None,
    };
    integrator
        .render(scene, &Camera::new(cam, size, size), &settings)
        .unwrap()
        .0
        .data
}

/// (chromaticity of the image mean, largest per-pixel colour deviation).
fn colour_stats(px: &[Vec3]) -> ([f32; 2], f32) {
    let mean = px.iter().fold(glam::DVec3::ZERO, |a, p| a + p.as_dvec3()) / px.len() as f64;
    let xy = chromaticity(linear_srgb_to_xyz(mean.as_vec3().to_array()));
    let lum = mean.element_sum() / 3.0;
    let worst = px
        .iter()
        .filter(|p| (p.element_sum() / 3.0) as f64 > 0.05 * lum)
        .map(|p| {
            let m = p.element_sum() / 3.0;
            (*p / m - Vec3::ONE).abs().max_element()
        })
        .fold(0f32, f32::max);
    (xy, worst)
}

fn assert_d65(name: &str, xy: [f32; 2]) {
    assert!(
        (xy[0] - D65_XY[0]).abs() < 0.002 && (xy[1] - D65_XY[1]).abs() < 0.002,
        "{name}: chromaticity {xy:?} vs D65 {D65_XY:?}"
    );
}

#[test]
fn d65_light_through_a_glass_block_stays_white() {
    let cam = CameraDesc {
        name: "top".into(),
        projection: Projection::Perspective {
            yfov: 0.6,
            aspect: None,
        },
        world_from_camera: look_at(Vec3::new(0.0, 2.5, 0.01), Vec3::ZERO, Vec3::Y),
    };
    let glass = |name: &str, dispersion: f32| MaterialDesc {
        thickness: 0.4,
        dispersion,
        ..common::clear_glass(name, 1.5)
    };
    let mut worst_clear = 0f32;
    for (name, d) in [("ior 1.5", 0.0), ("KHR dispersion 0", 0.0)] {
        let px = render_spectral(&block_scene(glass(name, d)), &cam, 24, 256, true);
        let (xy, worst) = colour_stats(&px);
        eprintln!("{name}: xy {xy:?}, worst pixel colour {worst}");
        assert_d65(name, xy);
        worst_clear = worst_clear.max(worst);
    }
    let dispersive = block_scene(glass("dispersion 1", 1.0));
    let (_, hero) = colour_stats(&render_spectral(&dispersive, &cam, 24, 256, false));
    let (xy, split) = colour_stats(&render_spectral(&dispersive, &cam, 24, 256, true));
    eprintln!("dispersion 1: xy {xy:?}, worst pixel colour hero only {hero}, split {split}");
    assert!(
        hero > 2.0 * worst_clear,
        "dispersive block shows no more colour ({hero}) than clear glass ({worst_clear})"
    );
    assert!(
        split < 0.5 * hero,
        "the split leaves as much colour ({split}) as the hero alone ({hero})"
    );
}

#[test]
fn dispersion_test_zero_column_stays_white() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let path = shared.join("khronos/DispersionTest/DispersionTest.glb");
    let mut desc = iris::load::load_scene(&path).unwrap();
    // Keep the backdrop, the labels and the dispersion-0 prisms (nodes `Prism_IOR<n>_D1`;
    // mesh names read `node 4 "Prism_IOR1.0_D3" mesh 4 "Prism" primitive 0`).
    let before = desc.meshes.len();
    desc.meshes
        .retain(|m| !m.name.contains("\"Prism_") || m.name.contains("_D1\""));
    assert_eq!(
        before - desc.meshes.len(),
        20,
        "expected 20 dispersive prisms removed"
    );
    let desc = SceneDesc {
        environment_light: Some(iris::light::env::Environment::Uniform {
            radiance: Vec3::ONE,
        }),
        ..desc
    };
    let scene = Scene::build(desc, Backend::Auto).unwrap();
    // Look straight at the column (x ≈ −0.05 m in the file) from the front.
    let cam = CameraDesc {
        name: "front".into(),
        projection: Projection::Perspective {
            yfov: 0.35,
            aspect: None,
        },
        world_from_camera: look_at(
            Vec3::new(-0.05, 0.0, 0.25),
            Vec3::new(-0.05, 0.0, 0.0),
            Vec3::Y,
        ),
    };
    let px = render_spectral(&scene, &cam, 24, 256, true);
    let (xy, worst) = colour_stats(&px);
    eprintln!("DispersionTest D1 column: xy {xy:?}, worst pixel colour {worst}");
    assert_d65("DispersionTest dispersion-0 column", xy);
}
