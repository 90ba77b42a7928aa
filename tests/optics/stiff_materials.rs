//! Stiff material inputs (issue 7, cases 5 and 6): extreme dispersion and Beer–Lambert
//! absorption at extreme distances, from the IOR models ([`iris::spectrum::IorModel`])
//! and the render [`Material`] up through the glTF loader and validator.
//!
//! 5. Extreme dispersion: KHR_materials_dispersion n(λ) = max(n_d + (n_d−1)(D/20)
//!    (523655/λ² − 1.5168), 1) (the extension's formula, λ in nm) with D = 20, 1000, 1e30;
//!    Cauchy n = b + c/λ² (λ in µm) with c up to f32::MAX: n(λ) ≥ 1 and finite over
//!    360–830 nm. Sellmeier n² = 1 + Σ B_i λ²/(λ² − C_i) (Sellmeier 1871; λ, √C_i in µm)
//!    has poles at λ_i = √C_i: the built-in glasses have none in 360–830 nm and stay
//!    smooth there; a glTF `extras.sellmeier` with a pole inside is rejected at load
//!    (file + material named), one just outside evaluates finite.
//! 6. Beer–Lambert (KHR_materials_volume): T = c^(x/d) per channel (the extension's
//!    attenuation law); d = 1e-9 underflows to exactly 0 (c < 1) and 1 (c = 1), never NaN,
//!    for any path length up to f32::MAX (x/d = +∞); d = 1e9 gives T = 1 to 1e-6 (c > 0);
//!    c = 0 gives exactly 0 at any d (an infinite absorption coefficient −ln c/d).

use crate::common;
use crate::fixtures;

use glam::Vec3;
use iris::load::load_scene;
use iris::material::Material;
use iris::spectrum::ior::KNOWN_NAMES;
use iris::spectrum::{
    Carrier, IorModel, Lambdas, SampledSpectrum, SampledWavelengths, LAMBDA_MAX, LAMBDA_MIN,
};
use iris::LoadErrorKind;
use serde_json::{json, Value};

/// λ from 360 to 830 nm every 0.5 nm, endpoints exact.
fn sampled_range() -> impl Iterator<Item = f32> {
    (0..=940).map(|i| LAMBDA_MIN + (LAMBDA_MAX - LAMBDA_MIN) * i as f32 / 940.0)
}

/// n over the sampled range: each finite and ≥ 1; returns (min, max).
fn check_range(model: &IorModel) -> (f32, f32) {
    let (mut lo, mut hi) = (f32::INFINITY, 0.0f32);
    for l in sampled_range() {
        let n = model.ior(l);
        assert!(n.is_finite() && n >= 1.0, "{model:?} at {l} nm: n = {n}");
        (lo, hi) = (lo.min(n), hi.max(n));
    }
    (lo, hi)
}

#[test]
fn khr_dispersion_extremes_stay_finite_and_at_least_one() {
    for n_d in [1.0001f32, 1.33, 1.5, 2.42, 4.0] {
        for d in [20.0f32, 1000.0, 1e30, f32::MAX] {
            let m = IorModel::KhrDispersion { n_d, dispersion: d };
            let (lo, hi) = check_range(&m);
            // The formula's bracket is +2.52 at 360 nm and −0.757 at 830 nm, so large D
            // drives the red end to the clamp and the blue end up; never below n_d there.
            assert!(hi >= n_d, "{m:?}: max {hi}");
            if d >= 1000.0 {
                assert_eq!(lo, 1.0, "{m:?}: the red end clamps to 1");
            }
        }
    }
    // D = 20 (Abbe 1): n_d = 1.5 gives 1.5 + 0.5·(523655/360² − 1.5168) = 2.7632 at 360 nm.
    let m = IorModel::KhrDispersion {
        n_d: 1.5,
        dispersion: 20.0,
    };
    let expected = 1.5 + 0.5 * (523_655.0 / (360.0f64 * 360.0) - 1.5168);
    assert!((f64::from(m.ior(360.0)) - expected).abs() < 1e-5);
}

#[test]
fn cauchy_with_huge_c_stays_finite_and_normal() {
    for b in [1.0f32, 1.5] {
        for c in [0.0042f32, 10.0, 1e6, 1e30, f32::MAX] {
            let m = IorModel::Cauchy { b, c };
            check_range(&m);
            // Normal dispersion: n never rises with λ (saturated values stay equal).
            let mut prev = f32::INFINITY;
            for l in sampled_range() {
                let n = m.ior(l);
                assert!(n <= prev, "{m:?} rises at {l} nm");
                prev = n;
            }
        }
    }
    // c = f32::MAX at 360 nm is 2.6e39 in f64: it saturates to f32::MAX (+∞ is reserved
    // for the `ior: 0` mode) instead of overflowing in the cast.
    let m = IorModel::Cauchy {
        b: 1.5,
        c: f32::MAX,
    };
    assert_eq!(m.ior(360.0), f32::MAX);
}

#[test]
fn built_in_sellmeier_glasses_have_no_pole_in_the_sampled_range() {
    for name in KNOWN_NAMES {
        let m = IorModel::named(name).unwrap();
        let poles = m.poles_nm();
        assert!(!poles.is_empty(), "{name}");
        assert_eq!(m.pole_in(LAMBDA_MIN, LAMBDA_MAX), None, "{name}: {poles:?}");
        // The nearest pole is far enough that n stays a glass's: 1.3–2.5 everywhere
        // (diamond at 360 nm is 2.47), and it moves by < 2e-3 per 0.5 nm step (water's
        // and BK7's are ~1e-5, diamond's 5e-4 at the blue end).
        let (lo, hi) = check_range(&m);
        assert!(lo > 1.3 && hi < 2.5, "{name}: n in [{lo}, {hi}]");
        let mut prev = m.ior(LAMBDA_MIN);
        for l in sampled_range().skip(1) {
            let n = m.ior(l);
            assert!((n - prev).abs() < 2e-3, "{name} jumps at {l} nm");
            prev = n;
        }
    }
    // A single term with its pole at 500 nm is found, and at 359.9 nm (just outside) not.
    let inside = IorModel::Sellmeier {
        b: [1.0, 0.0, 0.0, 0.0],
        c: [0.25, 0.0, 0.0, 0.0],
    };
    assert!((inside.pole_in(LAMBDA_MIN, LAMBDA_MAX).unwrap() - 500.0).abs() < 1e-3);
    let outside = IorModel::Sellmeier {
        b: [1.0, 0.0, 0.0, 0.0],
        c: [0.3599 * 0.3599, 0.0, 0.0, 0.0],
    };
    assert_eq!(outside.pole_in(LAMBDA_MIN, LAMBDA_MAX), None);
    let (_, hi) = check_range(&outside);
    eprintln!("pole at 359.9 nm: n(360 nm) = {hi}");
}

/// Writes the fixture cube with material 0 = `material` and loads it.
fn load_material(
    test: &str,
    material: Value,
) -> Result<iris::scene::desc::SceneDesc, iris::LoadError> {
    let dir = common::scratch_dir(test);
    let mut doc = fixtures::cube_doc();
    doc["extensionsUsed"] = json!([
        "KHR_materials_ior",
        "KHR_materials_dispersion",
        "KHR_materials_transmission",
        "KHR_materials_volume"
    ]);
    doc["materials"] = json!([material]);
    load_scene(&fixtures::write_json(&dir, "scene.gltf", &doc))
}

#[test]
fn sellmeier_extras_with_a_visible_pole_are_rejected_at_load() {
    let glass =
        |b: Value, c: Value| json!({"name": "Glass", "extras": {"sellmeier": {"b": b, "c": c}}});
    // Pole at √0.25 µm = 500 nm.
    let e = load_material("sellmeier_pole", glass(json!([1.0]), json!([0.25]))).unwrap_err();
    let text = e.to_string();
    assert_eq!(e.kind, LoadErrorKind::InvalidIor, "{text}");
    assert!(
        text.contains("scene.gltf") && text.contains("material 0 \"Glass\""),
        "{text}"
    );
    assert!(
        text.contains("500.0 nm") && text.contains("360–830 nm"),
        "{text}"
    );
    // The range is closed: a pole exactly at 830 nm is rejected too.
    let c = 0.83f32 * 0.83;
    assert!(load_material("sellmeier_edge", glass(json!([0.5]), json!([c]))).is_err());
    // Malformed coefficient lists name the expected shape.
    for (b, c) in [
        (json!([1.0]), json!([0.01, 100.0])),
        (json!([]), json!([])),
        (json!([1, 1, 1, 1, 1]), json!([1, 1, 1, 1, 1])),
        (json!("x"), json!([0.01])),
    ] {
        let e = load_material("sellmeier_shape", glass(b, c)).unwrap_err();
        assert!(e.to_string().contains("extras.sellmeier"), "{e}");
    }
    let e = load_material("sellmeier_negative", glass(json!([-1.0]), json!([0.01]))).unwrap_err();
    assert_eq!(e.kind, LoadErrorKind::InvalidIor, "{e}");
    // N-BK7's coefficients given by hand load and match the built-in glass.
    let bk7 = IorModel::named("N-BK7").unwrap();
    let IorModel::Sellmeier { b, c } = bk7 else {
        unreachable!()
    };
    let desc = load_material("sellmeier_bk7", glass(json!(&b[..3]), json!(&c[..3]))).unwrap();
    let m = Material::new(desc.materials[0].clone());
    assert_eq!(*m.ior_model(), bk7);
    assert!((m.ior() - 1.5168).abs() < 5e-5, "{}", m.ior());
    // Two explicit models on one material: an error naming both keys.
    let both = json!({"name": "Glass", "extras": {"sellmeier": {"b": [1.0], "c": [0.01]},
                      "cauchy": {"b": 1.5, "c": 0.004}}});
    let text = load_material("sellmeier_both", both)
        .unwrap_err()
        .to_string();
    assert!(text.contains("cauchy and sellmeier"), "{text}");
}

#[test]
fn khr_dispersion_20_and_1000_load_and_stay_finite() {
    for d in [20.0f32, 1000.0] {
        let desc = load_material(
            "dispersion_extreme",
            json!({"name": "Glass", "extensions": {"KHR_materials_ior": {"ior": 2.42},
                   "KHR_materials_dispersion": {"dispersion": d}}}),
        )
        .unwrap_or_else(|e| panic!("D {d}: {e}"));
        let m = Material::new(desc.materials[0].clone());
        assert!(m.is_dispersive());
        assert_eq!(m.ior(), 2.42, "RGB transport keeps n_d");
        check_range(m.ior_model());
        // ior_at is what the integrators call with the hero wavelength.
        for l in sampled_range() {
            let n = m.ior_at(Some(l), true);
            assert!(n.is_finite() && n >= 1.0, "D {d} {l} nm: {n}");
        }
    }
}

fn absorbing(distance: f32, color: Vec3) -> Material {
    Material::new(iris::material::MaterialDesc {
        attenuation_color: color,
        attenuation_distance: distance,
        ..common::clear_glass("absorbing", 1.5)
    })
}

/// Spectral transmittance at 16 wavelength sets spanning the range, with the upsampled
/// attenuation colour at the same wavelengths.
fn spectral_lanes(m: &Material, x: f32) -> Vec<(SampledSpectrum, SampledSpectrum)> {
    (0..16)
        .map(|i| {
            let l = Lambdas::new(SampledWavelengths::sample_uniform((i as f32 + 0.5) / 16.0));
            let r = SampledSpectrum::reflectance(m.desc.attenuation_color, &l);
            (m.transmittance_at::<SampledSpectrum>(x, &l), r)
        })
        .collect()
}

#[test]
fn beer_lambert_underflows_to_exact_zero_and_never_nan() {
    let c = Vec3::new(0.5, 0.0, 1.0);
    let tiny = absorbing(1e-9, c);
    // x/d from 1e3 to +∞ (f32::MAX/1e-9): exactly (0, 0, 1), no NaN from 0^∞ or 1^∞.
    for x in [1e-6f32, 1e-3, 1.0, 1e4, 1e30, f32::MAX] {
        assert_eq!(
            tiny.transmittance_at::<Vec3>(x, &()),
            Vec3::new(0.0, 0.0, 1.0),
            "x {x}"
        );
        for (t, r) in spectral_lanes(&tiny, x) {
            assert!(t.is_finite(), "x {x}: {t:?}");
            for k in 0..4 {
                assert!((0.0..=1.0).contains(&t[k]), "x {x}: lane {k} = {}", t[k]);
                // r^(x/d) with x/d ≥ 1e9 underflows for any lane r < 1 − 1e-6.
                if x >= 1.0 && r[k] < 1.0 - 1e-6 {
                    assert_eq!(t[k], 0.0, "x {x}: lane {k} (r = {})", r[k]);
                }
            }
        }
    }
    // A zero-length segment transmits everything, even for colour 0 (0^0 = 1).
    assert_eq!(tiny.transmittance_at::<Vec3>(0.0, &()), Vec3::ONE);
    // d = 1e9: c^(x/d) for x ≤ 1e3 differs from 1 by ≤ x/d·|ln c| ≤ 7e-7 for c ≥ 0.5; colour
    // 0 is still exactly 0.
    let huge = absorbing(1e9, c);
    for x in [1e-3f32, 1.0, 1e3] {
        let t = huge.transmittance_at::<Vec3>(x, &());
        assert!(
            (t.x - 1.0).abs() <= 1e-6 && t.y == 0.0 && t.z == 1.0,
            "x {x}: {t}"
        );
    }
    let grey = absorbing(1e9, Vec3::splat(0.5));
    for (t, _) in spectral_lanes(&grey, 1.0) {
        for k in 0..4 {
            assert!((t[k] - 1.0).abs() <= 1e-6, "lane {k}: {}", t[k]);
        }
    }
    // Through the loader: both distances are valid KHR_materials_volume values.
    for d in [1e-9f32, 1e9] {
        let desc = load_material(
            "beer_extreme",
            json!({"name": "Glass", "extensions": {
                "KHR_materials_transmission": {"transmissionFactor": 1.0},
                "KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationDistance": d,
                                         "attenuationColor": [0.5, 0.0, 1.0]}}}),
        )
        .unwrap_or_else(|e| panic!("d {d}: {e}"));
        let m = Material::new(desc.materials[0].clone());
        let t = m.transmittance_at::<Vec3>(1.0, &());
        let expected = if d < 1.0 { 0.0 } else { 1.0 };
        assert!(
            (t.x - expected).abs() <= 1e-6 && t.y == 0.0 && t.z == 1.0,
            "d {d}: {t}"
        );
    }
}

#[test]
fn carrier_powf_is_what_beer_lambert_uses() {
    // The Carrier power on edge exponents, lane by lane (IEEE pow: 0^0 = 1, 1^∞ = 1,
    // c^∞ = 0 for c < 1).
    let v = Vec3::new(0.0, 0.5, 1.0);
    assert_eq!(v.powf(0.0), Vec3::ONE);
    assert_eq!(v.powf(f32::INFINITY), Vec3::new(0.0, 0.0, 1.0));
    assert_eq!(Carrier::powf(v, 1e-9).z, 1.0);
}
