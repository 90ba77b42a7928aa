//! A ball lens focuses photons where geometric optics says.
//!
//! Scene ([`iris::assets::caustic::focus_bench`]): a glass sphere (n = 1.5, R = 1,
//! icosphere with 6 subdivisions and radial normals) behind an opaque plate with a hole of
//! radius `aperture` on the axis, lit by a directional light along −Z, a white screen
//! behind it. Photons are traced by the renderer's own emitter and tracer; those reaching
//! the screen after exactly two refractions (the caustic) are kept with their position,
//! direction and power.
//!
//! - Paraxial beam (aperture R/10): the power-weighted RMS spot radius, evaluated on planes
//!   z = −s by following each photon's straight line back and forth from the screen, is
//!   smallest at s within 2 % of f = nR/(2(n − 1)) = 1.5 (Hecht, "Optics", §6.2). Exact
//!   ray tracing of a perfect sphere puts the RMS-best plane at 0.998 f for this aperture
//!   (spherical aberration), so 2 % is the tessellation and sampling allowance.
//!   The screen itself is moved too: the spot is smaller on a screen at f than at 0.9 f
//!   or 1.1 f.
//! - Wide beam (aperture 0.9 R): the best plane moves toward the lens (spherical
//!   aberration). The prediction is computed here independently by tracing a perfect
//!   sphere in f64 with Snell's law and Fresnel transmission weights (the photon tracer
//!   chooses reflection or refraction with the Fresnel probability), over the same
//!   uniformly lit disc; it is ≈ 0.81 f, and the photons must agree within 3 %.

use crate::common;

use glam::{DVec3, Vec3};
use iris::photon::emit::PhotonEmitter;
use iris::photon::trace::{trace, Roulette, TraceSettings};
use rayon::prelude::*;

const N: f32 = 1.5;
const R: f32 = 1.0;

/// Photons on the screen after exactly two refractions: (position, unit travel direction,
/// power).
fn screen_photons(aperture: f32, screen: f32, photons: u64, tag: &str) -> Vec<(Vec3, Vec3, f32)> {
    let gen = iris::assets::caustic::focus_bench(N, R, aperture, screen, 6);
    // The light shines exactly along −Z: every photon direction has two zero components
    // (the BVH backend's finite-inverse slab test keeps this fast: src/accel/bvh.rs).
    let dir = common::scratch_dir(&format!("photon_focus_{tag}"));
    let path = dir.join(format!("{tag}.glb"));
    iris::authoring::write_glb(&path, &gen).expect("write focus bench");
    let (scene, _) = iris::app::load(&path, iris::accel::Backend::Auto).expect("load");
    let emitter = PhotonEmitter::new(&scene);
    let settings = TraceSettings {
        max_depth: 8,
        roulette: Roulette::Throughput,
    };
    let chunk = 65_536u64;
    (0..photons.div_ceil(chunk))
        .into_par_iter()
        .flat_map_iter(|c| {
            let mut out = Vec::new();
            for i in c * chunk..((c + 1) * chunk).min(photons) {
                let mut rng = iris::math::Rng::new(&[17, i]);
                let Some(ph) = emitter.emit_from(&scene, &mut rng) else {
                    continue;
                };
                trace::<Vec3>(&scene, &ph, (), &settings, &mut rng, |v, _| {
                    if v.bounces == 2 && v.caustic && (v.p.z + screen).abs() < 1e-3 {
                        out.push((v.p, -v.wi, v.power.y));
                    }
                });
            }
            out
        })
        .collect()
}

/// Power-weighted RMS distance from the spot's centroid of the photons' lines on the plane
/// z = −s.
fn rms_at(photons: &[(Vec3, Vec3, f32)], s: f64) -> f64 {
    let on_plane: Vec<(DVec3, f64)> = photons
        .iter()
        .map(|&(p, d, pw)| {
            let (p, d) = (p.as_dvec3(), d.as_dvec3());
            (p + d * ((-s - p.z) / d.z), pw as f64)
        })
        .collect();
    let w: f64 = on_plane.iter().map(|x| x.1).sum();
    let c = on_plane.iter().map(|(q, pw)| *q * *pw).sum::<DVec3>() / w;
    let sum: f64 = on_plane
        .iter()
        .map(|(q, pw)| pw * ((q.x - c.x).powi(2) + (q.y - c.y).powi(2)))
        .sum();
    (sum / w).sqrt()
}

/// The plane in [lo, hi] with the smallest RMS spot (fine scan, 0.1 % steps).
fn best_plane(rms: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    let steps = 1000;
    (0..=steps)
        .map(|i| lo + (hi - lo) * i as f64 / steps as f64)
        .min_by(|a, b| rms(*a).total_cmp(&rms(*b)))
        .unwrap()
}

/// Unpolarised Fresnel reflectance, cos θi ≥ 0, eta = n_t/n_i (Born & Wolf).
fn fresnel(ci: f64, eta: f64) -> f64 {
    let s2 = (1.0 - ci * ci) / (eta * eta);
    if s2 >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - s2).sqrt();
    let rs = (ci - eta * ct) / (ci + eta * ct);
    let rp = (eta * ci - ct) / (eta * ci + ct);
    0.5 * (rs * rs + rp * rp)
}

/// Snell refraction of unit `d` at unit normal `n` (against d), eta = n_i/n_t.
fn refract(d: DVec3, n: DVec3, eta: f64) -> DVec3 {
    let ci = -d.dot(n);
    let ct = (1.0 - eta * eta * (1.0 - ci * ci)).sqrt();
    eta * d + (eta * ci - ct) * n
}

/// A perfect sphere traced exactly: for a ray at height h along −Z, the exit point, exit
/// direction and the Fresnel transmission T₁T₂.
fn exact(h: f64) -> (DVec3, DVec3, f64) {
    let (n, r) = (N as f64, R as f64);
    let d = DVec3::NEG_Z;
    let p = DVec3::new(h, 0.0, (r * r - h * h).sqrt());
    let n1 = p / r;
    let t1 = 1.0 - fresnel(-d.dot(n1), n);
    let d2 = refract(d, n1, 1.0 / n);
    // Second intersection: p + t d2 on the sphere, the far root.
    let b = p.dot(d2);
    let t = -2.0 * b;
    let q = p + d2 * t;
    let n2 = -q / r;
    let t2 = 1.0 - fresnel(-d2.dot(n2), 1.0 / n);
    (q, refract(d2, n2, n), t1 * t2)
}

fn exact_rms(aperture: f64, s: f64) -> f64 {
    let m = 4000;
    let (mut sum, mut w) = (0.0, 0.0);
    for i in 0..m {
        let h = aperture * (i as f64 + 0.5) / m as f64;
        let (q, d, tr) = exact(h);
        let x = q.x + d.x * (-s - q.z) / d.z;
        // Uniform illumination of the disc: weight ∝ h dh.
        sum += h * tr * x * x;
        w += h * tr;
    }
    (sum / w).sqrt()
}

#[test]
fn a_paraxial_beam_focuses_at_the_paraxial_focal_length() {
    let f = (N * R / (2.0 * (N - 1.0))) as f64;
    // The screen beyond the focus; lines are followed back to each plane.
    let photons = screen_photons(0.1 * R, 2.2 * R, 6_000_000, "paraxial");
    assert!(
        photons.len() > 2000,
        "only {} photons through the hole",
        photons.len()
    );
    let best = best_plane(|s| rms_at(&photons, s), 0.7 * f, 1.3 * f);
    eprintln!(
        "paraxial: {} photons, best plane {best:.4} vs f {f:.4} ({:+.2} %), rms there {:.2e}",
        photons.len(),
        (best / f - 1.0) * 100.0,
        rms_at(&photons, best)
    );
    assert!((best / f - 1.0).abs() < 0.02, "best plane {best} vs f {f}");
    // The real screen at 0.9 f, f, 1.1 f: positions only.
    let spot = |s: f32, tag: &str| {
        let ph = screen_photons(0.1 * R, s, 2_000_000, tag);
        assert!(ph.len() > 500, "{tag}: {} photons", ph.len());
        rms_at(&ph, s as f64)
    };
    let (near, at, far) = (
        spot(0.9 * f as f32, "near"),
        spot(f as f32, "at"),
        spot(1.1 * f as f32, "far"),
    );
    eprintln!("screen RMS spot: 0.9f {near:.3e}, f {at:.3e}, 1.1f {far:.3e}");
    assert!(at < near && at < far);
}

#[test]
fn a_wide_beam_focuses_closer_as_exact_ray_tracing_predicts() {
    let f = (N * R / (2.0 * (N - 1.0))) as f64;
    let aperture = 0.9 * R as f64;
    let predicted = best_plane(|s| exact_rms(aperture, s), 0.5 * f, 1.2 * f);
    let photons = screen_photons(aperture as f32, 2.2 * R, 400_000, "wide");
    assert!(photons.len() > 5000, "only {} photons", photons.len());
    let best = best_plane(|s| rms_at(&photons, s), 0.5 * f, 1.2 * f);
    eprintln!(
        "wide (0.9R): {} photons, best plane {best:.4} = {:.3} f; exact sphere predicts {predicted:.4} = {:.3} f",
        photons.len(),
        best / f,
        predicted / f
    );
    // Spherical aberration: clearly closer than the paraxial focus.
    assert!(predicted < 0.9 * f);
    assert!(
        (best / predicted - 1.0).abs() < 0.03,
        "best {best} vs predicted {predicted}"
    );
}
