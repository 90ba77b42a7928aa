//! SPPM converges, with memory that does not grow with the number of passes.
//!
//! Scene: the point-lit glass sphere on a white floor (tests/common `caustic_sphere`): its
//! caustic is reachable only by photons. Reference: SPPM with 16× the photons per pass and
//! 512 passes (another seed). With α = 2/3 the error of Knaus & Zwicker's estimator falls as
//! passes^(−1/3) (variance ∝ 1/(i r²ᵢ) ∝ i^(−1/3)·… balanced with bias ∝ r²ᵢ), so 8× the
//! passes should give about half the RMSE; we allow up to 0.7 (the reference's own error
//! and pass-to-pass noise), averaged over 3 seeds.

use crate::common;

use iris::camera::Camera;
use iris::image::ImageRgb;
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::render::{Control, Progress, RenderSettings};

const W: u32 = 40;
const H: u32 = 30;

fn settings(seed: u64) -> RenderSettings {
    RenderSettings::quiet_rgb((W, H), 1, seed, 2)
}

fn sppm(passes: u32, photons: u64) -> Integrator {
    Integrator::new(
        Method::Sppm,
        16,
        &PhotonSettings {
            photons,
            passes,
            // The initial radius from the pixel footprint (2 pixels).
            radius: None,
            ..PhotonSettings::default()
        },
    )
    .expect("a resolved method")
}

fn rmse(a: &ImageRgb, b: &ImageRgb) -> f64 {
    let s: f64 = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(x, y)| (*x - *y).length_squared() as f64 / 3.0)
        .sum();
    (s / a.data.len() as f64).sqrt()
}

#[test]
fn sppm_error_falls_with_passes_and_memory_stays_flat() {
    // The live heap is counted for the whole process (the renderer's buffers are what
    // changes between checkpoints, as the test thread holds its images still): no other
    // test may allocate meanwhile.
    let _serial = common::alloc::SERIAL
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    let (scene, cam) = common::caustic_sphere(None);
    let camera = Camera::new(&cam, W, H);
    let (reference, _) = sppm(512, 32_000)
        .render(&scene, &camera, &settings(999))
        .unwrap();
    let mean: f64 =
        reference.data.iter().map(|p| p.y as f64).sum::<f64>() / reference.data.len() as f64;
    assert!(mean > 0.0);
    let (mut e8, mut e64) = (0.0, 0.0);
    let mut live = Vec::new();
    for seed in 1..=3u64 {
        let mut at8 = None;
        // Checkpoints at 1, 2, 4, …, 64 passes.
        let mut cb = |p: &Progress| -> iris::Result<Control> {
            if p.passes == 8 {
                at8 = Some(p.image.clone());
            }
            if seed == 1 {
                live.push((p.passes, common::alloc::live() as isize));
            }
            Ok(Control::Continue)
        };
        let (img64, stats) = sppm(64, 2000)
            .render_progressive(&scene, &camera, &settings(seed), Some(&mut cb))
            .unwrap();
        assert_eq!(stats.passes, 64);
        e8 += rmse(&at8.expect("checkpoint at pass 8"), &reference);
        e64 += rmse(&img64, &reference);
    }
    let ratio = e64 / e8;
    eprintln!("RMSE 8 passes {:.4e}, 64 passes {:.4e}, ratio {ratio:.3} (passes^-1/3 → 0.5); mean {mean:.4}", e8 / 3.0, e64 / 3.0);
    assert!(ratio < 0.7, "RMSE ratio 64/8 passes {ratio}");
    // Live heap at checkpoints 8..64 (seed 1): no growth beyond 5 % + 64 KiB of pass 8's.
    eprintln!("live heap by pass: {live:?}");
    let base = live.iter().find(|(p, _)| *p == 8).unwrap().1;
    for &(p, b) in &live {
        if p >= 8 {
            assert!(
                b as f64 <= base as f64 * 1.05 + 65536.0,
                "live heap grew from {base} B (pass 8) to {b} B (pass {p})"
            );
        }
    }
}
