//! Error against run time from the command line (issue 6): `iris render` with `--report`,
//! `--plot`, `--reference` and `--target-error`, and `iris converge`. Small images and short
//! budgets; each test checks files on disk, the printed summary, and that bad inputs fail
//! with a message naming the flag or file and leave no output behind.

use crate::common;

use common::{entries, iris};

use std::path::{Path, PathBuf};

fn asset(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/paper")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// The documented CSV columns (`docs/error-and-time.md`, "Measuring the error").
const COLUMNS: [&str; 19] = [
    "run",
    "stage",
    "wall_s",
    "samples_per_pixel",
    "passes",
    "rays",
    "photons",
    "rmse",
    "rel_mse",
    "mae",
    "est_rmse",
    "est_rel_mse",
    "est_mae",
    "denoised_rmse",
    "denoised_rel_mse",
    "denoised_mae",
    "denoise_s",
    "display_est",
    "display_rmse",
];

/// Rows of a CSV as cells, header first.
fn csv(path: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// A 32×24 path-traced reference of the spheres (64 spp) written to `dir/ref.exr`.
fn reference(dir: &Path) -> PathBuf {
    let o = iris(
        &[
            "render",
            &asset("fig7_1_spheres.glb"),
            "--size",
            "32x24",
            "--method",
            "path",
            "--spp",
            "64",
            "--seed",
            "99",
            "-q",
            "-o",
            "ref.exr",
        ],
        dir,
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    dir.join("ref.exr")
}

#[test]
fn report_and_plot_of_a_render() {
    let dir = common::scratch_dir("cli_converge_report");
    let r = reference(&dir);
    let o = iris(
        &[
            "render",
            &asset("fig7_1_spheres.glb"),
            "--method",
            "path",
            "--spp",
            "16",
            "--reference",
            r.to_str().unwrap(),
            "--report",
            "r.csv",
            "--plot",
            "p.png",
            "-o",
            "a.png",
            "-q",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    // The reference set the size (no --size given).
    let img = image::open(dir.join("a.png")).expect("decode image");
    assert_eq!((img.width(), img.height()), (32, 24));
    let rows = csv(&dir.join("r.csv"));
    assert_eq!(rows[0], COLUMNS.to_vec(), "header");
    assert_eq!(rows[0].join(","), iris::measure::report::CSV_HEADER);
    assert!(rows.iter().all(|r| r.len() == COLUMNS.len()), "{rows:?}");
    assert_eq!(rows[1][1], "load");
    assert_eq!(rows[2][1], "build");
    let render: Vec<_> = rows.iter().filter(|r| r[1] == "render").collect();
    // Checkpoints at 1, 2, 4, 8, 16 spp at most; at least 2 for the plot.
    assert!(render.len() >= 2 && render.len() <= 5, "{render:?}");
    let spp: Vec<u64> = render.iter().map(|r| r[3].parse().unwrap()).collect();
    assert!(spp.windows(2).all(|w| w[0] < w[1]), "{spp:?}");
    assert_eq!(*spp.last().unwrap(), 16);
    for r in &render {
        // The estimate needs two samples: before, its columns are empty.
        let cells = if r[3] == "1" {
            assert!(r[10..13].iter().all(|c| c.is_empty()), "{r:?}");
            7..10
        } else {
            7..13
        };
        for c in cells {
            let v: f64 = r[c].parse().unwrap_or_else(|_| panic!("cell {c} of {r:?}"));
            assert!(v.is_finite() && v >= 0.0, "{r:?}");
        }
    }
    // More samples, less error against the reference: the 16-spp error is below the first
    // checkpoint's (≥ 8× the samples; Monte Carlo error ∝ 1/√n leaves a wide margin).
    let rmse = |r: &Vec<String>| r[7].parse::<f64>().unwrap();
    assert!(rmse(render.last().unwrap()) < rmse(render[0]), "{render:?}");
    let plot = image::open(dir.join("p.png")).expect("plot is a valid PNG");
    assert!(plot.width() > 0 && plot.height() > 0);
    assert!(
        text(&o.stderr).contains("against the reference"),
        "{}",
        text(&o.stderr)
    );
}

#[test]
fn svg_plot_without_reference() {
    let dir = common::scratch_dir("cli_converge_svg");
    let o = iris(
        &[
            "render",
            &asset("fig7_1_spheres.glb"),
            "--size",
            "24x16",
            "--method",
            "path",
            "--spp",
            "4",
            "--report",
            "r.csv",
            "--plot",
            "p.svg",
            "-o",
            "a.exr",
            "-q",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let svg = std::fs::read_to_string(dir.join("p.svg")).unwrap();
    assert!(svg.contains("<svg"), "{svg}");
    // No reference: reference columns empty, estimate columns filled from 2 spp on.
    for r in csv(&dir.join("r.csv")).iter().filter(|r| r[1] == "render") {
        assert!(
            r[7].is_empty() && r[8].is_empty() && r[9].is_empty(),
            "{r:?}"
        );
        assert_eq!(r[11].parse::<f64>().is_ok(), r[3] != "1", "{r:?}");
    }
}

#[test]
fn target_error_stops_before_the_sample_bound() {
    let dir = common::scratch_dir("cli_converge_target");
    let o = iris(
        &[
            "render",
            &asset("fig7_1_spheres.glb"),
            "--size",
            "32x24",
            "--method",
            "path",
            "--spp",
            "65536",
            "--target-error",
            "0.3",
            "--report",
            "r.csv",
            "-o",
            // EXR: the raw image is what is written, so the report's (raw) estimate is the
            // number the stop test compared (a PNG is judged by its denoised image:
            // tests/cli/default_budget.rs).
            "a.exr",
            "-q",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let e = text(&o.stderr);
    assert!(e.contains("stopped at the error target 0.3"), "{e}");
    assert!(!e.contains("for the denoised image"), "{e}");
    let rows = csv(&dir.join("r.csv"));
    let last = rows.last().unwrap();
    let spp: u64 = last[3].parse().unwrap();
    // The estimate at 65536 spp would be far below 0.3; stopping there means the target was
    // ignored. The last checkpoint's estimate must be at or below the target.
    assert!(spp < 65536, "{last:?}");
    let est: f64 = last[11].parse().unwrap();
    assert!(est.sqrt() <= 0.3, "{last:?}");
    assert!(e.contains(&format!("{spp} spp")), "{e}");
}

#[test]
fn reference_of_another_size_fails_before_rendering() {
    let dir = common::scratch_dir("cli_converge_size");
    let r = reference(&dir);
    let o = iris(
        &[
            "render",
            &asset("fig7_1_spheres.glb"),
            "--size",
            "40x30",
            "--reference",
            r.to_str().unwrap(),
            "--report",
            "r.csv",
            "-o",
            "a.png",
            "-q",
        ],
        &dir,
    );
    assert!(!o.status.success());
    let e = text(&o.stderr);
    assert!(
        e.contains("ref.exr") && e.contains("32x24") && e.contains("40x30"),
        "{e}"
    );
    assert_eq!(entries(&dir), vec!["ref.exr".to_string()]);
}

#[test]
fn converge_with_a_reference_writes_everything_and_the_table() {
    let dir = common::scratch_dir("cli_converge_run");
    let r = reference(&dir);
    let o = iris(
        &[
            "converge",
            &asset("fig7_1_spheres.glb"),
            "--methods",
            "path,sppm",
            "--time",
            "0.3",
            "--reference",
            r.to_str().unwrap(),
            "-o",
            "out",
            "-q",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = dir.join("out");
    assert_eq!(
        entries(&out),
        [
            "convergence.png",
            "path.exr",
            "path.png",
            "report.csv",
            "sppm.exr",
            "sppm.png"
        ]
    );
    image::open(out.join("convergence.png")).expect("plot is a valid PNG");
    let rows = csv(&out.join("report.csv"));
    assert_eq!(rows[0], COLUMNS.to_vec());
    for m in ["path", "sppm"] {
        assert!(rows.iter().any(|r| r[0] == m && r[1] == "render"), "{m}");
    }
    let s = text(&o.stdout);
    for level in ["0.5 ", "0.2 ", "0.1 ", "0.05 ", "0.02 "] {
        assert!(s.lines().any(|l| l.starts_with(level)), "{level}: {s}");
    }
    assert!(s.contains("path:") && s.contains("sppm:"), "{s}");
}

#[test]
fn converge_renders_its_own_reference() {
    let dir = common::scratch_dir("cli_converge_noref");
    let o = iris(
        &[
            "converge",
            &asset("fig7_1_spheres.glb"),
            "--methods",
            "path",
            "--time",
            "0.2",
            "--size",
            "24x16",
            "-o",
            "out",
            "-q",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = dir.join("out");
    assert!(out.join("reference.exr").is_file());
    assert!(
        text(&o.stdout).contains("reference: rendered with"),
        "{}",
        text(&o.stdout)
    );
}

/// A crystal scene runs polarized under `iris converge`, as under `iris render`: in the
/// tourmaline bars of the gallery the near bar (optic axis across the view, half its light
/// polarized along c) is yellower than the far one (both modes ordinary). Rendered with one
/// index, unpolarized, the two bars are the same colour: green/red of the raw image, near
/// over far, measured 0.90 unpolarized against 0.54 polarized at 1 s and 0.38 at 0.02 s
/// (96×54 px), so the time budget (converge has no other) does not decide the outcome.
#[test]
fn converge_renders_a_crystal_polarized() {
    let dir = common::scratch_dir("cli_converge_crystal");
    let scene =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/pleochroic_tourmaline.glb");
    let o = iris(
        &[
            "converge",
            scene.to_str().unwrap(),
            "--methods",
            "path",
            "--time",
            "1",
            "--size",
            "96x54",
            "-o",
            "out",
            "-q",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    // The raw linear image (not the denoised PNG, which blends colours at few samples).
    let img = iris::output::read_exr(&dir.join("out/path.exr")).expect("path.exr");
    let green_over_red = |(y0, y1): (f32, f32)| {
        let (w, h) = (img.width as f32, img.height as f32);
        let (mut r, mut g) = (0.0, 0.0);
        for y in (y0 * h) as u32..(y1 * h) as u32 {
            for x in (0.4 * w) as u32..(0.6 * w) as u32 {
                let p = img.data[(y * img.width + x) as usize];
                (r, g) = (r + p.x, g + p.y);
            }
        }
        g / r
    };
    let (far, near) = (green_over_red((0.3, 0.45)), green_over_red((0.55, 0.7)));
    eprintln!("green/red far {far}, near {near}");
    assert!(
        near < 0.75 * far,
        "the bars should differ in colour (pleochroism): green/red far {far}, near {near}"
    );
}

#[test]
fn converge_bad_inputs_fail_cleanly() {
    let dir = common::scratch_dir("cli_converge_bad");
    std::fs::write(dir.join("file"), b"x").unwrap();
    let scene = asset("fig7_1_spheres.glb");
    let cases: [(&[&str], &str); 4] = [
        (&["--methods", "path,magic", "-o", "o1"], "--methods"),
        (&["--reference", "missing.exr", "-o", "o2"], "missing.exr"),
        (&["-o", "file/sub"], "file/sub"),
        (&["--methods", "path,path", "-o", "o3"], "twice"),
    ];
    for (extra, needle) in cases {
        let mut args = vec!["converge", scene.as_str(), "--time", "0.1", "-q"];
        args.extend_from_slice(extra);
        let o = iris(&args, &dir);
        assert!(!o.status.success(), "{args:?}");
        let e = text(&o.stderr);
        assert!(e.contains(needle), "{args:?}: {e}");
    }
    // Nothing written: only the file the test made.
    assert_eq!(entries(&dir), vec!["file".to_string()]);
    let o = iris(
        &["render", &scene, "--plot", "p.pdf", "-o", "a.png", "-q"],
        &dir,
    );
    assert!(!o.status.success());
    assert!(text(&o.stderr).contains("p.pdf"), "{}", text(&o.stderr));
    assert_eq!(entries(&dir), vec!["file".to_string()]);
}

/// `iris converge` checks every requested method against the scene before it renders
/// anything (issue 48: with media it rendered the reference and the path image, then
/// failed on the photon map, leaving reference.exr, path.exr and path.png).
#[test]
fn converge_refuses_a_method_that_cannot_render_the_scene_before_rendering() {
    let dir = common::scratch_dir("cli_converge_media");
    let hazy = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/hazy_prism.glb");
    for methods in [None, Some("path,vcm"), Some("bpt"), Some("path,photon")] {
        let mut args = vec![
            "converge",
            hazy.to_str().unwrap(),
            "--time",
            "0.2",
            "--size",
            "16x12",
            "-o",
            "out",
            "-q",
        ];
        args.extend(methods.iter().flat_map(|m| ["--methods", *m]));
        let o = iris(&args, &dir);
        let e = text(&o.stderr);
        assert!(!o.status.success(), "{methods:?}: {e}");
        assert!(
            e.contains("does not trace scattering media"),
            "{methods:?}: {e}"
        );
        assert!(
            entries(&dir).is_empty(),
            "{methods:?} wrote {:?}",
            entries(&dir)
        );
    }
}

/// A `--reference` inside DIR under a name a run writes is refused before rendering (the
/// path run would overwrite it).
#[test]
fn converge_refuses_a_reference_its_runs_would_overwrite() {
    let dir = common::scratch_dir("cli_converge_overwrite");
    std::fs::create_dir_all(dir.join("out")).unwrap();
    let r = reference(&dir);
    std::fs::rename(&r, dir.join("out/path.exr")).unwrap();
    let o = iris(
        &[
            "converge",
            &asset("fig7_1_spheres.glb"),
            "--methods",
            "path",
            "--time",
            "0.2",
            "--reference",
            "out/path.exr",
            "-o",
            "out",
            "-q",
        ],
        &dir,
    );
    let e = text(&o.stderr);
    assert!(!o.status.success(), "{e}");
    assert!(e.contains("path.exr") && e.contains("--reference"), "{e}");
    assert_eq!(entries(&dir.join("out")), vec!["path.exr".to_string()]);
}
