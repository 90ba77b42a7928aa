//! The Z-order Owen-scrambled Sobol' sampler's cost per draw ([`iris::sampler::ZSobol`]):
//! a 1D and a 2D draw at a fixed dimension, starting a pixel sample, and a path-like
//! sequence (start a pixel sample, then twelve mixed 1D/2D draws at the dimensions a
//! three-bounce camera path of the path tracer reads). Image 256×256; blocks of 64 samples
//! per pixel (a small render) and 2^20 (what `--time` renders use, 18 base-4 digits).
//!
//! Each iteration walks a fixed pseudo-random list of 1024 (pixel, sample index) pairs:
//! `random` (a new pixel and index each time) or `runs_of_64` (16 pixels, 64 consecutive
//! samples each, the order of a render's per-pixel loop). Criterion's throughput is draws
//! per second for `get_1d` and `get_2d` (random pixel samples, 32 draws at distinct
//! dimensions per started pixel sample, so the start is 1/32 of their cost), pixel samples
//! per second for the start and the path-like sequence.
//!
//! Run: `cargo bench --bench sampler`.
#![forbid(unsafe_code)]

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use iris::sampler::schedule::{bounce_dimension, BounceDim, WAVELENGTH};
use iris::sampler::{Randomize, ZSobol};
use std::time::Duration;

const RES: u32 = 256;
const POINTS: usize = 1024;

/// `POINTS` (x, y, sample index) triples below `spp` from a fixed seed: each at a random
/// pixel and index (`run` = 1), or runs of `run` consecutive samples of one pixel, as a
/// render's rounds take them.
fn pixel_samples(spp: u64, run: usize) -> Vec<(u32, u32, u64)> {
    let mut rng = iris::math::Rng::new(&[7]);
    let mut v = Vec::with_capacity(POINTS);
    while v.len() < POINTS {
        let x = rng.next_u32() % RES;
        let y = rng.next_u32() % RES;
        let wide = u64::from(rng.next_u32()) << 32 | u64::from(rng.next_u32());
        let k0 = wide % (spp - run as u64 + 1);
        v.extend((0..run as u64).map(|i| (x, y, k0 + i)));
    }
    v
}

/// One draw of a path-like sequence: a 1D or 2D number at a dimension.
#[derive(Clone, Copy)]
enum Draw {
    One(u32),
    Two(u32),
    Wavelength,
}

/// The twelve draws of a camera path through three vertices (the path tracer's schedule):
/// film position, wavelength, then per vertex light choice, light position, BSDF lobe and
/// direction (roulette at the last).
fn path_draws() -> Vec<Draw> {
    let mut v = vec![Draw::Two(0), Draw::Wavelength];
    for b in 0..3 {
        v.push(Draw::One(bounce_dimension(b, BounceDim::LightChoice)));
        v.push(Draw::Two(bounce_dimension(b, BounceDim::LightPosition)));
        v.push(Draw::Two(bounce_dimension(b, BounceDim::BsdfDirection)));
    }
    v.push(Draw::One(bounce_dimension(2, BounceDim::Roulette)));
    v
}

fn sampler(c: &mut Criterion) {
    let mut group = c.benchmark_group("zsobol_256");
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(4));
    for (spp_name, spp) in [("spp64", 64u64), ("spp2^20", 1 << 20)] {
        let points = pixel_samples(spp, 1);
        let runs = pixel_samples(spp, 64);
        let mut z = ZSobol::new(spp, (RES, RES), 1);
        group.throughput(Throughput::Elements(POINTS as u64));
        for (order, list) in [("random", &points), ("runs_of_64", &runs)] {
            let id = BenchmarkId::new(format!("start_pixel_sample_{order}"), spp_name);
            group.bench_function(id, |b| {
                b.iter(|| {
                    for &(x, y, k) in list {
                        z.start_pixel_sample(x, y, k);
                        black_box(&z);
                    }
                })
            });
        }
        // Draws: each point's pixel sample is started inside the loop (its cost, measured
        // above, is shared by `DRAWS` draws at distinct dimensions).
        const DRAWS: u32 = 32;
        group.throughput(Throughput::Elements(POINTS as u64 * u64::from(DRAWS)));
        group.bench_function(BenchmarkId::new("get_1d", spp_name), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for &(x, y, k) in &points {
                    z.start_pixel_sample(x, y, k);
                    for d in 0..DRAWS {
                        z.set_dimension(FIRST + 3 * d);
                        acc += z.get_1d();
                    }
                }
                acc
            })
        });
        group.bench_function(BenchmarkId::new("get_2d", spp_name), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for &(x, y, k) in &points {
                    z.start_pixel_sample(x, y, k);
                    for d in 0..DRAWS {
                        z.set_dimension(FIRST + 3 * d);
                        let [u, v] = z.get_2d();
                        acc += u + v;
                    }
                }
                acc
            })
        });
        let draws = path_draws();
        group.throughput(Throughput::Elements(POINTS as u64));
        for (order, list) in [("random", &points), ("runs_of_64", &runs)] {
            let id = BenchmarkId::new(format!("path_12_draws_{order}"), spp_name);
            group.bench_function(id, |b| b.iter(|| path(&mut z, list, &draws)));
        }
    }
    group.finish();
}

/// The draws of `draws` for every pixel sample of `list`: a sum of all numbers drawn.
fn path(z: &mut ZSobol, list: &[(u32, u32, u64)], draws: &[Draw]) -> f32 {
    let mut acc = 0.0f32;
    for &(x, y, k) in list {
        z.start_pixel_sample(x, y, k);
        for &d in draws {
            acc += match d {
                Draw::One(dim) => {
                    z.set_dimension(dim);
                    z.get_1d()
                }
                Draw::Two(dim) => {
                    z.set_dimension(dim);
                    let [u, v] = z.get_2d();
                    u + v
                }
                Draw::Wavelength => {
                    z.set_dimension(WAVELENGTH);
                    let [u, v] = z.get_2d_with(Randomize::Xor);
                    u + v
                }
            };
        }
    }
    acc
}

/// First dimension of the per-draw benches (a bounce's, past the camera's).
const FIRST: u32 = 6;

criterion_group!(benches, sampler);
criterion_main!(benches);
