//! Scene load and acceleration-structure build time per backend (issue 6): how long a user
//! waits before the first sample, split into its stages.
//!
//! For each scene (from `../shared/assets`, or `IRIS_SHARED_ASSETS`, plus the paper's
//! caustic scene from `assets/paper`), criterion times:
//!
//! - `load/<scene>`: file → [`SceneDesc`](iris::scene::desc::SceneDesc) → validated
//!   ([`iris::load::load_scene`]: parsing, buffers, texture decoding, validation);
//! - `scene_build/<scene>/<backend>`: [`Scene::build`] from the validated description (flattening,
//!   Morton ordering, area-light table, acceleration structure, contact marking), with the
//!   description cloned outside the timed part;
//! - `accel_build/<scene>/<backend>`: the acceleration structure alone
//!   ([`Accel::build`] over the scene's world-space triangles).
//!
//! Times are wall-clock seconds per iteration; the Embree build uses Embree's own threads
//! (all cores), the obvhs build its rayon pool (all cores).
//!
//! Run: `cargo bench --bench load_build` (about 2 minutes on 2 cores). Without the shared
//! assets the shared scenes are SKIPPED (said on stderr) and only the paper scene is timed.
#![forbid(unsafe_code)]

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion};
use iris::accel::Accel;
use iris::scene::Scene;
use std::path::PathBuf;
use std::time::Duration;

mod common;

/// (name, file) of every scene timed.
fn scenes() -> Vec<(&'static str, PathBuf)> {
    let mut v = vec![(
        "fig4_5_1_caustics",
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/paper/fig4_5_1_caustics.glb"),
    )];
    match common::shared_assets() {
        Some(a) => v.extend([
            (
                "CornellBox-Water",
                a.join("obj/CornellBox-McGuire/CornellBox-Water.obj"),
            ),
            (
                "GlassHurricaneCandleHolder",
                a.join("khronos/GlassHurricaneCandleHolder/GlassHurricaneCandleHolder.glb"),
            ),
            (
                "DispersionTest",
                a.join("khronos/DispersionTest/DispersionTest.glb"),
            ),
            (
                "TransmissionTest",
                a.join("khronos/TransmissionTest/TransmissionTest.glb"),
            ),
        ]),
        None => {
            eprintln!("SKIPPED shared scenes: ../shared/assets not found (set IRIS_SHARED_ASSETS)")
        }
    }
    v
}

fn load_build(c: &mut Criterion) {
    #[cfg(feature = "embree")]
    iris::accel::embree::enable_flush_to_zero();
    let mut group = c.benchmark_group("load_build");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for (name, path) in scenes() {
        let desc = match iris::load::load_scene(&path) {
            Ok(d) => d,
            Err(e) => {
                eprintln!("SKIPPED {name}: {e}");
                continue;
            }
        };
        let bytes = std::fs::metadata(&path).map_or(0, |m| m.len());
        let tris: usize = desc.meshes.iter().map(|m| m.indices.len()).sum();
        eprintln!("{name}: {tris} triangles, {bytes} bytes on disk");
        group.bench_function(BenchmarkId::new("load", name), |b| {
            b.iter(|| iris::load::load_scene(&path).expect("loads"))
        });
        for (bname, backend) in common::backends() {
            group.bench_function(
                BenchmarkId::new(format!("scene_build/{name}"), bname),
                |b| {
                    b.iter_batched(
                        || desc.clone(),
                        |d| Scene::build(d, backend).expect("builds"),
                        BatchSize::LargeInput,
                    )
                },
            );
            let scene = Scene::build(desc.clone(), backend).expect("builds");
            let indices: Vec<[u32; 3]> = scene.triangles().iter().map(|t| t.vertices).collect();
            group.bench_function(
                BenchmarkId::new(format!("accel_build/{name}"), bname),
                |b| b.iter(|| Accel::build(backend, scene.positions(), &indices).expect("builds")),
            );
        }
    }
    group.finish();
}

criterion_group!(benches, load_build);
criterion_main!(benches);
