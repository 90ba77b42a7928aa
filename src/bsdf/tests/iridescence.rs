//! Tests of the thin film (KHR_materials_iridescence) and anisotropic GGX
//! (KHR_materials_anisotropy): closed forms of the Airy reflectance, the RGB method against
//! the exact spectral integral, χ² of sampling vs pdf, albedo ≤ 1, and the shape of the
//! anisotropic lobe.

use super::*;
use crate::bsdf::anisotropic::{GgxAniso, Microfacet};
use crate::bsdf::interference::{airy, reflectance};
use crate::bsdf::iridescence::{rgb_reference, Iridescence};
use crate::bsdf::microfacet::{Distribution, Ggx};
use crate::optics::{fresnel_conductor, fresnel_dielectric};
use crate::spectrum::SampledSpectrum;

/// Closed-form normal-incidence Airy reflectance with real indices (Born & Wolf §1.6,
/// eq. 1.6.(58)): R = (r₁² + r₂² + 2r₁r₂cos 2δ)/(1 + r₁²r₂² + 2r₁r₂cos 2δ), r₁ = (1−n₁)/(1+n₁),
/// r₂ = (n₁−n₂)/(n₁+n₂), δ = 2π n₁ d/λ.
fn airy_normal(n1: f64, n2: f64, d: f64, lambda: f64) -> f64 {
    let r1 = (1.0 - n1) / (1.0 + n1);
    let r2 = (n1 - n2) / (n1 + n2);
    let c = (4.0 * std::f64::consts::PI * n1 * d / lambda).cos();
    (r1 * r1 + r2 * r2 + 2.0 * r1 * r2 * c) / (1.0 + r1 * r1 * r2 * r2 + 2.0 * r1 * r2 * c)
}

#[test]
fn normal_incidence_matches_closed_form() {
    for (n1, n2, d, lambda) in [
        (1.3, 1.5, 400.0, 550.0),
        (1.3, 1.5, 250.0, 450.0),
        (2.0, 1.5, 123.0, 633.0),
        (1.8, 1.3, 777.0, 400.0),
        (1.33, 2.42, 90.0, 700.0),
    ] {
        let r = airy(1.0, n1 as f32, d as f32, n2 as f32, 0.0, lambda as f32).0;
        let want = airy_normal(n1, n2, d, lambda);
        assert!(
            (r - want).abs() < 1e-6,
            "n1 {n1} n2 {n2} d {d} λ {lambda}: {r} vs {want}"
        );
    }
}

#[test]
fn quarter_and_half_wave_layers() {
    for (n1, n2, lambda) in [
        (1.38f64, 1.52f64, 550.0f64),
        (1.3, 1.5, 480.0),
        (2.0, 1.5, 600.0),
    ] {
        // λ = 4 n₁ d: the anti-reflection condition.
        let d = lambda / (4.0 * n1);
        let r = airy(1.0, n1 as f32, d as f32, n2 as f32, 0.0, lambda as f32).0;
        let want = ((n2 - n1 * n1) / (n2 + n1 * n1)).powi(2);
        assert!(
            (r - want).abs() < 1e-5,
            "quarter wave n1 {n1}: {r} vs {want}"
        );
        // λ = 2 n₁ d: the layer is absent.
        let r = airy(
            1.0,
            n1 as f32,
            (2.0 * d) as f32,
            n2 as f32,
            0.0,
            lambda as f32,
        )
        .0;
        let bare = ((n2 - 1.0) / (n2 + 1.0)).powi(2);
        assert!((r - bare).abs() < 1e-5, "half wave n1 {n1}: {r} vs {bare}");
    }
    // MgF₂ on glass: the classic ~1.3 % coating.
    let r = airy(1.0, 1.38, 550.0 / (4.0 * 1.38), 1.52, 0.0, 550.0).0;
    assert!((r - 0.0126).abs() < 5e-4, "{r}");
}

#[test]
fn bounded_thin_limit_and_energy() {
    for deg in [0.0f32, 30.0, 60.0, 80.0, 89.0] {
        let c = deg.to_radians().cos();
        for &(n1, n2, k2) in &[
            (1.3, 1.5, 0.0),
            (1.8, 1.2, 0.0),
            (1.3, 0.18, 3.0),
            (1.5, 1.4, 1.85),
        ] {
            for d in [0.0, 1.0, 50.0, 137.0, 400.0, 1200.0] {
                for lambda in [380.0, 455.0, 550.0, 700.0, 780.0] {
                    let (r, t) = airy(c, n1, d, n2, k2, lambda);
                    assert!((0.0..=1.0 + 1e-9).contains(&r), "R {r} out of [0,1]");
                    if k2 == 0.0 {
                        assert!(
                            (r + t - 1.0).abs() < 1e-9,
                            "R+T = {} at {deg}° d {d}",
                            r + t
                        );
                    }
                }
            }
            // d → 0: the bare substrate's exact Fresnel, continuously.
            let bare = if k2 == 0.0 {
                fresnel_dielectric(c, n2)
            } else {
                fresnel_conductor(c, n2, k2)
            };
            for d in [0.0, 0.01, 0.1] {
                let r = reflectance(c, n1, d, n2, k2, 550.0);
                assert!(
                    (r - bare).abs() < 2e-3 * (1.0 + d * 10.0),
                    "d {d}: {r} vs {bare}"
                );
            }
            assert!((reflectance(c, n1, 0.0, n2, k2, 550.0) - bare).abs() < 1e-5);
        }
    }
}

/// RGB transport's film colour (33 nodes, linear reconstruction) against the 1 nm spectral
/// integral of the same reflectance under D65: ≤ 0.01 per channel. The bound: the
/// reconstruction of a fringe of period p = λ²/(2 n d cos θ) at 12.5 nm spacing errs by
/// ≈ A (π·12.5/p)²/2 for an amplitude A ≈ 0.05, i.e. ≤ 0.005 for d ≤ 600 nm.
#[test]
fn rgb_iridescence_matches_spectral_integral() {
    for d in [100.0f32, 250.0, 400.0, 600.0] {
        for deg in [0.0f32, 45.0, 75.0] {
            for (eta, k) in [(1.5f32, 0.0f32), (0.2, 3.0)] {
                let c = deg.to_radians().cos();
                let layer = Iridescence {
                    factor: 1.0,
                    ior: 1.3,
                    thickness: d,
                    lanes: None,
                };
                let rgb = layer.reflectance::<Vec3>(c, Vec3::splat(eta), Vec3::splat(k));
                let want = rgb_reference(|nm| reflectance(c, 1.3, d, eta, k, nm));
                let err = (rgb - Vec3::from(want)).abs().max_element();
                assert!(err < 0.01, "d {d} {deg}° η {eta}: rgb {rgb} vs {want:?}");
            }
        }
    }
    // The colour is not grey (the test could fail): a 400 nm film on glass is coloured.
    let want = rgb_reference(|nm| reflectance(1.0, 1.3, 400.0, 1.5, 0.0, nm));
    let spread = want.iter().copied().fold(f32::MIN, f32::max)
        - want.iter().copied().fold(f32::MAX, f32::min);
    assert!(spread > 0.02, "{want:?}");
}

/// Spectral transport evaluates the film exactly at each lane's wavelength.
#[test]
fn spectral_lanes_are_exact() {
    let lanes = [420.0, 510.0, 600.0, 690.0];
    let layer = Iridescence {
        factor: 1.0,
        ior: 1.3,
        thickness: 300.0,
        lanes: Some(lanes),
    };
    let r = layer
        .reflectance::<SampledSpectrum>(0.8, SampledSpectrum::splat(1.5), SampledSpectrum::ZERO)
        .to_lanes();
    for i in 0..4 {
        assert_eq!(r[i], reflectance(0.8, 1.3, 300.0, 1.5, 0.0, lanes[i]));
    }
    assert!(r.iter().any(|&x| (x - r[0]).abs() > 0.01), "{r:?}");
}

fn iridescent(metallic: f32, thickness: f32) -> Bsdf {
    gltf_with(
        metallic,
        LobeExtensions {
            iridescence: Some(Iridescence {
                factor: 1.0,
                ior: 1.3,
                thickness,
                lanes: None,
            }),
            anisotropy: 0.0,
        },
    )
}

fn brushed(metallic: f32, alpha: f32, strength: f32) -> Bsdf {
    Bsdf::GltfPbr {
        base: Vec3::ONE,
        metallic,
        alpha,
        ior: 1.5,
        specular: 1.0,
        specular_color: Vec3::ONE,
        layers: crate::bsdf::Layers::none(),
        extensions: LobeExtensions {
            iridescence: None,
            anisotropy: strength,
        },
    }
}

fn brushed_gold(strength: f32) -> Bsdf {
    Bsdf::ComplexConductor {
        eta: Vec3::new(0.18, 0.45, 1.4),
        k: Vec3::new(3.0, 2.4, 1.85),
        alpha: 0.05,
        extensions: LobeExtensions {
            iridescence: Some(Iridescence {
                factor: 0.5,
                ior: 1.4,
                thickness: 350.0,
                lanes: None,
            }),
            anisotropy: strength,
        },
    }
}

/// The lobes under test, each with an outgoing direction. An iridescent lobe is
/// evaluated at 33 wavelengths per channel in RGB (`RGB_NODES`), which makes it the costly
/// case: each film is tried at one angle, the angles spread from near-normal to grazing.
fn iridescent_cases() -> Vec<(Bsdf, Vec3)> {
    let mut v = Vec::new();
    for (m, d, deg) in [(0.0, 400.0, 15.0), (1.0, 250.0, 70.0), (0.5, 600.0, 45.0)] {
        v.push((iridescent(m, d), wo_at(deg, false)));
    }
    for (m, a, s) in [(1.0, 0.05, 0.8), (0.0, 0.2, 0.5), (1.0, 0.3, 1.0)] {
        for (deg, phi) in [(10.0, 0.0), (60.0, 1.2), (80.0, 2.0)] {
            v.push((brushed(m, a, s), dir(f64::to_radians(deg), phi)));
        }
    }
    v.push((brushed_gold(0.7), wo_at(75.0, false)));
    v
}

/// χ² of sample() vs pdf() for the iridescent and anisotropic lobes (Šidák-corrected 0.01).
#[test]
fn iridescence_chi_square() {
    let cs = iridescent_cases();
    let alpha = 1.0 - (1.0f64 - 0.01).powf(1.0 / cs.len() as f64);
    // One thread per case: each is independent (its own seed).
    let results: Vec<(f64, f64)> = std::thread::scope(|scope| {
        let jobs: Vec<_> = cs
            .iter()
            .enumerate()
            .map(|(k, (b, wo))| {
                scope.spawn(move || {
                    let (obs, exp, total) = histograms(b, *wo, R, 500 + k as u64);
                    (chi2_pvalue(&obs, &exp), total)
                })
            })
            .collect();
        jobs.into_iter().map(|j| j.join().expect("case")).collect()
    });
    for ((b, wo), (p, total)) in cs.iter().zip(results) {
        eprintln!("iridescence chi2 {b:?} wo {wo}: p = {p:.4}, ∫pdf = {total:.4}");
        assert!(total < 1.01, "{b:?} ∫pdf = {total}");
        assert!(p > alpha, "{b:?} wo {wo}: χ² p = {p} < {alpha}");
    }
}

/// Albedo by sampling = quadrature (1 %), and ≤ 1 for a white anisotropic metal (a white
/// furnace: Schlick F = 1) at every strength, and the strength-0 BSDF is the isotropic one,
/// bit for bit.
#[test]
fn iridescence_albedo_and_furnace() {
    for (k, (b, wo)) in iridescent_cases().iter().enumerate() {
        let (mc, q) = albedos(b, *wo, R, 900 + k as u64);
        let err = (mc - q).abs().max_element();
        assert!(
            err <= 0.01 * q.max_element().max(0.05),
            "{b:?} wo {wo}: mc {mc} quad {q}"
        );
    }
    for s in [0.0, 0.3, 0.7, 1.0] {
        for deg in [0.0, 45.0, 80.0] {
            let (mc, _) = albedos(&brushed(1.0, 0.1, s), wo_at(deg, false), R, 77);
            assert!(mc.max_element() <= 1.003, "strength {s} {deg}°: {mc}");
            assert!(mc.min_element() > 0.5, "strength {s} {deg}°: {mc}");
        }
    }
    let iso = brushed(0.3, 0.2, 0.0);
    let mut rng = Rng::new(&[5, 6]);
    for _ in 0..1000 {
        let wo = dir(rng.next_f32() as f64 * 1.5, rng.next_f32() as f64 * 6.0);
        let wi = dir(rng.next_f32() as f64 * 1.5, rng.next_f32() as f64 * 6.0);
        let plain = Bsdf::GltfPbr {
            base: Vec3::ONE,
            metallic: 0.3,
            alpha: 0.2,
            ior: 1.5,
            specular: 1.0,
            specular_color: Vec3::ONE,
            layers: crate::bsdf::Layers::none(),
            extensions: LobeExtensions::NONE,
        };
        assert_eq!(iso.eval(wo, wi, R), plain.eval(wo, wi, R));
        assert_eq!(iso.pdf(wo, wi, R), plain.pdf(wo, wi, R));
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        assert_eq!(iso.sample(wo, 0.3, u, R), plain.sample(wo, 0.3, u, R));
    }
    // The anisotropic distribution with α_x = α_y is the isotropic one (to rounding).
    let (a, b) = (GgxAniso::khr(0.3, 0.0), Ggx { alpha: 0.3 });
    for i in 0..50 {
        let w = dir(i as f64 * 0.03, i as f64 * 0.7);
        assert!((a.d(w) - b.d(w)).abs() <= 1e-5 * b.d(w));
        assert!((a.lambda(w) - b.lambda(w)).abs() <= 1e-5 * (1.0 + b.lambda(w)));
    }
    assert!(matches!(Microfacet::khr(0.3, 0.0), Microfacet::Iso(_)));
}

/// Second moments of the reflected lobe at normal incidence: wider along x (the
/// anisotropy direction) than along y, by a margin; equal at strength 0.
#[test]
fn anisotropic_lobe_is_elongated_along_x() {
    let moments = |b: &Bsdf| {
        let mut rng = Rng::new(&[41]);
        let (mut sx, mut sy, mut w) = (0.0f64, 0.0f64, 0.0f64);
        for _ in 0..100_000 {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            if let Some(s) = b.sample(Vec3::Z, 0.5, u, R) {
                let weight = (s.f.x * s.wi.z / s.pdf) as f64;
                sx += weight * (s.wi.x as f64).powi(2);
                sy += weight * (s.wi.y as f64).powi(2);
                w += weight;
            }
        }
        (sx / w, sy / w)
    };
    let (x, y) = moments(&brushed(1.0, 0.05, 0.8));
    assert!(x > 4.0 * y, "⟨x²⟩ {x} ⟨y²⟩ {y}");
    let (x, y) = moments(&brushed(1.0, 0.05, 0.0));
    assert!((x - y).abs() < 0.1 * (x + y), "isotropic ⟨x²⟩ {x} ⟨y²⟩ {y}");
}
