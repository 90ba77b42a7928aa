//! The SoA kernel against the scalar path tracer on a glass sphere over a Lambert floor
//! under a point light (agreement), its refusals (qualification) and its determinism.

use super::super::Dispersion;
use super::features::Shade;
use super::*;
use crate::accel::Backend;
use crate::authoring::scene::placed;
use crate::authoring::shapes::icosphere;
use crate::image::ExactImage;
use crate::image::ImageRgb;
use crate::integrator::{Integrator, Method, PhotonSettings};
use crate::light::env::Environment;
use crate::light::Light;
use crate::material::{ImageDesc, MaterialDesc, TextureRef};
use crate::render::{render_batches, Film, Kernel, Prepass, RenderSettings};
use crate::scene::desc::{CameraDesc, MeshDesc, Projection, SceneDesc};
use glam::Vec3;
use std::ops::Range;
use std::sync::Arc;

pub(super) const W: u32 = 32;
pub(super) const H: u32 = 24;
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

/// The path tracer's scalar vertex with `max_depth` and `dispersion`.
pub(super) fn path_vertex(max_depth: u32, dispersion: Dispersion) -> OnScalar<Dispersion> {
    OnScalar {
        max_depth,
        strategy: dispersion,
    }
}

/// The path tracer's rules over `vertex`, in spectral transport or RGB.
pub(super) fn path_rules(vertex: &OnScalar<Dispersion>, spectral: bool) -> Rules<'_> {
    if spectral {
        Rules::Spectral(vertex, None)
    } else {
        Rules::Rgb(vertex)
    }
}

pub(super) fn settings(spp: u32, seed: u64) -> RenderSettings {
    RenderSettings::quiet_rgb((W, H), spp, seed, 2)
}

/// An image and its two halves (even and odd samples).
pub(super) type Halves = (ImageRgb, ImageRgb, ImageRgb);

/// The kernel's film through `cam` at `width` lanes of the samples `range` (all: `None`).
fn kernel_film(
    scene: &Scene,
    cam: &Camera,
    (s, width): (&RenderSettings, usize),
    range: Option<Range<u64>>,
) -> Film {
    let tables = qualify(scene, cam.is_perspective(), s.spectral).expect("the scene qualifies");
    let path = path_vertex(MAX_DEPTH, Dispersion::ALL);
    let rules = path_rules(&path, s.spectral);
    let estimate = |starts: &Starts, jobs: &[Job], out: &mut [Vec3]| {
        estimate_at(width, &tables, scene, (starts, jobs), &rules, out)
    };
    let (film, _) =
        render_batches(cam, s, range, Prepass::now(), None, estimate).expect("kernel render");
    film
}

/// The kernel's image at `width` lanes and its halves, through the test camera.
pub(super) fn kernel_image(scene: &Scene, s: &RenderSettings, width: usize) -> Halves {
    kernel_image_through(scene, &camera(), s, width)
}

/// The kernel's image through `cam` at `width` lanes and its halves.
pub(super) fn kernel_image_through(
    scene: &Scene,
    cam: &Camera,
    s: &RenderSettings,
    width: usize,
) -> Halves {
    let film = kernel_film(scene, cam, (s, width), None);
    let (a, b) = film.halves();
    (film.mean(), a, b)
}

/// The scalar path tracer's image and halves through the test camera.
pub(super) fn scalar_image(scene: &Scene, s: &RenderSettings) -> Halves {
    scalar_image_through(scene, &camera(), s)
}

/// The scalar path tracer's image through `cam` and its halves.
pub(super) fn scalar_image_through(scene: &Scene, cam: &Camera, s: &RenderSettings) -> Halves {
    let s = &RenderSettings {
        kernel: Kernel::Scalar,
        ..s.clone()
    };
    let path = Integrator::new(Method::Path, MAX_DEPTH, &PhotonSettings::default()).unwrap();
    let (film, _) = path
        .render_units(scene, cam, s, None, None)
        .expect("scalar render");
    let (a, b) = film.halves();
    (film.mean(), a, b)
}

/// Per block of `b`×`b` pixels and channel: the mean and the variance of that mean,
/// estimated from the two halves (each pixel's (h₁ − h₂)²/4, summed, over the pixels²).
fn blocks((img, h1, h2): &Halves, b: u32) -> Vec<(f64, f64)> {
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
fn z_scores(k: &Halves, s: &Halves, b: u32) -> (f64, f64) {
    let (bk, bs) = (blocks(k, b), blocks(s, b));
    let mut worst = 0.0f64;
    let (mut mk, mut ms, mut vk, mut vs) = (0.0, 0.0, 0.0, 0.0);
    for ((a, va), (c, vc)) in bk.iter().zip(&bs) {
        worst = worst.max((a - c).abs() / (va + vc).sqrt().max(1e-12));
        (mk, ms, vk, vs) = (mk + a, ms + c, vk + va, vs + vc);
    }
    (worst, (mk - ms).abs() / (vk + vs).sqrt().max(1e-12))
}

/// Asserts that the kernel's image `k` agrees with the scalar path tracer's `s` (another
/// seed) over `b`×`b`-pixel blocks — every block and channel within 5 σ ([`z_scores`]), the
/// image means within 4 standard errors — and, given the scalar image at `k`'s own seed
/// (`same`), that the two are equal up to float rounding (at most 7 pixels further apart
/// than [`differing_pixels`] allows). `what` names the case in the failure.
pub(super) fn assert_agrees(
    what: &str,
    (k, s, b): (&Halves, &Halves, u32),
    same: Option<&ImageRgb>,
) {
    let (worst, mean) = z_scores(k, s, b);
    assert!(worst < 5.0, "{what}: a block differs by {worst:.2} σ");
    assert!(
        mean < 4.0,
        "{what}: the means differ by {mean:.2} standard errors"
    );
    if let Some(same) = same {
        let n = differing_pixels(&k.0, same);
        assert!(
            n <= 7,
            "{what}: {n} pixels differ from the scalar image at the same seed"
        );
    }
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
    assert_agrees("glass sphere", (&k, &s, 4), None);
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

/// Scenes outside the class are refused with their reason: a medium (fog); materials
/// outside the kernel's lobes (a texture, a clearcoat, rough glass) are not refused but
/// named for the scalar vertex; the glTF BRDF with its specular or metal part (an emitter
/// with the default specular lobe, a metal) is the kernel's glossy lobe, and so is an
/// environment, in RGB and spectral transport.
#[test]
fn scenes_outside_the_class_are_refused_with_the_reason() {
    let cam = camera();
    let tables = |d: SceneDesc| qualify(&build(d, Backend::Bvh), cam.is_perspective(), false);
    let refused = |d: SceneDesc| tables(d).unwrap_err();
    let lamp = MaterialDesc::emitter("lamp", Vec3::splat(5.0));
    let t = tables(desc(MaterialDesc {
        name: "floor".into(),
        ..lamp
    }))
    .expect("an emitter with a specular lobe is the kernel's");
    assert!(t.scalar.is_empty() && t.shades[0] == Shade::Glossy);
    assert!(!t.plain(), "a glossy floor takes the full loop");
    let metal = MaterialDesc {
        metallic: 1.0,
        roughness: 0.4,
        specular: 0.0,
        ..lambert_floor()
    };
    let t = tables(desc(metal)).expect("a metal floor");
    assert!(t.scalar.is_empty() && t.shades[0] == Shade::Glossy);
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
    let t = tables(SceneDesc {
        images: vec![image],
        ..desc(textured)
    })
    .expect("a textured floor goes to the scalar vertex");
    assert_eq!(t.shades[0], Shade::Scalar);
    assert!(
        t.scalar[0].contains("\"floor\" is textured"),
        "{:?}",
        t.scalar
    );
    let fog = crate::volume::fog::parse("density=0.3,g=0.3").expect("fog");
    let e = refused(SceneDesc {
        fog: Some(fog),
        ..desc(lambert_floor())
    });
    assert!(e.contains("medium or fog"), "{e}");
    let t = tables(SceneDesc {
        environment_light: Some(Environment::Uniform {
            radiance: Vec3::ONE,
        }),
        ..desc(lambert_floor())
    })
    .expect("an environment is the kernel's");
    assert!(t.scalar.is_empty(), "{:?}", t.scalar);
    let t = tables(desc(super::tests_handoff::coated_floor())).expect("scalar floor");
    assert!(
        t.scalar[0].contains("\"floor\" has a clearcoat or sheen layer"),
        "{:?}",
        t.scalar
    );
    let t = tables(rough_sphere()).expect("a rough sphere");
    assert!(
        matches!(t.shades[0], Shade::Lambert(_)) && t.shades[1] == Shade::RoughGlass { eta: 1.5 }
    );
    assert!(t.scalar.is_empty(), "{:?}", t.scalar);
    let t = tables(rough_dispersive_sphere()).expect("scalar sphere");
    assert_eq!(t.shades[1], Shade::Scalar);
    assert!(
        t.scalar[0].contains("is rough dispersive glass"),
        "{:?}",
        t.scalar
    );
    let t = tables(super::tests_handoff::ball_in_glass()).expect("a rough ball in glass");
    assert_eq!(
        (t.shades[1], t.shades[2]),
        (
            Shade::Glass {
                eta: 1.5,
                tint: [1.0; 3],
                dispersive: false
            },
            Shade::Scalar
        )
    );
    assert!(
        t.scalar[0].contains("may lie inside another's"),
        "{:?}",
        t.scalar
    );
    let scene = build(desc(lambert_floor()), Backend::Bvh);
    for spectral in [false, true] {
        let t = qualify(&scene, cam.is_perspective(), spectral);
        assert!(t.is_ok_and(|t| t.scalar.is_empty() && t.spectral == spectral));
    }
}

/// The test scene with a rough glass sphere (roughness 0.2): the kernel's glossy lanes.
pub(super) fn rough_sphere() -> SceneDesc {
    let mut d = desc(lambert_floor());
    d.materials[1].roughness = 0.2;
    d
}

/// [`rough_sphere`] of a dispersive glass (Abbe 40): the scalar vertex's.
pub(super) fn rough_dispersive_sphere() -> SceneDesc {
    let mut d = rough_sphere();
    d.materials[1].dispersion = 0.5;
    d
}

/// The render plan's words for the kernel: which kernel renders and why, or why not.
#[test]
fn the_plan_names_the_kernel_or_the_reason() {
    let scene = build(desc(lambert_floor()), Backend::Bvh);
    let ran = super::plan_text(&scene, (true, false), false).expect("the test scene qualifies");
    assert!(ran.contains("structure-of-arrays kernel") && ran.contains("in expectation"));
    assert!(
        ran.contains("no emitter, environment, absorption, glossy or hand-over code"),
        "{ran}"
    );
    let rough = super::plan_text(&build(rough_sphere(), Backend::Bvh), (true, false), false);
    let rough = rough.expect("a rough sphere qualifies");
    assert!(
        rough.contains("the full loop") && !rough.contains("scalar vertex ("),
        "{rough}"
    );
    let orthographic = super::plan_text(&scene, (false, false), false).unwrap_err();
    assert!(orthographic.contains("orthographic"), "{orthographic}");
    let spectral = super::plan_text(&scene, (true, true), false).expect("qualifies in spectral");
    assert!(spectral.contains("4 wavelengths a lane"), "{spectral}");
    assert!(ran.contains("linear RGB"), "{ran}");
    let hybrid = super::plan_text(&scene, (true, false), true).expect("qualifies");
    assert!(hybrid.contains("the full loop"), "{hybrid}");
}

/// The pixels of the kernel's image of `scene` (16 lanes) that differ from the scalar path
/// tracer's at the same settings `s` ([`differing_pixels`]).
pub(super) fn same_seed_difference(scene: &Scene, s: &RenderSettings) -> usize {
    differing_pixels(&kernel_image(scene, s, 16).0, &scalar_image(scene, s).0)
}

/// The pixels of `a` whose relative difference from `b` exceeds 1e-4 in some channel
/// (relative to `b`'s largest channel, at least 1e-3).
pub(super) fn differing_pixels(a: &ImageRgb, b: &ImageRgb) -> usize {
    far_pixels(a, b, 1e-4)
}

/// Asserts that the kernel's image `k` is the scalar image at the same seed `same` where
/// glossy lobes magnify rounding (`what` names the case). A flipped decision (a roulette, a
/// Fresnel choice, an edge) moves a pixel by a sample's share, over 1e-2 at 128 samples
/// and more: at most 7 such pixels, 4 × 7 in `spectral` transport (a split sample is up to
/// 4 sub-paths, each passing as many thresholds as an RGB sample). Rounding alone stays
/// below 1e-4 except where a glossy lobe (a GGX floor, rough glass) magnifies a
/// direction's last bits into its narrow peak (gem_caustics.glb: 2–6 % of its pixels
/// beyond 1e-4, none beyond 1e-2, on either backend): at most 10 % beyond 1e-4, which a
/// bias of that size in every pixel would exceed.
pub(super) fn assert_near_same_seed(what: &str, (k, same): (&ImageRgb, &ImageRgb), spectral: bool) {
    let bound = if spectral { 28 } else { 7 };
    let flips = far_pixels(k, same, 1e-2);
    let fine = far_pixels(k, same, 1e-4);
    assert!(
        flips <= bound && fine <= (W * H) as usize / 10,
        "{what}: {flips} pixels beyond 1e-2 and {fine} beyond 1e-4 from the scalar image at \
         the same seed"
    );
}

/// The pixels of `a` whose difference from `b` exceeds `tol` relative to `b`'s largest
/// channel (at least 1e-3) in some channel.
pub(super) fn far_pixels(a: &ImageRgb, b: &ImageRgb, tol: f32) -> usize {
    let far =
        |(p, q): (&Vec3, &Vec3)| (*p - *q).abs().max_element() > tol * q.max_element().max(1e-3);
    a.data.iter().zip(&b.data).filter(|&pq| far(pq)).count()
}

/// At the same seed the kernel's image is the scalar path tracer's up to float rounding:
/// each sample reads the same numbers (the camera ray from the same pixel dimensions, each
/// vertex's decisions from the same dimensions of the schedule, or the same draws of the
/// independent stream) and maps them the same way, so only the kernel's own arithmetic
/// differs (its polynomial sine and cosine, under 4e-7; the hit record's and the
/// products' rounding). With f32's 6e-8 per operation over the few hundred operations of a
/// path, a pixel's relative difference stays far below 1e-4; a decision flipped by
/// rounding (a roulette or Fresnel threshold, a ray on an edge) would move a pixel by a
/// whole sample's share, so at most 1 % of the pixels (7 of 768) may differ more. With both
/// samplers, at 1 sample per pixel (the pixel centre) and 16.
#[test]
fn the_kernel_equals_the_scalar_path_tracer_at_the_same_seed() {
    let scene = build(desc(lambert_floor()), Backend::Auto);
    let mut counts = Vec::new();
    for sampler in crate::sampler::SamplerKind::ALL {
        for spp in [1u32, 16] {
            let s = RenderSettings {
                sampler,
                ..settings(spp, 11)
            };
            counts.push((sampler, spp, same_seed_difference(&scene, &s)));
        }
    }
    assert!(
        counts.iter().all(|c| c.2 <= 7),
        "pixels that differ (sampler, spp, count): {counts:?}"
    );
}

/// Shards of a kernel render merge into the whole render bit for bit: a job's estimate
/// depends on the job alone, not on the batch it is in (its camera ray is traced in
/// another coherent packet in a shard, its bounces in other packets), at 16 and 8 lanes.
/// Shards in any order; the last one is a single sample per pixel, so every packet of its
/// camera rays holds other jobs than in the whole render.
#[test]
fn shards_of_a_kernel_render_merge_into_the_whole() {
    let scene = build(desc(lambert_floor()), Backend::Auto);
    let s = settings(13, 3);
    for width in [16, 8] {
        let whole = kernel_film(&scene, &camera(), (&s, width), None);
        let mut merged = ExactImage::new(W, H);
        for range in [7..13, 0..6, 6..7] {
            merged.add(&kernel_film(&scene, &camera(), (&s, width), Some(range)).exact());
        }
        assert_eq!(merged, whole.exact(), "{width} lanes");
        assert_eq!(merged.mean(), whole.mean());
    }
}

/// The scene's class picks the loop ([`super::class`]): the glass sphere under a point light
/// is `Plain`, a rough sphere (glossy lanes), an absorbing one or an environment are not; and
/// the `Plain` loop's image is the `Full` loop's bit for bit on a plain scene (the features
/// it leaves out would add nothing there), so the specialisation only removes work.
#[test]
fn the_scene_class_picks_the_loop_and_changes_nothing() {
    let plain = build(desc(lambert_floor()), Backend::Auto);
    let cam = camera();
    let tables = |s: &Scene| qualify(s, true, false).expect("qualifies");
    assert!(tables(&plain).plain());
    assert!(!tables(&build(rough_sphere(), Backend::Bvh)).plain());
    let mut absorbing = desc(lambert_floor());
    absorbing.materials[1].attenuation_distance = 1.0;
    absorbing.materials[1].attenuation_color = Vec3::new(0.5, 0.8, 0.9);
    assert!(!tables(&build(absorbing, Backend::Bvh)).plain());
    let lit = SceneDesc {
        environment_light: Some(Environment::Uniform {
            radiance: Vec3::ONE,
        }),
        ..desc(lambert_floor())
    };
    assert!(!tables(&build(lit, Backend::Bvh)).plain());
    let t = tables(&plain);
    let s = settings(8, 4);
    let path = path_vertex(MAX_DEPTH, Dispersion::ALL);
    let rules = path_rules(&path, false);
    let image = |full: bool| {
        let estimate = |starts: &Starts, jobs: &[Job], out: &mut [Vec3]| {
            let op = Run {
                tables: &t,
                scene: &plain,
                run: (starts, jobs),
                rules: &rules,
                out,
            };
            if full {
                op.dispatch::<16, 3, class::Full>()
            } else {
                op.dispatch::<16, 3, class::Plain>()
            }
        };
        let (film, _) =
            render_batches(&cam, &s, None, Prepass::now(), None, estimate).expect("kernel render");
        film.exact()
    };
    assert_eq!(image(true), image(false));
}
