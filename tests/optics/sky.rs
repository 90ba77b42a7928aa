//! `--env sky:…` ([`iris::light::sky`]): single Rayleigh and Mie scattering, checked
//! against closed forms and against what a sky looks like:
//! - the sun straight overhead is attenuated by exactly the vertical optical depth:
//!   T(λ) = e^(−τ(λ)) with τ = β_R H_R + β_M/ϖ H_M (plane-parallel limit, exact for a
//!   vertical ray up to the atmosphere's top at 60 km, e^(−7.5) of H);
//! - air alone (turbidity 1), sun and view at the zenith: the singly scattered radiance
//!   has the closed form L = E₀ p_R(1) τ e^(−τ) (the transmittances of the view and sun
//!   segments multiply to e^(−τ) at every height; ∫ β_R e^(−h/H) dh = τ);
//! - a low sun is orange-red (R > G > B), a high one near white; the sky overhead is blue
//!   (B > G > R); the horizontal illuminance grows with the sun's elevation;
//! - the sun below the horizon gives no sun light; bad values are usage errors naming
//!   `--env` and the key.

use glam::DVec3;
use iris::light::env::Environment;
use iris::light::sky::atmosphere::{rayleigh_phase, Atmosphere};
use iris::light::sky::{Sky, SkyParams};

fn sky(elevation: f32, turbidity: f32) -> Sky {
    Sky::new(SkyParams {
        elevation,
        azimuth: 0.0,
        turbidity,
    })
    .expect("sky")
}

/// Bound 0.5 %: the midpoint rule's error over 64 quadratically spaced steps of an exponential with 8 km and
/// 1.2 km scale heights across 60 km is below 0.1 %; the truncation at the top e^(−7.5)·τ.
#[test]
fn the_overhead_sun_is_attenuated_by_the_vertical_optical_depth() {
    for t in [1.0, 2.0, 4.0] {
        let atm = Atmosphere::new(t);
        let lambdas = [400.0, 450.0, 550.0, 650.0, 700.0];
        let got = atm.sun_transmittance(DVec3::Y, &lambdas);
        for (l, g) in lambdas.iter().zip(&got) {
            let want = (-atm.zenith_optical_depth(*l)).exp();
            assert!(
                (g / want - 1.0).abs() < 0.005,
                "turbidity {t}, {l} nm: {g} vs e^-tau {want}"
            );
        }
    }
    // Rayleigh's optical depth at 550 nm, β_R·H = 0.108 (measured: 0.097, Bucholtz 1995).
    let tau = Atmosphere::new(1.0).zenith_optical_depth(550.0);
    assert!((tau - 0.108).abs() < 1e-3, "{tau}");
}

/// Bound 1 %: the view and sun segments are integrated separately (32 and 16 midpoint
/// steps): their product's quadrature error is a few 0.1 %.
#[test]
fn clear_air_at_the_zenith_matches_the_closed_form() {
    let atm = Atmosphere::new(1.0);
    let lambdas = [420.0, 550.0, 680.0];
    let got = atm.single_scatter(DVec3::Y, DVec3::Y, &atm.coefficients(&lambdas));
    for (l, g) in lambdas.iter().zip(&got) {
        let tau = atm.zenith_optical_depth(*l);
        let want = rayleigh_phase(1.0) * tau * (-tau).exp();
        assert!((g / want - 1.0).abs() < 0.01, "{l} nm: {g} vs {want}");
    }
}

#[test]
fn a_low_sun_is_red_a_high_one_white_and_the_sky_overhead_blue() {
    let sun = |e: f32| sky(e, 2.0).sun.expect("sun above the horizon").0;
    let low = sun(3.0);
    assert!(low.x > low.y && low.y > low.z, "sun at 3°: {low}");
    assert!(low.z / low.x < 0.3, "sun at 3°: {low}");
    // High, the sun is the Sun's 5772 K (warmer than D65, sRGB's white) through 1.15 air
    // masses: blue/red ≈ 0.75 × e^(−(τ(450) − τ(650))·1.15) ≈ 0.6.
    let high = sun(60.0);
    assert!(high.z / high.x > 0.5, "sun at 60°: {high}");
    assert!(high.z / high.x > 3.0 * low.z / low.x, "{high} vs {low}");
    let s = sky(45.0, 2.0);
    let zenith = s.map.eval(glam::Vec3::Y);
    assert!(
        zenith.z > zenith.y && zenith.y > zenith.x,
        "zenith {zenith}"
    );
    // Horizontal illuminance (sun + sky, luminance) grows with elevation: the ground below
    // the horizon is ρ E_h / π.
    let e = |el: f32| {
        let ground = sky(el, 2.0).map.eval(glam::Vec3::NEG_Y);
        iris::light::env::luminance(ground) * std::f32::consts::PI / iris::light::sky::GROUND_ALBEDO
    };
    let (e5, e30, e60) = (e(5.0), e(30.0), e(60.0));
    assert!(e5 < e30 && e30 < e60, "{e5} {e30} {e60}");
}

#[test]
fn the_sun_below_the_horizon_lights_nothing_and_bad_values_are_refused() {
    assert!(sky(-5.0, 2.0).sun.is_none());
    assert!(iris::prepare::input::sun_light(&sky(-5.0, 2.0)).is_none());
    let light = iris::prepare::input::sun_light(&sky(30.0, 2.0)).expect("a sun light");
    assert_eq!(light.name(), "sky sun");
    for (arg, needle) in [
        ("sky:", "elevation"),
        ("sky:elevation=abc", "elevation"),
        ("sky:elevation=95", "elevation"),
        ("sky:elevation=10,turbidity=0.5", "turbidity"),
        ("sky:elevation=10,haze=3", "haze"),
        ("sky:elevation=10,elevation=20", "twice"),
        ("sky:elevation=inf", "elevation"),
        ("sky:elevation", "KEY=VALUE"),
        ("sky:elevation=10,azimuth=1e30", "azimuth"),
        ("sky:elevation=10,azimuth=-360.5", "azimuth"),
        ("sky:elevation=10,azimuth=nan", "azimuth"),
    ] {
        let e = Environment::parse_arg(arg)
            .err()
            .unwrap_or_else(|| panic!("{arg} accepted"));
        let msg = e.to_string();
        assert!(
            msg.contains("--env") && msg.contains(needle),
            "{arg}: {msg}"
        );
    }
    let ok = Environment::parse_arg("sky:elevation=10, azimuth=90 ,turbidity=3").unwrap();
    match ok {
        Some(Environment::Sky(s)) => {
            assert_eq!(s.params.azimuth, 90.0);
            // Azimuth 90° puts the sun towards +X.
            assert!(s.params.sun_direction().x > 0.9);
        }
        _ => panic!("not a sky"),
    }
}
