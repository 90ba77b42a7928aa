//! The path tracer's wavelength split at smooth dispersive interfaces
//! (`iris::integrator::path::Dispersion::split`) against the collapse to the hero it
//! replaces, at equal wall time, for the path tracer and the hybrid (whose camera paths
//! split the same way): for each stone and method, both settings render [`SECONDS`] per seed
//! for seeds 1 and 2 (alternating, so both see the same machine load), and the table gives
//! samples per pixel and the seed-to-seed relative RMSE (mean over channels and pixels of
//! |a − b| / (|a| + |b|)/2 in the RMS sense, over √2: one render's error against the
//! converged image, as `tests/render/wavelength_split.rs`).
//!
//! Stones, spectral transport, 160 × 90, 2 threads, `max_depth` 64, each as `iris render`
//! prepares it by default (studio, floor, framing):
//! - `assets/gems/round_diamond.glb` (diamond, n_d 2.417, Abbe 55);
//! - `assets/gems/pear_cubic_zirconia.glb` (cubic zirconia, more dispersive than diamond).
//!
//! Run: `cargo bench --bench dispersion_split` (about 2 × 2 × 4 × [`SECONDS`] s).
#![forbid(unsafe_code)]

use iris::accel::Backend;
use iris::camera::Camera;
use iris::image::ImageRgb;
use iris::integrator::path::Dispersion;
use iris::integrator::{CausticSettings, Integrator, PhotonSettings};
use iris::prepare::default_preview_scene;
use iris::render::RenderSettings;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Wall time per render.
const SECONDS: u64 = 10;
const SIZE: (u32, u32) = (160, 90);

/// The path tracer or the hybrid, split or collapsed.
fn integrator(hybrid: bool, split: bool) -> Integrator {
    match hybrid {
        false => Integrator::Path {
            max_depth: 64,
            dispersion: Dispersion {
                spectral_mis: true,
                split,
            },
            polarization: None,
        },
        true => Integrator::Hybrid {
            max_depth: 64,
            caustics: CausticSettings {
                split,
                ..PhotonSettings::default().caustics()
            },
            polarization: None,
        },
    }
}

/// One render of `path` for [`SECONDS`]: the image and its samples per pixel.
fn render(path: &Path, (hybrid, split): (bool, bool), seed: u64) -> (ImageRgb, f64) {
    let (scene, camera) = default_preview_scene(path, Backend::default(), SIZE).expect("prepare");
    let integrator = integrator(hybrid, split);
    let settings = RenderSettings {
        width: SIZE.0,
        height: SIZE.1,
        spp: 1 << 20,
        seed,
        threads: 2,
        quiet: true,
        spectral: true,
        time_limit: Some(Duration::from_secs(SECONDS)),
        sampler: Default::default(),
        adaptive: None,
        cancel: Default::default(),
        kernel: Default::default(),
    };
    let (img, stats) = integrator
        .render(&scene, &Camera::new(&camera, SIZE.0, SIZE.1), &settings)
        .expect("render");
    let spp = stats.samples as f64 / f64::from(SIZE.0 * SIZE.1);
    (img, spp)
}

/// Seed-to-seed relative RMSE over √2 of two renders.
fn seed_to_seed(a: &ImageRgb, b: &ImageRgb) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (p, q) in a.data.iter().zip(&b.data) {
        for (x, y) in p.to_array().into_iter().zip(q.to_array()) {
            num += f64::from(x - y).powi(2);
            den += (f64::from(x + y) / 2.0).powi(2);
        }
    }
    (num / den).sqrt() / 2f64.sqrt()
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let stones = ["round_diamond", "pear_cubic_zirconia"]
        .map(|s| (s, root.join(format!("assets/gems/{s}.glb"))));
    println!(
        "| stone | method | collapse spp | split spp | collapse rel. RMSE | split rel. RMSE | ratio |"
    );
    println!("|---|---|---|---|---|---|---|");
    for ((name, path), hybrid) in stones.iter().flat_map(|s| [(s, false), (s, true)]) {
        let method = if hybrid { "hybrid" } else { "path" };
        let mut runs = [Vec::new(), Vec::new()];
        for seed in 1..=2 {
            for split in [false, true] {
                runs[split as usize].push(render(path, (hybrid, split), seed));
            }
        }
        let err = |r: &[(ImageRgb, f64)]| seed_to_seed(&r[0].0, &r[1].0);
        let spp = |r: &[(ImageRgb, f64)]| (r[0].1 + r[1].1) / 2.0;
        let (c, s) = (err(&runs[0]), err(&runs[1]));
        println!(
            "| {name} | {method} | {:.0} | {:.0} | {c:.3} | {s:.3} | {:.2} |",
            spp(&runs[0]),
            spp(&runs[1]),
            s / c
        );
    }
}
