//! Photon tracing throughput (issue 5): photons traced per second through the caustic
//! sphere scene ([`iris::assets::bench::caustic_sphere`], point light; every photon
//! from the light, those hitting the glass refracted twice, then the floor) with 1 and 2
//! rayon threads, RGB and spectral transport. One iteration traces 100 000 photons in
//! fixed chunks of 4096 (as SPPM does) on a pool of the given size; throughput is
//! photons/s. The 2-thread/1-thread ratio is the parallel scaling (goal ≥ 1.8×).
//!
//! Run: `cargo bench --bench photon_trace`.
#![forbid(unsafe_code)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::Vec3;
use iris::math::Rng;
use iris::photon::emit::PhotonEmitter;
use iris::photon::trace::{trace, Roulette, TraceSettings};
use iris::scene::Scene;
use iris::spectrum::{Carrier, SampledSpectrum};
use rayon::prelude::*;
use std::hint::black_box;
use std::time::Duration;

const PHOTONS: u64 = 100_000;
const CHUNK: u64 = 4096;

fn scene() -> Scene {
    let (desc, _) = iris::assets::bench::caustic_sphere(None);
    let desc = iris::scene::validate::validate(desc).expect("valid");
    Scene::build(desc, iris::accel::Backend::Auto).expect("build")
}

/// Traces `PHOTONS` photons; returns the stored vertices (so nothing is optimised away).
fn shoot<C: Carrier>(scene: &Scene, emitter: &PhotonEmitter) -> u64 {
    let settings = TraceSettings {
        max_depth: 16,
        roulette: Roulette::Throughput,
    };
    (0..PHOTONS.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut stored = 0u64;
            for i in c * CHUNK..((c + 1) * CHUNK).min(PHOTONS) {
                let mut rng = Rng::new(&[1, i]);
                let Some(ph) = emitter.emit_from(scene, &mut rng) else {
                    continue;
                };
                let lambda = C::sample_lambda(rng.next_f32());
                trace::<C>(scene, &ph, lambda, &settings, &mut rng, |_, _| stored += 1);
            }
            stored
        })
        .sum()
}

fn photon_trace(c: &mut Criterion) {
    let scene = scene();
    let emitter = PhotonEmitter::new(&scene);
    let mut g = c.benchmark_group("photon_trace");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(8))
        .throughput(Throughput::Elements(PHOTONS));
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .start_handler(|_| {
                #[cfg(feature = "embree")]
                iris::accel::embree::enable_flush_to_zero();
            })
            .build()
            .expect("pool");
        g.bench_with_input(BenchmarkId::new("rgb", threads), &threads, |b, _| {
            b.iter(|| pool.install(|| black_box(shoot::<Vec3>(&scene, &emitter))))
        });
        g.bench_with_input(BenchmarkId::new("spectral", threads), &threads, |b, _| {
            b.iter(|| pool.install(|| black_box(shoot::<SampledSpectrum>(&scene, &emitter))))
        });
    }
    g.finish();
}

criterion_group!(benches, photon_trace);
criterion_main!(benches);
