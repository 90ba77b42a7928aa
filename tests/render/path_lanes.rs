//! The path tracer in lanes (`iris::integrator::path::estimate_lanes`, chosen by the
//! plan's "lanes" stage) against its scalar loop. Each lane's estimate is the scalar one bit
//! for bit, because its numbers are its own, the packet queries answer as the single-ray
//! queries do, and a vertex's light is added in the same order. So the EXR written with 8
//! and with 16 lanes equals the single-ray EXR byte for byte. This holds on the default
//! backend and on the BVH, for the scenes of assets/ and of ../shared/assets: textures,
//! alpha BLEND and MASK, volumes, touching media, dispersion with spectral MIS, thin films,
//! clearcoat, sheen and anisotropy.
//!
//! `IRIS_LANES` picks the width in each child process. The plan printed by `--explain`
//! shows which loop ran, so a width that is silently ignored fails here.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// Renders `scene` with `method` (`--method` and its flags: the path tracer, or the hybrid,
/// whose camera paths run in lanes too) at `lanes` (`off`, `8`, `16`) on `accel` and returns the EXR's bytes,
/// checking that the plan names that loop.
fn render_with(scene: &Path, method: &[&str], lanes: &str, accel: &str, out: &Path) -> Vec<u8> {
    // The scalar vertex's lanes: the structure-of-arrays kernel has its own tests.
    let o = Command::new(env!("CARGO_BIN_EXE_iris"))
        .env("IRIS_LANES", lanes)
        .env("IRIS_KERNEL", "scalar")
        .arg("render")
        .arg(scene)
        .arg("--method")
        .args(method)
        .args(["--size", "40x30", "--spp", "3", "--seed", "11"])
        // The lanes are the unpolarized loops' (the crystals' polarized one is scalar).
        .args(["--polarization", "off"])
        .args([
            "--denoise",
            "off",
            "--threads",
            "2",
            "--accel",
            accel,
            "--explain",
            "-o",
        ])
        .arg(out)
        .output()
        .expect("run iris");
    let err = common::stderr(&o);
    assert!(o.status.success(), "{}: {err}", scene.display());
    let plan = err
        .lines()
        .find(|l| l.trim_start().starts_with("lanes "))
        .unwrap_or_else(|| panic!("{}: no lanes stage in the plan:\n{err}", scene.display()));
    let want = match lanes {
        "off" => "left out".to_string(),
        n => format!("{n} camera paths per packet"),
    };
    assert!(
        plan.contains(&want),
        "{}: IRIS_LANES={lanes}: {plan}",
        scene.display()
    );
    std::fs::read(out).expect("read the EXR")
}

/// [`render_with`] the path tracer.
fn render(scene: &Path, lanes: &str, accel: &str, out: &Path) -> Vec<u8> {
    render_with(scene, &["path"], lanes, accel, out)
}

/// Every scene of `scenes`: the lanes' EXRs equal the single-ray EXR, on each backend of
/// `accels` with each width of `widths`.
fn check(name: &str, scenes: &[PathBuf], accels: &[(&str, &[&str])]) {
    assert!(!scenes.is_empty(), "{name}: no scenes found");
    let dir = common::scratch_dir(name);
    for scene in scenes {
        for &(accel, widths) in accels {
            let single = render(scene, "off", accel, &dir.join("off.exr"));
            for w in widths {
                let lanes = render(scene, w, accel, &dir.join(format!("{w}.exr")));
                assert!(
                    lanes == single,
                    "{}: {w} lanes on {accel} differ from single rays",
                    scene.display()
                );
            }
        }
    }
}

#[test]
fn lanes_equal_single_rays_on_the_project_assets() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let scenes = common::files_with_ext(&root, &["glb", "gltf"]);
    check(
        "lanes_assets",
        &scenes,
        &[("auto", &["8", "16"]), ("bvh", &["8"])],
    );
}

#[test]
fn lanes_equal_single_rays_on_the_shared_assets() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let scenes = common::files_with_ext(&shared, &["glb", "gltf", "obj"]);
    check("lanes_shared", &scenes, &[("auto", &["8", "16"])]);
}

/// The hybrid's camera paths (caustic map gathered at the first diffuse vertex, light
/// tracing's split with `--caustics mixed`) in lanes equal them on single rays.
#[test]
fn hybrid_camera_paths_in_lanes_equal_single_rays() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let dir = common::scratch_dir("lanes_hybrid");
    let runs: [(&str, &[&str]); 4] = [
        ("scenes/gem_caustics.glb", &["hybrid"]),
        (
            "scenes/gem_caustics.glb",
            &["hybrid", "--caustics", "mixed"],
        ),
        (
            "paper/fig4_5_1_caustics.glb",
            &["hybrid", "--caustics", "light"],
        ),
        ("gems/oval_ruby.glb", &["hybrid"]),
    ];
    for (rel, method) in runs {
        let scene = root.join(rel);
        let single = render_with(&scene, method, "off", "auto", &dir.join("off.exr"));
        for w in ["8", "16"] {
            let lanes = render_with(&scene, method, w, "auto", &dir.join(format!("{w}.exr")));
            assert!(lanes == single, "{rel} {method:?}: {w} lanes differ");
        }
    }
}

#[test]
fn a_bad_lane_width_is_refused_with_nothing_written() {
    let dir = common::scratch_dir("lanes_bad_width");
    let out = dir.join("x.png");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gems/round_diamond.glb");
    let o = Command::new(env!("CARGO_BIN_EXE_iris"))
        .env("IRIS_LANES", "12")
        .arg("render")
        .arg(&scene)
        .args(["--method", "path", "--size", "16x12", "--spp", "1", "-o"])
        .arg(&out)
        .output()
        .expect("run iris");
    assert!(!o.status.success());
    let err = common::stderr(&o);
    assert!(
        err.contains("IRIS_LANES=12") && err.contains("off, 8 or 16"),
        "{err}"
    );
    assert!(!out.exists(), "{} written", out.display());
}

/// An `IRIS_KERNEL` other than `soa` or `scalar` is refused naming it, nothing written;
/// unset, the path tracer's plan names the structure-of-arrays kernel for a scene in its
/// class, and with `IRIS_KERNEL=scalar` it does not (the scalar vertex's lanes or single
/// rays), each render written.
#[test]
fn the_kernel_is_the_default_and_the_environment_picks_the_scalar_vertex() {
    let dir = common::scratch_dir("kernel_choice");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/gem_caustics.glb");
    let run = |kernel: Option<&str>, out: &Path| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_iris"));
        if let Some(k) = kernel {
            c.env("IRIS_KERNEL", k);
        } else {
            c.env_remove("IRIS_KERNEL");
        }
        c.arg("render")
            .arg(&scene)
            .args([
                "--method",
                "path",
                "--size",
                "16x12",
                "--spp",
                "2",
                "--explain",
            ])
            .args(["--denoise", "off", "-o"])
            .arg(out)
            .output()
            .expect("run iris")
    };
    let bad = dir.join("bad.exr");
    let o = run(Some("simd"), &bad);
    let err = common::stderr(&o);
    assert!(
        !o.status.success() && err.contains("IRIS_KERNEL=simd"),
        "{err}"
    );
    assert!(!bad.exists(), "{} written", bad.display());
    for (kernel, kernel_runs) in [(None, true), (Some("scalar"), false)] {
        let out = dir.join(format!("{kernel:?}.exr"));
        let o = run(kernel, &out);
        let err = common::stderr(&o);
        assert!(o.status.success(), "{kernel:?}: {err}");
        let lanes = err
            .lines()
            .find(|l| l.trim_start().starts_with("lanes "))
            .unwrap_or_else(|| panic!("no lanes stage:\n{err}"));
        assert_eq!(
            lanes.contains("structure-of-arrays kernel"),
            kernel_runs,
            "{kernel:?}: {lanes}"
        );
        assert!(out.exists());
    }
}
