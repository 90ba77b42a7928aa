//! Path-tracer throughput on real scenes: samples per second and rays per second for
//! `--method path` at 512×512, 2 threads, on each backend (issue 3's performance figures).
//!
//! Scenes (from `../shared/assets`, or `IRIS_SHARED_ASSETS`): Khronos `TransmissionTest`
//! (its own camera; no lights in the file, so it is lit by a uniform environment of radiance
//! 0.5, which replaces the default lights) and McGuire's
//! `CornellBox-Water` (lit by its emissive ceiling, auto-framed camera). One criterion
//! iteration renders the whole image at 1 spp with a fixed seed, so every iteration traces
//! the same rays; criterion's throughput is pixel samples/s, and the rays per iteration
//! (counted once, printed) give rays/s = rays per iteration / time per iteration.
//! Load and acceleration build are outside the timed loop.
//!
//! Run: `cargo bench --bench path` (`--no-default-features` for the BVH alone). Without the
//! shared assets the bench says so and measures nothing.
#![forbid(unsafe_code)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use iris::accel::Backend;
use iris::app::choose_camera;
use iris::camera::Camera;
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::light::env::Environment;
use iris::render::RenderSettings;
use iris::scene::desc::SceneDesc;
use iris::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Duration;

mod common;

const SIZE: u32 = 512;

/// Loads and builds `path`, lit by a uniform environment of radiance `env` when given
/// (which replaces the default lights of a file with none).
fn load_lit(path: &Path, backend: Backend, env: Option<f32>) -> Scene {
    let desc = iris::load::load_scene(path).expect("scene loads");
    let desc = SceneDesc {
        environment_light: env.map(|g| Environment::Uniform {
            radiance: glam::Vec3::splat(g),
        }),
        ..desc
    };
    Scene::build(desc, backend).expect("scene builds")
}

fn path_tracer(c: &mut Criterion) {
    let Some(assets) = common::shared_assets() else {
        eprintln!("SKIPPED: ../shared/assets not found (set IRIS_SHARED_ASSETS)");
        return;
    };
    let scenes = [
        (
            "TransmissionTest",
            assets.join("khronos/TransmissionTest/TransmissionTest.glb"),
            Some(0.5f32),
        ),
        (
            "CornellBox-Water",
            assets.join("obj/CornellBox-McGuire/CornellBox-Water.obj"),
            None,
        ),
    ];
    let integrator =
        Integrator::new(Method::Path, 8, &PhotonSettings::default()).expect("a resolved method");
    let settings = RenderSettings::quiet_rgb((SIZE, SIZE), 1, 1, 2);
    let mut group = c.benchmark_group("path_tracer_512");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(2));
    group.measurement_time(Duration::from_secs(15));
    group.throughput(Throughput::Elements(u64::from(SIZE * SIZE)));
    for (name, path, env) in &scenes {
        for (bname, backend) in common::backends() {
            let scene = load_lit(path, backend, *env);
            let (cam, _) = choose_camera(&scene, None, 1.0).expect("camera");
            let camera = Camera::new(&cam, SIZE, SIZE);
            let (_, stats) = integrator
                .render(&scene, &camera, &settings)
                .expect("renders");
            eprintln!(
                "{name}/{bname}: {} rays per iteration ({:.2} rays per sample)",
                stats.rays,
                stats.rays as f64 / stats.samples as f64
            );
            group.bench_function(BenchmarkId::new(*name, bname), |b| {
                b.iter(|| {
                    integrator
                        .render(&scene, &camera, &settings)
                        .expect("renders")
                })
            });
        }
    }
    group.finish();
}

/// `--spectral on` vs `off` on non-dispersive scenes (issue 4: the spectral path must cost
/// ≤ 1.3× per sample): the paper's Fig. 7.1 spheres (in the repo) and TransmissionTest,
/// 256×256, 2 spp per iteration, Embree (or the BVH without it).
fn spectral_overhead(c: &mut Criterion) {
    let mut scenes = vec![(
        "fig7_1_spheres",
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/paper/fig7_1_spheres.glb"),
        None,
    )];
    if let Some(assets) = common::shared_assets() {
        scenes.push((
            "TransmissionTest",
            assets.join("khronos/TransmissionTest/TransmissionTest.glb"),
            Some(0.5f32),
        ));
    }
    let integrator =
        Integrator::new(Method::Path, 8, &PhotonSettings::default()).expect("a resolved method");
    let mut group = c.benchmark_group("spectral_overhead_256");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(2));
    group.measurement_time(Duration::from_secs(8));
    group.throughput(Throughput::Elements(256 * 256 * 2));
    for (name, path, env) in &scenes {
        let scene = load_lit(path, common::backends()[0].1, *env);
        let (cam, _) = choose_camera(&scene, None, 1.0).expect("camera");
        let camera = Camera::new(&cam, 256, 256);
        for spectral in [false, true] {
            let settings = RenderSettings {
                width: 256,
                height: 256,
                spp: 2,
                seed: 1,
                threads: 2,
                quiet: true,
                spectral,
                time_limit: None,
                sampler: Default::default(),
                adaptive: None,
                cancel: Default::default(),
                kernel: Default::default(),
            };
            let id = if spectral {
                "spectral_on"
            } else {
                "spectral_off"
            };
            group.bench_function(BenchmarkId::new(*name, id), |b| {
                b.iter(|| {
                    integrator
                        .render(&scene, &camera, &settings)
                        .expect("renders")
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, path_tracer, spectral_overhead);
criterion_main!(benches);
