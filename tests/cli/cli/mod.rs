//! The `iris` binary as a user meets it: a successful render writes the image and a
//! one-line summary; bad files, values and flags end in a clear message naming the file or
//! the flag, a non-zero exit code, and no output (not even a temporary file). Special and
//! oversized input files: `cli/files.rs`; outputs checked before the work: `cli/outputs.rs`.

use crate::common;
mod files;
mod outputs;

use common::{entries, iris, stderr};

use std::path::{Path, PathBuf};

fn asset(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/paper")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

#[test]
fn render_writes_default_output_and_summary() {
    let dir = common::scratch_dir("cli_ok");
    let o = iris(
        &[
            "render",
            &asset("fig4_4_1_prism.glb"),
            "--size",
            "64x48",
            "--spp",
            "1",
            "--quiet",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // Default output: <scene stem>.png in the current directory, and nothing else.
    assert_eq!(entries(&dir), vec!["fig4_4_1_prism.png".to_string()]);
    let img = image_size(&dir.join("fig4_4_1_prism.png"));
    assert_eq!(img, (64, 48));
    let e = stderr(&o);
    assert!(
        e.contains("triangles") && e.contains("Mrays/s") && e.contains("64x48"),
        "{e}"
    );
}

fn image_size(p: &Path) -> (u32, u32) {
    // PNG IHDR: width and height are big-endian u32 at bytes 16..24.
    let b = std::fs::read(p).unwrap();
    assert_eq!(&b[1..4], b"PNG");
    (
        u32::from_be_bytes(b[16..20].try_into().unwrap()),
        u32::from_be_bytes(b[20..24].try_into().unwrap()),
    )
}

#[test]
fn bad_inputs_fail_cleanly_without_output() {
    let dir = common::scratch_dir("cli_bad");
    let missing = dir.join("missing.glb");
    let garbage = dir.join("garbage.glb");
    std::fs::write(&garbage, b"glTF\x02\x00\x00\x00 this is not a glb").unwrap();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                "render".into(),
                missing.to_string_lossy().into(),
                "-o".into(),
                "a.png".into(),
            ],
            "missing.glb",
        ),
        (
            vec![
                "render".into(),
                garbage.to_string_lossy().into(),
                "-o".into(),
                "b.png".into(),
            ],
            "garbage.glb",
        ),
        (
            vec![
                "render".into(),
                asset("fig4_4_1_prism.glb"),
                "-o".into(),
                "c.jpg".into(),
            ],
            "c.jpg",
        ),
        (
            vec![
                "render".into(),
                asset("fig4_4_1_prism.glb"),
                "--size".into(),
                "0x10".into(),
                "-o".into(),
                "d.png".into(),
            ],
            "--size",
        ),
        (
            vec![
                "render".into(),
                asset("fig4_4_1_prism.glb"),
                "--size".into(),
                "1000000x1000000".into(),
                "-o".into(),
                "e.png".into(),
            ],
            "--size",
        ),
        (
            vec![
                "render".into(),
                asset("fig4_4_1_prism.glb"),
                "--camera".into(),
                "nope".into(),
                "-o".into(),
                "f.png".into(),
            ],
            "nope",
        ),
        (
            vec![
                "render".into(),
                asset("fig4_4_1_prism.glb"),
                "--spp".into(),
                "0".into(),
                "-o".into(),
                "g.png".into(),
            ],
            "--spp",
        ),
        (
            vec![
                "render".into(),
                asset("fig4_4_1_prism.glb"),
                "--exposure".into(),
                "bright".into(),
                "-o".into(),
                "h.png".into(),
            ],
            "--exposure",
        ),
        (
            vec!["info".into(), missing.to_string_lossy().into()],
            "missing.glb",
        ),
    ];
    for (args, needle) in cases {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = iris(&a, &dir);
        assert!(!o.status.success(), "{args:?} should fail");
        let e = stderr(&o);
        assert!(
            e.contains(needle),
            "{args:?}: message should name {needle}: {e}"
        );
        assert!(!e.contains("panicked"), "{args:?} panicked: {e}");
    }
    // Nothing was written: only the input file remains.
    assert_eq!(entries(&dir), vec!["garbage.glb".to_string()]);
}

#[test]
fn info_lists_materials_lights_and_cameras() {
    let dir = common::scratch_dir("cli_info");
    let o = iris(&["info", &asset("fig7_1_spheres.glb")], &dir);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = String::from_utf8_lossy(&o.stdout);
    for needle in [
        "triangles",
        "ior 1.2",
        "ior 1.4",
        "ior 1.6",
        "transmission 1",
        "point",
        "cameras:",
        "perspective",
    ] {
        assert!(s.contains(needle), "info output lacks {needle:?}:\n{s}");
    }
}

/// `iris diff`: an image against itself has RMSE 0; against a scaled copy the RMSE is what
/// the scale implies; different sizes are a usage error naming both files.
#[test]
fn diff_measures_rmse_and_rejects_size_mismatch() {
    use iris::image::ImageRgb;
    use iris::output::{write_image, DisplayOptions};
    let dir = common::scratch_dir("cli_diff");
    let img = |w: u32, h: u32, v: f32| ImageRgb {
        width: w,
        height: h,
        data: vec![glam::Vec3::splat(v); (w * h) as usize],
    };
    let (a, b, c) = (dir.join("a.exr"), dir.join("b.exr"), dir.join("c.exr"));
    write_image(&a, &img(4, 3, 1.0), &DisplayOptions::default()).unwrap();
    write_image(&b, &img(4, 3, 1.5), &DisplayOptions::default()).unwrap();
    write_image(&c, &img(3, 4, 1.0), &DisplayOptions::default()).unwrap();
    let same = iris::app::diff_command(&a, &a).unwrap();
    assert_eq!(same.rmse, 0.0);
    let d = iris::app::diff_command(&b, &a).unwrap();
    assert!(
        (d.rmse - 0.5).abs() < 1e-6 && (d.relative_rmse - 0.5).abs() < 1e-6,
        "{d:?}"
    );
    // Relative MSE: 0.5² / (1² + 0.01).
    assert!((d.rel_mse - 0.25 / 1.01).abs() < 1e-6, "{d:?}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_iris"))
        .args(["diff"])
        .arg(&c)
        .arg(&a)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("c.exr") && err.contains("a.exr"), "{err}");
    // `--exact`: bit-identical passes, any differing value fails and says how many.
    assert_eq!((same.differing, d.differing), (0, 12));
    let exact = |x: &std::path::Path, y: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_iris"))
            .args(["diff", "--exact"])
            .arg(x)
            .arg(y)
            .output()
            .unwrap()
    };
    assert!(exact(&a, &a).status.success());
    let out = exact(&b, &a);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("12 pixels differ"),
        "{err}"
    );
}

/// Issue 15: every numeric flag has a documented bound (its `--help` text). An absurd value
/// ends in a message naming the flag, the value and (for range flags) the bound, a non-zero
/// exit and no output. `--threads 100000` used to spawn threads until the process died: it
/// is now rejected while parsing, before any thread starts.
#[test]
fn absurd_numbers_are_rejected_before_anything_runs() {
    let dir = common::scratch_dir("cli_bounds");
    let prism = asset("fig4_4_1_prism.glb");
    let render = |extra: &[&str]| -> Vec<String> {
        let mut v = vec!["render".to_string(), prism.clone()];
        v.extend(extra.iter().map(|s| s.to_string()));
        v.extend(["-o".into(), "out.png".into()]);
        v
    };
    let cases: Vec<(Vec<String>, Vec<&str>)> = vec![
        (
            render(&["--threads", "100000"]),
            vec!["--threads", "100000", "1024"],
        ),
        (
            vec![
                "converge".into(),
                prism.clone(),
                "--time".into(),
                "1".into(),
                "--threads".into(),
                "100000".into(),
                "-o".into(),
                "conv".into(),
            ],
            vec!["--threads", "100000", "1024"],
        ),
        (
            render(&["--max-depth", "5000"]),
            vec!["--max-depth", "5000", "1024"],
        ),
        (
            render(&["--method", "photon", "--photons", "4000000000"]),
            vec!["--photons", "4000000000", "16777216"],
        ),
        (
            render(&["--spp", "2000000"]),
            vec!["--spp", "2000000", "1000000"],
        ),
        (
            render(&["--method", "sppm", "--passes", "20000000"]),
            vec!["--passes", "20000000", "10000000"],
        ),
        (
            render(&["--checkpoint", "20000000"]),
            vec!["--checkpoint", "20000000", "10000000"],
        ),
        (
            render(&["--size", "9000x9000"]),
            vec!["--size", "9000x9000", "8192x8192"],
        ),
        // Under the pixel cap, but SPPM's per-pixel buffers would need 28 GiB: rejected
        // after loading, before any buffer is allocated.
        (
            render(&["--method", "sppm", "--size", "8000x8000"]),
            vec!["--size", "8000x8000", "sppm", "GiB"],
        ),
        (render(&["--radius", "1e39"]), vec!["--radius", "1e39"]),
        (
            render(&["--turn", "360/360"]),
            vec!["--turn", "360/360", "F < N"],
        ),
        (render(&["--turn", "1/0"]), vec!["--turn", "1/0"]),
        (
            render(&["--camera-look-at", "0,0,1:0,0,1:30"]),
            vec!["--camera-look-at", "same point"],
        ),
        (
            render(&["--camera-look-at", "0,0,1:0,0,0:200"]),
            vec!["--camera-look-at", "field of view"],
        ),
        (
            render(&["--camera-look-at", "0,0,1:0,0,0:30", "--view", "top"]),
            vec!["--camera-look-at", "--view top", "choose one camera"],
        ),
        (
            render(&["--time", "1e9"]),
            vec!["--time", "1e9", "10000000"],
        ),
        (
            render(&["--target-error", "nan"]),
            vec!["--target-error", "nan"],
        ),
        (
            render(&["--exposure", "1000"]),
            vec!["--exposure", "1000", "64"],
        ),
        (
            vec![
                "converge".into(),
                prism.clone(),
                "--time".into(),
                "1e9".into(),
                "-o".into(),
                "conv".into(),
            ],
            vec!["--time", "1e9"],
        ),
        (
            vec![
                "gallery".into(),
                "--out".into(),
                "gal".into(),
                "--size".into(),
                "0x1".into(),
            ],
            vec!["--size", "0x1"],
        ),
        (
            vec![
                "gallery".into(),
                "--out".into(),
                "gal".into(),
                "--time".into(),
                "0".into(),
            ],
            vec!["--time", "0"],
        ),
    ];
    let gem = |size: &str| -> Vec<String> {
        [
            "gem", "--cut", "round", "--stone", "diamond", "--size", size, "-o", "g.glb",
        ]
        .map(String::from)
        .to_vec()
    };
    let gems = ["nan", "-3", "1e300", "0", "1001"].map(|s| (gem(s), vec!["--size", s, "1000"]));
    for (args, needles) in cases.into_iter().chain(gems) {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = iris(&a, &dir);
        let e = stderr(&o);
        assert!(!o.status.success(), "{args:?} should fail: {e}");
        for n in needles {
            assert!(e.contains(n), "{args:?}: message should name {n:?}: {e}");
        }
        assert!(!e.contains("panicked"), "{args:?} panicked: {e}");
        assert!(
            entries(&dir).is_empty(),
            "{args:?} wrote {:?}",
            entries(&dir)
        );
    }
}

/// The largest accepted thread count and depth work (a tiny render, so 1024 threads cost
/// little).
#[test]
fn largest_threads_and_depth_are_accepted() {
    let dir = common::scratch_dir("cli_bounds_ok");
    let o = iris(
        &[
            "render",
            &asset("fig4_4_1_prism.glb"),
            "--threads",
            "1024",
            "--max-depth",
            "1024",
            "--size",
            "8x8",
            "--spp",
            "1",
            "--quiet",
            "-o",
            "ok.png",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(entries(&dir), vec!["ok.png".to_string()]);
}

/// Library callers get the CLI's bounds as errors, not a crash: a thread count over
/// [`iris::render::MAX_THREADS`] fails before the pool is built, and so do out-of-range
/// depths and photon counts.
#[test]
fn library_rejects_absurd_threads_depth_and_photons() {
    let dir = common::scratch_dir("cli_bounds_lib");
    let out = dir.join("lib.png");
    let scene = PathBuf::from(asset("fig4_4_1_prism.glb"));
    let base = iris::app::RenderOptions {
        size: Some((8, 8)),
        spp: 1,
        quiet: true,
        ..iris::app::RenderOptions::new(&scene, Some(&out))
    };
    let mut threads = base.clone();
    threads.threads = 100_000;
    let mut depth = base.clone();
    depth.max_depth = 100_000;
    let mut photons = base.clone();
    photons.method = iris::integrator::Method::Photon;
    photons.photon.photons = 4_000_000_000;
    for (opts, needle) in [
        (threads, "--threads 100000"),
        (depth, "--max-depth 100000"),
        (photons, "--photons 4000000000"),
    ] {
        let e = iris::app::render_command(&opts)
            .expect_err(needle)
            .to_string();
        assert!(e.contains(needle), "{e}");
    }
    let settings = iris::render::RenderSettings::quiet_rgb((8, 8), 1, 0, 100_000);
    let e = iris::render::thread_pool(&settings).expect_err("100000 threads");
    assert!(e.to_string().contains("--threads 100000"), "{e}");
    assert!(entries(&dir).is_empty());
}
