//! The default budget (issue 18, item 3): without `--spp`/`--passes` a render is bounded by
//! time and error, not by a sample count, and says what ended it. Through the library (the
//! budget `iris render`'s flags resolve to, [`iris::app::budget`]) with small images, so
//! the file runs in seconds; the time limits are either the outcome's cause by
//! construction (an unreachable target) or generous guards against hangs that a correct
//! run never reaches.

use crate::common;

use glam::{Vec3, Vec4};
use iris::app::budget::{next_check, BudgetFlags, DEFAULT_TARGET, MIN_STOP_UNITS};
use iris::app::{render_command, RenderOptions, RenderSummary};
use iris::authoring::shapes;
use iris::authoring::{look_at, placed};
use iris::integrator::Method;
use iris::material::MaterialDesc;
use iris::measure::relative_rmse;
use iris::render::EndReason;
use iris::scene::desc::SceneDesc;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// A guard against hangs, far above what a correct run takes (a few seconds): never the
/// cause of a passing test's outcome.
const HANG_GUARD: Duration = Duration::from_secs(600);

/// An easy scene: a white diffuse box on a grey diffuse floor under the file's own uniform
/// environment (radiance 1), with its camera. Path traced (`--method auto` finds no caustic
/// paths), smooth everywhere: its noise falls as samples^−1/2 with no rare paths.
fn easy_scene(dir: &Path) -> PathBuf {
    let scene = SceneDesc {
        name: "easy".into(),
        meshes: vec![
            placed("floor", shapes::ground_plane(2.0, 2.0), 0, None),
            placed(
                "box",
                shapes::cuboid(Vec3::splat(0.3)),
                1,
                Some(Vec3::new(0.0, 0.3, 0.0)),
            ),
        ],
        materials: vec![
            MaterialDesc::diffuse("grey", Vec3::splat(0.5)),
            MaterialDesc {
                base_color: Vec4::new(0.8, 0.8, 0.8, 1.0),
                ..MaterialDesc::diffuse("white", Vec3::ONE)
            },
        ],
        cameras: vec![look_at(
            "view",
            Vec3::new(1.2, 1.0, 1.6),
            Vec3::new(0.0, 0.3, 0.0),
            Vec3::Y,
            40f32.to_radians(),
            Some(4.0 / 3.0),
        )],
        environment: Some(iris::scene::desc::EnvironmentDesc::Uniform(Vec3::splat(
            1.0,
        ))),
        ..Default::default()
    };
    let path = dir.join("easy.glb");
    iris::authoring::write_glb(&path, &scene).expect("write the easy scene");
    path
}

/// Renders `scene` at 32×24 with the budget `flags` resolve to, seed 7, 2 threads.
fn render(scene: &Path, out: &Path, flags: BudgetFlags) -> RenderSummary {
    let opts = RenderOptions {
        size: Some((32, 24)),
        seed: 7,
        threads: 2,
        quiet: true,
        ..RenderOptions::new(scene, Some(out))
    }
    .with_budget(&flags.resolve());
    render_command(&opts).expect("render")
}

/// The samples per pixel the render reached: the driver's count at its last checkpoint
/// (adaptive sampling, on for these open budgets, may rest tiles below it).
fn spp(s: &RenderSummary) -> u64 {
    let last = s.rows.iter().rev().find(|r| r.stage == "render");
    last.expect("a render row").samples
}

#[test]
fn an_easy_scene_stops_at_the_default_target_at_the_same_count_every_time() {
    let dir = common::scratch_dir("budget_easy");
    let scene = easy_scene(&dir);
    let flags = BudgetFlags {
        time: Some(HANG_GUARD),
        target_error: Some(DEFAULT_TARGET),
        ..Default::default()
    };
    let a = render(&scene, &dir.join("a.exr"), flags);
    let b = render(&scene, &dir.join("b.exr"), flags);
    assert_eq!(a.method, Method::Path, "auto on a scene without caustics");
    assert_eq!(a.end(), EndReason::Target, "{}", a.end_text());
    // Fixed seed: the checkpoints' images, hence the estimates and the stop, are the same.
    assert_eq!(spp(&a), spp(&b));
    assert_eq!(a.image.data, b.image.data);
    // It stopped at the first checkpoint (from MIN_STOP_UNITS on) whose estimate met the
    // target: the one before did not (or came before the minimum).
    let n = spp(&a);
    assert!(n >= MIN_STOP_UNITS, "{n} spp");
    let estimates: Vec<(u64, f64)> = a
        .rows
        .iter()
        .filter(|r| r.stage == "render")
        .filter_map(|r| r.estimate.map(|e| (r.samples, relative_rmse(&e))))
        .collect();
    let (last, before) = (
        estimates[estimates.len() - 1],
        estimates[estimates.len() - 2],
    );
    assert_eq!(last.0, n);
    assert!(last.1 <= DEFAULT_TARGET, "{estimates:?}");
    assert!(
        before.1 > DEFAULT_TARGET || before.0 < MIN_STOP_UNITS,
        "{estimates:?}"
    );
    // The checkpoint after one whose estimate was above the target is where 1/√n says the
    // target is met ([`next_check`]), within the doubling; before the minimum, the doubling.
    let expected = if before.0 < MIN_STOP_UNITS {
        2 * before.0
    } else {
        next_check(before.0, before.1, DEFAULT_TARGET).clamp(before.0 + 1, 2 * before.0)
    };
    assert_eq!(n, expected, "{estimates:?}");
    assert_eq!(a.target_estimate, Some(last.1));
    let text = a.end_text();
    assert!(
        text.starts_with(&format!(
            "stopped at the error target {DEFAULT_TARGET} (estimated"
        )),
        "{text}"
    );
    eprintln!("easy scene: {n} spp, {text}");
}

#[test]
fn an_unreachable_target_stops_at_the_time_limit() {
    // Fig. 4.5.1 (caustics under a point light) with a target no render reaches (1e-9:
    // some 10¹⁴ samples per pixel) and a 1 s limit: the time limit ends it, whatever the
    // machine.
    let dir = common::scratch_dir("budget_hard");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/paper/fig4_5_1_caustics.glb");
    let s = render(
        &scene,
        &dir.join("hard.png"),
        BudgetFlags {
            time: Some(Duration::from_secs(1)),
            target_error: Some(1e-9),
            ..Default::default()
        },
    );
    assert_eq!(s.end(), EndReason::TimeLimit, "{}", s.end_text());
    assert!(s.stats.time >= Duration::from_secs(1));
    let text = s.end_text();
    assert!(
        text.starts_with("stopped at the time limit 1 s (error target 0.000000001"),
        "{text}"
    );
    assert!(dir.join("hard.png").is_file());
}

#[test]
fn a_sample_count_still_ends_a_render_at_that_count() {
    let dir = common::scratch_dir("budget_count");
    let scene = easy_scene(&dir);
    let s = render(
        &scene,
        &dir.join("c.png"),
        BudgetFlags {
            spp: Some(3),
            ..Default::default()
        },
    );
    assert_eq!(s.end(), EndReason::Samples);
    assert_eq!(spp(&s), 3);
    assert_eq!(s.end_text(), "3 spp done");
    assert_eq!((s.target_error, s.time_limit), (None, None));
}

#[test]
fn time_alone_is_the_whole_budget_on_the_command_line() {
    // `--time T` alone: no sample cap (not the fixed 4 spp of the library's default,
    // which ends after a fraction of a second) and no error target, so only the time limit can
    // end it: the summary says so.
    let dir = common::scratch_dir("budget_cli_time");
    let scene = easy_scene(&dir);
    let o = common::iris(
        &[
            "render",
            scene.to_str().unwrap(),
            "--time",
            "1",
            "--size",
            "16x12",
            "-q",
            "-o",
            "t.png",
        ],
        &dir,
    );
    let err = common::stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("iris: stopped at the time limit 1 s;"),
        "{err}"
    );
    assert!(
        !err.contains("error target"),
        "no target with --time alone: {err}"
    );
    assert!(dir.join("t.png").is_file());
}

#[cfg(feature = "denoise")]
#[test]
fn a_denoised_png_stops_on_the_denoised_estimate() {
    // What the output shows decides the stop: the PNG preview is denoised (`--denoise
    // auto`), so its target is met by the denoised image's estimate, at fewer samples than
    // the raw EXR of the same render needs; the EXR's stop is unchanged (raw estimate).
    let dir = common::scratch_dir("budget_denoised");
    let scene = easy_scene(&dir);
    let flags = BudgetFlags {
        time: Some(HANG_GUARD),
        target_error: Some(DEFAULT_TARGET),
        ..Default::default()
    };
    let png = render(&scene, &dir.join("d.png"), flags);
    let exr = render(&scene, &dir.join("d.exr"), flags);
    assert_eq!(png.end(), EndReason::Target, "{}", png.end_text());
    assert_eq!(exr.end(), EndReason::Target, "{}", exr.end_text());
    assert_eq!(png.target_measure, "display error of the denoised picture");
    assert_eq!(exr.target_measure, "rel. error");
    assert!(png.denoised.is_some(), "the PNG is denoised");
    let (n_png, n_exr) = (spp(&png), spp(&exr));
    assert!(
        n_png < n_exr,
        "denoised stop at {n_png} spp, raw at {n_exr} spp"
    );
    assert!(n_png >= MIN_STOP_UNITS, "{n_png} spp");
    // The PNG's estimate is the denoised picture's display error: below the target, and
    // the report's `display_est` of the last checkpoint (its `estimate` column stays the
    // raw relative one).
    let e = png.target_estimate.expect("an estimate");
    let last = png.rows.last().unwrap();
    let raw_last = relative_rmse(&last.estimate.unwrap());
    assert!(e <= DEFAULT_TARGET, "{e}");
    assert_eq!(last.display_estimate, Some(e));
    let text = png.end_text();
    assert!(
        text.contains("display error of the denoised picture"),
        "{text}"
    );
    assert!(
        png.notes
            .iter()
            .any(|n| n.starts_with("error target checked on the denoised image at ")),
        "the stop test's cost is noted: {:?}",
        png.notes
    );
    eprintln!("denoised stop: {n_png} spp ({e:.4}; raw {raw_last:.4}); raw stop: {n_exr} spp");
}
