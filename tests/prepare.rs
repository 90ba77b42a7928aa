//! One scene preparation (issue 16): `iris render`, `iris converge` and `iris info` describe
//! and render the same scene for the same file and flags. Before, `iris converge` on a file
//! with no light rendered the plain key and fill with no floor, while `iris render` showed
//! the studio and a floor: three commands prepared the scene three ways.

mod common;

use iris::accel::Backend;
use iris::app::{PreviewOptions, RenderOptions};
use iris::converge::ConvergeOptions;
use iris::integrator::Method;
use iris::prepare::prepare;
use std::path::{Path, PathBuf};

/// A round diamond with no camera, light or floor: every drop-in decision is taken.
fn bare() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gems/round_diamond_bare.glb")
}

/// Lines starting with `note: ` on stderr.
fn notes(stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .filter_map(|l| l.strip_prefix("note: ").map(String::from))
        .collect()
}

#[test]
fn render_and_converge_options_prepare_the_same_scene() {
    let path = bare();
    let dir = common::scratch_dir("prepare_lib");
    let render = RenderOptions {
        size: Some((48, 27)),
        accel: Backend::Bvh,
        ..RenderOptions::new(&path, Some(&dir.join("r.png")))
    };
    let converge = ConvergeOptions {
        scene: path.clone(),
        methods: vec![Method::Path],
        time: std::time::Duration::from_secs(1),
        reference: None,
        out_dir: dir.join("c"),
        size: Some((48, 27)),
        seed: 0,
        threads: 0,
        accel: Backend::Bvh,
        quiet: true,
    };
    let a = prepare(
        &path,
        &render.prepare_options(&PreviewOptions::default(), None),
    )
    .expect("render's preparation");
    let b = prepare(&path, &converge.prepare_options(None)).expect("converge's preparation");
    assert_eq!(a.notes(), b.notes());
    assert_eq!(a.size, b.size);
    assert_eq!(a.scene.triangle_count(), b.scene.triangle_count());
    assert_eq!(a.scene.lights.len(), b.scene.lights.len());
    assert_eq!(a.scene.environment.is_some(), b.scene.environment.is_some());
    assert_eq!(
        a.camera.world_from_camera, b.camera.world_from_camera,
        "same framing"
    );
    // And it is the drop-in preview: the studio lights the stone and a floor is added.
    let n = a.notes().join("\n");
    assert!(n.contains("studio `soft`"), "{n}");
    assert!(n.contains("white floor added"), "{n}");
    assert!(
        a.scene.environment.is_some(),
        "the studio's softbox environment"
    );
    // The same preparation twice is the same scene (nothing depends on call order).
    let c = prepare(&path, &converge.prepare_options(None)).expect("again");
    assert_eq!(c.notes(), b.notes());
    assert_eq!(c.scene.positions, b.scene.positions);
}

#[test]
fn cli_converge_notes_the_preparation_render_notes() {
    let dir = common::scratch_dir("prepare_cli");
    let scene = bare();
    let scene = scene.to_str().unwrap();
    let r = common::iris(
        &[
            "render", scene, "--method", "path", "--spp", "1", "--size", "32x18", "-q", "-o",
            "r.png",
        ],
        &dir,
    );
    let r_err = common::stderr(&r);
    assert!(r.status.success(), "{r_err}");
    let c = common::iris(
        &[
            "converge",
            scene,
            "--methods",
            "path",
            "--time",
            "0.1",
            "--size",
            "32x18",
            "-q",
            "-o",
            "out",
        ],
        &dir,
    );
    let c_err = common::stderr(&c);
    assert!(c.status.success(), "{c_err}");
    let (rn, cn) = (notes(&r_err), notes(&c_err));
    // Lights, floor and camera: three preparation notes, each also in render's.
    assert_eq!(cn.len(), 3, "{cn:?}");
    for n in &cn {
        assert!(rn.contains(n), "converge: {n:?}\nrender: {rn:?}");
    }
    assert!(cn.iter().any(|n| n.contains("studio")), "{cn:?}");
    assert!(cn.iter().any(|n| n.contains("floor added")), "{cn:?}");
}

#[test]
fn info_plans_the_scene_render_plans() {
    // `iris info` plans `iris render FILE --method auto` at the probe size: the stage lines
    // (without the measured costs, which are timings) are the same.
    let dir = common::scratch_dir("prepare_info");
    let scene = bare();
    let scene = scene.to_str().unwrap();
    let plan_lines = |text: &str| -> Vec<String> {
        text.lines()
            .skip_while(|l| !l.starts_with("render plan:"))
            .take_while(|l| l.starts_with("render plan:") || l.starts_with("  "))
            // Costs are timings; info's last line says which method the plan is for.
            .filter(|l| !l.trim_start().starts_with("cost:") && !l.starts_with("  ("))
            .map(String::from)
            .collect()
    };
    let info = common::iris(&["info", scene], &dir);
    assert!(info.status.success(), "{}", common::stderr(&info));
    let info_text = String::from_utf8_lossy(&info.stdout).into_owned();
    let r = common::iris(
        &[
            "render",
            scene,
            "--explain",
            "--method",
            "auto",
            "--size",
            "32x24",
            "--passes",
            "1",
            "-q",
            "-o",
            "x.png",
        ],
        &dir,
    );
    let r_err = common::stderr(&r);
    assert!(r.status.success(), "{r_err}");
    let (a, b) = (plan_lines(&info_text), plan_lines(&r_err));
    assert!(a.len() >= 8, "{info_text}");
    assert_eq!(a, b, "info:\n{info_text}\nrender:\n{r_err}");
}
