//! The prism rainbow is a caustic ordered as Snell's law says.
//!
//! Scene: `assets/scenes/fig5_3_1_rainbow.glb` ([`iris::assets::rainbow`]): a beam through a
//! 3 mm slit meets an N-BK7 prism at minimum deviation and lands on a white screen 1.2 m
//! beyond. Photons are started across the slit along the sun's direction (the scene's own
//! emitter would spend ~3·10⁵ photons per photon through the slit), each with its own
//! random wavelengths, and traced by the renderer's photon tracer; the prism is
//! dispersive, so each photon keeps its hero wavelength. For every photon reaching the
//! screen after exactly two refractions (not the Fresnel ghosts reflected inside the
//! prism, 3 in 20 000 here) we compare its position along the layout's `dispersion` axis with the landing
//! point of the axis ray traced by vector Snell's law at that wavelength's N-BK7 index
//! (Sellmeier, [`iris::assets::rainbow::rainbow_landing`]): each must lie within the beam's
//! half-width (1.5 mm, the slit's, preserved at minimum deviation) plus 0.5 mm, and violet
//! (λ < 450 nm) must land beyond red (λ > 630 nm) by about the predicted 20 mm.

use glam::{DVec3, Vec3};
use iris::assets::rainbow::{rainbow_landing, rainbow_layout, SLIT_HEIGHT, SLIT_WIDTH};
use iris::math::{Ray, Rng};
use iris::photon::emit::EmittedPhoton;
use iris::photon::trace::{trace, Roulette, TraceSettings};
use iris::spectrum::{Carrier, IorModel, Lambdas, SampledSpectrum, SampledWavelengths};

#[test]
fn the_rainbow_on_the_screen_is_ordered_by_snells_law() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/fig5_3_1_rainbow.glb");
    let (scene, _) =
        iris::app::load(&path, iris::accel::Backend::Auto).expect("load the rainbow scene");
    let l = rainbow_layout();
    let across = DVec3::Y.cross(l.dir_in).normalize();
    let bk7 = IorModel::named("N-BK7").unwrap();
    let settings = TraceSettings {
        max_depth: 8,
        roulette: Roulette::Throughput,
    };
    let mut landed = Vec::new();
    for i in 0..20_000u64 {
        let mut rng = Rng::new(&[5, i]);
        let o = l.slit
            + across * ((rng.next_f32() as f64 - 0.5) * SLIT_WIDTH)
            + DVec3::Y * ((rng.next_f32() as f64 - 0.5) * SLIT_HEIGHT * 0.5);
        let photon = EmittedPhoton {
            ray: Ray::new(o.as_vec3(), l.dir_in.as_vec3()),
            power: Vec3::ONE,
            shape: None,
            range: None,
            source: iris::photon::emit::Source::Environment,
        };
        let lambda = Lambdas::new(SampledWavelengths::sample_visible(rng.next_f32()));
        let hero = lambda.wl.hero();
        trace::<SampledSpectrum>(&scene, &photon, lambda, &settings, &mut rng, |v, lam| {
            let p = v.p.as_dvec3();
            if v.caustic
                && v.bounces == 2
                && (p - l.screen_centre).dot(l.screen_normal).abs() < 1e-3
            {
                assert!(
                    SampledSpectrum::is_hero_only(lam),
                    "dispersed photon kept all wavelengths"
                );
                landed.push((hero, (p - l.screen_centre).dot(l.dispersion)));
            }
        });
    }
    assert!(
        landed.len() > 10_000,
        "{} photons reached the screen",
        landed.len()
    );
    let mut worst = 0.0f64;
    for &(lambda, x) in &landed {
        let (_, _, hit) = rainbow_landing(bk7.ior(lambda) as f64).expect("no TIR");
        let predicted = (hit - l.screen_centre).dot(l.dispersion);
        worst = worst.max((x - predicted).abs());
    }
    let mean_x = |lo: f32, hi: f32| {
        let v: Vec<f64> = landed
            .iter()
            .filter(|(l, _)| *l >= lo && *l < hi)
            .map(|p| p.1)
            .collect();
        assert!(v.len() > 100);
        v.iter().sum::<f64>() / v.len() as f64
    };
    let (violet, red) = (mean_x(380.0, 450.0), mean_x(630.0, 720.0));
    eprintln!(
        "{} photons on the screen; worst distance from Snell's landing {:.2} mm; violet (380–450 nm) at {:+.1} mm, red (630–720 nm) at {:+.1} mm along the dispersion axis",
        landed.len(),
        worst * 1e3,
        violet * 1e3,
        red * 1e3
    );
    assert!(worst < SLIT_WIDTH / 2.0 + 5e-4, "worst residual {worst}");
    assert!(violet - red > 0.015, "violet {violet} vs red {red}");
}
