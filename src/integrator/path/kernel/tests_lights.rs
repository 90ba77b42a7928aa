//! The SoA kernel against the scalar path tracer where light has an area or lies at
//! infinity, and through absorbing glasses: an emissive quad over a glass sphere on a
//! Lambert floor (emission met with MIS, the quad sampled for next-event estimation), the
//! same under a uniform environment, two absorbing glasses of different index under a point
//! light (Beer–Lambert, several dielectrics); and what is still refused.

use super::tests::{
    assert_agrees, build, camera, desc, floor, kernel_image, lambert_floor, scalar_image, settings,
    Halves,
};
use super::*;
use crate::accel::Backend;
use crate::authoring::scene::placed;
use crate::authoring::shapes::icosphere;
use crate::image::ImageRgb;
use crate::light::env::Environment;
use crate::material::MaterialDesc;
use crate::render::RenderSettings;
use crate::scene::desc::{MeshDesc, SceneDesc};
use glam::Vec3;

/// A quad of half-size `h` centred at `c`, facing down (−y): the test floor (half-size 3,
/// facing up) scaled, moved and turned over.
fn lamp_quad(c: Vec3, h: f32, material: usize) -> MeshDesc {
    let mut q = floor(material);
    q.name = "lamp".into();
    q.positions.iter_mut().for_each(|p| *p = c + *p * (h / 3.0));
    q.indices.iter_mut().for_each(|t| t.swap(1, 2));
    q
}

/// The floor, the glass sphere and a single-sided black Lambert quad emitting (6, 5, 4)
/// down onto them from the upper left, lit by nothing else.
pub(super) fn lamp_scene(environment: Option<Environment>) -> Scene {
    let lamp = MaterialDesc {
        specular: 0.0,
        ..MaterialDesc::emitter("lamp", Vec3::new(6.0, 5.0, 4.0))
    };
    lamp_scene_with((desc(lambert_floor()), lamp), environment)
}

/// [`lamp_scene`] over the scene `d` (the floor and the sphere in their materials) with the
/// lamp's material `lamp`.
pub(super) fn lamp_scene_with(
    (mut d, lamp): (SceneDesc, MaterialDesc),
    environment: Option<Environment>,
) -> Scene {
    d.meshes.push(lamp_quad(
        Vec3::new(-0.7, 1.0, -0.3),
        0.35,
        d.materials.len(),
    ));
    d.materials.push(lamp);
    d.environment_light = environment;
    let d = crate::scene::validate::validate(d).expect("valid");
    Scene::build_with_lights(d, Backend::Auto, Vec::new()).expect("build")
}

/// The kernel's image of `scene` and the scalar path tracer's agree (as
/// [`super::tests`]'s agreement test: every 4×4 block within 5 σ, the image mean within 4
/// standard errors), the image is lit, and at the same seed it is the scalar image up to
/// float rounding (the bound of `the_kernel_equals_the_scalar_path_tracer_at_the_same_seed`),
/// in RGB and in spectral transport.
fn agrees(scene: &Scene) {
    for spectral in [false, true] {
        let (k, s, same_seed) = three_images(scene, spectral, 21);
        let what = if spectral {
            "lights, spectral"
        } else {
            "lights"
        };
        assert_agrees(what, (&k, &s, 4), Some(&same_seed));
        let lit = k.0.data.iter().map(|p| p.max_element()).fold(0.0, f32::max);
        assert!(lit > 0.05, "the image is dark: {lit}");
    }
}

/// The kernel's image of `scene` at 256 samples per pixel and seed `seed`, in spectral
/// transport or RGB, the scalar path tracer's at seed + 1 and the scalar image at `seed`.
pub(super) fn three_images(scene: &Scene, spectral: bool, seed: u64) -> (Halves, Halves, ImageRgb) {
    let at = |seed| RenderSettings {
        spectral,
        ..settings(256, seed)
    };
    let k = kernel_image(scene, &at(seed), 16);
    let s = scalar_image(scene, &at(seed + 1));
    (k, s, scalar_image(scene, &at(seed)).0)
}

/// An emissive quad over the glass sphere and the floor: the kernel samples the quad for
/// next-event estimation and adds the emission its paths meet, both weighted by the power
/// heuristic, as the scalar path tracer does. Without the MIS weights (1 on both sides)
/// the floor's direct light doubles; without the emission met at hits the floor loses the
/// BSDF-sampled half of it and the sphere's refracted image of the quad: both fail by far.
#[test]
fn an_area_light_agrees_with_the_scalar_path_tracer() {
    let scene = lamp_scene(None);
    assert!(!scene.area_lights().is_empty());
    agrees(&scene);
}

/// The same under a uniform environment: it lights what the rays escaping to it see
/// (weighted against its next-event samples) and next-event estimation samples it as a
/// third of the light choices.
#[test]
fn an_environment_agrees_with_the_scalar_path_tracer() {
    let env = Environment::Uniform {
        radiance: Vec3::new(0.3, 0.4, 0.5),
    };
    let scene = lamp_scene(Some(env));
    assert_eq!(scene.light_sampler().lights().len(), 2);
    agrees(&scene);
}

/// Two absorbing glass spheres of different index and colour side by side under the test
/// point light: Beer–Lambert along every segment inside either, each refracting against
/// air. Without the transmittance the spheres and their caustic shadows brighten by tens
/// of σ.
#[test]
fn absorbing_glasses_agree_with_the_scalar_path_tracer() {
    let glass = |name: &str, ior: f32, color: Vec3, distance: f32| MaterialDesc {
        attenuation_color: color,
        attenuation_distance: distance,
        ..MaterialDesc::clear_glass(name, ior, 1.0)
    };
    let sphere = |x: f32, m: usize| {
        placed(
            "sphere",
            icosphere(0.42, 3),
            m,
            Some(Vec3::new(x, 0.42, 0.0)),
        )
    };
    let d = SceneDesc {
        source: "kernel test".into(),
        meshes: vec![floor(0), sphere(-0.5, 1), sphere(0.5, 2)],
        materials: vec![
            lambert_floor(),
            glass("blue", 1.5, Vec3::new(0.3, 0.6, 0.9), 0.5),
            glass("amber", 1.8, Vec3::new(0.9, 0.5, 0.2), 0.7),
        ],
        ..Default::default()
    };
    let scene = build(d, Backend::Auto);
    assert!(scene.materials()[1].absorbs() && scene.materials()[2].absorbs());
    agrees(&scene);
}

/// Still refused, with the reason: glass meshes whose bounding boxes overlap (a sphere in
/// a sphere: one volume might lie inside the other).
#[test]
fn nested_glass_is_refused_with_the_reason() {
    let mut d = desc(lambert_floor());
    let inner = placed(
        "inner",
        icosphere(0.2, 2),
        1,
        Some(Vec3::new(0.0, 0.5, 0.0)),
    );
    d.meshes.push(inner);
    let scene = build(d, Backend::Bvh);
    let e = qualify(&scene, camera().is_perspective(), false).unwrap_err();
    assert!(e.contains("overlapping bounding boxes"), "{e}");
    let apart = lamp_scene(None);
    assert!(qualify(&apart, true, false).is_ok());
}
