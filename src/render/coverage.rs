//! The coverage pass for `--background`: per pixel, the fraction α of camera samples whose
//! primary ray hits a surface, and the mean environment radiance the escaped ones saw
//! ([`crate::output::background`] defines both and how they are used).
//!
//! It replays the per-sample methods' camera rays exactly: sample k of pixel (x, y) is
//! jittered by its pixel dimensions from the render's sampler (the pixel centre when `spp`
//! = 1), as [`super::render_samples`] does (one [`primary_ray`], one [`pixel_sampler`]), so
//! α and the escaped radiance are those of the rendered samples (SPPM jitters its own rays:
//! same distribution). One closest-hit query per sample; parallel over rows on the current rayon pool. Units:
//! linear RGB radiance.

use super::samples::{pixel_sampler, primary_ray};
use super::RenderSettings;
use crate::camera::Camera;
use crate::image::Coverage;
use crate::scene::Scene;
use glam::Vec3;
use rayon::prelude::*;

/// Most samples per pixel the pass takes (beyond this α is exact to < 0.4 %, under one
/// 8-bit step).
pub const MAX_COVERAGE_SAMPLES: u64 = 256;

/// Coverage of `samples` camera samples per pixel (at least 1, at most
/// [`MAX_COVERAGE_SAMPLES`]) for the render `settings` describe.
pub fn coverage(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    samples: u64,
) -> Coverage {
    let (w, h) = (settings.width, settings.height);
    let n = samples.clamp(1, MAX_COVERAGE_SAMPLES);
    let sampler = pixel_sampler(settings, u64::from(settings.spp.max(1)));
    let rows: Vec<(Vec<f32>, Vec<Vec3>)> = (0..h)
        .into_par_iter()
        .map(|y| {
            let mut alpha = Vec::with_capacity(w as usize);
            let mut escaped = Vec::with_capacity(w as usize);
            for x in 0..w {
                let (mut hits, mut env) = (0u64, Vec3::ZERO);
                for k in 0..n {
                    let mut sample = sampler.start(x, y, k);
                    let ray = primary_ray(camera, x, y, settings.spp <= 1, &mut sample);
                    if scene.intersect(&ray).is_some() {
                        hits += 1;
                    } else if let Some(e) = &scene.environment() {
                        let l = e.eval(ray.dir.normalize());
                        if l.is_finite() {
                            env += l;
                        }
                    }
                }
                alpha.push(hits as f32 / n as f32);
                escaped.push(env / n as f32);
            }
            (alpha, escaped)
        })
        .collect();
    let mut out = Coverage {
        width: w,
        height: h,
        alpha: Vec::with_capacity(w as usize * h as usize),
        escaped: Vec::with_capacity(w as usize * h as usize),
    };
    for (a, e) in rows {
        out.alpha.extend(a);
        out.escaped.extend(e);
    }
    out
}
