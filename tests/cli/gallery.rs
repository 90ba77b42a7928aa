//! `iris gallery` end to end through the binary: two small entries at a tiny size and a
//! short time limit into a scratch directory, then the page and the images are checked; an
//! unknown `--only` pattern must fail before anything renders.

use crate::common;

use common::{iris, scratch_dir, stderr};
use std::path::Path;

/// The project root: the gallery's project entries are relative to it.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Mean of the 8-bit sRGB channels of a decoded PNG.
fn mean_value(path: &Path) -> f64 {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{} does not decode: {e}", path.display()))
        .to_rgb8();
    let n = img.as_raw().len().max(1) as f64;
    img.as_raw().iter().map(|&v| f64::from(v)).sum::<f64>() / n
}

#[test]
fn gallery_renders_selected_entries_and_writes_the_page() {
    let out = scratch_dir("gallery_two");
    let out_s = out.to_string_lossy().into_owned();
    let o = iris(
        &[
            "gallery",
            "--out",
            &out_s,
            "--size",
            "48x32",
            "--time",
            "0.3",
            "--only",
            "fig4_4_1",
            "--only",
            "round_diamond_bare",
            "-q",
        ],
        root(),
    );
    assert!(o.status.success(), "gallery failed: {}", stderr(&o));
    let page = std::fs::read_to_string(out.join("README.md")).expect("page written");
    for name in ["fig4_4_1_prism", "round_diamond_bare"] {
        let png = out.join(format!("{name}.png"));
        assert_eq!(
            image::image_dimensions(&png).expect("png header"),
            (48, 32),
            "{name}"
        );
        // Auto exposure maps the log-average luminance to 0.18 (sRGB ≈ 118 before the tone
        // map): a lit scene is far above 5/255, a black or failed render is at or near 0.
        let mean = mean_value(&png);
        assert!(mean > 5.0, "{name} is black: mean {mean}");
        assert!(
            page.contains(&format!("]({name}.png)")),
            "{name} not on the page"
        );
        assert!(
            page.contains(&format!("## {name}")),
            "{name} has no section"
        );
    }
    // Exactly one plan block and one timing line per image, nothing else rendered.
    assert_eq!(page.matches("```text\nrender plan:").count(), 2, "{page}");
    let times: Vec<f64> = page
        .lines()
        .filter_map(|l| l.strip_prefix("- render time: "))
        .map(|t| {
            t.split(' ')
                .next()
                .and_then(|v| v.parse().ok())
                .expect("seconds")
        })
        .collect();
    assert_eq!(times.len(), 2, "{page}");
    assert!(times.iter().all(|t| *t > 0.0 && *t < 60.0), "{times:?}");
    assert!(page.contains("- method: "), "{page}");
    // What ended each render is said (`--time` alone is the whole budget).
    assert_eq!(
        page.matches("- stopped at the time limit 0.3 s").count(),
        2,
        "{page}"
    );
    assert!(page.contains("--size 48x32 --time 0.3`"), "{page}");
    assert!(page.contains("cores"), "machine header missing: {page}");
    assert!(!page.contains("compare_dispersion"), "--only was ignored");
    let pngs = common::entries(&out)
        .into_iter()
        .filter(|f| f.ends_with(".png"))
        .count();
    assert_eq!(
        pngs,
        2,
        "only the selected images: {:?}",
        common::entries(&out)
    );
}

#[test]
fn unknown_only_pattern_is_a_clear_error() {
    let out = scratch_dir("gallery_unknown");
    let out_s = out.to_string_lossy().into_owned();
    let o = iris(
        &[
            "gallery",
            "--out",
            &out_s,
            "--only",
            "no_such_scene_xyz",
            "-q",
        ],
        root(),
    );
    assert!(!o.status.success(), "an unknown --only must fail");
    let err = stderr(&o);
    assert!(
        err.contains("no_such_scene_xyz") && err.contains("round_diamond"),
        "the error names the pattern and the entries: {err}"
    );
    assert!(common::entries(&out).is_empty(), "nothing written");
}

/// Runs the gallery binary from the project root with extra environment variables.
fn gallery_with_env(args: &[&str], env: &[(&str, &str)]) -> std::process::Output {
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_iris"));
    cmd.arg("gallery").args(args).current_dir(root());
    cmd.env_remove("IRIS_REQUIRE_SHARED");
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().expect("run iris")
}

#[test]
fn missing_shared_assets_are_noted_unless_required() {
    let out = scratch_dir("gallery_no_shared");
    let out_s = out.to_string_lossy().into_owned();
    let missing = out.join("no_shared_assets_here");
    let missing_s = missing.to_string_lossy().into_owned();
    let args = [
        "--out",
        out_s.as_str(),
        "--only",
        "compare_dispersion",
        "-q",
    ];
    // Absent and not required: said on stderr and on the page, nothing rendered, exit 0.
    let o = gallery_with_env(&args, &[("IRIS_SHARED_ASSETS", missing_s.as_str())]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("shared assets"), "{}", stderr(&o));
    let page = std::fs::read_to_string(out.join("README.md")).expect("page written");
    assert!(
        page.contains("shared assets folder was not found"),
        "{page}"
    );
    assert!(!out.join("compare_dispersion.png").exists());
    // Required: an error.
    let o = gallery_with_env(
        &args,
        &[
            ("IRIS_SHARED_ASSETS", missing_s.as_str()),
            ("IRIS_REQUIRE_SHARED", "1"),
        ],
    );
    assert!(!o.status.success(), "IRIS_REQUIRE_SHARED=1 must fail");
    assert!(stderr(&o).contains("IRIS_REQUIRE_SHARED"), "{}", stderr(&o));
}

#[test]
fn a_before_image_in_the_folder_makes_a_before_after_pair() {
    // `oval_ruby` has a before caption: with `oval_ruby_before.png` in the folder the page
    // shows the pair (and never rewrites the before image); `fig4_4_1_prism` has none.
    let out = scratch_dir("gallery_pair");
    let before = out.join("oval_ruby_before.png");
    image::RgbImage::from_pixel(4, 3, image::Rgb([200, 10, 10]))
        .save(&before)
        .expect("write the before image");
    let bytes = std::fs::read(&before).unwrap();
    std::fs::write(out.join("fig4_4_1_prism_before.png"), &bytes).unwrap();
    let out_s = out.to_string_lossy().into_owned();
    let o = iris(
        &[
            "gallery",
            "--out",
            &out_s,
            "--size",
            "32x24",
            "--time",
            "0.2",
            "--only",
            "oval_ruby",
            "--only",
            "fig4_4_1",
            "-q",
        ],
        root(),
    );
    assert!(o.status.success(), "gallery failed: {}", stderr(&o));
    let page = std::fs::read_to_string(out.join("README.md")).expect("page written");
    assert!(
        page.contains(
            "| ![oval_ruby before](oval_ruby_before.png) | ![oval_ruby](oval_ruby.png) |"
        ),
        "{page}"
    );
    assert!(page.contains("Iris before issue 18"), "{page}");
    assert_eq!(page.matches("| before | now |").count(), 1, "{page}");
    assert!(
        page.contains("![fig4_4_1_prism](fig4_4_1_prism.png)"),
        "{page}"
    );
    assert_eq!(
        std::fs::read(&before).unwrap(),
        bytes,
        "before image untouched"
    );
}

#[test]
fn a_partial_run_keeps_the_other_entries_of_the_page() {
    // Two `--only` runs into one directory: the second puts its entry into the page the
    // first wrote, in the gallery's order, and leaves the first's section as it was.
    let out = scratch_dir("gallery_partial");
    let out_s = out.to_string_lossy().into_owned();
    let run = |only: &str| {
        let args = [
            "gallery", "--out", &out_s, "--size", "24x16", "--time", "0.2", "--only", only, "-q",
        ];
        let o = iris(&args, root());
        assert!(o.status.success(), "gallery --only {only}: {}", stderr(&o));
        std::fs::read_to_string(out.join("README.md")).expect("page written")
    };
    let first = run("round_diamond_bare");
    let section = |page: &str, name: &str| {
        let start = page.find(&format!("## {name}\n")).expect("section");
        let rest = &page[start + 3..];
        page[start..start + 3 + rest.find("\n## ").unwrap_or(rest.len())].to_string()
    };
    let diamond = section(&first, "round_diamond_bare");
    let page = run("fig4_4_1");
    assert!(page.contains("## fig4_4_1_prism\n"), "{page}");
    assert_eq!(
        section(&page, "round_diamond_bare").trim_end(),
        diamond.trim_end()
    );
    assert!(
        page.find("## fig4_4_1_prism").unwrap() < page.find("## round_diamond_bare").unwrap(),
        "the gallery's order: {page}"
    );
    assert_eq!(page.matches("```text\nrender plan:").count(), 2, "{page}");
}
