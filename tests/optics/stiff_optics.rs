//! Stiff cases of the smooth interface (issue 7, cases 1–4), on the formulas
//! ([`iris::optics`]), the BSDF ([`iris::bsdf::Bsdf`]) and single rays traced through the
//! integrators' own interface step ([`shading::meet`] + [`shading::interface`]) on both
//! backends. Renders of the same cases are in `tests/optics/stiff_renders.rs`.
//!
//! 1. Grazing incidence (θ = 89.9°, 89.999°, 90°, dir·n = ±1e-8), entering and exiting:
//!    R → 1 with the closed-form slope 1 − R ≈ 2 cos θ_i (η²+1)/√(η²−1) (first order of
//!    the Fresnel equations, Born & Wolf §1.5.2, at cos θ_t → √(η²−1)/η), R monotone from
//!    Brewster's angle atan η to 90°, the refracted direction unit and obeying Snell's law
//!    n_i sin θ_i = n_t sin θ_t, BSDF sample/eval/pdf finite.
//! 2. IOR → 1 (1 + 1e-7 and 1): a ray through a sphere keeps its direction to 1e-6.
//! 3. IOR 0.8 (the air bubble of paper Fig. 7.2): total internal reflection exactly for
//!    impact parameters b/R > 0.8 (sin θ_i = b/R for a ray parallel to the axis).
//! 4. IOR ≫ 1 (4, 10, 100, and 1e30 / +∞): R(0) = ((n−1)/(n+1))², R + T = 1 with T from
//!    the Fresnel transmission amplitudes (Born & Wolf §1.5.3), critical angle asin(1/n)
//!    from inside; the `ior: 0` mode (+∞) reflects everything.

use crate::common;

use glam::{DVec3, Vec2, Vec3};
use iris::accel::Backend;
use iris::bsdf::{Bsdf, TransportMode};
use iris::math::{Frame, Ray};
use iris::medium_stack::MediumStack;
use iris::optics::{critical_angle, fresnel_dielectric, refract};
use iris::scene::desc::{MeshDesc, SceneDesc};
use iris::scene::Scene;
use iris::shading;

/// Unit direction at polar angle θ (from +z) in the xz plane, from its cosine (f64, so the
/// angles near 90° are not rounded to each other).
fn dir_cos(cos: f64) -> Vec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    DVec3::new(sin, 0.0, cos).as_vec3()
}

/// The grazing cosines of case 1: 89.9°, 89.999°, exactly 90°, and dir·n = ±1e-8.
fn grazing_cosines() -> [f64; 5] {
    [
        89.9f64.to_radians().cos(),
        89.999f64.to_radians().cos(),
        0.0,
        1e-8,
        -1e-8,
    ]
}

#[test]
fn grazing_fresnel_tends_to_one_with_the_closed_form_slope() {
    for eta in [1.2f32, 1.5, 2.417, 4.0, 100.0] {
        let e = f64::from(eta);
        let slope = 2.0 * (e * e + 1.0) / (e * e - 1.0).sqrt();
        let cos_t0 = (e * e - 1.0).sqrt() / e;
        for cos in [
            89.9f64.to_radians().cos(),
            89.999f64.to_radians().cos(),
            1e-6,
        ] {
            let r = f64::from(fresnel_dielectric(cos as f32, eta));
            let expected = slope * cos;
            // Linearisation error: each amplitude is (1−x)/(1+x) with x ≤ η cos θ_i/cos θ_t,
            // squared 1 − 4x + O(x²), so the relative error of 1 − R is ≤ 2x (4x here);
            // plus 2 ulps of 1.0 in f32 for R itself.
            let tol = expected * 4.0 * e * cos / cos_t0 + 2.4e-7;
            assert!(
                ((1.0 - r) - expected).abs() <= tol,
                "η {eta} cos {cos:e}: 1 − R = {:e}, closed form {expected:e}",
                1.0 - r
            );
        }
        // Exactly grazing and the ±1e-8 cosines: R = 1 to 2 ulps (slope·1e-8 ≤ 2e-6·η).
        for cos in [0.0f32, -1e-8] {
            assert_eq!(fresnel_dielectric(cos, eta), 1.0, "η {eta} cos {cos}");
        }
        let r = fresnel_dielectric(1e-8, eta);
        assert!(r <= 1.0 && 1.0 - r <= (slope * 1e-8) as f32 + 1.2e-7, "{r}");
        // Exiting (η' = 1/η): grazing is past the critical angle, R is exactly 1.
        for cos in grazing_cosines() {
            assert_eq!(fresnel_dielectric(cos as f32, 1.0 / eta), 1.0);
        }
    }
}

#[test]
fn fresnel_is_monotone_from_brewster_to_grazing() {
    for eta in [1.0f32 + 1e-3, 1.5, 2.417, 100.0, 1.0 / 1.5, 0.8, 0.01] {
        let brewster = f64::from(eta).atan();
        let n = 4000;
        let mut prev = 0.0f32;
        for k in 0..=n {
            let theta = brewster + (std::f64::consts::FRAC_PI_2 - brewster) * k as f64 / n as f64;
            let r = fresnel_dielectric(theta.cos() as f32, eta);
            assert!(
                r.is_finite() && (0.0..=1.0).contains(&r),
                "η {eta}: R = {r}"
            );
            // R_s rises everywhere and R_p rises past Brewster's angle, so their mean does;
            // 1e-6 absorbs the f32 rounding of R (a few ulps of values ≤ 1).
            assert!(r >= prev - 1e-6, "η {eta} θ {theta}: {r} < {prev}");
            prev = r;
        }
        assert_eq!(prev, 1.0, "η {eta}: R(90°)");
    }
}

#[test]
fn grazing_refraction_is_unit_and_obeys_snell() {
    let n = Vec3::Z;
    for eta in [1.0f32, 1.0 + 1e-7, 1.5, 2.417, 4.0, 100.0] {
        for cos in grazing_cosines() {
            let wi = dir_cos(cos);
            let wt = refract(wi, n, eta).unwrap_or_else(|| panic!("η {eta} cos {cos}: no T"));
            assert!(wt.is_finite(), "η {eta} cos {cos}: {wt}");
            assert!(
                (wt.length() - 1.0).abs() < 1e-6,
                "not unit: {}",
                wt.length()
            );
            // Crosses (z ≤ 0; the −1e-8 input starts 1e-8 below the surface itself).
            assert!(
                wt.z <= 1e-7 && wt.x <= 0.0,
                "η {eta} cos {cos}: {wt} does not cross"
            );
            // n_i sin θ_i = n_t sin θ_t; sin θ_t from an f32 unit vector is good to ~1e-7,
            // times η.
            let sin_t = f64::from(wt.x.hypot(wt.y));
            let sin_i = f64::from(wi.x.hypot(wi.y));
            let e = f64::from(eta);
            assert!(
                (e * sin_t - sin_i).abs() <= 1e-6 * e.max(1.0),
                "η {eta} cos {cos}: η sin θt {} vs sin θi {sin_i}",
                e * sin_t
            );
        }
        // Exiting at grazing: total internal reflection.
        if eta > 1.0 + 1e-3 {
            for cos in grazing_cosines() {
                assert!(refract(dir_cos(cos), n, 1.0 / eta).is_none());
            }
        }
    }
    // η = 1: the direction is exactly unchanged, even at 89.999° (the f32 form of
    // cos θ_t = √(1 − sin²θ_i) loses cos²θ_i ≈ 3e-10 there and bent it by 1.7e-5).
    for cos in grazing_cosines() {
        let wi = dir_cos(cos);
        assert_eq!(refract(wi, n, 1.0), Some(-wi), "cos {cos}");
    }
}

/// Every (wo, uc, u) the grazing cases exercise, on both sides of the surface.
fn grazing_wos() -> Vec<Vec3> {
    let mut v = Vec::new();
    for cos in grazing_cosines() {
        for side in [1.0f32, -1.0] {
            let w = dir_cos(cos);
            v.push(Vec3::new(w.x * 0.6, w.x * 0.8, w.z * side));
        }
    }
    v
}

#[test]
fn bsdf_sample_eval_pdf_stay_finite_at_grazing() {
    let etas = [
        1.0f32,
        1.0 + 1e-7,
        1.5,
        1.0 / 1.5,
        0.8,
        100.0,
        1e30,
        f32::INFINITY,
    ];
    let us = [0.0f32, 1e-7, 0.3, 0.5, 0.9, 0.99999994];
    let wis = grazing_wos();
    for eta in etas {
        for alpha in [0.0f32, 0.01, 0.3, 1.0] {
            let tint = Vec3::ONE;
            let bsdfs: [Bsdf; 2] = [
                Bsdf::Dielectric { eta, alpha, tint },
                Bsdf::ThinDielectric { eta, tint },
            ];
            for bsdf in bsdfs {
                for &wo in &wis {
                    for mode in [TransportMode::Radiance, TransportMode::Importance] {
                        for &uc in &us {
                            for &u in &us {
                                let Some(s) = bsdf.sample(wo, uc, Vec2::new(u, 1.0 - u), mode)
                                else {
                                    continue;
                                };
                                let ok = s.wi.is_finite()
                                    && (s.wi.length() - 1.0).abs() < 1e-5
                                    && s.f.is_finite()
                                    && s.f.min_element() >= 0.0
                                    && s.pdf.is_finite()
                                    && s.pdf > 0.0;
                                assert!(ok, "{bsdf:?} wo {wo} uc {uc} u {u}: {s:?}");
                                // Delta lobes in importance mode carry f·|cos|/pdf ≤ 1
                                // (R/R or T/T; tint 1): no energy gain.
                                if s.delta && mode == TransportMode::Importance {
                                    let k = s.f.max_element() * s.wi.z.abs() / s.pdf;
                                    assert!(k <= 1.0 + 1e-5, "{bsdf:?} wo {wo}: gain {k}");
                                }
                            }
                        }
                        for &wi in &wis {
                            let f = bsdf.eval(wo, wi, mode);
                            let p = bsdf.pdf(wo, wi, mode);
                            assert!(
                                f.is_finite()
                                    && f.min_element() >= 0.0
                                    && p.is_finite()
                                    && p >= 0.0,
                                "{bsdf:?} wo {wo} wi {wi}: f {f} pdf {p}"
                            );
                        }
                    }
                }
            }
        }
    }
}

/// A unit icosphere (subdivision 5, interpolated normals) of clear glass of index `ior`.
fn sphere_scene(ior: f32, backend: Backend) -> Scene {
    let mesh = iris::authoring::shapes::icosphere(1.0, 5);
    let desc = SceneDesc {
        source: "stiff sphere".into(),
        meshes: vec![MeshDesc {
            name: "sphere".into(),
            positions: mesh.positions,
            normals: mesh.normals,
            indices: mesh.indices,
            material: Some(0),
            ..Default::default()
        }],
        materials: vec![common::clear_glass("glass", ior)],
        ..Default::default()
    };
    Scene::build(iris::scene::validate::validate(desc).unwrap(), backend).unwrap()
}

/// The interface the integrators see at the first hit of `ray`, from air: the hit, the
/// incident-side shading normal, η = n_t/n_i and the BSDF (with its shading frame).
fn first_interface(scene: &Scene, ray: &Ray) -> Option<(Vec3, Vec3, f32, Bsdf, Frame)> {
    let hit = scene.intersect(ray)?;
    let (hit, co) = shading::meet(scene, hit);
    let (n_i, n_t, _, _) = shading::interface::<Vec3>(scene, &hit, &co, MediumStack::new(), &());
    let sp = scene.materials()[hit.material as usize].shade(&scene.textures_at(hit.uv));
    let (bsdf, _, _) =
        shading::bsdf_at::<Vec3>(scene, &hit, &co, &sp, MediumStack::new(), 0.0, &());
    let n = if hit.front_face { hit.ns } else { -hit.ns };
    Some((hit.wo, n, n_t / n_i, bsdf, Frame::from_normal(hit.ns)))
}

/// Follows a ray through `scene` refracting at every surface (the integrators' interface
/// step, media tracked), `None` on total internal reflection; the exit ray and the count of
/// interfaces crossed.
fn refract_through(scene: &Scene, mut ray: Ray) -> Option<(Ray, usize)> {
    let mut media = MediumStack::new();
    for k in 0..8 {
        let Some(hit) = scene.intersect(&ray) else {
            return Some((ray, k));
        };
        let (hit, co) = shading::meet(scene, hit);
        let (n_i, n_t, after, _) = shading::interface::<Vec3>(scene, &hit, &co, media, &());
        let n = if hit.front_face { hit.ns } else { -hit.ns };
        ray = hit.spawn_ray(refract(hit.wo, n, n_t / n_i)?);
        media = after;
    }
    None
}

#[test]
fn ior_near_one_passes_rays_straight_through() {
    for backend in common::backends() {
        for ior in [1.0f32 + 1e-7, 1.0] {
            let s = sphere_scene(ior, backend);
            for i in 0..=90 {
                // Impact parameters up to 0.9 R: tan θ_i ≤ 2.1, so Snell bends by
                // ≤ 2.1 × 1.2e-7 per interface; the two bends cancel to first order.
                let b = 0.01 * i as f32;
                let d_in = Vec3::new(0.0, 0.0, -1.0);
                let ray = Ray::new(Vec3::new(b, 0.013, 5.0), d_in);
                let (out, crossed) = refract_through(&s, ray).expect("no TIR at n ≈ 1");
                assert_eq!(crossed, 2, "{backend:?} n {ior} b {b}");
                let d = out.dir.normalize();
                // f32 refraction and normalisation: a few 1e-7 per interface.
                assert!((d - d_in).length() < 1e-6, "{backend:?} n {ior} b {b}: {d}");
                // The exit ray continues the entry line (to the offset rule's few 1e-6).
                assert!(
                    out.origin.truncate().distance(Vec2::new(b, 0.013)) < 2e-5,
                    "{backend:?} n {ior} b {b}: exit at {}",
                    out.origin
                );
                // The BSDF the integrators sample transmits straight on too.
                let (wo, _, _, bsdf, frame) = first_interface(&s, &ray).unwrap();
                let smp = bsdf
                    .sample(
                        frame.to_local(wo),
                        0.5,
                        Vec2::splat(0.5),
                        TransportMode::Radiance,
                    )
                    .unwrap();
                assert!(smp.transmission, "{backend:?} n {ior} b {b}: reflected");
                let wt = frame.to_world(smp.wi);
                assert!((wt - d_in).length() < 1e-6, "{backend:?} b {b}: {wt}");
                assert!((smp.f.x * smp.wi.z.abs() / smp.pdf - 1.0).abs() < 1e-6);
            }
        }
    }
}

#[test]
fn bubble_totally_reflects_beyond_the_critical_impact_parameter() {
    // Fig. 7.2's bubble: relative index 0.8. A ray parallel to the axis at impact b meets
    // the sphere at sin θ_i = b/R, so TIR iff b/R > 0.8 (sin θ_c = n_bubble/n_water).
    // Step 1e-3 of R; the icosphere's interpolated normal at a hit is the direction of the
    // hit point on the flat facet, whose radius is short of R by ≤ 1.4e-4 R (edge 0.033 R),
    // well inside one step.
    let n_rel = 0.8f32;
    let step = 1e-3f32;
    for backend in common::backends() {
        let s = sphere_scene(n_rel, backend);
        let mut first_tir = None;
        for i in 0..1000 {
            let b = i as f32 * step;
            let ray = Ray::new(Vec3::new(b, 0.0, 5.0), Vec3::NEG_Z);
            let (wo, n, eta, bsdf, frame) = first_interface(&s, &ray).expect("hits");
            assert!((eta - n_rel).abs() < 1e-6, "η {eta}");
            let cos = wo.dot(n);
            let tir = refract(wo, n, eta).is_none();
            assert_eq!(tir, fresnel_dielectric(cos, eta) == 1.0, "b {b}");
            // The integrators' BSDF agrees: beyond θ_c even uc → 1 reflects.
            let smp = bsdf
                .sample(
                    frame.to_local(wo),
                    0.99999994,
                    Vec2::splat(0.5),
                    TransportMode::Radiance,
                )
                .unwrap();
            assert_eq!(!smp.transmission, tir, "{backend:?} b {b}: BSDF vs refract");
            if tir && first_tir.is_none() {
                first_tir = Some(b);
            }
            if b < n_rel - step {
                assert!(!tir, "{backend:?} b/R {b}: TIR below the critical impact");
            }
            if b > n_rel + step {
                assert!(
                    tir,
                    "{backend:?} b/R {b}: transmits beyond the critical impact"
                );
            }
        }
        let b_c = first_tir.expect("a TIR ring");
        eprintln!("{backend:?}: TIR from b/R = {b_c} (closed form {n_rel})");
        assert!(
            (b_c - n_rel).abs() <= step,
            "{backend:?}: ring starts at {b_c}"
        );
    }
}

#[test]
fn high_index_fresnel_energy_and_critical_angle() {
    let n = Vec3::Z;
    for ior in [4.0f32, 10.0, 100.0] {
        let expected = ((ior - 1.0) / (ior + 1.0)).powi(2);
        // f64 inside, one f32 rounding out: 1e-6 relative.
        for eta in [ior, 1.0 / ior] {
            let r = fresnel_dielectric(1.0, eta);
            assert!(
                (r - expected).abs() <= 1e-6 * expected,
                "η {eta}: {r} vs {expected}"
            );
        }
        // R + T = 1 with T from the amplitude transmission coefficients and the flux
        // factor η cos θ_t / cos θ_i (Born & Wolf §1.5.3), an independent formula; f64,
        // so 1e-6 covers R's f32 rounding.
        for eta in [ior, 1.0 / ior] {
            let e = f64::from(eta);
            for i in 0..900 {
                // The reference uses the f32 cosine R sees (near θ_c, R is steep in θ).
                let ci32 = (f64::from(i) * 0.1).to_radians().cos() as f32;
                let ci = f64::from(ci32);
                let s2t = (1.0 - ci * ci) / (e * e);
                let r = f64::from(fresnel_dielectric(ci32, eta));
                if s2t >= 1.0 {
                    assert_eq!(r, 1.0);
                    continue;
                }
                let ct = (1.0 - s2t).sqrt();
                let ts = 2.0 * ci / (ci + e * ct);
                let tp = 2.0 * ci / (e * ci + ct);
                let t = 0.5 * (ts * ts + tp * tp) * e * ct / ci;
                assert!(
                    (r + t - 1.0).abs() < 1e-6,
                    "η {eta} θ {}°: R {r} T {t}",
                    i as f32 / 10.0
                );
            }
        }
        // Critical angle from inside: asin(1/n), and refraction switches there, ±5e-3 of
        // θ_c: the interface sees θ through an f32 cosine, which resolves θ only to
        // ulp(cos)/sin θ = 6e-8/0.01 = 6e-6 rad (6e-4 of θ_c) at n = 100.
        let tc = critical_angle(1.0 / ior).unwrap();
        assert!((f64::from(tc) - (1.0 / f64::from(ior)).asin()).abs() < 1e-7);
        let below = dir_cos(f64::from(tc * (1.0 - 5e-3)).cos());
        let above = dir_cos(f64::from(tc * (1.0 + 5e-3)).cos());
        assert!(refract(below, n, 1.0 / ior).is_some(), "n {ior}");
        assert!(fresnel_dielectric(below.z, 1.0 / ior) < 1.0);
        assert!(refract(above, n, 1.0 / ior).is_none(), "n {ior}");
        assert_eq!(fresnel_dielectric(above.z, 1.0 / ior), 1.0);
    }
}

#[test]
fn extreme_and_infinite_indices_give_no_nan() {
    let n = Vec3::Z;
    for eta in [1e30f32, 1e-30, f32::MAX, f32::MIN_POSITIVE, f32::INFINITY] {
        for i in 0..=1000 {
            let cos = 1.0 - f64::from(i) / 1000.0;
            let r = fresnel_dielectric(cos as f32, eta);
            assert!((0.0..=1.0).contains(&r), "η {eta} cos {cos}: R {r}");
            if let Some(wt) = refract(dir_cos(cos), n, eta) {
                assert!(
                    wt.is_finite() && (wt.length() - 1.0).abs() < 1e-6,
                    "η {eta}: {wt}"
                );
            }
        }
    }
    // `ior: 0` (η = +∞): a perfect mirror from either side, whatever the angle.
    let mirror: Bsdf = Bsdf::Dielectric {
        eta: f32::INFINITY,
        alpha: 0.0,
        tint: Vec3::ONE,
    };
    for wo in grazing_wos().into_iter().chain([Vec3::Z, Vec3::NEG_Z]) {
        if wo.z == 0.0 {
            continue;
        }
        for uc in [0.0f32, 0.5, 0.99999994] {
            let s = mirror
                .sample(wo, uc, Vec2::ZERO, TransportMode::Radiance)
                .unwrap();
            assert!(!s.transmission && s.wi.z == wo.z, "wo {wo}: {s:?}");
            assert!((s.f.x * s.wi.z.abs() / s.pdf - 1.0).abs() < 1e-6);
        }
    }
}
