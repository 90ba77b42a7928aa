//! Tests of what each lobe answers ([`super::lobe::Lobe`]) against its own scattering: its
//! Mueller matrix at normal incidence against its sampled weight, its denoiser albedo and
//! its photon roulette colours against the directional-hemispherical reflectance estimated
//! by sampling, its photon transmission direction against its sampled one; and a walk over
//! one example of every variant ([`examples`], kept complete by [`variant`]).
//! Deterministic quadrature, no random numbers.

use super::conductor::ComplexConductor;
use super::dielectric::Dielectric;
use super::lobe::Lobe;
use super::*;
use crate::polar::fresnel::MIRROR;

const I: TransportMode = TransportMode::Importance;

/// The index of `b`'s variant: an exhaustive match, so a new variant fails to compile
/// here until it is given an index (and [`examples`] an example of it).
fn variant(b: &Bsdf) -> usize {
    match b {
        Bsdf::Lambert { .. } => 0,
        Bsdf::Conductor { .. } => 1,
        Bsdf::ComplexConductor { .. } => 2,
        Bsdf::Dielectric { .. } => 3,
        Bsdf::ThinDielectric { .. } => 4,
        Bsdf::GltfPbr { .. } => 5,
    }
}
const VARIANTS: usize = 6;

/// A gold-like measured metal (n, k per channel).
fn gold(alpha: f32) -> Bsdf {
    Bsdf::ComplexConductor {
        eta: Vec3::new(0.18, 0.42, 1.37),
        k: Vec3::new(3.42, 2.35, 1.77),
        alpha,
        extensions: LobeExtensions::NONE,
    }
}

fn glass(alpha: f32) -> Bsdf {
    Bsdf::Dielectric {
        eta: 1.5,
        alpha,
        tint: Vec3::ONE,
    }
}

fn gltf(metallic: f32, roughness: f32) -> Bsdf {
    Bsdf::GltfPbr {
        base: Vec3::new(0.9, 0.6, 0.3),
        metallic,
        alpha: roughness * roughness,
        ior: 1.5,
        specular: 1.0,
        specular_color: Vec3::ONE,
        layers: Layers::none(),
        extensions: LobeExtensions::NONE,
    }
}

/// Smooth and rough examples of every variant.
fn examples() -> Vec<Bsdf> {
    vec![
        Bsdf::Lambert {
            albedo: Vec3::new(0.2, 0.5, 0.8),
        },
        Bsdf::Conductor {
            f0: Vec3::new(0.95, 0.64, 0.54),
            alpha: 0.0,
        },
        Bsdf::Conductor {
            f0: Vec3::new(0.95, 0.64, 0.54),
            alpha: 0.3,
        },
        gold(0.0),
        gold(0.3),
        glass(0.0),
        glass(0.3),
        Bsdf::ThinDielectric {
            eta: 1.5,
            tint: Vec3::ONE,
        },
        gltf(1.0, 0.1),
        gltf(0.0, 0.5),
    ]
}

/// The directional-hemispherical reflectance plus transmittance at `wo` (energy: radiance
/// transport, in which the rough dielectric's compensation conserves energy, with the 1/η'²
/// of a refraction undone): the mean of f·|cos θi|/pdf over a 64 × 64 grid of direction
/// numbers, each with a lobe number from the golden-ratio sequence.
fn rho(b: &Bsdf, wo: Vec3) -> Vec3 {
    let n = 64;
    let mut acc = DVec3Sum::default();
    for k in 0..n * n {
        let uc = (0.5 + k as f64 * 0.618_033_988_749_895).fract() as f32;
        let u = Vec2::new(
            ((k % n) as f32 + 0.5) / n as f32,
            ((k / n) as f32 + 0.5) / n as f32,
        );
        if let Some(s) = b.sample(wo, uc, u, TransportMode::Radiance) {
            let undo = match b.interface_eta() {
                Some(eta) if s.transmission => {
                    let etap = if wo.z > 0.0 { eta } else { 1.0 / eta };
                    etap * etap
                }
                _ => 1.0,
            };
            acc.add(s.f * (s.wi.z.abs() / s.pdf * undo));
        }
    }
    acc.mean(n * n)
}

#[derive(Default)]
struct DVec3Sum([f64; 3]);

impl DVec3Sum {
    fn add(&mut self, v: Vec3) {
        for (a, v) in self.0.iter_mut().zip(v.to_array()) {
            *a += f64::from(v);
        }
    }
    fn mean(&self, n: usize) -> Vec3 {
        Vec3::new(
            (self.0[0] / n as f64) as f32,
            (self.0[1] / n as f64) as f32,
            (self.0[2] / n as f64) as f32,
        )
    }
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol
}

fn roulette_total(b: &Bsdf) -> Vec3 {
    let r = b.roulette_lobes();
    r.diffuse + r.specular + r.transmission
}

/// Whether a normalized Mueller matrix leaves unpolarized light unpolarized and does not
/// mix linear and circular states (what every interface does at normal incidence).
fn non_polarizing(n: &crate::polar::stokes::Mueller) -> bool {
    (n[0][0] - 1.0).abs() < 1e-6
        && (0..4).all(|i| (0..4).all(|j| i == j || n[i][j].abs() < 1e-5))
        && (0..4).all(|i| (n[i][i].abs() - 1.0).abs() < 1e-5)
}

#[test]
fn lambert_answers_its_albedo() {
    let a = Vec3::new(0.2, 0.5, 0.8);
    let b = Bsdf::Lambert { albedo: a };
    assert!(close(rho(&b, Vec3::Z), a, 1e-5), "{}", rho(&b, Vec3::Z));
    assert_eq!(b.albedo(), a);
    assert_eq!(b.roulette_lobes().diffuse, a);
    assert_eq!(roulette_total(&b), a);
    assert!(b.depolarizes() && b.mueller(Vec3::Z, Vec3::Z).is_none());
    assert!(b.is_diffuse_like() && !b.is_delta() && b.interface_eta().is_none());
}

/// The Schlick conductor: a perfect mirror for polarization; its reflectance at normal
/// incidence is f0, its albedo and its photons' specular colour. Rough (α 0.3), GGX single
/// scattering loses the same fraction in every channel (Fresnel ≈ f0 near the normal):
/// the reflectance is f0 times one factor, asserted within 1 % per channel and in
/// [0.8, 1].
#[test]
fn conductor_answers_its_normal_reflectance() {
    let f0 = Vec3::new(0.95, 0.64, 0.54);
    let smooth = Bsdf::Conductor { f0, alpha: 0.0 };
    assert!(
        close(rho(&smooth, Vec3::Z), f0, 1e-5),
        "{}",
        rho(&smooth, Vec3::Z)
    );
    let ratio = rho(&Bsdf::Conductor { f0, alpha: 0.3 }, Vec3::Z) / f0;
    assert!(ratio.max_element() - ratio.min_element() < 0.01, "{ratio}");
    assert!(
        ratio.min_element() >= 0.8 && ratio.max_element() <= 1.0,
        "{ratio}"
    );
    for alpha in [0.0, 0.3] {
        let b = Bsdf::Conductor { f0, alpha };
        assert_eq!(b.albedo(), f0);
        assert_eq!(roulette_total(&b), f0);
        assert_eq!(b.mueller(Vec3::Z, Vec3::Z), Some((MIRROR, Vec3::Z)));
        assert!(!b.depolarizes() && !b.hero_polarizes());
    }
}

/// The measured metal: the Mueller matrix's M₀₀ at normal incidence (hero lane) is the
/// mirror's sampled weight f·|cos θ|/pdf, the albedo and the photons' specular colour; a
/// rough lobe at normal incidence equals a Schlick lobe of that f0.
#[test]
fn complex_conductor_mueller_agrees_with_its_weight() {
    let b = gold(0.0);
    let Bsdf::ComplexConductor { eta, k, .. } = b else {
        unreachable!()
    };
    let lobe = ComplexConductor {
        eta,
        k,
        alpha: 0.0,
        extensions: LobeExtensions::NONE,
    };
    let (m, normal) = lobe.mueller(Vec3::Z, Vec3::Z).unwrap();
    assert_eq!(normal, Vec3::Z);
    let s = b.sample(Vec3::Z, 0.5, Vec2::splat(0.5), I).unwrap();
    let weight = s.f * (s.wi.z.abs() / s.pdf);
    assert!((m[0][0] - weight.x).abs() < 1e-5, "{m:?} {weight}");
    assert!(close(b.albedo(), weight, 1e-5), "{} {weight}", b.albedo());
    assert!(close(roulette_total(&b), weight, 1e-5));
    assert!(non_polarizing(&b.mueller(Vec3::Z, Vec3::Z).unwrap().0));
    assert!(b.hero_polarizes() && !b.depolarizes());
    let rough = gold(0.3);
    let schlick = Bsdf::Conductor {
        f0: Vec3::splat(m[0][0]),
        alpha: 0.3,
    };
    let (a, c) = (
        rough.eval(Vec3::Z, Vec3::Z, I).x,
        schlick.eval(Vec3::Z, Vec3::Z, I).x,
    );
    assert!((a - c).abs() <= 1e-5 * c, "{a} vs {c}");
}

/// The smooth dielectric: M₀₀ of the reflection and transmission matrices at normal
/// incidence are the sampled reflection's and transmission's weights; reflectance plus
/// transmittance is the (white) tint, and so are the photons' specular plus transmission
/// colours; a photon's transmission direction is the sampled refraction.
#[test]
fn dielectric_mueller_and_photons_agree_with_its_samples() {
    let lobe = Dielectric {
        eta: 1.5,
        alpha: 0.0,
        tint: Vec3::ONE,
    };
    let b = glass(0.0);
    let weight = |uc: f32| {
        let s = b.sample(Vec3::Z, uc, Vec2::splat(0.5), I).unwrap();
        (s.f * (s.wi.z.abs() / s.pdf)).x * s.pdf
    };
    let (r, _) = lobe.mueller(Vec3::Z, Vec3::Z).unwrap();
    let (t, _) = lobe.mueller(Vec3::Z, -Vec3::Z).unwrap();
    assert!((r[0][0] - weight(0.0)).abs() < 1e-6, "{r:?}");
    assert!((t[0][0] - weight(0.999)).abs() < 1e-6, "{t:?}");
    assert!(non_polarizing(&b.mueller(Vec3::Z, Vec3::Z).unwrap().0));
    assert!(close(rho(&b, Vec3::Z), b.albedo(), 1e-5));
    assert!(close(roulette_total(&b), b.albedo(), 1e-6));
    assert!((b.roulette_lobes().specular.x - r[0][0]).abs() < 1e-6);
    let wo = Vec3::new(0.6, 0.0, 0.8);
    let refracted = b.sample(wo, 0.999, Vec2::splat(0.5), I).unwrap();
    assert!(refracted.transmission);
    assert!(close(b.roulette_transmission(wo), refracted.wi, 1e-6));
    assert_eq!(b.interface_eta(), Some(1.5));
    let lane = b.with_lane(1.6, 0).unwrap();
    assert_eq!(lane.interface_eta(), Some(1.6));
    assert!(!b.is_diffuse_like() && glass(0.3).is_diffuse_like());
}

/// The rough dielectric's energy at normal incidence is its white tint within 0.02 (the
/// multiple-scattering compensation's table, 1 %, and the quadrature's error).
#[test]
fn rough_dielectric_albedo_is_its_tint() {
    let b = glass(0.3);
    assert!(
        close(rho(&b, Vec3::Z), b.albedo(), 0.02),
        "{}",
        rho(&b, Vec3::Z)
    );
    assert!(non_polarizing(&b.mueller(Vec3::Z, Vec3::Z).unwrap().0));
}

/// The thin wall: reflectance plus transmittance is the (white) tint, as are the photons'
/// colours; a photon passes straight through as the sampled transmission does; its
/// reflection matrix at normal incidence does not polarize.
#[test]
fn thin_dielectric_answers_its_tint() {
    let b = Bsdf::ThinDielectric {
        eta: 1.5,
        tint: Vec3::ONE,
    };
    assert!(close(rho(&b, Vec3::Z), b.albedo(), 1e-5));
    assert!(close(roulette_total(&b), b.albedo(), 1e-6));
    let wo = Vec3::new(0.6, 0.0, 0.8);
    let through = b.sample(wo, 0.999, Vec2::splat(0.5), I).unwrap();
    assert!(through.transmission);
    assert_eq!(b.roulette_transmission(wo), through.wi);
    assert!(non_polarizing(&b.mueller(Vec3::Z, Vec3::Z).unwrap().0));
    assert!(non_polarizing(&b.mueller(Vec3::Z, -Vec3::Z).unwrap().0));
    assert!(b.is_delta() && !b.samples_direction() && b.interface_eta().is_none());
}

/// The glTF lobe as a smooth metal reflects its base colour at normal incidence (within
/// 0.02: α is floored at 0.01), its albedo and its photons' specular colour; it
/// depolarizes.
#[test]
fn gltf_metal_answers_its_base_colour() {
    let b = gltf(1.0, 0.1);
    let base = Vec3::new(0.9, 0.6, 0.3);
    assert!(close(rho(&b, Vec3::Z), base, 0.02), "{}", rho(&b, Vec3::Z));
    assert_eq!(b.albedo(), base);
    assert!(close(b.roulette_lobes().specular, base, 1e-6));
    assert!(b.depolarizes() && b.mueller(Vec3::Z, Vec3::Z).is_none());
    assert!(!b.is_diffuse_like() && gltf(0.0, 0.5).is_diffuse_like());
}

/// Every variant has an example, and every example's answers agree with its scattering:
/// a delta lobe has eval = pdf = 0 and samples only deltas (so photons are not stored
/// there), a non-delta lobe samples non-deltas with the pdf its `pdf` gives; a polarizing
/// lobe's normalized matrix has M₀₀ = 1 and a depolarizing one has none; the albedo is in
/// [0, 1]; the photons' colours never add to above 1; only interfaces have an η.
#[test]
fn every_lobe_answers_consistently() {
    let ex = examples();
    let mut seen = [false; VARIANTS];
    for b in &ex {
        seen[variant(b)] = true;
    }
    assert!(
        seen.iter().all(|&s| s),
        "a variant has no example: {seen:?}"
    );
    let wo = Vec3::new(0.3, -0.2, 0.9).normalize();
    for b in &ex {
        for k in 0..16 {
            let u = Vec2::new((k as f32 + 0.5) / 16.0, 0.37);
            let Some(s) = b.sample(wo, (k as f32 + 0.5) / 16.0, u, I) else {
                continue;
            };
            assert_eq!(s.delta, b.is_delta(), "{b:?}");
            if b.is_delta() {
                assert_eq!(b.eval(wo, s.wi, I), Vec3::ZERO);
                assert_eq!(b.pdf(wo, s.wi, I), 0.0);
            } else {
                assert!((b.pdf(wo, s.wi, I) - s.pdf).abs() <= 1e-3 * s.pdf, "{b:?}");
            }
            match b.mueller(wo, s.wi) {
                Some((n, _)) => {
                    assert!(!b.depolarizes() && (n[0][0] - 1.0).abs() < 1e-6, "{b:?}")
                }
                None => assert!(b.depolarizes(), "{b:?} at {wo} {}", s.wi),
            }
        }
        let a = b.albedo();
        assert!(a.min_element() >= 0.0 && a.max_element() <= 1.0, "{b:?}");
        assert!(roulette_total(b).max_element() <= 1.0 + 1e-6, "{b:?}");
        let interface = matches!(b, Bsdf::Dielectric { .. });
        assert_eq!(b.interface_eta().is_some(), interface, "{b:?}");
        assert_eq!(b.with_lane(1.4, 0).is_some(), interface, "{b:?}");
    }
}

/// At Brewster's angle the smooth glass's reflection is a polarizer: unpolarized in, fully
/// s-polarized out.
#[test]
fn smooth_glass_reflection_at_brewster_is_a_polarizer() {
    let eta = 1.5f32;
    let th = eta.atan();
    let wi = Vec3::new(th.sin(), 0.0, th.cos());
    let wo = Vec3::new(-th.sin(), 0.0, th.cos());
    let (n, m) = glass(0.0).mueller(wo, wi).unwrap();
    assert_eq!(m, Vec3::Z);
    assert!(
        (n[0][0] - 1.0).abs() < 1e-6 && (n[1][0] - 1.0).abs() < 1e-4,
        "{n:?}"
    );
}
