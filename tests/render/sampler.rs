//! The low-discrepancy samplers (`iris::sampler`) through the public API: integration error
//! against independent random numbers, ZSobol determinism whatever order the pixels and
//! samples are visited in, and (issue 17 item 1) the Sobol' sampler in the path tracer:
//! lower image error at 16 spp, and grey skies from its stratified wavelengths. No
//! assertion depends on time.

use crate::common;

use glam::{Vec2, Vec3};
use iris::camera::Camera;
use iris::image::ImageRgb;
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::render::RenderSettings;
use iris::sampler::SamplerKind;
use iris::scene::desc::CameraDesc;

use iris::math::Rng;
use iris::sampler::halton::halton_sample;
use iris::sampler::{sobol_sample, Scramble, ZSobol};
use std::f64::consts::PI;

/// A smooth integrand on the unit square with known integral:
/// ∫∫ sin(πx) sin(πy) (1 + xy) dx dy = 4/π² + 1/π².
fn f(x: f64, y: f64) -> f64 {
    (PI * x).sin() * (PI * y).sin() * (1.0 + x * y)
}
const EXACT: f64 = 5.0 / (PI * PI);

/// Root-mean-square error over `seeds` estimates of `n` points each.
fn rms_error(seeds: u64, n: u64, point: impl Fn(u64, u64) -> (f64, f64)) -> f64 {
    let sq: f64 = (0..seeds)
        .map(|seed| {
            let est = (0..n).map(|i| {
                let (x, y) = point(seed, i);
                f(x, y)
            });
            (est.sum::<f64>() / n as f64 - EXACT).powi(2)
        })
        .sum();
    (sq / seeds as f64).sqrt()
}

#[test]
fn owen_sobol_integrates_a_smooth_function_far_better_than_random() {
    // Owen (1997, "Scrambled net variance for integrals of smooth functions"): for smooth
    // integrands the scrambled-net RMS error falls as N^-3/2 (log N)^((d-1)/2), against
    // N^-1/2 for independent points, so at N = 256 the ratio is of order 1/N ≈ 0.004 times
    // a constant of order 1. The bound 0.2 leaves a 50x margin; with 64 seeds the random
    // RMS error is itself known to about ±9 %.
    let (seeds, n) = (64, 256);
    let sobol = rms_error(seeds, n, |seed, i| {
        let (s0, s1) = ((seed * 2 + 1) as u32, (seed * 2 + 2) as u32 ^ 0x9e37_79b9);
        let x = sobol_sample(i, 0, Scramble::Owen(s0.wrapping_mul(0x2545_f491)));
        let y = sobol_sample(i, 1, Scramble::Owen(s1.wrapping_mul(0x2545_f491)));
        (f64::from(x), f64::from(y))
    });
    let random = rms_error(seeds, n, |seed, i| {
        let mut rng = Rng::new(&[seed, i]);
        (f64::from(rng.next_f32()), f64::from(rng.next_f32()))
    });
    let zsobol = rms_error(seeds, n, |seed, i| {
        let mut s = ZSobol::new(n, (16, 16), seed);
        s.start_pixel_sample(3, 9, i);
        let [x, y] = s.get_2d();
        (f64::from(x), f64::from(y))
    });
    let halton = rms_error(seeds, n, |seed, i| {
        (
            f64::from(halton_sample(i, 0, seed)),
            f64::from(halton_sample(i, 1, seed)),
        )
    });
    eprintln!("rms error, {n} points: random {random:.2e}, owen sobol {sobol:.2e}, zsobol {zsobol:.2e}, owen halton {halton:.2e}");
    assert!(
        sobol < 0.2 * random,
        "owen sobol {sobol:e} vs random {random:e}"
    );
    assert!(
        zsobol < 0.2 * random,
        "zsobol {zsobol:e} vs random {random:e}"
    );
    assert!(
        halton < 0.2 * random,
        "halton {halton:e} vs random {random:e}"
    );
}

/// Every value of pixel `(x, y)`, samples `0..spp`, dimensions `0..dims`, from `s`.
fn pixel_values(s: &mut ZSobol, x: u32, y: u32, spp: u64, dims: u32) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..spp {
        s.start_pixel_sample(x, y, i);
        for _ in 0..dims / 2 {
            out.extend(s.get_2d());
        }
        out.push(s.get_1d());
    }
    out
}

#[test]
fn zsobol_values_do_not_depend_on_visiting_order() {
    let (w, h, spp, dims) = (13u32, 7u32, 8u64, 9u32);
    let pixels: Vec<(u32, u32)> = (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).collect();
    // Row order with one sampler for everything.
    let mut one = ZSobol::new(spp, (w, h), 42);
    let forward: Vec<Vec<f32>> = pixels
        .iter()
        .map(|&(x, y)| pixel_values(&mut one, x, y, spp, dims))
        .collect();
    // Reverse order, a fresh sampler per pixel (as threads would).
    for (k, &(x, y)) in pixels.iter().enumerate().rev() {
        let mut fresh = ZSobol::new(spp, (w, h), 42);
        assert_eq!(
            pixel_values(&mut fresh, x, y, spp, dims),
            forward[k],
            "({x},{y})"
        );
    }
    // Samples split into rounds (odd indices first, then even), interleaved across pixels.
    let mut shard = ZSobol::new(spp, (w, h), 42);
    for parity in [1, 0] {
        for (k, &(x, y)) in pixels.iter().enumerate() {
            for i in (parity..spp).step_by(2) {
                shard.start_pixel_sample(x, y, i);
                let mut v = Vec::new();
                for _ in 0..dims / 2 {
                    v.extend(shard.get_2d());
                }
                v.push(shard.get_1d());
                let at = (i as usize) * v.len();
                assert_eq!(v[..], forward[k][at..at + v.len()], "({x},{y}) sample {i}");
            }
        }
    }
    assert!(forward.iter().flatten().all(|u| (0.0..1.0).contains(u)));
}

fn settings(w: u32, h: u32, spp: u32, seed: u64, sampler: SamplerKind) -> RenderSettings {
    RenderSettings {
        width: w,
        height: h,
        spp,
        seed,
        threads: 2,
        quiet: true,
        spectral: false,
        time_limit: None,
        sampler,
        adaptive: None,
        cancel: Default::default(),
        kernel: Default::default(),
    }
}

fn path_render(scene: &iris::scene::Scene, cam: &CameraDesc, s: &RenderSettings) -> ImageRgb {
    let integrator =
        Integrator::new(Method::Path, 16, &PhotonSettings::default()).expect("resolved");
    integrator
        .render(scene, &Camera::new(cam, s.width, s.height), s)
        .expect("render")
        .0
}

fn rmse(a: &ImageRgb, b: &ImageRgb) -> f64 {
    let s: f64 = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(x, y)| (*x - *y).as_dvec3().length_squared() / 3.0)
        .sum();
    (s / a.data.len() as f64).sqrt()
}

#[test]
fn zsobol_lowers_the_path_tracers_error_at_16_spp() {
    let (scene, cam) = common::caustic_sphere(Some(0.5));
    let (w, h) = (48, 36);
    let reference = path_render(
        &scene,
        &cam,
        &settings(w, h, 4096, 1000, SamplerKind::Independent),
    );
    let mut e = [0.0; 2];
    for seed in 1..=4 {
        for (i, kind) in [SamplerKind::Independent, SamplerKind::ZSobol]
            .into_iter()
            .enumerate()
        {
            e[i] += rmse(
                &path_render(&scene, &cam, &settings(w, h, 16, seed, kind)),
                &reference,
            );
        }
    }
    eprintln!(
        "RMSE at 16 spp: independent {:.4e}, zsobol {:.4e}, ratio {:.3}",
        e[0] / 4.0,
        e[1] / 4.0,
        e[1] / e[0]
    );
    // Measured (2026-12-02): ratio 0.676. Each RMSE pools 1728 pixels × 4 seeds, so it is
    // known to a few %; 0.8 leaves that margin, and a sampler no better than independent
    // numbers (ratio 1 ± 0.05) fails.
    assert!(e[1] < 0.8 * e[0], "{e:?}");
}

#[test]
fn zsobol_wavelengths_make_a_grey_sky_grey_at_4_spp() {
    // A white environment (RGB 1) seen directly in spectral transport: each sample carries
    // 4 wavelengths u + i/4; with the Sobol' sampler a pixel's 4 samples put their offsets
    // on a shifted regular grid (digit-shift randomisation, `spectrum::hero_number`), so the
    // 16 wavelengths are a regular quadrature of the sampling density and the pixel is grey
    // to about 1 % (measured max deviation 0.6 % on a 0.6 sky at 64×48). Independent numbers
    // with the golden-ratio lattice left up to 16 % there.
    let scene = common::sphere_in_white_environment(common::white_lambert());
    let cam = common::camera_facing_origin(1.4);
    let (w, h) = (32, 32);
    let dev = |kind| {
        let s = RenderSettings {
            spectral: true,
            ..settings(w, h, 4, 7, kind)
        };
        let img = path_render(&scene, &cam, &s);
        let camera = Camera::new(&cam, w, h);
        let mut worst = 0.0f32;
        for (i, p) in img.data.iter().enumerate() {
            let (x, y) = ((i as u32 % w) as f32, (i as u32 / w) as f32);
            let ray = camera.generate_ray(Vec2::new(x, y) + 0.5);
            let d = ray.dir.normalize();
            // Pixels whose whole footprint misses the unit sphere: impact parameter > 1.2.
            if (ray.origin - d * ray.origin.dot(d)).length() > 1.2 {
                worst = worst.max((*p - Vec3::ONE).abs().max_element());
            }
        }
        worst
    };
    let (sobol, independent) = (dev(SamplerKind::ZSobol), dev(SamplerKind::Independent));
    eprintln!(
        "worst background deviation at 4 spp: zsobol {sobol:.4}, independent {independent:.4}"
    );
    assert!(sobol < 0.02, "{sobol}");
    assert!(independent > 2.0 * sobol, "{independent} vs {sobol}");
}
