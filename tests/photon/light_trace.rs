//! Light tracing of the hybrid's caustic paths (`--caustics mixed`,
//! [`iris::integrator::light_trace`]): the splats and the map split the caustic-origin
//! paths by how the camera path reaches its first non-delta vertex, so every path is
//! counted once:
//! - the pinhole importance: a point light's direct light splatted onto a diffuse plane
//!   equals the path tracer's next-event estimate of it;
//! - the analytic room lit through glass (all its light caustic-origin) is reproduced;
//! - under a small area light mixed agrees with the plain path tracer;
//! - under a point light mixed and map (two estimators of the same paths) agree on a
//!   caustic seen directly, and a caustic seen only through glass is the map's in both
//!   (the images are identical);
//! - the white furnace is still 1, and the image is the same on 1 and 3 threads.

use crate::common;

use glam::Vec3;
use iris::camera::{look_at, Camera};
use iris::image::ImageRgb;
use iris::integrator::light_trace::Splatter;
use iris::integrator::{CausticMode, Integrator, Method, PhotonSettings};
use iris::material::MaterialDesc;
use iris::photon::emit::PhotonEmitter;
use iris::photon::trace::{self, Roulette, TraceSettings};
use iris::render::RenderSettings;
use iris::scene::desc::{CameraDesc, LightDesc, MeshDesc, Projection, SceneDesc};
use iris::scene::Scene;

const W: u32 = 48;
const H: u32 = 36;

fn settings(spp: u32, seed: u64, threads: usize) -> RenderSettings {
    common::render_settings((W, H), spp, seed, threads)
}

fn photons(n: u64, mode: CausticMode) -> PhotonSettings {
    PhotonSettings {
        photons: n,
        caustic_mode: mode,
        ..PhotonSettings::default()
    }
}

fn render_depth(
    scene: &Scene,
    cam: &CameraDesc,
    method: Method,
    max_depth: u32,
    s: &RenderSettings,
    photon: PhotonSettings,
) -> ImageRgb {
    let integrator = Integrator::new(method, max_depth, &photon).expect("a resolved method");
    let (img, _) = integrator
        .render(scene, &Camera::new(cam, s.width, s.height), s)
        .unwrap();
    assert!(img.data.iter().all(|p| p.is_finite()));
    img
}

fn render(
    scene: &Scene,
    cam: &CameraDesc,
    method: Method,
    s: &RenderSettings,
    photon: PhotonSettings,
) -> ImageRgb {
    render_depth(scene, cam, method, 32, s, photon)
}

use common::{blocks, mean, relative_rmse};

/// [`common::caustic_region`] of this file's image size.
fn caustic_region(b: &[f64]) -> (Vec<usize>, f64) {
    common::caustic_region(b, ((W / 4) as i32, (H / 4) as i32))
}

fn region_sum(b: &[f64], region: &[usize]) -> f64 {
    region.iter().map(|&i| b[i]).sum()
}

fn build(desc: SceneDesc) -> Scene {
    let desc = iris::scene::validate::validate(desc).expect("valid scene");
    Scene::build(desc, iris::accel::Backend::Auto).expect("build")
}

fn point_light(position: Vec3) -> LightDesc {
    LightDesc::Point {
        name: "bulb".into(),
        position,
        color: Vec3::ONE,
        intensity: 1.0,
        range: None,
        spectrum: None,
    }
}

fn sphere_mesh(name: &str, radius: f32, material: usize) -> MeshDesc {
    common::mesh(
        name,
        iris::authoring::shapes::icosphere(radius, 5),
        material,
    )
}

fn camera(eye: Vec3, target: Vec3, yfov: f32) -> CameraDesc {
    CameraDesc {
        name: "cam".into(),
        projection: Projection::Perspective { yfov, aspect: None },
        world_from_camera: look_at(eye, target, Vec3::Y),
    }
}

/// W_e: a point light (I = 1) 1 m above a white Lambertian floor, seen from above at an
/// angle. Its direct light splatted by [`Splatter::connect`] (the photons' first vertices,
/// 1.6 M photons, the light-tracing code path of the hybrid) against the path tracer's
/// next-event estimate (`max_depth` 1: exact per camera ray, 16 jittered rays per pixel):
/// both estimate the same box-filtered pixels. Measured (2026-12-02): with 400 000
/// photons the means differ by 0.4 % and the block RMSE is 5.5 % (splat noise, ∝ 1/√n:
/// ≈ 2.8 % at 1.6 M). Bounds: mean 1 %, block RMSE 4.5 % — a wrong cos θ power, pixel
/// area or d² moves the mean or tilts the image by more.
#[test]
fn splatted_direct_light_equals_next_event_estimation() {
    let floor = common::mesh("floor", iris::authoring::shapes::ground_plane(1.0, 1.0), 0);
    let scene = build(SceneDesc {
        source: "lit floor".into(),
        meshes: vec![floor],
        materials: vec![common::white_lambert()],
        lights: vec![point_light(Vec3::new(0.3, 1.0, -0.2))],
        ..Default::default()
    });
    let cam = camera(Vec3::new(-0.2, 1.2, 1.6), Vec3::new(0.0, 0.0, -0.1), 0.9);
    let path = render_depth(
        &scene,
        &cam,
        Method::Path,
        1,
        &settings(16, 1, 2),
        photons(0, CausticMode::Map),
    );
    let camera = Camera::new(&cam, W, H);
    let splatter = Splatter::new(&scene, &camera, (W, H), 2, true).expect("a perspective camera");
    let emitter = PhotonEmitter::new(&scene);
    let ts = TraceSettings {
        max_depth: 1,
        roulette: Roulette::Throughput,
    };
    let n = 1_600_000u64;
    let mut img = vec![Vec3::ZERO; (W * H) as usize];
    let mut rays = 0;
    for i in 0..n {
        let mut rng = iris::math::Rng::new(&[7, i]);
        let ph = emitter.emit_from(&scene, &mut rng).expect("a photon");
        trace::trace::<Vec3>(&scene, &ph, (), &ts, &mut rng, |v, l| {
            if v.bounces == 0 {
                if let Some((p, rgb)) = splatter.connect(v, v.power / n as f32, l, &mut rays) {
                    img[p as usize] += rgb;
                }
            }
        });
    }
    let splat = blocks(&ImageRgb {
        data: img,
        ..path.clone()
    });
    let nee = blocks(&path);
    let m_err = mean(&splat) / mean(&nee) - 1.0;
    let err = relative_rmse(&splat, &nee);
    eprintln!(
        "W_e: splat mean {:.5} nee {:.5} ({m_err:+.4}); block RMSE {err:.4}",
        mean(&splat),
        mean(&nee)
    );
    assert!(mean(&nee) > 0.01, "the floor is lit");
    assert!(m_err.abs() < 0.01, "image mean: splats vs NEE {m_err}");
    assert!(err < 0.045, "block RMSE: splats vs NEE {err}");
}

const RHO: f32 = 0.5;

/// tests/photon/hybrid.rs's closed diffuse room (R = 1, ρ = ½) around a point light in a glass
/// ball: L = ρ I / (π R² (1 − ρ)) = 1/π everywhere, all of it caustic-origin light. On the
/// walls seen directly, `light` splats all of it, `mixed` splats the direct half and
/// gathers the later-bounce photons for the rest; the wall seen through the ball is the
/// map's in both. 64 passes of 20 000 photons: ~14 % of the wall is in
/// view, ~2 800 splats a pass (σ of the image mean ≲ 0.5 %). Bound 2 %.
#[test]
fn mixed_renders_the_analytic_room_lit_through_glass() {
    let white = MaterialDesc {
        base_color: glam::Vec4::new(RHO, RHO, RHO, 1.0),
        ..common::white_lambert()
    };
    let scene = build(SceneDesc {
        source: "glass lantern room".into(),
        meshes: vec![sphere_mesh("room", 1.0, 0), sphere_mesh("ball", 0.2, 1)],
        materials: vec![white, common::clear_glass("glass", 1.5)],
        lights: vec![point_light(Vec3::ZERO)],
        ..Default::default()
    });
    let cam = camera(Vec3::new(0.0, 0.0, 0.4), Vec3::new(0.3, -0.2, -1.0), 1.2);
    let expected = (RHO / (std::f32::consts::PI * (1.0 - RHO))) as f64;
    for mode in [CausticMode::Mixed, CausticMode::Light] {
        let img = render(
            &scene,
            &cam,
            Method::Hybrid,
            &settings(64, 5, 2),
            photons(20_000, mode),
        );
        let m = img.data.iter().map(|p| p.y as f64).sum::<f64>() / img.data.len() as f64;
        eprintln!("room ({mode:?}): {m:.5}, expected {expected:.5}");
        assert!(
            (m / expected - 1.0).abs() < 0.02,
            "{mode:?}: {m} vs {expected}"
        );
    }
}

/// Under a 40 × 40 cm lamp (tests/photon/hybrid.rs's agreement test and bounds, at half the
/// samples): mixed (512 passes of 20 000 photons) vs the mean of two 512 spp path renders.
/// Measured at 1024 (2026-12-02): path vs path block RMSE 1.5 %, mixed vs path 0.7 %,
/// caustic region −0.2 %, mean −0.1 %; half the samples raise the noise by √2.
#[test]
fn mixed_agrees_with_the_path_tracer_under_a_small_area_light() {
    let (scene, cam) = common::caustic_sphere(Some(0.2));
    let none = photons(0, CausticMode::Map);
    let path1 = blocks(&render(
        &scene,
        &cam,
        Method::Path,
        &settings(512, 1, 2),
        none,
    ));
    let path2 = blocks(&render(
        &scene,
        &cam,
        Method::Path,
        &settings(512, 2, 2),
        none,
    ));
    let mixed = blocks(&render(
        &scene,
        &cam,
        Method::Hybrid,
        &settings(512, 3, 2),
        photons(20_000, CausticMode::Mixed),
    ));
    let path: Vec<f64> = path1
        .iter()
        .zip(&path2)
        .map(|(a, b)| 0.5 * (a + b))
        .collect();
    let (region, _) = caustic_region(&path);
    let noise = relative_rmse(&path2, &path1);
    let err = relative_rmse(&mixed, &path);
    let c = |b: &[f64]| region_sum(b, &region);
    let c_err = c(&mixed) / c(&path) - 1.0;
    let m_err = mean(&mixed) / mean(&path) - 1.0;
    eprintln!(
        "block RMSE path vs path {noise:.4}, mixed vs path {err:.4}; caustic region {c_err:+.4}; \
         mean {m_err:+.4}"
    );
    assert!(m_err.abs() < 0.01, "image mean: mixed vs path {m_err}");
    assert!(c_err.abs() < 0.06, "caustic region: mixed vs path {c_err}");
    assert!(err < 0.05, "block RMSE: mixed vs path {err}");
}

/// Under a point light the floor's caustic is seen directly: mixed splats it, map gathers
/// it (128 passes of 20 000 photons each; the path tracer cannot see it). The two
/// estimators of the same paths agree on the caustic region within 5 % (the map's kernel
/// blurs the peak, as against SPPM in tests/photon/hybrid.rs) and on the image mean within 2 %.
/// Measured at 256 passes (2026-12-02): region −0.5 %, mean 0.0 %.
#[test]
fn mixed_and_map_agree_on_a_caustic_seen_directly() {
    let (scene, cam) = common::caustic_sphere(None);
    let map = blocks(&render(
        &scene,
        &cam,
        Method::Hybrid,
        &settings(128, 12, 2),
        photons(20_000, CausticMode::Map),
    ));
    let mixed = blocks(&render(
        &scene,
        &cam,
        Method::Hybrid,
        &settings(128, 14, 2),
        photons(20_000, CausticMode::Mixed),
    ));
    let (region, excess) = caustic_region(&map);
    let c = |b: &[f64]| region_sum(b, &region);
    let err = c(&mixed) / c(&map) - 1.0;
    let m_err = mean(&mixed) / mean(&map) - 1.0;
    eprintln!(
        "caustic region: map {:.4} mixed {:.4} ({err:+.4}); excess {excess:.3}; means {m_err:+.4}",
        c(&map),
        c(&mixed)
    );
    assert!(excess > 0.3, "a caustic: {excess}");
    assert!(err.abs() < 0.05, "caustic region: mixed vs map {err}");
    assert!(m_err.abs() < 0.02, "image mean: mixed vs map {m_err}");
}

/// The caustic seen only through glass: a clear slab (5 cm thick, 10 m wide) between the
/// camera and the whole scene. Every camera path reaches its first non-delta vertex
/// through the slab (delta bounces), every connection to the camera is occluded by it, so
/// mixed gathers the map everywhere and splats nothing: its image is map's, bit for bit
/// (both on the scalar vertex: the structure-of-arrays kernel takes map mode only, and its
/// rounding is its own); and the caustic is there.
#[test]
fn a_caustic_seen_through_glass_stays_the_maps() {
    let (desc, cam) = iris::assets::bench::caustic_sphere(None);
    let mut desc = desc;
    let (p, t) = common::cuboid([10.0, 0.05, 10.0], [0.0, 1.05, 0.0]);
    desc.materials.push(common::clear_glass("slab", 1.5));
    desc.meshes.push(MeshDesc {
        name: "slab".into(),
        positions: p.into_iter().map(Vec3::from).collect(),
        indices: t,
        material: Some(desc.materials.len() - 1),
        ..Default::default()
    });
    let scene = build(desc);
    let run = |mode| {
        render(
            &scene,
            &cam,
            Method::Hybrid,
            &RenderSettings {
                kernel: iris::render::Kernel::Scalar,
                ..settings(16, 21, 2)
            },
            photons(20_000, mode),
        )
    };
    let (map, mixed) = (run(CausticMode::Map), run(CausticMode::Mixed));
    let (_, excess) = caustic_region(&blocks(&map));
    eprintln!("through glass: caustic excess {excess:.3}");
    assert!(excess > 0.3, "a caustic through the slab: {excess}");
    assert!(
        mixed.data == map.data,
        "mixed differs from map through glass"
    );
}

/// The white furnace (uniform environment 1, a glass and a white sphere): no caustic light,
/// nothing splatted; still 1 in mixed mode (σ ≈ 0.2 %; bound 1 %).
#[test]
fn white_furnace_renders_one_in_mixed_mode() {
    let white = MaterialDesc {
        base_color: glam::Vec4::new(1.0, 1.0, 1.0, 1.0),
        ..common::white_lambert()
    };
    let mut a = sphere_mesh("glass", 0.4, 0);
    a.positions.iter_mut().for_each(|p| p[0] -= 0.5);
    let mut b = sphere_mesh("white", 0.4, 1);
    b.positions.iter_mut().for_each(|p| p[0] += 0.5);
    let scene = build(SceneDesc {
        source: "furnace".into(),
        meshes: vec![a, b],
        materials: vec![common::clear_glass("glass", 1.5), white],
        environment_light: Some(iris::light::env::Environment::Uniform {
            radiance: Vec3::ONE,
        }),
        ..Default::default()
    });
    let cam = camera(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 0.8);
    let img = render(
        &scene,
        &cam,
        Method::Hybrid,
        &settings(64, 7, 2),
        photons(1000, CausticMode::Mixed),
    );
    let m = img
        .data
        .iter()
        .map(|p| (p.x + p.y + p.z) as f64 / 3.0)
        .sum::<f64>()
        / img.data.len() as f64;
    assert!((m - 1.0).abs() < 0.01, "furnace mean {m}");
}

/// Splats are applied in the map's fixed photon chunks: the image is the same on 1 and 3
/// threads (8 000 photons a pass: two chunks), and differs from map mode's.
#[test]
fn mixed_is_deterministic_across_threads() {
    let (scene, cam) = common::caustic_sphere(None);
    let run = |threads, mode| {
        render(
            &scene,
            &cam,
            Method::Hybrid,
            &settings(4, 9, threads),
            photons(8000, mode),
        )
    };
    let one = run(1, CausticMode::Mixed);
    assert!(
        one.data == run(3, CausticMode::Mixed).data,
        "thread count changed the image"
    );
    assert!(
        one.data != run(1, CausticMode::Map).data,
        "no splat changed the image?"
    );
}
