//! Photon-map and hash-grid performance (issue 5, part 2): kd-tree build time, kNN (k = 50)
//! and radius queries per second, hash-grid rebuild time and radius queries per second, on
//! 1M photons, plus the bytes each structure spends per photon.
//!
//! Data (deterministic, no files read): 1M photons on three surfaces of a 4 m room, in metres,
//! at about the same density (2.5·10⁴ photons/m²): 40% on the floor (y = 0, 4 × 4 m), 40% on
//! the back wall (z = −2, 4 × 4 m) and 20% on a sphere (radius 0.8 at (0, 0.8, 0)). 10 000
//! query points come from the same surfaces with another seed. The radius query uses the
//! median 50-th-neighbour distance of those queries, so about 50 photons each (mean and median
//! counts are printed). Correctness on clustered data (caustic spots) is covered by the unit
//! tests; here a fixed radius in a dense spot would just measure the spot's photon count.
//! Queries run on one thread; builds use rayon's pool.
//!
//! Run: `cargo bench --bench photon`.
#![forbid(unsafe_code)]

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use glam::Vec3;
use iris::math::Rng;
use iris::photon::grid::HashGrid;
use iris::photon::kdtree::PhotonMap;
use iris::photon::store::Photon;
use std::hint::black_box;
use std::time::Duration;

const PHOTONS: usize = 1_000_000;
const QUERIES: usize = 10_000;
const K: usize = 50;

/// A point on one of the bench's surfaces (see the module documentation).
fn surface_point(rng: &mut Rng) -> Vec3 {
    let mut u = || rng.next_f32();
    let s = u();
    if s < 0.4 {
        Vec3::new(4.0 * u() - 2.0, 0.0, 4.0 * u() - 2.0)
    } else if s < 0.8 {
        Vec3::new(4.0 * u() - 2.0, 4.0 * u(), -2.0)
    } else {
        let z = 2.0 * u() - 1.0;
        let phi = std::f32::consts::TAU * u();
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(0.0, 0.8, 0.0) + 0.8 * Vec3::new(r * phi.cos(), z, r * phi.sin())
    }
}

fn photons() -> Vec<Photon> {
    let mut rng = Rng::new(&[2026, 5]);
    (0..PHOTONS)
        .map(|i| {
            let p = surface_point(&mut rng);
            let wi = Vec3::new(rng.next_f32() - 0.5, 1.0, rng.next_f32() - 0.5);
            Photon::new(p, wi, [1e-6; 4], (i % 4) as u32)
        })
        .collect()
}

fn queries() -> Vec<Vec3> {
    let mut rng = Rng::new(&[2026, 6]);
    (0..QUERIES).map(|_| surface_point(&mut rng)).collect()
}

fn photon_bench(c: &mut Criterion) {
    let photons = photons();
    let queries = queries();
    let map = PhotonMap::build(photons.clone());

    // The radius for ~K neighbours: median K-th-neighbour distance over the queries.
    let mut out = Vec::with_capacity(K);
    let mut far: Vec<f32> = queries
        .iter()
        .map(|&q| map.knn(q, K, f32::INFINITY, &mut out))
        .collect();
    far.sort_by(f32::total_cmp);
    let r2 = far[far.len() / 2];
    let r = r2.sqrt();
    let mut counts: Vec<usize> = queries
        .iter()
        .map(|&q| {
            let mut n = 0;
            map.for_each_within(q, r2, |_, _| n += 1);
            n
        })
        .collect();
    let found: usize = counts.iter().sum();
    counts.sort_unstable();
    let mut grid = HashGrid::new();
    grid.rebuild(&photons, r);
    println!(
        "photon bench: {PHOTONS} photons, {QUERIES} queries, radius {r:.5} m \
         (photons per radius query: mean {:.1}, median {})",
        found as f64 / QUERIES as f64,
        counts[QUERIES / 2]
    );
    println!(
        "bytes per photon: Photon {} B, kd-tree {} B, hash grid {:.1} B (+ the photons)",
        std::mem::size_of::<Photon>(),
        PhotonMap::bytes_per_photon(),
        grid.capacity() as f64 / PHOTONS as f64
    );
    println!("rayon threads: {}", rayon::current_num_threads());

    let mut g = c.benchmark_group("photon");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(8));

    g.throughput(Throughput::Elements(PHOTONS as u64));
    g.bench_function("kdtree_build_1M", |b| {
        b.iter_batched(|| photons.clone(), PhotonMap::build, BatchSize::LargeInput)
    });
    g.bench_function("hashgrid_rebuild_1M", |b| {
        b.iter(|| grid.rebuild(black_box(&photons), r))
    });

    g.throughput(Throughput::Elements(QUERIES as u64));
    g.bench_function("kdtree_knn50", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for &q in &queries {
                s += map.knn(black_box(q), K, f32::INFINITY, &mut out);
            }
            s
        })
    });
    g.bench_function("kdtree_radius", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for &q in &queries {
                map.for_each_within(black_box(q), r2, |ph, _| s += ph.power()[0]);
            }
            s
        })
    });
    g.bench_function("hashgrid_radius", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for &q in &queries {
                grid.for_each_within(black_box(q), r, |_, d2| s += d2);
            }
            s
        })
    });
    g.finish();
}

criterion_group!(benches, photon_bench);
criterion_main!(benches);
