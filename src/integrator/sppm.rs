//! Stochastic progressive photon mapping (`--method sppm`): Hachisuka & Jensen 2009
//! ("Stochastic Progressive Photon Mapping"), with the per-pass radius sequence of Knaus &
//! Zwicker 2011 ("Progressive Photon Mapping: A Probabilistic Approach"):
//! r²ᵢ₊₁ = r²ᵢ · (i + α)/(i + 1), α = 2/3 by default, and the image is the plain average of
//! the passes' estimates, so it converges (bias and variance both vanish) with memory that
//! does not grow with the number of passes.
//!
//! Each pass (following pbrt-v4's `SPPMIntegrator`):
//! 1. draws ONE set of wavelengths shared by all its camera paths and photons (spectral
//!    transport), so a caustic of a dispersive prism is estimated per wavelength set and
//!    colours converge without splotches;
//! 2. traces one camera path per pixel with the path tracer's loop ([`path::camera_path`]):
//!    emission, direct light (NEE with MIS) and glossy/specular bounces are the path
//!    tracer's; the path stops at its first diffuse-like hit, the visible point, where
//!    direct light is estimated once more without MIS;
//! 3. traces `photons` photons from the lights ([`crate::photon`]) and keeps every photon
//!    vertex after at least one bounce (direct light was the camera path's: no path is
//!    counted twice);
//! 4. gathers, at each visible point, the photons within the pass radius r:
//!    L = β · Σ f(wo, wi_p) Φ_p / (N_photons π r²) (a constant kernel).
//!
//! Gathering is a pixel-parallel query of a hash grid over the pass's photons
//! ([`crate::photon::store::HashGrid`]), so each pixel sums its photons in a fixed order:
//! the image is the same whatever the thread count.
//!
//! The initial radius, unless given, is 2 pixel footprints at the median visible point of
//! the first pass.
//!
//! Progress: per pixel, the sums of the passes' estimates are kept apart for even and odd
//! passes (two independent half images). After 1, 2, 4, … passes and at the end an
//! observer ([`crate::render::Observer`]) sees the mean so far and the halves' means, and
//! may stop the render; the time limit is checked between passes.

use super::path::{self, StopAt, VisiblePoint};
use super::{Context, Integrator, StoreBudget, MAX_PHOTONS};
use crate::bsdf::TransportMode;
use crate::camera::Camera;
use crate::error::Result;
use crate::math::Rng;
use crate::output::ImageRgb;
use crate::photon::emit::PhotonEmitter;
use crate::photon::grid::HashGrid;
use crate::photon::store::Photon;
use crate::photon::trace::{self, TraceSettings};
use crate::render::{
    guard, progress_bar, Control, Observer, Progress, RenderSettings, RenderStats,
};
use crate::scene::Scene;
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::{DVec3, Vec2, Vec3};
use rayon::prelude::*;
use std::time::Instant;

/// Photons traced per parallel work item (the split is fixed, so results are deterministic).
const CHUNK: u64 = 4096;

/// Renders with SPPM: `passes` passes, fewer if the time limit or the observer stops it.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    settings: &RenderSettings,
    observer: Option<Observer>,
) -> Result<(ImageRgb, RenderStats)> {
    if settings.spectral {
        run::<SampledSpectrum>(scene, camera, integrator, settings, observer)
    } else {
        run::<Vec3>(scene, camera, integrator, settings, observer)
    }
}

/// The radius-sequence factor of pass `i` (1-based): r²ᵢ₊₁ / r²ᵢ = (i + α)/(i + 1).
pub fn radius2_factor(i: u32, alpha: f32) -> f64 {
    (i as f64 + alpha as f64) / (i as f64 + 1.0)
}

/// The pixel footprint (world size of one pixel) at distance `d` from the camera, from two
/// neighbouring rays at the image centre.
pub fn pixel_footprint(camera: &Camera, settings: &RenderSettings, d: f32) -> f32 {
    let c = Vec2::new(settings.width as f32, settings.height as f32) * 0.5;
    let a = camera.generate_ray(c);
    let b = camera.generate_ray(c + Vec2::X);
    let (da, db) = (a.dir.normalize(), b.dir.normalize());
    (a.origin + da * d).distance(b.origin + db * d)
}

/// Sum of f · Φ over the photons within `r` of a visible point, with the hero-wavelength
/// bookkeeping: when both the camera path and the photon kept only the hero (each then
/// carries 4× the hero lane), the product is divided by 4 once.
fn gather<C: Carrier>(vp: &VisiblePoint<C>, photons: &[Photon], grid: &HashGrid, r: f32) -> C {
    let mut phi = C::ZERO;
    let vp_hero = C::is_hero_only(&vp.lambda);
    grid.for_each_within(vp.p, r, |i, _d2| {
        let ph = &photons[i as usize];
        let wi = vp.frame.to_local(ph.wi());
        let f = vp.bsdf.eval(vp.wo, wi, TransportMode::Radiance);
        let mut c = f * C::from_lanes(ph.power());
        if vp_hero && ph.flags() & Photon::HERO_ONLY != 0 {
            c /= 4.0;
        }
        phi += c;
    });
    phi
}

fn run<C: Carrier>(
    scene: &Scene,
    camera: &Camera,
    integrator: &Integrator,
    settings: &RenderSettings,
    mut observer: Option<Observer>,
) -> Result<(ImageRgb, RenderStats)> {
    let ps = &integrator.photon;
    let (w, h) = (settings.width, settings.height);
    let n_pix = (w as usize) * (h as usize);
    let n_photons = if ps.photons > 0 {
        ps.photons
    } else {
        (n_pix as u64).min(MAX_PHOTONS)
    };
    let emitter = PhotonEmitter::new(scene);
    let trace_settings = TraceSettings {
        max_depth: integrator.max_depth,
        roulette: ps.roulette,
    };
    let passes = ps.passes.max(1);
    let bar = progress_bar(settings.quiet, passes as u64, "sppm passes");
    let mut last_estimate: Option<f64> = None;
    let start = Instant::now();
    // Per-pixel sums over even [0] and odd [1] passes of the direct (camera) and photon
    // estimates.
    let mut ld = vec![[DVec3::ZERO; 2]; n_pix];
    let mut tau = vec![[DVec3::ZERO; 2]; n_pix];
    let mut vps: Vec<Option<VisiblePoint<C>>> = vec![None; n_pix];
    let mut photons: Vec<Photon> = Vec::new();
    let mut grid = HashGrid::new();
    let mut r2: Option<f64> = ps.radius.map(|r| (r as f64) * (r as f64));
    let (mut rays, mut emitted) = (0u64, 0u64);
    let mut done = 0u32;
    let (mut bad, mut interrupted) = (0u64, false);
    for pass in 0..passes {
        let half = (pass % 2) as usize;
        // 1. The pass's wavelengths: a golden-ratio sequence over passes.
        let u_l = (0.5 + pass as f64 * 0.618_033_988_749_895 + (settings.seed % 1024) as f64 * 0.1)
            .fract() as f32;
        let lambda = C::sample_lambda(u_l.min(1.0 - f32::EPSILON));
        // 2. Camera paths.
        let (cam_rays, cam_bad) = ld
            .par_chunks_mut(w as usize)
            .zip(vps.par_chunks_mut(w as usize))
            .enumerate()
            .map(|(y, (ld_row, vp_row))| {
                let (mut rays, mut bad) = (0, 0);
                for x in 0..w as usize {
                    let mut ctx = Context {
                        rng: Rng::new(&[settings.seed, pass as u64, x as u64, y as u64]),
                        rays: 0,
                    };
                    let jitter = Vec2::new(ctx.rng.next_f32(), ctx.rng.next_f32());
                    let ray = camera.generate_ray(Vec2::new(x as f32, y as f32) + jitter);
                    let (l, vp) = path::camera_path::<C>(
                        scene,
                        &ray,
                        integrator.max_depth,
                        lambda,
                        StopAt::Diffuse,
                        &mut ctx,
                    );
                    ld_row[x][half] += guard::admit(l.to_rgb(&lambda), &mut bad).as_dvec3();
                    vp_row[x] = vp;
                    rays += ctx.rays;
                }
                (rays, bad)
            })
            .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
        rays += cam_rays;
        bad += cam_bad;
        if r2.is_none() {
            let o = camera
                .generate_ray(Vec2::new(w as f32, h as f32) * 0.5)
                .origin;
            let mut d: Vec<f32> = vps.iter().flatten().map(|v| v.p.distance(o)).collect();
            let r = if d.is_empty() {
                0.01 * (scene.bounds.1 - scene.bounds.0).length()
            } else {
                let mid = d.len() / 2;
                let (_, m, _) = d.select_nth_unstable_by(mid, f32::total_cmp);
                2.0 * pixel_footprint(camera, settings, *m)
            };
            let r = if r.is_finite() && r > 0.0 { r } else { 1e-3 };
            r2 = Some((r as f64) * (r as f64));
        }
        let r = r2.map_or(0.0, f64::sqrt) as f32;
        // 3. Photons, in fixed chunks.
        let chunks = n_photons.div_ceil(CHUNK);
        let budget = StoreBudget::default();
        let per_chunk: Vec<(Vec<Photon>, u64)> = (0..chunks)
            .into_par_iter()
            .map(|c| {
                let mut out = Vec::new();
                let mut rays = 0;
                let inv_n = 1.0 / n_photons as f32;
                for i in c * CHUNK..((c + 1) * CHUNK).min(n_photons) {
                    let mut rng = Rng::new(&[settings.seed, pass as u64, i, 0x9E07]);
                    let Some(ph) = emitter.emit_from(scene, &mut rng) else {
                        continue;
                    };
                    let before = out.len();
                    rays +=
                        trace::trace::<C>(scene, &ph, lambda, &trace_settings, &mut rng, |v, l| {
                            if v.bounces > 0 {
                                let flags = if C::is_hero_only(l) {
                                    Photon::HERO_ONLY
                                } else {
                                    0
                                };
                                out.push(Photon::new(
                                    v.p,
                                    v.wi,
                                    (v.power * inv_n).to_lanes(),
                                    flags,
                                ));
                            }
                        });
                    if !budget.add(out.len() - before) {
                        break;
                    }
                }
                (out, rays)
            })
            .collect();
        budget.check(n_photons, integrator.max_depth)?;
        photons.clear();
        // Exact reservation: the buffer's capacity is the largest pass's photon count, not
        // a doubling of it.
        photons.reserve_exact(per_chunk.iter().map(|c| c.0.len()).sum());
        for (p, r) in per_chunk {
            photons.extend_from_slice(&p);
            rays += r;
        }
        emitted += n_photons;
        // 4. Gather.
        grid.rebuild(&photons, r);
        let area = std::f64::consts::PI * r2.unwrap_or(0.0);
        bad += tau
            .par_iter_mut()
            .zip(vps.par_iter())
            .map(|(t, vp)| {
                let mut bad = 0;
                if let (Some(vp), true) = (vp, area > 0.0) {
                    let phi = gather(vp, &photons, &grid, r);
                    let l = guard::admit((vp.beta * phi).to_rgb(&vp.lambda), &mut bad);
                    t[half] += l.as_dvec3() / area;
                }
                bad
            })
            .sum::<u64>();
        done = pass + 1;
        r2 = r2.map(|x| x * radius2_factor(done, ps.alpha));
        bar.inc(1);
        bar.set_message(format!(
            "{done} passes, {rays} rays, r {r:.3e}, {} photons stored{}",
            photons.len(),
            crate::render::estimate_note(last_estimate)
        ));
        interrupted = guard::stop_requested() && done < passes;
        let finished = done == passes
            || settings.time_limit.is_some_and(|t| start.elapsed() >= t)
            || interrupted;
        let checkpoint = finished || done.is_power_of_two();
        // The two halves (even and odd passes), built once per checkpoint for the observer
        // and the progress bar's error estimate.
        let halves = (checkpoint && (observer.is_some() || !settings.quiet)).then(|| {
            let (n0, n1) = (done.div_ceil(2), done / 2);
            let a = image(&ld, &tau, n0, w, h, |s| s[0]);
            let b = if n1 > 0 {
                image(&ld, &tau, n1, w, h, |s| s[1])
            } else {
                a.clone()
            };
            (a, b)
        });
        if let (Some((a, b)), true) = (&halves, done >= 2) {
            last_estimate = crate::render::relative_error_estimate(a, b);
        }
        if let (Some(obs), Some((a, b))) = (observer.as_mut(), &halves) {
            let mean = image(&ld, &tau, done, w, h, |s| s[0] + s[1]);
            let progress = Progress {
                image: &mean,
                halves: (a, b),
                elapsed: start.elapsed(),
                samples: done as u64,
                passes: done,
                rays,
                photons: emitted,
                done: finished,
            };
            if obs(&progress)? == Control::Stop {
                break;
            }
        }
        if finished {
            break;
        }
    }
    bar.finish_and_clear();
    Ok((
        image(&ld, &tau, done, w, h, |s| s[0] + s[1]),
        RenderStats {
            time: start.elapsed(),
            rays,
            samples: n_pix as u64 * done as u64,
            photons: emitted,
            passes: done,
            bad_samples: bad,
            interrupted,
        },
    ))
}

/// The mean over `passes` passes of `pick`(per-parity sums of direct + photon estimates).
fn image(
    ld: &[[DVec3; 2]],
    tau: &[[DVec3; 2]],
    passes: u32,
    w: u32,
    h: u32,
    pick: impl Fn([DVec3; 2]) -> DVec3,
) -> ImageRgb {
    let inv = 1.0 / passes.max(1) as f64;
    ImageRgb {
        width: w,
        height: h,
        data: ld
            .iter()
            .zip(tau)
            .map(|(a, b)| (pick([a[0] + b[0], a[1] + b[1]]) * inv).as_vec3())
            .collect(),
    }
}
