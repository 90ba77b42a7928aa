//! The `iris` binary as a user meets it: a successful render writes the image and a
//! one-line summary; bad files, values and flags end in a clear message naming the file or
//! the flag, a non-zero exit code, and no output (not even a temporary file).

mod common;

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
    use iris::output::{write_image, DisplayOptions, ImageRgb};
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
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_iris"))
        .args(["diff"])
        .arg(&c)
        .arg(&a)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("c.exr") && err.contains("a.exr"), "{err}");
}
