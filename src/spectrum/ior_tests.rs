//! Tests of [`super::IorModel`] against catalogue values.

use super::*;

fn named(name: &str) -> IorModel {
    IorModel::named(name).unwrap()
}

#[test]
fn n_bk7_matches_schott() {
    let m = named("N-BK7");
    // SCHOTT data sheet: n_d = 1.51680, V_d = 64.17; the Sellmeier fit reproduces the
    // catalogue to ~1e-5, so 2e-4 / 0.3 are the brief's margins.
    assert!((m.n_d() - 1.5168).abs() < 2e-4, "{}", m.n_d());
    assert!((m.abbe_number() - 64.17).abs() < 0.3, "{}", m.abbe_number());
    assert!(m.is_dispersive());
    // Normal dispersion: blue bends more.
    assert!(m.ior(400.0) > m.ior(700.0));
}

#[test]
fn n_sf11_matches_schott() {
    let m = named("n-sf11");
    // SCHOTT: n_d = 1.78472, V_d = 25.68.
    assert!((m.n_d() - 1.78472).abs() < 3e-4, "{}", m.n_d());
    assert!((m.abbe_number() - 25.68).abs() < 0.3, "{}", m.abbe_number());
}

#[test]
fn other_named_materials() {
    // Fused silica n_d = 1.4585 (Malitson 1965, Table 2 at 587.6 nm: 1.45846).
    let fs = named("Fused Silica");
    assert!((fs.n_d() - 1.4585).abs() < 2e-4, "{}", fs.n_d());
    assert!(
        (fs.abbe_number() - 67.8).abs() < 0.5,
        "{}",
        fs.abbe_number()
    );
    // Diamond n_d ≈ 2.4175 (Peter 1923 fit; gemmological 2.417).
    let d = named("DIAMOND");
    assert!((d.n_d() - 2.4175).abs() < 1e-3, "{}", d.n_d());
    // Water at 20 °C: this fit gives 1.33340 at 587.56 nm, handbooks 1.33299 at 589.3 nm;
    // ±5e-4 (the brief's bound) covers both.
    let w = named("water");
    assert!((w.n_d() - 1.3330).abs() < 5e-4, "{}", w.n_d());
    // Sapphire ordinary ray n_o(587.6 nm) = 1.7682 (Malitson & Dodge 1972).
    let s = named("sapphire");
    assert!((s.ior(587.6) - 1.7682).abs() < 1e-3, "{}", s.ior(587.6));
    // Aliases and separators.
    assert_eq!(named("bk7"), named("N_BK7"));
    assert_eq!(named(" fused_silica "), fs);
}

#[test]
fn unknown_name_lists_known_ones() {
    let e = IorModel::named("unobtainium").unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("unobtainium"), "{msg}");
    for k in KNOWN_NAMES {
        assert!(msg.contains(k), "{msg}");
        assert!(IorModel::named(k).is_ok(), "{k}");
    }
}

#[test]
fn khr_dispersion_formula() {
    for (n_d, dispersion) in [(1.5, 1.0), (1.5168, 20.0 / 64.17), (2.42, 20.0 / 55.3)] {
        let m = IorModel::KhrDispersion { n_d, dispersion };
        // 523655/587.56² = 1.51687, so n(587.56) differs from n_d by < 1e-5.
        assert!((m.ior(587.56) - n_d).abs() < 1e-4, "{}", m.ior(587.56));
        // The formula's F−C difference is 1.00005·(n_d−1)/V_d → V within 1 %.
        let v = 20.0 / dispersion;
        assert!(
            (m.abbe_number() - v).abs() < 0.01 * v,
            "{} vs {v}",
            m.abbe_number()
        );
        assert!(m.is_dispersive());
    }
    // Clamp: a huge dispersion drives the red end below 1.
    let m = IorModel::KhrDispersion {
        n_d: 1.05,
        dispersion: 400.0,
    };
    assert_eq!(m.ior(830.0), 1.0);
    assert!(m.ior(360.0) > 1.05);
}

#[test]
fn from_khr_special_cases() {
    assert_eq!(IorModel::from_khr(1.5, 0.0), IorModel::Constant(1.5));
    assert_eq!(IorModel::from_khr(0.0, 1.0), IorModel::Constant(0.0));
    assert_eq!(IorModel::from_khr(1.5, f32::NAN), IorModel::Constant(1.5));
    assert!(IorModel::from_khr(1.5, 0.5).is_dispersive());
    assert!(!IorModel::Constant(1.5).is_dispersive());
    assert_eq!(IorModel::Constant(1.33).ior(400.0), 1.33);
    assert!(IorModel::Constant(1.5).abbe_number().is_infinite());
}

#[test]
fn cauchy_formula() {
    let m = IorModel::Cauchy { b: 1.5, c: 0.0042 };
    // λ = 0.5 µm: n = b + c/0.25.
    assert!((m.ior(500.0) - (1.5 + 0.0042 / 0.25)).abs() < 1e-6);
    assert!(m.is_dispersive());
    assert!(!IorModel::Cauchy { b: 1.5, c: 0.0 }.is_dispersive());
    // ≥ 1 clamp.
    assert_eq!(IorModel::Cauchy { b: 0.5, c: 0.0 }.ior(500.0), 1.0);
}

#[test]
fn sellmeier_never_nan() {
    // A resonance inside the visible range must not produce NaN (n² < 0 is clamped to 1).
    let m = IorModel::Sellmeier {
        b: [1.0, 0.0, 0.0, 0.0],
        c: [0.25, 0.0, 0.0, 0.0],
    };
    for l in [360.0, 499.0, 500.0, 501.0, 830.0, f32::NAN] {
        assert!(m.ior(l) >= 1.0 && m.ior(l).is_finite(), "{l}: {}", m.ior(l));
    }
}

#[test]
fn dispersive_models_saturate_instead_of_overflowing() {
    // c = f32::MAX µm² at 0.36 µm is 2.6e39 in f64, beyond f32: n saturates to f32::MAX
    // (finite); +∞ stays reserved for `Constant(+∞)`, the `ior: 0` mode.
    let m = IorModel::Cauchy {
        b: 1.5,
        c: f32::MAX,
    };
    assert_eq!(m.ior(360.0), f32::MAX);
    // KHR with D = f32::MAX: 4 + 3·(D/20)·2.52 = 1.3e38 at 360 nm, still finite.
    let k = IorModel::KhrDispersion {
        n_d: 4.0,
        dispersion: f32::MAX,
    };
    assert!(k.ior(360.0).is_finite() && k.ior(360.0) > 1e38);
    assert_eq!(k.ior(830.0), 1.0);
    let k = IorModel::KhrDispersion {
        n_d: 100.0,
        dispersion: f32::MAX,
    };
    assert_eq!(k.ior(360.0), f32::MAX);
}

#[test]
fn sellmeier_poles() {
    // √0.25 µm² = 500 nm; terms with b = 0 or c ≤ 0 have no pole.
    let m = IorModel::Sellmeier {
        b: [1.0, 0.0, 2.0, 1.0],
        c: [0.25, 0.09, 100.0, 0.0],
    };
    let poles = m.poles_nm();
    assert_eq!(poles.len(), 2);
    assert!((poles[0] - 500.0).abs() < 1e-3 && (poles[1] - 10_000.0).abs() < 1e-2);
    assert!((m.pole_in(360.0, 830.0).unwrap() - 500.0).abs() < 1e-3);
    assert_eq!(m.pole_in(501.0, 9_000.0), None);
    assert!(IorModel::Cauchy { b: 1.5, c: 0.1 }.poles_nm().is_empty());
    for name in KNOWN_NAMES {
        assert_eq!(named(name).pole_in(360.0, 830.0), None, "{name}");
    }
}
