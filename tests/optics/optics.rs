//! Optics at a smooth interface, checked against the textbook formulas: Snell's law,
//! Fresnel reflectance at normal incidence ((n−1)/(n+1))², energy conservation R + T = 1
//! with T from the Fresnel transmission coefficients, the critical angle asin(1/n), and
//! the η vs 1/η choice made from `front_face`.
//!
//! Tolerances: f32 arithmetic on unit vectors carries ~1e-7 relative error per operation;
//! the chains here have < 20 operations, so 1e-5 absolute on sines and reflectances is a
//! safe bound that still catches any formula error (which shows at the 1e-2 level).

use glam::Vec3;
use iris::optics::{critical_angle, fresnel_dielectric, reflect, refract};

fn dir_at(theta: f32) -> Vec3 {
    // Unit vector at angle theta from +Z in the XZ plane, pointing away from the surface.
    Vec3::new(theta.sin(), 0.0, theta.cos())
}

#[test]
fn snell_law_holds_for_many_angles_and_indices() {
    let n = Vec3::Z;
    for &eta in &[1.2f32, 1.333, 1.5, 2.417, 1.0 / 1.5, 0.8] {
        for i in 0..90 {
            let theta_i = (i as f32).to_radians();
            let wi = dir_at(theta_i);
            match refract(wi, n, eta) {
                Some(wt) => {
                    assert!((wt.length() - 1.0).abs() < 1e-5, "not unit");
                    assert!(wt.z < 0.0, "transmitted ray must cross the surface");
                    // Coplanar with the incident ray and the normal: y stays 0.
                    assert!(wt.y.abs() < 1e-6);
                    let sin_t = (wt.x * wt.x + wt.y * wt.y).sqrt();
                    // n_i sin θ_i = n_t sin θ_t with η = n_t / n_i; tangential part flips sign.
                    assert!(
                        (theta_i.sin() - eta * sin_t).abs() < 1e-5,
                        "eta {eta} θ {i}°: {} vs {}",
                        theta_i.sin(),
                        eta * sin_t
                    );
                    assert!(wt.x <= 1e-7, "refracted ray continues to the other side");
                }
                None => {
                    // TIR only beyond the critical angle.
                    let tc = critical_angle(eta).expect("TIR needs eta < 1");
                    assert!(theta_i >= tc - 1e-5, "TIR below the critical angle at {i}°");
                }
            }
        }
    }
}

#[test]
fn fresnel_at_normal_incidence_matches_closed_form() {
    for &n in &[1.0f32, 1.2, 1.333, 1.5, 1.5168, 2.417, 4.0] {
        let expect = ((n - 1.0) / (n + 1.0)).powi(2);
        assert!((fresnel_dielectric(1.0, n) - expect).abs() < 1e-6, "n={n}");
        // Symmetric: the same from inside.
        assert!(
            (fresnel_dielectric(1.0, 1.0 / n) - expect).abs() < 1e-6,
            "1/n={n}"
        );
    }
    // Known values (anchors.md §5): water 0.0204, glass 0.0400, diamond 0.1720.
    assert!((fresnel_dielectric(1.0, 1.333) - 0.0204).abs() < 1e-4);
    assert!((fresnel_dielectric(1.0, 1.5) - 0.0400).abs() < 1e-4);
    assert!((fresnel_dielectric(1.0, 2.417) - 0.1720).abs() < 1e-4);
}

#[test]
fn reflectance_plus_transmittance_is_one() {
    // T from the Fresnel amplitude transmission coefficients (Born & Wolf §1.5.3), with the
    // flux factor η cos θ_t / cos θ_i: an independent formula from the one in optics.rs.
    for &eta in &[1.333f32, 1.5, 2.417, 1.0 / 1.5] {
        for i in 0..89 {
            let ci = (i as f32).to_radians().cos();
            let s2t = (1.0 - ci * ci) / (eta * eta);
            if s2t >= 1.0 {
                assert_eq!(
                    fresnel_dielectric(ci, eta),
                    1.0,
                    "TIR must reflect everything"
                );
                continue;
            }
            let ct = (1.0 - s2t).sqrt();
            let ts = 2.0 * ci / (ci + eta * ct);
            let tp = 2.0 * ci / (eta * ci + ct);
            let flux = eta * ct / ci;
            let t = 0.5 * (ts * ts + tp * tp) * flux;
            let r = fresnel_dielectric(ci, eta);
            assert!(
                (r + t - 1.0).abs() < 1e-5,
                "eta {eta} θ {i}°: R {r} + T {t}"
            );
        }
    }
    // Grazing incidence reflects everything.
    assert!((fresnel_dielectric(0.0, 1.5) - 1.0).abs() < 1e-6);
}

#[test]
fn critical_angle_switches_to_total_internal_reflection() {
    let n = Vec3::Z;
    for &ior in &[1.333f32, 1.5, 2.417] {
        let eta = 1.0 / ior; // from inside the denser medium
        let tc = critical_angle(eta).unwrap();
        assert!((tc - (1.0 / ior).asin()).abs() < 1e-7);
        let below = tc - 1e-3;
        let above = tc + 1e-3;
        assert!(
            refract(dir_at(below), n, eta).is_some(),
            "ior {ior}: refracts below θc"
        );
        assert!(fresnel_dielectric(below.cos(), eta) < 1.0);
        assert!(
            refract(dir_at(above), n, eta).is_none(),
            "ior {ior}: TIR above θc"
        );
        assert_eq!(fresnel_dielectric(above.cos(), eta), 1.0);
    }
    // Known values (anchors.md §5): water 48.61°, glass 41.81°, diamond 24.44°.
    assert!((critical_angle(1.0 / 1.333).unwrap().to_degrees() - 48.61).abs() < 0.01);
    assert!((critical_angle(1.0 / 1.5).unwrap().to_degrees() - 41.81).abs() < 0.01);
    assert!((critical_angle(1.0 / 2.417).unwrap().to_degrees() - 24.44).abs() < 0.01);
    assert!(critical_angle(1.5).is_none());
}

#[test]
fn reflection_is_mirror() {
    let n = Vec3::Z;
    let wi = dir_at(0.7);
    let r = reflect(wi, n);
    assert!((r - Vec3::new(-wi.x, -wi.y, wi.z)).length() < 1e-6);
}
