//! `--background COLOR|transparent` (issue 8, drop-in preview item 4), through the `iris`
//! binary on a bare generated gem (no camera, no light) under a uniform environment:
//! escaped camera rays show the colour or alpha 0, the model keeps alpha 1, PNG is RGBA8
//! for `transparent`, EXR gets an A channel, a bad value is a clear error, and the output
//! is deterministic.

use crate::common;

use common::{entries, iris, stderr};
use std::path::{Path, PathBuf};

/// A bare round diamond (6.5 mm) in `dir`.
fn gem(dir: &Path) -> PathBuf {
    let path = dir.join("d.glb");
    let o = iris(
        &[
            "gem", "--cut", "round", "--stone", "diamond", "--bare", "-o", "d.glb",
        ],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    path
}

/// Renders the gem to `out` (64×48, 2 spp, environment 0.6) with extra flags.
fn render(dir: &Path, out: &str, extra: &[&str]) {
    let mut args = vec![
        "render",
        "d.glb",
        "-o",
        out,
        "--size",
        "64x48",
        "--spp",
        "2",
        "--env",
        "0.6",
        "-q",
        "--threads",
        "2",
    ];
    args.extend_from_slice(extra);
    let o = iris(&args, dir);
    assert!(o.status.success(), "{}", stderr(&o));
}

const CORNERS: [(u32, u32); 4] = [(0, 0), (63, 0), (0, 47), (63, 47)];
const CENTRE: (u32, u32) = (32, 24);

#[test]
fn transparent_png_is_rgba_with_alpha_0_around_and_255_on_the_model() {
    let dir = common::scratch_dir("bg_transparent");
    gem(&dir);
    render(&dir, "t.png", &["--background", "transparent"]);
    let img = image::open(dir.join("t.png")).expect("decode");
    assert_eq!(img.color(), image::ColorType::Rgba8);
    let img = img.to_rgba8();
    for (x, y) in CORNERS {
        assert_eq!(img.get_pixel(x, y).0, [0, 0, 0, 0], "corner ({x}, {y})");
    }
    assert_eq!(img.get_pixel(CENTRE.0, CENTRE.1).0[3], 255);
    // The model (the gem seen through a 35° three-quarter view) covers a sensible part.
    let opaque = img.pixels().filter(|p| p.0[3] == 255).count() as f64 / (64.0 * 48.0);
    assert!((0.2..0.8).contains(&opaque), "opaque fraction {opaque}");
    // The environment lights the stone: its pixels are not black.
    let lit = img
        .pixels()
        .filter(|p| p.0[3] == 255 && p.0[..3] != [0, 0, 0])
        .count();
    assert!(lit > 0);
    // Same flags, same bytes.
    render(&dir, "t2.png", &["--background", "transparent"]);
    assert_eq!(
        std::fs::read(dir.join("t.png")).unwrap(),
        std::fs::read(dir.join("t2.png")).unwrap()
    );
}

#[test]
fn colour_background_is_exact_in_png_and_linear_in_exr() {
    let dir = common::scratch_dir("bg_colour");
    gem(&dir);
    render(&dir, "c.png", &["--background", "#ff8000"]);
    let img = image::open(dir.join("c.png")).expect("decode");
    assert_eq!(img.color(), image::ColorType::Rgb8);
    let img = img.to_rgb8();
    for (x, y) in CORNERS {
        assert_eq!(img.get_pixel(x, y).0, [255, 128, 0], "corner ({x}, {y})");
    }
    assert_ne!(img.get_pixel(CENTRE.0, CENTRE.1).0, [255, 128, 0]);
    // EXR: linear, the colour sRGB-decoded (#808080 → 0.2158).
    render(&dir, "c.exr", &["--background", "#808080"]);
    let exr = iris::output::read_exr(&dir.join("c.exr")).expect("exr");
    let grey = iris::image::srgb::srgb_eotf(128.0 / 255.0);
    assert!((grey - 0.2158).abs() < 1e-3);
    for (x, y) in CORNERS {
        let p = exr.get(x, y).unwrap();
        assert!(
            (p - glam::Vec3::splat(grey)).abs().max_element() < 1e-6,
            "{p}"
        );
    }
    // Without the flag (and without the floor `--ground auto` adds under glass then) the
    // corners show the environment (0.6, to spectral noise).
    render(&dir, "e.exr", &["--ground", "off"]);
    let env = iris::output::read_exr(&dir.join("e.exr")).expect("exr");
    for (x, y) in CORNERS {
        let p = env.get(x, y).unwrap();
        assert!(
            (p - glam::Vec3::splat(0.6)).abs().max_element() < 0.15,
            "{p}"
        );
    }
}

#[test]
fn transparent_exr_has_an_alpha_channel() {
    let dir = common::scratch_dir("bg_exr_alpha");
    gem(&dir);
    render(&dir, "t.exr", &["--background", "transparent"]);
    let img = exr::prelude::read_first_rgba_layer_from_file(
        dir.join("t.exr"),
        |res, _| (res.width(), vec![[0f32; 4]; res.area()]),
        |(w, px): &mut (usize, Vec<[f32; 4]>), pos, (r, g, b, a): (f32, f32, f32, f32)| {
            px[pos.y() * *w + pos.x()] = [r, g, b, a];
        },
    )
    .expect("rgba exr");
    let (w, px) = &img.layer_data.channel_data.pixels;
    assert_eq!(*w, 64);
    for (x, y) in CORNERS {
        assert_eq!(
            px[y as usize * 64 + x as usize],
            [0.0; 4],
            "corner ({x}, {y})"
        );
    }
    assert_eq!(px[CENTRE.1 as usize * 64 + CENTRE.0 as usize][3], 1.0);
    // Premultiplied colour: never brighter than allowed by alpha 0 = black.
    assert!(px.iter().all(|p| p[3] > 0.0 || p[..3] == [0.0; 3]));
}

#[test]
fn bad_background_and_view_values_are_clear_errors() {
    let dir = common::scratch_dir("bg_bad");
    gem(&dir);
    for (flag, value) in [
        ("--background", "blue-ish"),
        ("--background", "#12345"),
        ("--background", "1,0"),
        ("--background", "0,0,2"),
        ("--view", "bottom"),
    ] {
        let o = iris(
            &[
                "render", "d.glb", "-o", "x.png", "--size", "8x8", flag, value,
            ],
            &dir,
        );
        assert!(!o.status.success(), "{flag} {value}");
        let e = stderr(&o);
        assert!(e.contains(flag) && e.contains(value), "{e}");
        if flag == "--background" {
            assert!(e.contains("transparent") && e.contains("#rrggbb"), "{e}");
        } else {
            assert!(e.contains("threequarter"), "{e}");
        }
    }
    assert_eq!(
        entries(&dir),
        vec!["d.glb".to_string()],
        "no output written"
    );
}
