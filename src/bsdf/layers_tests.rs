//! Tests of the KHR layers ([`super::layers`], [`super::sheen`]): the sheen albedo table
//! (against its file and by Monte Carlo), χ² of the layered material's sampling against its
//! pdf, white-furnace bounds, reciprocity, and the properties each extension must show.
//! Deterministic `Rng` streams.

use super::layers::Layered;
use super::tests::chi2::chi2_pvalue;
use super::tests::rand_dir;
use super::*;
use crate::math::Rng;
use std::f64::consts::PI;

const R: TransportMode = TransportMode::Radiance;

/// The embedded sheen table equals a fresh quadrature (to its u16 quantisation);
/// `IRIS_REGEN_SHEEN_TABLE=1` rewrites the file instead.
#[test]
fn sheen_table_file_is_current() {
    if std::env::var_os("IRIS_REGEN_SHEEN_TABLE").is_some() {
        std::fs::write(sheen::TABLE_PATH, sheen::generate_file()).expect("write the sheen table");
        return;
    }
    let dev = sheen::max_file_deviation();
    assert!(
        dev <= 1.0 / 65535.0,
        "sheen table deviates by {dev}: regenerate it"
    );
}

/// A glTF material with the given base, metallic, roughness, specular factor and layers.
fn material(base: f32, metallic: f32, roughness: f32, specular: f32, layers: Layers) -> Bsdf {
    Bsdf::GltfPbr {
        base: Vec3::splat(base),
        metallic,
        alpha: roughness * roughness,
        ior: 1.5,
        specular,
        specular_color: Vec3::ONE,
        layers,
        extensions: crate::bsdf::LobeExtensions::NONE,
    }
}

fn coat(factor: f32, roughness: f32) -> Layers {
    Layers {
        clearcoat: factor,
        clearcoat_alpha: roughness * roughness,
        ..Layers::none()
    }
}

fn sheen_layer(colour: Vec3, alpha: f32) -> Layers {
    Layers {
        sheen_color: colour,
        sheen_alpha: alpha,
        ..Layers::none()
    }
}

fn transmission(factor: f32, colour: Vec3) -> Layers {
    Layers {
        diffuse_transmission: factor,
        diffuse_transmission_color: colour,
        ..Layers::none()
    }
}

fn wo_at(deg: f32, inside: bool) -> Vec3 {
    let t = deg.to_radians();
    let z = if inside { -t.cos() } else { t.cos() };
    Vec3::new(t.sin() * 0.6, t.sin() * 0.8, z)
}

/// Directional albedo by sampling: (reflected, transmitted, standard error of the total's
/// mean channel).
fn albedo(b: &Bsdf, wo: Vec3, n: usize, seed: u64) -> (Vec3, Vec3, f64) {
    let mut rng = Rng::new(&[seed, 0x1A7E]);
    let (mut refl, mut trans) = (Vec3::ZERO, Vec3::ZERO);
    let (mut s1, mut s2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let uc = rng.next_f32();
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(s) = b.sample(wo, uc, u, R) {
            let w = s.f * (s.wi.z.abs() / s.pdf);
            if s.transmission {
                trans += w;
            } else {
                refl += w;
            }
            let m = w.element_sum() as f64 / 3.0;
            s1 += m;
            s2 += m * m;
        }
    }
    let (nf, mean) = (n as f32, s1 / n as f64);
    let var = (s2 / n as f64 - mean * mean).max(0.0);
    (refl / nf, trans / nf, (var / n as f64).sqrt())
}

/// The white sheen lobe's albedo by sampling the full BSDF (black base, no specular, so
/// f = f_sheen) equals the table within 1.5 % + 4σ, and is ≤ 1.
#[test]
fn sheen_albedo_follows_its_table() {
    let mut k = 0;
    for &alpha in &[0.07f32, 0.3, 0.6, 1.0] {
        for &mu in &[0.05f32, 0.2, 0.5, 0.8, 1.0] {
            k += 1;
            let b = material(0.0, 0.0, 0.5, 0.0, sheen_layer(Vec3::ONE, alpha));
            let s = (1.0 - mu * mu).sqrt();
            let wo = Vec3::new(s, 0.0, mu);
            let (r, t, se) = albedo(&b, wo, 200_000, k);
            let table = sheen::albedo(mu, alpha) as f64;
            let mc = r.x as f64;
            eprintln!("sheen α {alpha} μ {mu}: MC {mc:.4} ± {se:.4}, table {table:.4}");
            assert!(t == Vec3::ZERO, "sheen transmits");
            assert!(mc <= 1.0 + 4.0 * se, "sheen albedo {mc} > 1");
            assert!(
                (mc - table).abs() <= 0.015 * table + 4.0 * se + 1e-3,
                "α {alpha} μ {mu}: MC {mc} vs table {table}"
            );
        }
    }
}

/// Bins of the whole sphere, uniform in (cos θ, φ): `NZ` × `NP`.
const NZ: usize = 40;
const NP: usize = 80;

fn bin_of(w: Vec3) -> usize {
    let iz = (((w.z + 1.0) * 0.5 * NZ as f32) as usize).min(NZ - 1);
    let phi = w.y.atan2(w.x).rem_euclid(std::f32::consts::TAU);
    let ip = ((phi / std::f32::consts::TAU * NP as f32) as usize).min(NP - 1);
    iz * NP + ip
}

/// Expected counts: n · ∫ pdf over each bin (8×8 midpoints per bin, dω = dz dφ), plus
/// the "no sample" cell.
fn expected(b: &Bsdf, wo: Vec3, n: usize) -> Vec<f64> {
    const S: usize = 8;
    let mut exp = vec![0.0; NZ * NP + 1];
    let (dz, dp) = (2.0 / NZ as f64, 2.0 * PI / NP as f64);
    let mut total = 0.0;
    for iz in 0..NZ {
        for ip in 0..NP {
            let mut acc = 0.0;
            for a in 0..S {
                let z = -1.0 + (iz as f64 + (a as f64 + 0.5) / S as f64) * dz;
                let r = (1.0 - z * z).max(0.0).sqrt();
                for c in 0..S {
                    let phi = (ip as f64 + (c as f64 + 0.5) / S as f64) * dp;
                    let wi = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                    acc += b.pdf(wo, wi, R) as f64;
                }
            }
            let e = acc * dz * dp / (S * S) as f64;
            exp[iz * NP + ip] = e * n as f64;
            total += e;
        }
    }
    exp[NZ * NP] = (1.0 - total).max(0.0) * n as f64;
    exp
}

fn chi2_case(b: &Bsdf, wo: Vec3, n: usize, seed: u64) -> f64 {
    let mut obs = vec![0.0; NZ * NP + 1];
    let mut rng = Rng::new(&[seed, 0xC412]);
    for _ in 0..n {
        let uc = rng.next_f32();
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        match b.sample(wo, uc, u, R) {
            Some(s) => {
                let pdf = b.pdf(wo, s.wi, R);
                assert!(
                    (pdf - s.pdf).abs() <= 1e-4 * pdf.max(1.0),
                    "sample pdf {} vs pdf {pdf}",
                    s.pdf
                );
                let f = b.eval(wo, s.wi, R);
                assert!((f - s.f).abs().max_element() <= 1e-5 * f.max_element().max(1.0));
                obs[bin_of(s.wi)] += 1.0;
            }
            None => obs[NZ * NP] += 1.0,
        }
    }
    chi2_pvalue(&obs, &expected(b, wo, n))
}

/// The layered materials of the χ² and furnace tests: each lobe alone and combined.
fn cases(base: f32) -> Vec<(&'static str, Bsdf)> {
    let all = Layers {
        clearcoat: 0.7,
        clearcoat_alpha: 0.3 * 0.3,
        sheen_color: Vec3::new(1.0, 0.8, 0.6),
        sheen_alpha: 0.4,
        diffuse_transmission: 0.5,
        diffuse_transmission_color: Vec3::new(1.0, 0.9, 0.7),
    };
    vec![
        ("coat", material(base, 0.0, 0.8, 1.0, coat(1.0, 0.3))),
        ("coat/metal", material(base, 0.5, 0.5, 1.0, coat(0.5, 0.5))),
        (
            "sheen",
            material(base, 0.0, 0.6, 1.0, sheen_layer(Vec3::ONE, 0.3)),
        ),
        (
            "sheen α1",
            material(base, 0.0, 0.3, 1.0, sheen_layer(Vec3::splat(0.5), 1.0)),
        ),
        (
            "transmission",
            material(base, 0.0, 0.5, 1.0, transmission(0.6, Vec3::ONE)),
        ),
        (
            "transmission 1",
            material(base, 0.0, 0.5, 0.0, transmission(1.0, Vec3::ONE)),
        ),
        ("all", material(base, 0.0, 0.5, 1.0, all)),
        ("all/metal", material(base, 0.3, 0.7, 1.0, all)),
    ]
}

/// χ² of sampling against the pdf for every case at 10°, 60°, 85° and from below (the
/// material is two-sided), 300k samples each; Šidák-corrected threshold for a
/// family-wise significance of 0.01. Sample and pdf/eval must agree at every sample.
#[test]
fn layered_sampling_matches_pdf() {
    let cases = cases(0.8);
    let wos = [
        wo_at(10.0, false),
        wo_at(60.0, false),
        wo_at(85.0, false),
        wo_at(40.0, true),
    ];
    let m = (cases.len() * wos.len()) as f64;
    let threshold = 1.0 - 0.99f64.powf(1.0 / m);
    let mut k = 0;
    for (name, b) in &cases {
        for &wo in &wos {
            k += 1;
            let p = chi2_case(b, wo, 300_000, k);
            eprintln!("χ² {name} wo.z {:.3}: p = {p:.4}", wo.z);
            assert!(p > threshold, "{name} at wo {wo}: χ² p = {p} < {threshold}");
        }
    }
}

/// White furnace: with a white base, every case's directional albedo (reflection plus
/// transmission, per channel) is ≤ 1 within 4σ of its Monte Carlo noise, or — where the
/// glTF base alone already exceeds 1 (its diffuse term's (1 − F) at the half vector is not
/// an exact energy split at grazing angles) — at most the base's own albedo: the layers
/// add no energy. 5 angles from both sides.
#[test]
fn layered_albedo_at_most_one() {
    let mut k = 100;
    for (name, b) in cases(1.0) {
        let Bsdf::GltfPbr {
            metallic,
            alpha,
            specular,
            ..
        } = b
        else {
            unreachable!()
        };
        let plain = material(1.0, metallic, alpha.sqrt(), specular, Layers::none());
        for &(deg, inside) in &[
            (0.0, false),
            (30.0, false),
            (60.0, false),
            (80.0, true),
            (88.0, false),
        ] {
            k += 1;
            let wo = wo_at(deg, inside);
            let (r, t, se) = albedo(&b, wo, 100_000, k);
            let (r0, _, se0) = albedo(&plain, wo, 100_000, k + 1000);
            let total = (r + t).max_element() as f64;
            let bound = 1f64.max(r0.max_element() as f64) + 4.0 * (se + se0) + 1e-3;
            eprintln!("furnace {name} {deg}°: R {r:?} T {t:?} ± {se:.4} (base {r0:?})");
            assert!(total <= bound, "{name} at {deg}°: albedo {total} > {bound}");
        }
    }
}

/// Energy of the non-absorbing layered material (white base, KHR_materials_specular 0 so
/// the base is a Lambertian without a GGX loss, white layers): all that is not
/// absorbed by the sheen's albedo scaling is scattered — diffuse transmission 1 white
/// scatters exactly 1, and so does a white sheen over a white Lambertian base (view-only
/// albedo scaling: E(μo) + (1 − E(μo))·1, up to the table's error); a clearcoat over the
/// transmitting base: a smooth coat (α 0.01) ≥ 0.99; a rough one (α 0.25) ≥ 0.8 — the
/// spec's blend 1 − cc·F_c(cos θo) takes more than the rough coat reflects at grazing
/// angles, where its microfacets see |wo·h| > cos θo (measured 0.997 at 5° and 45°, 0.854
/// at 75°).
#[test]
fn non_absorbing_layers_conserve_energy() {
    let full = |layers: Layers| material(1.0, 0.0, 0.5, 0.0, layers);
    let sheen_over = Layers {
        sheen_color: Vec3::ONE,
        sheen_alpha: 0.5,
        ..Layers::none()
    };
    let coat_over = |alpha: f32| Layers {
        clearcoat: 1.0,
        clearcoat_alpha: alpha,
        diffuse_transmission: 1.0,
        diffuse_transmission_color: Vec3::ONE,
        ..Layers::none()
    };
    for (name, b, lo) in [
        ("transmission", full(transmission(1.0, Vec3::ONE)), 0.995),
        ("lambert+sheen", full(sheen_over), 0.99),
        ("smooth coat+transmission", full(coat_over(0.01)), 0.99),
        ("rough coat+transmission", full(coat_over(0.25)), 0.8),
    ] {
        for (i, deg) in [5.0f32, 45.0, 75.0].into_iter().enumerate() {
            let (r, t, se) = albedo(&b, wo_at(deg, false), 100_000, 300 + i as u64);
            let e = (r + t).x as f64;
            eprintln!("energy {name} {deg}°: {e:.4} ± {se:.4}");
            assert!(
                e >= lo - 4.0 * se && e <= 1.0 + 4.0 * se,
                "{name} {deg}°: {e}"
            );
        }
    }
}

/// Importance mode is the exact adjoint of Radiance mode, f_Importance(wo, wi) =
/// f_Radiance(wi, wo), also where the coat's and the sheen's scalings break reciprocity (so
/// photons gathered on a coated or sheened surface estimate what the path tracer does);
/// without the adjoint the coat alone breaks it by a_c(wi)/a_c(wo), up to 1/(1 − 0.04) at
/// normal against grazing incidence. Tolerance 1e-3 relative.
#[test]
fn layered_importance_mode_is_the_adjoint() {
    const I: TransportMode = TransportMode::Importance;
    let mut rng = Rng::new(&[8, 0xad70]);
    let layered = Layers {
        clearcoat: 1.0,
        clearcoat_alpha: 0.09,
        sheen_color: Vec3::new(0.9, 0.6, 0.3),
        sheen_alpha: 0.4,
        diffuse_transmission: 0.5,
        diffuse_transmission_color: Vec3::ONE,
    };
    let b = material(0.8, 0.0, 0.5, 1.0, layered);
    let mut broken = 0.0f32;
    for _ in 0..8000 {
        let reflect = rng.next_f32() < 0.7;
        let (wo, wi) = (rand_dir(&mut rng, true), rand_dir(&mut rng, reflect));
        let (imp, rad) = (b.eval(wo, wi, I), b.eval(wi, wo, R));
        let scale = imp.max_element().max(rad.max_element()).max(1e-3);
        assert!(
            (imp - rad).abs().max_element() <= 1e-3 * scale,
            "f_I({wo}, {wi}) = {imp} but f_R({wi}, {wo}) = {rad}"
        );
        let same = b.eval(wo, wi, R);
        broken = broken.max((same - rad).abs().max_element() / scale);
    }
    assert!(
        broken > 0.01,
        "the layers should break reciprocity: {broken}"
    );
}

/// f(wo, wi) = f(wi, wo) for random pairs (both hemispheres) where it holds: diffuse
/// transmission over the base (the coat and sheen scalings depend on wo, see
/// `super::layers`). Tolerance 1e-3 relative (half vectors of nearly opposite grazing pairs
/// lose precision).
#[test]
fn layered_material_is_reciprocal() {
    let mut rng = Rng::new(&[7, 0x4ec1]);
    let dir = |rng: &mut Rng| {
        let z = rng.next_f32() * 2.0 - 1.0;
        let phi = rng.next_f32() * std::f32::consts::TAU;
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    };
    let mut checked = 0;
    let reciprocal = [
        (
            "transmission",
            material(
                0.7,
                0.0,
                0.5,
                1.0,
                transmission(0.6, Vec3::new(1.0, 0.5, 0.2)),
            ),
        ),
        (
            "transmission/metal",
            material(0.7, 0.4, 0.3, 1.0, transmission(1.0, Vec3::ONE)),
        ),
    ];
    for (name, b) in reciprocal {
        for _ in 0..8000 {
            let (a, c) = (dir(&mut rng), dir(&mut rng));
            let (f1, f2) = (b.eval(a, c, R), b.eval(c, a, R));
            let scale = f1.max_element().max(f2.max_element());
            if scale > 0.0 {
                checked += 1;
            }
            assert!(
                (f1 - f2).abs().max_element() <= 1e-3 * scale.max(1e-3),
                "{name}: f({a}, {c}) = {f1:?} but f({c}, {a}) = {f2:?}"
            );
        }
    }
    assert!(checked > 10_000, "only {checked} non-zero pairs");
}

/// Absent layers: the layered evaluation equals the plain glTF BRDF (and the Bsdf then
/// uses the plain one), so factor 0 is exactly "no extension".
#[test]
fn zero_factors_equal_no_extension() {
    let plain = material(0.6, 0.3, 0.5, 1.0, Layers::none());
    let zero = Layers {
        clearcoat: 0.0,
        clearcoat_alpha: 0.2,
        sheen_color: Vec3::ZERO,
        sheen_alpha: 0.5,
        diffuse_transmission: 0.0,
        diffuse_transmission_color: Vec3::new(0.2, 0.3, 0.4),
    };
    assert!(zero.is_none());
    let g = pbr::GltfPbr {
        base: Vec3::splat(0.6),
        metallic: 0.3,
        alpha: 0.5 * 0.5,
        ior: 1.5,
        specular: 1.0,
        specular_color: Vec3::ONE,
        layers: Layers::none(),
        extensions: crate::bsdf::LobeExtensions::NONE,
    }
    .brdf();
    let l = Layered::new(g, &zero);
    let mut rng = Rng::new(&[3, 0x2e0]);
    for _ in 0..5000 {
        let wo = wo_at(rng.next_f32() * 89.0, rng.next_f32() < 0.5);
        let wi = wo_at(rng.next_f32() * 89.0, rng.next_f32() < 0.5) * Vec3::new(-1.0, 1.0, 1.0);
        let (a, b) = (g.eval(wo, wi), l.eval(wo, wi, R));
        assert!(
            (a - b).abs().max_element() <= 1e-6 * a.max_element().max(1.0),
            "{a} vs {b}"
        );
        let with_zero = material(0.6, 0.3, 0.5, 1.0, zero);
        assert_eq!(with_zero.eval(wo, wi, R), plain.eval(wo, wi, R));
        assert_eq!(with_zero.pdf(wo, wi, R), plain.pdf(wo, wi, R));
    }
}

/// Clearcoat: F_c(1) = 0.04; a smooth coat over a black base reflects 0.04·factor at
/// normal incidence; over a rough base it adds a sharp peak in the mirror direction (at
/// least 20× the uncoated value there) and changes little away from it.
#[test]
fn clearcoat_properties() {
    assert!((coat_fresnel(1.0) - 0.04).abs() < 1e-7);
    assert!((coat_fresnel(0.0) - 1.0).abs() < 1e-7);
    for (i, factor) in [0.25f32, 0.5, 1.0].into_iter().enumerate() {
        let b = material(0.0, 0.0, 1.0, 0.0, coat(factor, 0.0));
        let (r, t, se) = albedo(&b, Vec3::Z, 100_000, 500 + i as u64);
        eprintln!("coat {factor} at normal incidence: {r:?} ± {se:.5}");
        assert!(t == Vec3::ZERO);
        let want = 0.04 * factor;
        assert!(
            (r.x - want).abs() <= 0.01 * want + 4.0 * se as f32,
            "{r} vs {want}"
        );
    }
    let wo = wo_at(30.0, false);
    let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
    let off = wo_at(60.0, false) * Vec3::new(1.0, -1.0, 1.0);
    let bare = material(0.5, 0.0, 0.9, 1.0, Layers::none());
    let coated = material(0.5, 0.0, 0.9, 1.0, coat(1.0, 0.1));
    let (peak0, peak1) = (bare.eval(wo, mirror, R).x, coated.eval(wo, mirror, R).x);
    eprintln!("mirror direction: bare {peak0}, coated {peak1}");
    assert!(peak1 > 20.0 * peak0, "coat peak {peak1} vs bare {peak0}");
    let (o0, o1) = (bare.eval(wo, off, R).x, coated.eval(wo, off, R).x);
    assert!(o1 <= o0 * 1.01 && o1 >= o0 * 0.9, "off-peak {o0} → {o1}");
}

/// Sheen raises the grazing reflectance of a dark base much more than the normal one.
#[test]
fn sheen_brightens_grazing_reflection() {
    let dark = material(0.02, 0.0, 0.8, 1.0, Layers::none());
    let velvet = material(0.02, 0.0, 0.8, 1.0, sheen_layer(Vec3::ONE, 0.3));
    let gain = |deg: f32, seed: u64| {
        let wo = wo_at(deg, false);
        let (r0, _, _) = albedo(&dark, wo, 100_000, seed);
        let (r1, _, _) = albedo(&velvet, wo, 100_000, seed);
        (r1 - r0).x
    };
    let (grazing, normal) = (gain(80.0, 600), gain(0.0, 601));
    eprintln!("sheen gain: 80° {grazing}, 0° {normal}");
    assert!(grazing > 0.1, "grazing gain {grazing}");
    assert!(
        grazing > 2.0 * normal,
        "grazing {grazing} vs normal {normal}"
    );
}

/// Diffuse transmission: factor 1 white (no specular) reflects nothing and transmits
/// everything; factor t, colour c transmits t·c of the diffuse part and reflects
/// (1 − t)·base.
#[test]
fn diffuse_transmission_fractions() {
    let full = material(0.7, 0.0, 0.5, 0.0, transmission(1.0, Vec3::ONE));
    let (r, t, _) = albedo(&full, wo_at(35.0, false), 50_000, 700);
    assert!(r == Vec3::ZERO, "reflection {r}");
    assert!(
        (t - Vec3::ONE).abs().max_element() < 1e-4,
        "transmission {t}"
    );
    let c = Vec3::new(0.9, 0.5, 0.2);
    for (i, tf) in [0.25f32, 0.5, 0.8].into_iter().enumerate() {
        let b = material(0.6, 0.0, 0.5, 0.0, transmission(tf, c));
        for inside in [false, true] {
            let (r, t, se) = albedo(&b, wo_at(50.0, inside), 100_000, 710 + i as u64);
            let tol = 0.01 + 4.0 * se as f32;
            eprintln!("transmission {tf}: R {r:?} T {t:?}");
            assert!(
                (t - c * tf).abs().max_element() <= tol,
                "T {t} vs {}",
                c * tf
            );
            assert!(
                (r - Vec3::splat(0.6 * (1.0 - tf))).abs().max_element() <= tol,
                "R {r}"
            );
        }
    }
}
