//! Statistical and analytic tests of the BSDFs (pbrt-v4 / Mitsuba style). Histograms bin
//! the sphere in the microfacet-normal (half-vector) domain, per lobe (`hv_bins`: 16×32 bins
//! per lobe, warped so that half of them cover the GGX core); expected counts come from an
//! adaptive quadrature of `pdf` over each bin, done in that domain with solid angles taken
//! from the geometry of the half-vector maps (not from the BSDF code). Deterministic `Rng`
//! streams.
//!
//! Measured (2026-12-01, 500k samples/case):
//! - χ²: 56 cases (Lambert ×2, Conductor α 0.05 at 10/60/75/85/89°, α 0.3/0.8 at
//!   10/60/85°, Dielectric α 0.1/0.4 × η 1.5, 1/1.5, 0.8 × 5 wo incl. 85° and 2 inside,
//!   Dielectric α 0.05 × η 1.5, 1/1.5 at 85°/89° from both sides, GltfPbr metallic 0/0.5
//!   ×2 wo). p-values spread over (0, 1); smallest 0.0118 (Dielectric η 1/1.5 α 0.1 at
//!   65°), then 0.0267; the per-case threshold is the Šidák-corrected
//!   1 − 0.99^(1/56) ≈ 1.8e-4 (family-wise significance 0.01). Conductor α 0.05: p 0.42
//!   at 85°, 0.95 at 89°.
//! - The grazing α 0.05 conductor (excluded until 2026-12-01) was a quadrature artefact,
//!   not a BSDF bug: the old (θ, φ) bins with a 16×16 midpoint sub-grid per bin gave ∫pdf
//!   0.9782 at 85° (0.9904 at 89°), against 0.9689 (0.9894) from a 4000×8000 (θ, φ) grid,
//!   0.9688 (0.9892) from the sampler's failure rate over 2M samples (σ 1.2e-4), and
//!   0.9690 (0.9895) from `hv_bins`; the old 512² albedo quadrature was 1.0 % (7.4 %) low,
//!   while the MC albedo 0.8799 (0.9156) matched the fine grid 0.8799 (0.9157). The lobe
//!   is ≈ 0.3° (0.06°) wide in φ there, below the old 0.56° sub-cells.
//! - ∫pdf: Lambert 1.0000; others < 1 by the mass of rejected samples (microfacet reflections
//!   under the horizon), e.g. Conductor α 0.8 at normal incidence 0.61, Dielectric α 0.4
//!   0.75–0.99 (0.75: η 0.8 at 85°), α 0.1 ≥ 0.93, α 0.05 ≥ 0.96, GltfPbr ≥ 0.988. The "no sample" cell is part of the χ² test.
//! - Albedo MC vs quadrature: within 1 % everywhere tested (Lambert MC exact to 1e-5).
//! - Energy (Radiance mode with 1/η'² undone, tint 1): rough GGX without multiple scattering loses energy:
//!   α 0.1: 0.906–0.999; α 0.4: 0.639–0.976 (worst: η 0.8, wo outside at 75°); over the
//!   energy-test grid (α 0.05–1, η_eff 1/2.4–2.4, μo 0.05–1) down to 0.309. With the
//!   multiple-scattering compensation (2026-12-01, `energy`): 1 within 0.52 % everywhere
//!   on that grid (worst s.e. 0.19 %); E_ss table vs fine quadrature ≤ 0.23 %.
//! - Mutation checks (done by hand, reverted): dropping the square of the transmission
//!   Jacobian denominator in `Rough::pdf` fails the χ² and albedo tests (re-checked with the
//!   half-vector quadrature, which borrows no Jacobian: p = 0, albedo MC 1.256 vs
//!   quadrature 0.467 for η 1.5, α 0.1 at 20°); dividing by η' instead
//!   of η'² in `Rough::eval` fails the generalised-reciprocity test.

use super::*;
use crate::math::Rng;
use chi2::chi2_pvalue;
use hv_bins::{Bins, Lobe, Node};
use std::f64::consts::PI;

pub(super) mod chi2;
mod hv_bins;
mod iridescence;

const R: TransportMode = TransportMode::Radiance;
const I: TransportMode = TransportMode::Importance;

fn dir(theta: f64, phi: f64) -> Vec3 {
    let (st, ct) = theta.sin_cos();
    Vec3::new((st * phi.cos()) as f32, (st * phi.sin()) as f32, ct as f32)
}

/// The half-vector bins of `b` seen from `wo` (see `hv_bins`): a reflection lobe, plus a
/// refraction lobe for the dielectric, warped by the GGX α (1 for Lambert).
fn bins(b: &Bsdf, wo: Vec3) -> Bins {
    let (lobes, alpha_w): (&[Lobe], f32) = match *b {
        Bsdf::Lambert { .. } => (&[Lobe::Reflect], 1.0),
        Bsdf::Conductor { alpha, .. } | Bsdf::ComplexConductor { alpha, .. } => {
            (&[Lobe::Reflect], alpha)
        }
        Bsdf::Dielectric { eta, alpha, .. } => {
            (&[Lobe::Reflect, Lobe::Transmit(eta as f64)], alpha)
        }
        Bsdf::GltfPbr { alpha, .. } => (&[Lobe::Reflect], alpha.max(gltf_brdf::GLTF_MIN_ALPHA)),
        Bsdf::ThinDielectric { .. } => (&[], 1.0),
    };
    Bins::new(wo, lobes, alpha_w as f64)
}

/// ∫ g dω over each bin from quadrature nodes.
fn integrate_nodes(n_bins: usize, nodes: &[Node], g: impl Fn(Vec3) -> f64) -> Vec<f64> {
    let mut out = vec![0.0; n_bins];
    for n in nodes {
        out[n.bin] += g(n.wi) * n.w;
    }
    out
}

const N_SAMPLES: usize = 500_000;

/// Histogram of `sample` (non-delta) over `bins`, checking each sample's pdf/f against
/// pdf()/eval(). Two extra cells at the end: samples outside every bin (where the pdf must
/// be 0), and "no sample".
fn sample_counts(b: &Bsdf, wo: Vec3, mode: TransportMode, seed: u64, bins: &Bins) -> Vec<f64> {
    let n = bins.len();
    let mut rng = Rng::new(&[seed, 0xB5DF]);
    let mut obs = vec![0.0; n + 2];
    for _ in 0..N_SAMPLES {
        let uc = rng.next_f32();
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        match b.sample(wo, uc, u, mode) {
            Some(s) if !s.delta => {
                let p = b.pdf(wo, s.wi, mode);
                assert!(
                    (s.pdf - p).abs() <= 1e-3 * p.max(s.pdf),
                    "{b:?} wo {wo} wi {}: sample pdf {} vs pdf() {p}",
                    s.wi,
                    s.pdf
                );
                let f = b.eval(wo, s.wi, mode);
                assert!((s.f - f).abs().max_element() <= 1e-3 * f.max_element().max(1e-6));
                obs[bins.bin_of(s.wi).unwrap_or(n)] += 1.0;
            }
            _ => obs[n + 1] += 1.0,
        }
    }
    obs
}

/// Expected counts of [`sample_counts`]'s cells for the density `pdf`, and ∫pdf.
fn expected_counts(bins: &Bins, nodes: &[Node], pdf: impl Fn(Vec3) -> f64) -> (Vec<f64>, f64) {
    let mut exp = integrate_nodes(bins.len(), nodes, pdf);
    let total: f64 = exp.iter().sum();
    for e in &mut exp {
        *e *= N_SAMPLES as f64;
    }
    exp.push(0.0);
    exp.push(((1.0 - total) * N_SAMPLES as f64).max(0.0));
    (exp, total)
}

/// Observed and expected counts (see [`sample_counts`]) and ∫pdf for one case.
fn histograms(b: &Bsdf, wo: Vec3, mode: TransportMode, seed: u64) -> (Vec<f64>, Vec<f64>, f64) {
    let bins = bins(b, wo);
    let obs = sample_counts(b, wo, mode, seed, &bins);
    let pdf = |w| b.pdf(wo, w, mode) as f64;
    let (exp, total) = expected_counts(&bins, &bins.nodes(pdf, hv_bins::ACCURACY), pdf);
    (obs, exp, total)
}

fn wo_at(deg: f64, inside: bool) -> Vec3 {
    let t = deg.to_radians();
    let t = if inside { PI - t } else { t };
    dir(t, 0.7)
}

fn gltf(metallic: f32) -> Bsdf {
    gltf_with(metallic, LobeExtensions::NONE)
}

/// The test glTF material (orange, roughness 0.3, ior 1.5, no layers) with `extensions`.
fn gltf_with(metallic: f32, extensions: LobeExtensions) -> Bsdf {
    Bsdf::GltfPbr {
        base: Vec3::new(0.8, 0.5, 0.2),
        metallic,
        alpha: 0.3 * 0.3,
        ior: 1.5,
        specular: 1.0,
        specular_color: Vec3::ONE,
        layers: Layers::none(),
        extensions,
    }
}

/// Non-delta cases: (bsdf, wo, always produces a sample).
fn cases() -> Vec<(Bsdf, Vec3, bool)> {
    let mut v = Vec::new();
    let lam = Bsdf::Lambert {
        albedo: Vec3::new(0.9, 0.5, 0.1),
    };
    v.push((lam, wo_at(30.0, false), true));
    v.push((lam, wo_at(70.0, true), true));
    for alpha in [0.05, 0.3, 0.8] {
        let c = Bsdf::Conductor {
            f0: Vec3::new(0.95, 0.64, 0.54),
            alpha,
        };
        // α = 0.05 at 85° and 89°: the lobe is a sliver against the horizon (≈ 0.3° and
        // 0.06° wide in φ), resolved by the half-vector bins and quadrature (`hv_bins`).
        let degs: &[f64] = if alpha < 0.1 {
            &[10.0, 60.0, 75.0, 85.0, 89.0]
        } else {
            &[10.0, 60.0, 85.0]
        };
        for &deg in degs {
            v.push((c, wo_at(deg, false), false));
        }
    }
    for alpha in [0.1, 0.4] {
        for eta in [1.5, 1.0 / 1.5, 0.8] {
            let d = Bsdf::Dielectric {
                eta,
                alpha,
                tint: Vec3::new(1.0, 0.9, 0.8),
            };
            for (deg, inside) in [
                (20.0, false),
                (65.0, false),
                (85.0, false),
                (30.0, true),
                (60.0, true),
            ] {
                v.push((d, wo_at(deg, inside), false));
            }
        }
    }
    // Grazing narrow dielectric lobes, from both sides.
    for eta in [1.5, 1.0 / 1.5] {
        let d = Bsdf::Dielectric {
            eta,
            alpha: 0.05,
            tint: Vec3::ONE,
        };
        for (deg, inside) in [(85.0, false), (89.0, false), (85.0, true), (89.0, true)] {
            v.push((d, wo_at(deg, inside), false));
        }
    }
    for m in [0.0, 0.5] {
        for deg in [15.0, 70.0] {
            v.push((gltf(m), wo_at(deg, false), false));
        }
    }
    v
}

/// Tests 1 + 2: χ² goodness of fit of sample() vs pdf() for every case, at significance
/// 0.01 with the Šidák correction over the cases; ∫pdf = 1 (Lambert) or ≤ 1.
#[test]
fn chi_square_sample_matches_pdf() {
    let cs = cases();
    let alpha = 1.0 - (1.0f64 - 0.01).powf(1.0 / cs.len() as f64);
    let mut worst = 1.0f64;
    for (k, (b, wo, always)) in cs.iter().enumerate() {
        let (obs, exp, total) = histograms(b, *wo, R, k as u64);
        if *always {
            assert!((total - 1.0).abs() < 0.01, "{b:?} ∫pdf = {total}");
        } else {
            assert!(total < 1.01, "{b:?} ∫pdf = {total}");
        }
        let p = chi2_pvalue(&obs, &exp);
        eprintln!("chi2 {b:?} wo {wo}: p = {p:.4}, ∫pdf = {total:.4}");
        worst = worst.min(p);
        assert!(p > alpha, "{b:?} wo {wo}: χ² p = {p} < {alpha}");
    }
    eprintln!("worst p = {worst}");
}

/// The χ² test can fail: cosine-weighted Lambert samples judged against a uniform
/// hemisphere pdf must be rejected, and so must a grazing GGX lobe judged against a
/// slightly wider one.
#[test]
fn chi_square_rejects_wrong_pdf() {
    let b = Bsdf::Lambert { albedo: Vec3::ONE };
    let wo = wo_at(30.0, false);
    let hb = bins(&b, wo);
    let obs = sample_counts(&b, wo, R, 99, &hb);
    let uniform = |w: Vec3| if w.z > 0.0 { 0.5 / PI } else { 0.0 };
    let (exp, total) = expected_counts(&hb, &hb.nodes(uniform, hv_bins::ACCURACY), uniform);
    assert!((total - 1.0).abs() < 1e-3, "∫ uniform pdf = {total}");
    assert!(chi2_pvalue(&obs, &exp) < 1e-6);
    // The narrow grazing lobe is resolved: α = 0.05 samples at 85° against the pdf of a
    // 5 % wider lobe must be rejected too.
    let c = |alpha| Bsdf::Conductor {
        f0: Vec3::ONE,
        alpha,
    };
    let wo = wo_at(85.0, false);
    let hb = bins(&c(0.05), wo);
    let obs = sample_counts(&c(0.05), wo, R, 98, &hb);
    let wrong = |w| c(0.0525).pdf(wo, w, R) as f64;
    let (exp, _) = expected_counts(&hb, &hb.nodes(wrong, hv_bins::ACCURACY), wrong);
    let p = chi2_pvalue(&obs, &exp);
    assert!(p < 1e-6, "α 0.05 vs 0.0525: p = {p}");
}

/// The energy a dielectric scatters from `wo` (red channel), by sampling: mean of
/// f|cos|/pdf in Radiance mode with the transmission's 1/η'² undone (η' = n_t/n_i from wo to
/// wi), the energy a camera vertex's compensation conserves.
pub(super) fn energy_albedo(b: &Bsdf, wo: Vec3, seed: u64) -> f64 {
    let Bsdf::Dielectric { eta, .. } = *b else {
        unreachable!("a dielectric")
    };
    let etap = if wo.z > 0.0 { eta } else { 1.0 / eta };
    let n = 200_000;
    let mut rng = Rng::new(&[seed, 0xE4E]);
    let mut sum = 0.0f64;
    for _ in 0..n {
        let uc = rng.next_f32();
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(s) = b.sample(wo, uc, u, R) {
            let undo = if s.transmission { etap * etap } else { 1.0 };
            sum += (s.f.x * s.wi.z.abs() / s.pdf * undo) as f64;
        }
    }
    sum / n as f64
}

/// Sampling estimate mean(f|cos|/pdf) and half-vector-domain quadrature ∫ f|cos| dω.
fn albedos(b: &Bsdf, wo: Vec3, mode: TransportMode, seed: u64) -> (Vec3, Vec3) {
    let n = 200_000;
    let mut rng = Rng::new(&[seed, 0xA1BE]);
    let mut mc = [0.0f64; 3];
    for _ in 0..n {
        let uc = rng.next_f32();
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(s) = b.sample(wo, uc, u, mode) {
            let w = s.f * s.wi.z.abs() / s.pdf;
            for c in 0..3 {
                mc[c] += w[c] as f64;
            }
        }
    }
    let mut q = [0.0f64; 3];
    let g = |w: Vec3| (b.eval(wo, w, mode) * w.z.abs()).max_element() as f64;
    for n in bins(b, wo).nodes(g, hv_bins::ALBEDO_ACCURACY) {
        let f = b.eval(wo, n.wi, mode) * n.wi.z.abs();
        for c in 0..3 {
            q[c] += f[c] as f64 * n.w;
        }
    }
    let v =
        |a: [f64; 3], s: f64| Vec3::new((a[0] / s) as f32, (a[1] / s) as f32, (a[2] / s) as f32);
    (v(mc, n as f64), v(q, 1.0))
}

/// Test 3: sampling estimator = quadrature (1 %); white Lambert albedo 1; non-absorbing
/// rough dielectric: the energy it scatters ([`energy_albedo`]) ≤ 1 + 1 %.
#[test]
fn albedo_sampling_matches_quadrature() {
    for (k, (b, wo, _)) in cases().iter().enumerate() {
        let (mc, q) = albedos(b, *wo, R, k as u64);
        let err = (mc - q).abs().max_element();
        eprintln!("albedo {b:?} wo {wo}: mc {mc} quad {q}");
        assert!(
            err <= 0.01 * q.max_element().max(0.05),
            "{b:?} wo {wo}: mc {mc} vs quad {q}"
        );
    }
    let (mc, q) = albedos(
        &Bsdf::Lambert { albedo: Vec3::ONE },
        wo_at(40.0, false),
        R,
        7,
    );
    assert!(
        (mc - Vec3::ONE).abs().max_element() < 1e-4 && (q - Vec3::ONE).abs().max_element() < 0.01
    );
    // The measured-metal conductor (gold-like indices per channel) samples as the Schlick
    // one does; its albedo estimate meets the quadrature of its own eval.
    let gold = Bsdf::ComplexConductor {
        eta: Vec3::new(0.18, 0.45, 1.4),
        k: Vec3::new(3.0, 2.4, 1.85),
        alpha: 0.3,
        extensions: LobeExtensions::NONE,
    };
    for deg in [20.0, 70.0] {
        let (mc, q) = albedos(&gold, wo_at(deg, false), R, 11);
        let err = (mc - q).abs().max_element();
        assert!(
            err <= 0.01 * q.max_element(),
            "gold {deg}°: mc {mc} quad {q}"
        );
    }
    for alpha in [0.1, 0.4] {
        for eta in [1.5, 1.0 / 1.5, 0.8] {
            for (deg, inside) in [(20.0, false), (75.0, false), (40.0, true)] {
                let b = Bsdf::Dielectric {
                    eta,
                    alpha,
                    tint: Vec3::ONE,
                };
                let e = energy_albedo(&b, wo_at(deg, inside), 3);
                eprintln!("energy α {alpha} η {eta} θ {deg} inside {inside}: {e}");
                assert!(e <= 1.01, "gains energy: {e}");
            }
        }
    }
}

/// A random direction in the upper (z > 0) or lower hemisphere, |cos θ| ≥ 1e-3.
pub(super) fn rand_dir(rng: &mut Rng, upper: bool) -> Vec3 {
    let z = rng.next_f32().max(1e-3);
    let p = 2.0 * std::f32::consts::PI * rng.next_f32();
    let r = (1.0 - z * z).sqrt();
    Vec3::new(r * p.cos(), r * p.sin(), if upper { z } else { -z })
}

/// The reciprocal single-scatter part of `b.eval`: for a rough dielectric the BSDF without
/// the multiple-scattering compensation (which scales by 1/E_ss(wo), see `energy`).
fn eval_ss(b: &Bsdf, wo: Vec3, wi: Vec3, mode: TransportMode) -> Vec3 {
    match *b {
        Bsdf::Dielectric { eta, alpha, tint } if !b.is_delta() => {
            dielectric::Rough { eta, alpha, tint }.eval_ss(wo, wi, mode)
        }
        _ => b.eval(wo, wi, mode),
    }
}

/// Test 4: reciprocity eval(wo, wi) = eval(wi, wo) for reflection (single-scatter part for
/// the rough dielectric; its compensation is covered by
/// `energy_tests::compensation_breaks_reciprocity_by_the_albedo_ratio`).
#[test]
fn reflection_is_reciprocal() {
    let mut rng = Rng::new(&[4]);
    let mut bs: Vec<Bsdf> = cases().into_iter().map(|c| c.0).collect();
    bs.dedup();
    for b in bs {
        for _ in 0..2000 {
            let up = rng.next_f32() < 0.5 || !matches!(b, Bsdf::Dielectric { .. });
            let (wo, wi) = (rand_dir(&mut rng, up), rand_dir(&mut rng, up));
            let (a, c) = (eval_ss(&b, wo, wi, R), eval_ss(&b, wi, wo, R));
            assert!(
                (a - c).abs().max_element() <= 1e-4 * a.max_element().max(1e-6),
                "{b:?}: {a} vs {c}"
            );
        }
    }
}

/// Test 5: generalised reciprocity of transmission (Veach 1997, eq. 5.14, written for
/// pbrt's argument order f(wo, wi) = f_s(wi → wo)): f(wo, wi)/η(wo)² = f(wi, wo)/η(wi)² in
/// Radiance mode, η(w) the index of the medium w lies in; and the adjoint relation
/// f_Importance(wo, wi) = f_Radiance(wi, wo). Checked on the single-scatter part (for the
/// compensated BSDF see
/// `energy_tests::compensation_breaks_reciprocity_by_the_albedo_ratio`).
#[test]
fn transmission_generalised_reciprocity() {
    let mut rng = Rng::new(&[5]);
    for eta in [1.5f32, 1.0 / 1.5, 0.8] {
        for alpha in [0.1, 0.4] {
            let b = Bsdf::Dielectric {
                eta,
                alpha,
                tint: Vec3::new(1.0, 0.7, 0.4),
            };
            let mut n = 0;
            for _ in 0..20_000 {
                let (wo, wi) = (rand_dir(&mut rng, true), rand_dir(&mut rng, false));
                let (a, c) = (eval_ss(&b, wo, wi, R), eval_ss(&b, wi, wo, R));
                // f32 cancellation in (wi·wm + wo·wm/η')² makes tiny values noisy (0.7 %
                // at f ≈ 4e-7), so only values ≥ 1e-3 are compared.
                // Grazing pairs (|cos| < 0.1) are excluded for the same reason (1.3 % at f ≈ 5e-4).
                if a.max_element() < 1e-3 || c.max_element() < 1e-3 || wo.z < 0.1 || wi.z > -0.1 {
                    continue;
                }
                n += 1;
                let (l, r) = (a / 1.0, c / (eta * eta));
                // Measured: worst relative difference ≈ 1.1e-3 (f32 rounding); tolerance 5e-3.
                assert!(
                    (l - r).abs().max_element() <= 5e-3 * l.max_element(),
                    "η {eta}: {l} vs {r}"
                );
                let imp = eval_ss(&b, wo, wi, I);
                assert!((imp - c).abs().max_element() <= 5e-3 * c.max_element());
            }
            assert!(n > 1000, "too few valid pairs: {n}");
        }
    }
}

/// Test 6: smooth dielectric — R with probability F (4σ), Snell via `optics`, TIR, weights.
#[test]
fn smooth_dielectric() {
    use crate::optics::{fresnel_dielectric, orient_interface, refract};
    let n = 100_000;
    for eta in [1.5f32, 1.0 / 1.5, 0.8] {
        for (deg, inside) in [
            (0.0, false),
            (35.0, false),
            (70.0, false),
            (25.0, true),
            (60.0, true),
        ] {
            let tint = Vec3::new(1.0, 0.8, 0.6);
            let b = Bsdf::Dielectric {
                eta,
                alpha: 0.0,
                tint,
            };
            assert!(b.is_delta());
            let wo = wo_at(deg, inside);
            let (nrm, etar) = orient_interface(!inside, Vec3::Z, eta);
            let f = fresnel_dielectric(wo.dot(nrm), etar);
            let mut rng = Rng::new(&[6, deg as u64]);
            let mut refl = 0usize;
            for _ in 0..n {
                let s = b
                    .sample(
                        wo,
                        rng.next_f32(),
                        Vec2::new(rng.next_f32(), rng.next_f32()),
                        R,
                    )
                    .unwrap();
                let w = s.f * s.wi.z.abs() / s.pdf;
                assert!(s.delta);
                if s.transmission {
                    let wt = refract(wo, nrm, etar).expect("transmission under TIR");
                    assert!((wt - s.wi).length() < 1e-5, "Snell: {wt} vs {}", s.wi);
                    assert!(
                        (w - tint / (etar * etar)).abs().max_element() < 1e-5,
                        "weight {w}"
                    );
                    let si = b.sample(wo, 0.999_999, Vec2::ZERO, I).unwrap();
                    assert!((si.f * si.wi.z.abs() / si.pdf - tint).abs().max_element() < 1e-5);
                } else {
                    refl += 1;
                    assert!((s.wi - Vec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-6);
                    assert!((w - Vec3::ONE).abs().max_element() < 1e-5);
                }
            }
            let (nf, sd) = (
                n as f64 * f as f64,
                (n as f64 * f as f64 * (1.0 - f as f64)).sqrt(),
            );
            assert!(
                (refl as f64 - nf).abs() <= 4.0 * sd + 1e-9,
                "η {eta} θ {deg}: {refl} vs {nf}"
            );
            if f == 1.0 {
                assert_eq!(refl, n, "TIR must reflect everything");
            }
        }
    }
    // TIR cases exist among those above (η = 1/1.5 outside at 70°, η = 1.5 inside at 60°).
    assert_eq!(
        fresnel_dielectric(wo_at(60.0, true).dot(-Vec3::Z), 1.0 / 1.5),
        1.0
    );
    // η = 1: straight through, f = tint/|cos|; η = ∞: mirror.
    let tint = Vec3::new(0.5, 0.6, 0.7);
    let wo = wo_at(40.0, false);
    let s = Bsdf::Dielectric {
        eta: 1.0,
        alpha: 0.3,
        tint,
    }
    .sample(wo, 0.0, Vec2::ZERO, R)
    .unwrap();
    assert!(
        s.transmission
            && (s.wi + wo).length() < 1e-6
            && (s.f * s.wi.z.abs() - tint).length() < 1e-6
    );
    let s = Bsdf::Dielectric {
        eta: f32::INFINITY,
        alpha: 0.0,
        tint,
    }
    .sample(wo, 0.99, Vec2::ZERO, R)
    .unwrap();
    assert!(!s.transmission && s.pdf == 1.0);
    // Thin: straight through with weight tint, reflection with weight 1.
    let thin = Bsdf::ThinDielectric { eta: 1.5, tint };
    let t = thin.sample(wo, 0.999, Vec2::ZERO, R).unwrap();
    assert!(t.transmission && (t.wi + wo).length() < 1e-6);
    assert!((t.f * t.wi.z.abs() / t.pdf - tint).length() < 1e-6);
}

/// Rough dielectric with η = ∞ reflects only and stays finite at grazing.
#[test]
fn edge_cases_are_finite() {
    let mut rng = Rng::new(&[8]);
    for b in [
        Bsdf::Dielectric {
            eta: f32::INFINITY,
            alpha: 0.3,
            tint: Vec3::ONE,
        },
        Bsdf::Dielectric {
            eta: 1.5,
            alpha: 0.3,
            tint: Vec3::ONE,
        },
        Bsdf::Dielectric {
            eta: 0.8,
            alpha: 0.05,
            tint: Vec3::ONE,
        },
        Bsdf::Conductor {
            f0: Vec3::ONE,
            alpha: 0.2,
        },
        gltf(0.5),
    ] {
        for wo in [
            Vec3::new(1.0, 0.0, 1e-7).normalize(),
            Vec3::new(0.0, 1.0, -1e-7).normalize(),
            Vec3::X,
        ] {
            for _ in 0..1000 {
                if let Some(s) = b.sample(
                    wo,
                    rng.next_f32(),
                    Vec2::new(rng.next_f32(), rng.next_f32()),
                    R,
                ) {
                    assert!(
                        s.f.is_finite() && s.pdf.is_finite() && s.wi.is_finite(),
                        "{b:?} {s:?}"
                    );
                    if matches!(b, Bsdf::Dielectric { eta, .. } if eta.is_infinite()) {
                        assert!(!s.transmission);
                    }
                }
                let up = rng.next_f32() < 0.5;
                let w = rand_dir(&mut rng, up);
                assert!(b.eval(wo, w, R).is_finite() && b.pdf(wo, w, R).is_finite());
            }
        }
    }
}

/// Thin dielectric: reflection probability R' = R + T²R/(1 − R²) (4σ over 100k samples), both
/// sides, and the straight-through direction.
#[test]
fn thin_dielectric_probabilities() {
    use crate::optics::fresnel_dielectric;
    let n = 100_000;
    for (deg, inside) in [(0.0, false), (50.0, false), (80.0, true)] {
        let wo = wo_at(deg, inside);
        let r = fresnel_dielectric(wo.z.abs(), 1.5) as f64;
        let rp = r + (1.0 - r) * (1.0 - r) * r / (1.0 - r * r);
        let b = Bsdf::ThinDielectric {
            eta: 1.5,
            tint: Vec3::ONE,
        };
        let mut rng = Rng::new(&[9, deg as u64]);
        let mut refl = 0usize;
        for _ in 0..n {
            let s = b.sample(wo, rng.next_f32(), Vec2::ZERO, R).unwrap();
            assert!(s.delta && (s.f * s.wi.z.abs() / s.pdf - Vec3::ONE).length() < 1e-5);
            if s.transmission {
                assert!((s.wi + wo).length() < 1e-6);
            } else {
                refl += 1;
            }
        }
        let sd = (n as f64 * rp * (1.0 - rp)).sqrt();
        assert!(
            (refl as f64 - n as f64 * rp).abs() <= 4.0 * sd,
            "{refl} vs {}",
            n as f64 * rp
        );
    }
}

/// The quadrature accuracies of `hv_bins` against a much finer reference on every case
/// (numbers in `hv_bins::ACCURACY`). Slow (≈ 1 min): run by hand with `--ignored`.
#[test]
#[ignore]
fn half_vector_quadrature_converged() {
    use hv_bins::Accuracy;
    let reference = Accuracy {
        sub: 12,
        max_depth: 7,
        n: 1e8,
    };
    for (b, wo, _) in cases() {
        let bs = bins(&b, wo);
        let pdf = |w| b.pdf(wo, w, R) as f64;
        let rf = integrate_nodes(bs.len(), &bs.nodes(pdf, reference), pdf);
        let hv = integrate_nodes(bs.len(), &bs.nodes(pdf, hv_bins::ACCURACY), pdf);
        let n = N_SAMPLES as f64;
        let shift: f64 = (hv.iter().zip(&rf))
            .filter(|(_, &r)| r * n > 5.0)
            .map(|(h, r)| ((h - r) * n).powi(2) / (r * n))
            .sum();
        let g = |w: Vec3| (b.eval(wo, w, R) * w.z.abs()).max_element() as f64;
        let alb = |nodes: Vec<Node>| nodes.iter().map(|n| g(n.wi) * n.w).sum::<f64>();
        let (a, ar) = (
            alb(bs.nodes(g, hv_bins::ALBEDO_ACCURACY)),
            alb(bs.nodes(g, reference)),
        );
        eprintln!("{b:?} {wo}: Σ ΔE²/E {shift:.3}, albedo {a:.5} vs {ar:.5}");
        // Measured ≤ 0.93 and ≤ 5.7e-4.
        assert!(shift < 2.0 && (a - ar).abs() < 1e-3 * ar.max(0.05));
    }
}
