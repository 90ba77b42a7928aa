//! Adaptive sampling (`--adaptive`, [`iris::render::adaptive`]): tiles that converged rest
//! while the others take samples.
//! - The estimator is unchanged: on the caustic sphere under an area light, the
//!   adaptive path tracer agrees with uniform sampling (block means) within the bound two
//!   uniform renders of different seeds set.
//! - Samples go where the error is: the tiles that rest are the clean ones, and the film's
//!   per-pixel counts are exact (its total is the sum of the tiles' counts).
//! - The half-buffer estimate stays honest with uneven counts: against a reference, it
//!   reads the adaptive image's error as well as it reads the uniform image's.
//! - Determinism: the same scene, seed and backend give the same image on 1 and 3 threads.
//! - The CLI: `--adaptive on` with `--shard` is refused before anything is written; an
//!   open-budget shard says that adaptive sampling is off; `--explain` names the stage.

use crate::common;

use common::{blocks, relative_rmse};
use iris::camera::Camera;
use iris::image::metrics::{compare, half_buffer_estimate};
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::render::{Adaptive, Film, RenderSettings, RenderStats};
use iris::sampler::SamplerKind;

const W: u32 = 96;
const H: u32 = 64;

fn settings(spp: u32, seed: u64, threads: usize, adaptive: bool) -> RenderSettings {
    RenderSettings {
        adaptive: adaptive.then_some(Adaptive { target: None }),
        ..common::render_settings((W, H), spp, seed, threads)
    }
}

/// The path tracer's film of the caustic sphere under a 60 cm area light (a large light
/// keeps the caustic's fireflies rare, so two seeds' MSE agree within tens of per cent).
fn render(s: &RenderSettings) -> (Film, RenderStats) {
    let (scene, cam) = common::caustic_sphere(Some(0.3));
    let integrator = Integrator::new(Method::Path, 16, &PhotonSettings::default()).unwrap();
    integrator
        .render_units(&scene, &Camera::new(&cam, W, H), s, None, None)
        .unwrap()
}

#[test]
fn adaptive_sampling_keeps_the_estimator_and_puts_samples_where_the_error_is() {
    let spp = 256;
    let (uniform, _) = render(&settings(spp, 1, 0, false));
    let (uniform2, _) = render(&settings(spp, 2, 0, false));
    let (adaptive, stats) = render(&settings(spp, 3, 0, true));

    // Tiles rested: fewer samples in total, and uneven counts.
    let states: Vec<_> = adaptive.tile_states().collect();
    let (lo, hi) = adaptive.unit_span();
    let total: u64 = states.iter().map(|t| t.pixels * t.units).sum();
    assert_eq!(stats.samples, total, "the stats count the film's samples");
    assert_eq!(hi, u64::from(spp), "the noisiest tiles take every sample");
    assert!(
        lo < hi / 2,
        "some tile rested for most of the render: {lo}..{hi}"
    );
    let share = total as f64 / (u64::from(spp) * u64::from(W * H)) as f64;
    assert!(
        share < 0.9,
        "adaptive sampling took {share:.2} of uniform's samples"
    );

    // The clean tiles are the ones that rested: the uniform render's per-tile error is
    // higher in the tiles that kept sampling.
    let (ua, ub) = uniform.halves();
    let e2 = iris::render::adaptive::tile_errors(&uniform, (&ua, &ub), false);
    let mean_e2 = |full: bool| {
        let v: Vec<f64> = states
            .iter()
            .zip(&e2)
            .filter(|(t, _)| (t.units == hi) == full)
            .map(|(_, e)| *e)
            .collect();
        v.iter().sum::<f64>() / v.len().max(1) as f64
    };
    assert!(
        mean_e2(true) > 4.0 * mean_e2(false),
        "tiles that kept sampling: relative MSE {:.3e}; tiles that rested: {:.3e}",
        mean_e2(true),
        mean_e2(false)
    );

    // Same estimator: block means agree within the spread of two uniform seeds (3× its
    // RMSE, as tests/photon/hybrid.rs; the adaptive image has fewer samples in clean tiles, so
    // its spread is a little higher there).
    let (bu, bu2, ba) = (
        blocks(&uniform.mean()),
        blocks(&uniform2.mean()),
        blocks(&adaptive.mean()),
    );
    let spread = relative_rmse(&bu2, &bu);
    let off = relative_rmse(&ba, &bu);
    assert!(
        off < 3.0 * spread.max(1e-3),
        "adaptive vs uniform {off:.4}, uniform seed spread {spread:.4}"
    );
    let m = |b: &[f64]| b.iter().sum::<f64>() / b.len() as f64;
    assert!(
        (m(&ba) / m(&bu) - 1.0).abs() < 0.02,
        "mean {} vs {}",
        m(&ba),
        m(&bu)
    );

    // The estimate stays honest with uneven counts: two renders of different seeds differ
    // by √2 times one's error (E[(x₁−x₂)²] = σ₁² + σ₂²), so half their mean squared
    // difference measures the error without a reference; the half-buffer estimate must
    // read it as well for the adaptive renders as for the uniform ones. Independent
    // numbers: with Sobol' points each half is less stratified than the whole, and the
    // estimate reads high by a factor that is the sampler's, not the adaptivity's.
    // Measured over seven seed sets: uniform 0.77–1.21 (mean 1.02), adaptive 0.78–1.01
    // (mean 0.92: tiles that rested on an estimate low by chance keep it, so the adaptive
    // estimate reads about 8 % low in MSE, 4 % in RMSE). The bounds catch a bias five
    // times that.
    let independent = |seed, adaptive| {
        let s = RenderSettings {
            sampler: SamplerKind::Independent,
            ..settings(spp, seed, 0, adaptive)
        };
        render(&s).0
    };
    let (uniform, uniform2) = (independent(11, false), independent(12, false));
    let (adaptive, adaptive2) = (independent(13, true), independent(14, true));
    let ratio = |f1: &Film, f2: &Film| {
        let actual = compare(&f1.mean(), &f2.mean()).unwrap().rmse.powi(2) / 2.0;
        let est = |f: &Film| {
            let (a, b) = f.halves();
            half_buffer_estimate(&a, &b).unwrap().rmse.powi(2)
        };
        0.5 * (est(f1) + est(f2)) / actual
    };
    let (ru, ra) = (ratio(&uniform, &uniform2), ratio(&adaptive, &adaptive2));
    assert!(
        (0.6..1.6).contains(&ru) && (0.6..1.6).contains(&ra),
        "estimated/actual MSE: uniform {ru:.3}, adaptive {ra:.3}"
    );
}

#[test]
fn adaptive_renders_do_not_depend_on_the_thread_count() {
    let (one, _) = render(&settings(64, 5, 1, true));
    let (three, _) = render(&settings(64, 5, 3, true));
    assert!(one.unit_span().0 < one.unit_span().1, "tiles rested");
    assert_eq!(one.exact(), three.exact());
}

/// Runs `iris` with `args` and then `out` (the output path).
fn iris_to(args: &[&str], out: &std::path::Path) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_iris"))
        .args(args)
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn the_cli_refuses_adaptive_shards_and_explains_the_stage() {
    let dir = common::scratch_dir("adaptive_cli");
    let scene =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gems/round_diamond.glb");
    let scene = scene.to_str().unwrap();
    let out = dir.join("part.exr");
    let o = iris_to(
        &[
            "render",
            scene,
            "--size",
            "32x24",
            "--adaptive",
            "on",
            "--shard",
            "1/2",
            "-q",
            "-o",
        ],
        &out,
    );
    let err = common::stderr(&o);
    assert!(!o.status.success());
    assert!(err.contains("--adaptive on with --shard"), "{err}");
    assert!(!out.exists(), "nothing written");

    let o = common::iris(&["render", scene, "--adaptive", "sometimes"], &dir);
    assert!(!o.status.success());
    assert!(
        common::stderr(&o).contains("--adaptive"),
        "{}",
        common::stderr(&o)
    );

    // An open-budget shard: adaptive sampling off, said on stderr.
    let o = iris_to(
        &[
            "render", scene, "--size", "32x24", "--time", "0.2", "--shard", "1/2", "-o",
        ],
        &out,
    );
    let err = common::stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("adaptive sampling off in a shard"), "{err}");

    // The plan names the stage and the rule.
    let png = dir.join("x.png");
    let o = iris_to(
        &[
            "render",
            scene,
            "--size",
            "32x24",
            "--time",
            "0.2",
            "--explain",
            "-q",
            "-o",
        ],
        &png,
    );
    let err = common::stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("adaptive") && err.contains("Neyman"), "{err}");
    let o = iris_to(
        &[
            "render",
            scene,
            "--size",
            "32x24",
            "--spp",
            "2",
            "--explain",
            "-q",
            "-o",
        ],
        &png,
    );
    assert!(
        common::stderr(&o).contains("off for a fixed count"),
        "{}",
        common::stderr(&o)
    );
}

#[test]
fn tiles_are_measured_on_the_halves_the_observer_judged() {
    // An observer that judges by halves equal everywhere but in the top-left tile: every
    // other tile shows no error there, so from 32 samples on only that tile keeps sampling,
    // whatever the raw halves say.
    let (scene, cam) = common::caustic_sphere(Some(0.3));
    let integrator = Integrator::new(Method::Path, 16, &PhotonSettings::default()).unwrap();
    let s = settings(64, 6, 0, true);
    let mut observe = |p: &iris::render::Progress| {
        let mut b = p.halves.0.clone();
        for y in 0..16 {
            for x in 0..16 {
                b.data[y * W as usize + x] += glam::Vec3::ONE;
            }
        }
        let _ = p.judged.set(iris::render::Judged {
            halves: Some((p.halves.0.clone(), b)),
            absolute: false,
            estimate: 1.0,
            target: None,
            name: "test",
        });
        Ok(iris::render::Control::Continue)
    };
    let (film, _) = integrator
        .render_units(
            &scene,
            &Camera::new(&cam, W, H),
            &s,
            None,
            Some(&mut observe),
        )
        .unwrap();
    let counts: Vec<u64> = film.tile_states().map(|t| t.units).collect();
    assert_eq!(counts[0], 64, "{counts:?}");
    assert!(counts[1..].iter().all(|&n| n == 32), "{counts:?}");
}

#[cfg(feature = "denoise")]
#[test]
fn the_denoised_stop_hands_its_halves_to_adaptive_sampling() {
    use iris::app::budget::{stop_error, Measure, StopImage};
    let (film, _) = render(&settings(16, 7, 0, false));
    let (a, b) = film.halves();
    let image = film.mean();
    let progress = || iris::render::Progress::at(&image, (&a, &b), 16, false);
    let raw = progress();
    let e_raw = stop_error(&raw, StopImage::Raw, Measure::Linear)
        .unwrap()
        .unwrap();
    assert!(
        raw.judged.get().unwrap().halves.is_none(),
        "the raw stop judges by the raw halves"
    );
    let den = progress();
    let e_den = stop_error(&den, StopImage::Denoised(None), Measure::Linear)
        .unwrap()
        .unwrap();
    let judged = den.judged.get().expect("the denoised halves");
    let (ja, jb) = judged.halves.as_ref().expect("the denoised halves");
    assert!(!judged.absolute);
    let again = iris::render::relative_error_estimate(ja, jb).unwrap();
    assert_eq!(again, e_den, "the stop's estimate is the judged halves'");
    assert!(e_den < e_raw, "denoised {e_den} vs raw {e_raw}");
}
