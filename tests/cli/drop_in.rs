//! The drop-in preview (issue 8): a file with no camera and no light, rendered with no
//! flags but the size and a fixed quick budget (Whitted, 4 spp: the default budget renders
//! until an error target), gives a non-black image in which the model is framed.
//!
//! Through the `iris` binary, on models written here: a bare generated round diamond and
//! emerald (glass: the studio lights them, `--ground auto` adds a floor) and an opaque OBJ
//! box (no floor). "Framed" is measured on the coverage alpha of a second render with
//! `--background transparent` (same camera: the view does not depend on the background):
//! the covered pixels' bounding box must be centred, touch no image edge and span a
//! sensible part of the frame.

use crate::common;

use common::{iris, stderr};
use std::path::Path;

const W: u32 = 160;
const H: u32 = 90;

/// Renders `file` in `dir` with the default drop-in choices (studio, floor, framing): only
/// the size, quiet and a fixed quick budget (Whitted, 4 spp; the default budget renders
/// until an error target or a time limit), plus `extra`.
fn render(dir: &Path, file: &str, out: &str, extra: &[&str]) -> String {
    let size = format!("{W}x{H}");
    let mut args = vec!["render", file, "-o", out, "--size", &size, "-q"];
    args.extend(["--method", "whitted", "--spp", "4"]);
    args.extend_from_slice(extra);
    let o = iris(&args, dir);
    assert!(o.status.success(), "{file}: {}", stderr(&o));
    stderr(&o)
}

/// Mean of the sRGB-encoded channels over the pixels where `keep` holds, in [0, 1].
fn mean_where(img: &image::RgbImage, keep: impl Fn(u32, u32) -> bool) -> f64 {
    let (mut sum, mut n) = (0.0, 0u32);
    for (x, y, p) in img.enumerate_pixels() {
        if keep(x, y) {
            sum += p.0.iter().map(|&c| f64::from(c)).sum::<f64>() / (3.0 * 255.0);
            n += 1;
        }
    }
    assert!(n > 0, "no pixel selected");
    sum / f64::from(n)
}

/// Checks one model: non-black, framed, and (for glass) standing on a lit floor.
fn check(dir: &Path, file: &str, glass: bool) {
    let notes = render(dir, file, "lit.png", &[]);
    assert!(notes.contains("no camera in the file"), "{file}: {notes}");
    // The default studio: `jeweller` for a gem (transmissive, dispersive), else `soft`.
    let preset = if glass {
        "studio `jeweller`"
    } else {
        "studio `soft`"
    };
    assert!(notes.contains(preset), "{file}: {notes}");
    assert_eq!(
        notes.contains("white floor added"),
        glass,
        "{file}: {notes}"
    );
    render(dir, file, "cut.png", &["--background", "transparent"]);
    let lit = image::open(dir.join("lit.png")).expect("decode").to_rgb8();
    let cut = image::open(dir.join("cut.png")).expect("decode").to_rgba8();

    // Coverage: the bounding box of pixels a camera ray hits on the model.
    let covered = |x: u32, y: u32| cut.get_pixel(x, y).0[3] > 0;
    let (mut x0, mut y0, mut x1, mut y1, mut count) = (W, H, 0, 0, 0u32);
    for y in 0..H {
        for x in 0..W {
            if covered(x, y) {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
                count += 1;
            }
        }
    }
    let fraction = f64::from(count) / f64::from(W * H);
    let (bw, bh) = (f64::from(x1 + 1 - x0), f64::from(y1 + 1 - y0));
    // The framing fits the model to 0.8 of the limiting dimension (tests/cli/framing.rs checks
    // that to a pixel); here only "sensible": between half and all of it, and a tenth to
    // three quarters of the pixels (a gem's outline is round, a box's is a hexagon).
    let span = (bw / f64::from(W)).max(bh / f64::from(H));
    assert!((0.5..=0.95).contains(&span), "{file}: span {span:.3}");
    assert!(
        (0.1..=0.75).contains(&fraction),
        "{file}: coverage {fraction:.3}"
    );
    assert!(
        x0 > 0 && y0 > 0 && x1 < W - 1 && y1 < H - 1,
        "{file}: model touches an edge"
    );
    // Centred: the box's centre within 10 % of the image centre on each axis.
    let (cx, cy) = (f64::from(x0 + x1) / 2.0, f64::from(y0 + y1) / 2.0);
    assert!(
        (cx / f64::from(W - 1) - 0.5).abs() < 0.1 && (cy / f64::from(H - 1) - 0.5).abs() < 0.1,
        "{file}: centre ({cx}, {cy})"
    );

    // Non-black: the model itself is lit (mean sRGB value over its pixels), and so is the
    // image as a whole. 0.1 in sRGB is about 1 % of white in linear light; an unlit file
    // without the studio renders exactly 0 (tests/gems/studio.rs).
    let on_model = mean_where(&lit, covered);
    let overall = mean_where(&lit, |_, _| true);
    assert!(on_model > 0.1, "{file}: model mean {on_model:.3}");
    assert!(overall > 0.1, "{file}: image mean {overall:.3}");
    eprintln!(
        "{file}: span {span:.3}, coverage {fraction:.3}, centre ({cx:.1}, {cy:.1}), \
         model mean {on_model:.3}, image mean {overall:.3}"
    );
    if glass {
        // The floor below the model (the bottom rows under its box) is lit.
        let floor = mean_where(&lit, |x, y| y > y1 && x >= x0 && x <= x1);
        assert!(floor > 0.1, "{file}: floor mean {floor:.3}");
    }
}

#[test]
fn files_without_camera_or_light_render_framed_and_lit() {
    let dir = common::scratch_dir("drop_in");
    for (cut, stone, file) in [
        ("round", "diamond", "round.glb"),
        ("emerald", "sapphire", "emerald.glb"),
    ] {
        let o = iris(
            &["gem", "--cut", cut, "--stone", stone, "--bare", "-o", file],
            &dir,
        );
        assert!(o.status.success(), "{}", stderr(&o));
        check(&dir, file, true);
    }
    // An opaque box (OBJ, default material), 2 × 1 × 1 units, off the origin.
    let (p, t) = common::cuboid([2.0, 1.0, 1.0], [11.0, 5.5, 0.5]);
    common::write_obj(&dir, "box", &p, &t);
    check(&dir, "box.obj", false);
}
