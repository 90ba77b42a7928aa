//! The SoA kernel against the scalar path tracer on a glass sphere over a Lambert floor
//! under a point light (agreement), its refusals (qualification) and its determinism.

use super::*;
use crate::accel::Backend;
use crate::authoring::scene::placed;
use crate::authoring::shapes::icosphere;
use crate::image::ImageRgb;
use crate::integrator::{Integrator, Method, PhotonSettings};
use crate::light::Light;
use crate::material::{ImageDesc, MaterialDesc, TextureRef};
use crate::render::{render_batches, Prepass, RenderSettings};
use crate::scene::desc::{CameraDesc, MeshDesc, Projection, SceneDesc};
use glam::Vec3;
use std::sync::Arc;

const W: u32 = 32;
const H: u32 = 24;
const MAX_DEPTH: u32 = 64;

/// A floor quad of half-size 3 at y = 0 facing up.
pub(super) fn floor(material: usize) -> MeshDesc {
    let p = [(-3.0, -3.0), (3.0, -3.0), (3.0, 3.0), (-3.0, 3.0)].map(|(x, z)| Vec3::new(x, 0.0, z));
    MeshDesc {
        name: "floor".into(),
        positions: p.to_vec(),
        indices: vec![[0, 2, 1], [0, 3, 2]],
        material: Some(material),
        ..Default::default()
    }
}

/// The test scene's description with the floor's material `floor_mat` (a pure Lambert
/// lobe unless changed): a glass sphere (η 1.5, radius 0.5, 1280 triangles, smooth normals)
/// resting on a coloured floor.
pub(super) fn desc(floor_mat: MaterialDesc) -> SceneDesc {
    let glass = MaterialDesc::clear_glass("glass", 1.5, 1.0);
    let sphere = placed(
        "sphere",
        icosphere(0.5, 3),
        1,
        Some(Vec3::new(0.0, 0.5, 0.0)),
    );
    SceneDesc {
        source: "kernel test".into(),
        meshes: vec![floor(0), sphere],
        materials: vec![floor_mat, glass],
        ..Default::default()
    }
}

/// The floor: Lambert, albedo (0.8, 0.6, 0.4) (`specular` 0: `make_variant.py --spec0`).
pub(super) fn lambert_floor() -> MaterialDesc {
    MaterialDesc {
        specular: 0.0,
        ..MaterialDesc::diffuse("floor", Vec3::new(0.8, 0.6, 0.4))
    }
}

/// `desc` built with a point light of 30 cd up and to the left.
pub(super) fn build(desc: SceneDesc, backend: Backend) -> Scene {
    let desc = crate::scene::validate::validate(desc).expect("valid");
    let point = Light::Point {
        position: Vec3::new(-1.2, 2.5, -0.6),
        intensity: Vec3::splat(30.0),
        range: None,
    };
    Scene::build_with_lights(desc, backend, vec![point]).expect("build")
}

pub(super) fn camera() -> Camera {
    let desc = CameraDesc {
        name: "test".into(),
        projection: Projection::Perspective {
            yfov: 0.7,
            aspect: None,
        },
        world_from_camera: crate::camera::look_at(
            Vec3::new(0.0, 1.3, 2.6),
            Vec3::new(0.0, 0.35, 0.0),
            Vec3::Y,
        ),
    };
    Camera::new(&desc, W, H)
}

pub(super) fn settings(spp: u32, seed: u64) -> RenderSettings {
    RenderSettings::quiet_rgb((W, H), spp, seed, 2)
}

/// The kernel's image at `width` lanes and its two halves (even and odd samples).
pub(super) fn kernel_image(
    scene: &Scene,
    s: &RenderSettings,
    width: usize,
) -> (ImageRgb, ImageRgb, ImageRgb) {
    let cam = camera();
    let tables = qualify(scene, cam.is_perspective(), false).expect("the test scene qualifies");
    let estimate = |starts: &Starts, jobs: &[Job], out: &mut [Vec3]| {
        estimate_at(
            width,
            &tables,
            scene,
            (starts, jobs),
            (s.seed, MAX_DEPTH),
            out,
        )
    };
    let (film, _) =
        render_batches(&cam, s, None, Prepass::now(), None, estimate).expect("kernel render");
    let (a, b) = film.halves();
    (film.mean(), a, b)
}

/// The scalar path tracer's image and halves.
pub(super) fn scalar_image(scene: &Scene, s: &RenderSettings) -> (ImageRgb, ImageRgb, ImageRgb) {
    // `render_units` takes the kernel when IRIS_KERNEL=soa: the reference would be the
    // kernel itself, so the test refuses to run that way rather than pass.
    assert_ne!(
        std::env::var("IRIS_KERNEL").ok().as_deref(),
        Some("soa"),
        "unset IRIS_KERNEL: the scalar reference would be the kernel"
    );
    let path = Integrator::new(Method::Path, MAX_DEPTH, &PhotonSettings::default()).unwrap();
    let (film, _) = path
        .render_units(scene, &camera(), s, None, None)
        .expect("scalar render");
    let (a, b) = film.halves();
    (film.mean(), a, b)
}

/// Per block of `b`×`b` pixels and channel: the mean and the variance of that mean,
/// estimated from the two halves (each pixel's (h₁ − h₂)²/4, summed, over the pixels²).
fn blocks((img, h1, h2): &(ImageRgb, ImageRgb, ImageRgb), b: u32) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for by in 0..H / b {
        for bx in 0..W / b {
            for c in 0..3 {
                let (mut sum, mut var) = (0.0f64, 0.0f64);
                for y in by * b..(by + 1) * b {
                    for x in bx * b..(bx + 1) * b {
                        let i = (y * W + x) as usize;
                        sum += f64::from(img.data[i][c]);
                        let d = f64::from(h1.data[i][c]) - f64::from(h2.data[i][c]);
                        var += d * d / 4.0;
                    }
                }
                let n = f64::from(b * b);
                out.push((sum / n, var / (n * n)));
            }
        }
    }
    out
}

/// The largest |difference| / σ over the blocks of `b`×`b` pixels, and the image means'
/// difference in standard errors.
pub(super) fn z_scores(
    k: &(ImageRgb, ImageRgb, ImageRgb),
    s: &(ImageRgb, ImageRgb, ImageRgb),
    b: u32,
) -> (f64, f64) {
    let (bk, bs) = (blocks(k, b), blocks(s, b));
    let mut worst = 0.0f64;
    let (mut mk, mut ms, mut vk, mut vs) = (0.0, 0.0, 0.0, 0.0);
    for ((a, va), (c, vc)) in bk.iter().zip(&bs) {
        worst = worst.max((a - c).abs() / (va + vc).sqrt().max(1e-12));
        (mk, ms, vk, vs) = (mk + a, ms + c, vk + va, vs + vc);
    }
    (worst, (mk - ms).abs() / (vk + vs).sqrt())
}

/// The kernel's image agrees with the scalar path tracer's: over 4×4-pixel blocks and
/// channels (144 comparisons), each block mean within 5 σ, σ² the sum of the two block
/// means' variances estimated from each render's halves (a pixel's (h₁ − h₂)²/4); at 512
/// samples per pixel the estimate has 16·256 pixel-halves behind it per block. Under a
/// normal error 5 σ fails by chance with probability 144 · 5.7e-7 ≈ 1e-4. The image mean
/// agrees within 4 standard errors. Dropping the shadow ray (the sphere's shadow lit),
/// the Fresnel weight or the refraction moves blocks by tens of σ (checked by breaking
/// the kernel so, BENCHMARKS.md).
#[test]
fn the_kernel_agrees_with_the_scalar_path_tracer() {
    let scene = build(desc(lambert_floor()), Backend::Auto);
    let k = kernel_image(&scene, &settings(512, 11), 16);
    let s = scalar_image(&scene, &settings(512, 12));
    let (worst, mean) = z_scores(&k, &s, 4);
    assert!(worst < 5.0, "a block differs by {worst:.2} σ");
    assert!(
        mean < 4.0,
        "the image means differ by {mean:.2} standard errors"
    );
    let lit =
        k.0.data
            .iter()
            .map(|p| p.max_element())
            .fold(0.0f32, f32::max);
    assert!(lit > 0.05, "the image is dark: {lit}");
}

/// The same seed gives the same image, bit for bit, at 16 and 8 lanes and on two runs.
#[test]
fn the_same_seed_gives_the_same_image() {
    let scene = build(desc(lambert_floor()), Backend::Auto);
    let s = settings(8, 5);
    let a = kernel_image(&scene, &s, 16).0;
    let b = kernel_image(&scene, &s, 16).0;
    let c = kernel_image(&scene, &s, 8).0;
    assert!(a.data == b.data && a.data == c.data);
    let d = kernel_image(&scene, &settings(8, 6), 16).0;
    assert!(a.data != d.data, "another seed gives another image");
}

/// Scenes outside the class are refused with their reason: an emitter with a specular
/// lobe, a texture, a medium (fog), a specular lobe, rough glass, spectral transport.
#[test]
fn scenes_outside_the_class_are_refused_with_the_reason() {
    let cam = camera();
    let refused =
        |d: SceneDesc| qualify(&build(d, Backend::Bvh), cam.is_perspective(), false).unwrap_err();
    let lamp = MaterialDesc::emitter("lamp", Vec3::splat(5.0));
    let e = refused(desc(MaterialDesc {
        name: "floor".into(),
        ..lamp
    }));
    assert!(e.contains("\"floor\" has a specular or metal lobe"), "{e}");
    let textured = MaterialDesc {
        base_color_texture: Some(TextureRef::new(0, 0)),
        ..lambert_floor()
    };
    let image = ImageDesc {
        name: "white".into(),
        width: 1,
        height: 1,
        rgba8: Arc::new(vec![255; 4]),
    };
    let e = refused(SceneDesc {
        images: vec![image],
        ..desc(textured)
    });
    assert!(e.contains("\"floor\" is textured"), "{e}");
    let fog = crate::volume::fog::parse("density=0.3,g=0.3").expect("fog");
    let e = refused(SceneDesc {
        fog: Some(fog),
        ..desc(lambert_floor())
    });
    assert!(e.contains("medium or fog"), "{e}");
    let e = refused(desc(MaterialDesc::diffuse("floor", Vec3::ONE)));
    assert!(e.contains("specular or metal lobe"), "{e}");
    let mut rough = desc(lambert_floor());
    rough.materials[1].roughness = 0.2;
    assert!(refused(rough).contains("rough glass"));
    let scene = build(desc(lambert_floor()), Backend::Bvh);
    assert!(qualify(&scene, cam.is_perspective(), true)
        .unwrap_err()
        .contains("spectral"));
    assert!(qualify(&scene, cam.is_perspective(), false).is_ok());
}

/// The render plan's words for the kernel: which kernel renders and why, or why not.
#[test]
fn the_plan_names_the_kernel_or_the_reason() {
    let scene = build(desc(lambert_floor()), Backend::Bvh);
    let ran = super::plan_text(&scene, true, false).expect("the test scene qualifies");
    assert!(ran.contains("structure-of-arrays kernel") && ran.contains("in expectation"));
    let orthographic = super::plan_text(&scene, false, false).unwrap_err();
    assert!(orthographic.contains("orthographic"), "{orthographic}");
    let spectral = super::plan_text(&scene, true, true).unwrap_err();
    assert!(spectral.contains("spectral"), "{spectral}");
}
