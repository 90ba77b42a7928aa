//! The photon methods from the command line: `--method sppm|photon|hybrid|auto`, `--passes`,
//! `--time`, `--checkpoint`, `--photons`, `--radius`, `--alpha`, `--photon-rr`; bad values
//! end in a message naming the flag, a non-zero exit and no output.

use crate::common;

use common::{iris, stderr};

use std::path::{Path, PathBuf};

fn asset(path: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets")
        .join(path)
        .to_string_lossy()
        .into_owned()
}

fn mean_of_png(p: &Path) -> f64 {
    let img = image::open(p).expect("png").to_rgb8();
    img.pixels()
        .map(|p| p.0.iter().map(|&c| c as f64).sum::<f64>())
        .sum::<f64>()
        / (3.0 * img.pixels().len() as f64)
}

#[test]
fn sppm_renders_in_passes_and_reports_them() {
    let dir = common::scratch_dir("cli_sppm");
    let o = iris(
        &[
            "render",
            &asset("paper/fig4_5_1_caustics.glb"),
            "--method",
            "sppm",
            "--passes",
            "4",
            "--photons",
            "20000",
            "--size",
            "64x48",
            "-q",
            "-o",
            "s.exr",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("4 passes") && e.contains("80000 photons"), "{e}");
    assert!(dir.join("s.exr").is_file());
}

#[test]
fn photon_method_and_lobe_roulette_render() {
    let dir = common::scratch_dir("cli_photon");
    for rr in ["throughput", "lobe"] {
        let out = format!("p_{rr}.png");
        let o = iris(
            &[
                "render",
                &asset("paper/fig4_5_1_caustics.glb"),
                "--method",
                "photon",
                "--photons",
                "50000",
                "--photon-rr",
                rr,
                "--size",
                "48x36",
                "--spp",
                "2",
                "-q",
                "-o",
                &out,
            ],
            &dir,
        );
        assert!(o.status.success(), "{rr}: {}", stderr(&o));
        assert!(mean_of_png(&dir.join(&out)) > 1.0, "{rr}: black image");
    }
}

#[test]
fn checkpoints_write_the_image_while_passes_run_and_time_stops_them() {
    let dir = common::scratch_dir("cli_checkpoint");
    // 1 000 000 passes would take hours: the 1.5 s budget must stop it.
    let o = iris(
        &[
            "render",
            &asset("paper/fig4_5_1_caustics.glb"),
            "--method",
            "sppm",
            "--passes",
            "1000000",
            "--time",
            "1.5",
            "--checkpoint",
            "2",
            "--photons",
            "5000",
            "--size",
            "32x24",
            "-q",
            "-o",
            "c.png",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    let passes: u64 = e
        .split(" passes")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no pass count in {e}"));
    assert!((1..1_000_000).contains(&passes), "{passes} passes");
    assert!(dir.join("c.png").is_file());
    // No temporary files left behind.
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, vec!["c.png".to_string()]);
}

/// `--method auto` says which method and why: the point light's small caustic under the
/// glass sphere in a lit room → the hybrid; the stone under a 3° spot, whose light is mostly
/// caustic → VCM; a scene with nothing specular → the path tracer.
#[test]
fn auto_picks_hybrid_vcm_or_path() {
    let dir = common::scratch_dir("cli_auto");
    let run = |file: &str, out: &str| {
        iris(
            &[
                "render",
                &asset(file),
                "--method",
                "auto",
                "--spp",
                "2",
                "--passes",
                "2",
                "--photons",
                "5000",
                "--size",
                "32x24",
                "-q",
                "-o",
                out,
            ],
            &dir,
        )
    };
    let o = run("paper/fig4_5_1_caustics.glb", "a.png");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("(hybrid)"), "{}", stderr(&o));
    let o = run("scenes/gem_caustics.glb", "g.png");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("): VCM"), "{}", stderr(&o));
    // A scene with no transmissive or mirror material: the path tracer.
    let mut scene = iris::scene::desc::SceneDesc {
        name: "diffuse only".into(),
        ..Default::default()
    };
    scene.meshes.push(iris::authoring::placed(
        "floor",
        iris::authoring::shapes::ground_plane(1.0, 1.0),
        0,
        None,
    ));
    scene.materials.push(iris::material::MaterialDesc::diffuse(
        "white",
        glam::Vec3::splat(0.8),
    ));
    scene.lights.push(iris::scene::desc::LightDesc::Point {
        name: "bulb".into(),
        position: glam::Vec3::new(0.0, 1.0, 0.0),
        color: glam::Vec3::ONE,
        intensity: 1.0,
        range: None,
        spectrum: None,
    });
    let plain = dir.join("plain.glb");
    iris::authoring::write_glb(&plain, &scene).unwrap();
    let o = iris(
        &[
            "render",
            plain.to_str().unwrap(),
            "--method",
            "auto",
            "--spp",
            "2",
            "--size",
            "32x24",
            "-q",
            "-o",
            "b.png",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("path tracer"), "{}", stderr(&o));
    assert!(!stderr(&o).contains("(hybrid)"), "{}", stderr(&o));
}

#[test]
fn bad_photon_flags_fail_cleanly() {
    let dir = common::scratch_dir("cli_photon_bad");
    for (flag, value) in [
        ("--alpha", "1.5"),
        ("--alpha", "0"),
        ("--radius", "-1"),
        ("--radius", "nan"),
        ("--time", "0"),
        ("--passes", "0"),
        ("--photons", "0"),
        ("--checkpoint", "0"),
        ("--photon-rr", "fast"),
        ("--method", "bdpt"),
    ] {
        let o = iris(
            &[
                "render",
                &asset("paper/fig4_5_1_caustics.glb"),
                "--method",
                "sppm",
                flag,
                value,
                "-o",
                "x.png",
            ],
            &dir,
        );
        assert!(!o.status.success(), "{flag} {value} should fail");
        let e = stderr(&o);
        assert!(e.contains(flag), "{flag} {value}: {e}");
        assert!(!e.contains("panicked"), "{e}");
    }
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}

/// `--method hybrid` renders; a misspelt method is rejected naming the accepted ones.
#[test]
fn cli_accepts_hybrid_and_rejects_nonsense() {
    let dir = common::scratch_dir("cli_hybrid");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/gem_caustics.glb"
    );
    let o = common::iris(
        &[
            "render",
            scene,
            "--method",
            "hybrid",
            "--spp",
            "2",
            "--photons",
            "2000",
            "--size",
            "32x24",
            "-q",
            "-o",
            "h.png",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", common::stderr(&o));
    assert!(dir.join("h.png").exists());
    let o = common::iris(
        &[
            "render", scene, "--method", "hybird", "--size", "32x24", "-q", "-o", "x.png",
        ],
        &dir,
    );
    assert!(!o.status.success());
    let err = common::stderr(&o);
    assert!(err.contains("hybird") && err.contains("hybrid"), "{err}");
    assert!(!dir.join("x.png").exists());
    // `--caustics map|light|mixed`: each renders, a misspelt one is rejected naming them.
    for mode in ["map", "light", "mixed"] {
        let args = [
            "render",
            scene,
            "--method",
            "hybrid",
            "--caustics",
            mode,
            "--spp",
            "1",
            "--photons",
            "500",
            "--size",
            "16x12",
            "-q",
            "-o",
            "c.png",
        ];
        let o = common::iris(&args, &dir);
        assert!(o.status.success(), "{mode}: {}", common::stderr(&o));
    }
    let args = [
        "render",
        scene,
        "--method",
        "hybrid",
        "--caustics",
        "lite",
        "-q",
        "-o",
        "y.png",
    ];
    let o = common::iris(&args, &dir);
    assert!(!o.status.success());
    let err = common::stderr(&o);
    assert!(err.contains("--caustics") && err.contains("mixed"), "{err}");
    assert!(!dir.join("y.png").exists());
}

/// A `--radius` that parses (finite, > 0) but is far below or above the scene's scale is
/// refused before rendering, for every method that gathers, naming the flag and the bound
/// (issue 48: 1e-35..3e-20 made every hybrid gather NaN, 1e-39 fell back to the default).
#[test]
fn a_radius_out_of_the_scenes_range_is_refused_before_rendering() {
    let dir = common::scratch_dir("cli_photon_radius");
    for method in ["hybrid", "sppm", "photon", "vcm"] {
        for (radius, says) in [
            ("1e-30", "below the smallest gather radius"),
            ("3e-20", "below the smallest gather radius"),
            ("1e-39", "below the smallest gather radius"),
            ("1e30", "above the largest gather radius"),
        ] {
            let o = iris(
                &[
                    "render",
                    &asset("paper/fig4_5_1_caustics.glb"),
                    "--method",
                    method,
                    "--radius",
                    radius,
                    "--spp",
                    "1",
                    "--passes",
                    "1",
                    "--size",
                    "16x12",
                    "-o",
                    "x.png",
                ],
                &dir,
            );
            let e = stderr(&o);
            assert!(
                !o.status.success(),
                "{method} --radius {radius} rendered: {e}"
            );
            assert!(
                e.contains("--radius") && e.contains(says),
                "{method} {radius}: {e}"
            );
            assert!(!e.contains("panicked"), "{e}");
        }
    }
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    // A small radius within the bound renders a finite, non-black image.
    let o = iris(
        &[
            "render",
            &asset("paper/fig4_5_1_caustics.glb"),
            "--method",
            "hybrid",
            "--radius",
            "1e-3",
            "--spp",
            "2",
            "--size",
            "16x12",
            "-o",
            "ok.exr",
        ],
        &dir,
    );
    let e = stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(!e.contains("NaN"), "{e}");
}
