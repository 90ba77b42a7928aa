//! Drop-in preview lighting (issue 8): the studio presets (`--studio`) light a bare gem that
//! the old directional default lights left black, and `--ground` adds a white floor that
//! receives light. Renders are tiny (64×48, 2 spp, Whitted, 2 threads) so the file runs in
//! seconds; thresholds are justified beside each assertion.

use crate::common;

use iris::accel::Backend;
use iris::app::{render_command, PreviewOptions, RenderOptions, RenderSummary};
use iris::authoring::cuts::preview::{write_gem, GemSpec};
use iris::authoring::cuts::Cut;
use iris::authoring::stones::Stone;
use iris::image::ImageRgb;
use iris::output::read_exr;
use iris::prepare::Note;
use iris::studio::{ground, GroundMode, Studio};
use std::path::{Path, PathBuf};

const W: u32 = 64;
const H: u32 = 48;

/// A bare round-brilliant diamond (no camera, light, floor or environment).
fn bare_gem(dir: &Path) -> PathBuf {
    let path = dir.join("bare_diamond.glb");
    write_gem(
        &path,
        &GemSpec {
            cut: Cut::Round,
            stone: Stone::Diamond,
            size_mm: 6.5,
            bare: true,
        },
    )
    .expect("write gem");
    path
}

fn render(
    scene: &Path,
    out: &Path,
    accel: Backend,
    studio: Studio,
    ground: GroundMode,
    seed: u64,
) -> (ImageRgb, RenderSummary) {
    let opts = RenderOptions {
        size: Some((W, H)),
        spp: 2,
        max_depth: 16,
        accel,
        seed,
        threads: 2,
        quiet: true,
        ..RenderOptions::new(scene, Some(out))
    };
    let preview = PreviewOptions {
        studio: Some(studio),
        ground,
        ..Default::default()
    };
    let s = render_command(&RenderOptions { preview, ..opts }).expect("render");
    (read_exr(out).expect("read exr"), s)
}

fn lum(c: glam::Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

fn mean_lum(px: &[glam::Vec3]) -> f32 {
    px.iter().map(|&c| lum(c)).sum::<f32>() / px.len().max(1) as f32
}

#[test]
fn bare_gem_sparkles_under_the_default_studio_on_both_backends() {
    let dir = common::scratch_dir("studio_bare");
    let gem = bare_gem(&dir);
    // Without a floor the background is the studio gradient below the horizon (≤ 0.35
    // nits for `soft`: the auto-framed camera looks down, so escaping camera rays go
    // below the horizon). Pixels above 1 nit (≈ 3× that) can only be softboxes (6–12
    // nits) seen through or in the stone: the sparkle.
    let bright = |img: &ImageRgb| img.data.iter().filter(|&&c| lum(c) > 1.0).count();
    for backend in common::backends() {
        let (img, s) = render(
            &gem,
            &dir.join("soft.exr"),
            backend,
            Studio::Soft,
            GroundMode::Off,
            1,
        );
        assert!(img.data.iter().all(|c| c.is_finite()));
        let mean = mean_lum(&img.data);
        let sparkle = bright(&img) as f32 / img.data.len() as f32;
        eprintln!("{backend:?}: soft mean {mean} nits, sparkle fraction {sparkle}");
        assert!(
            s.notes.iter().any(|n| n.contains("studio `soft`")),
            "{:?}",
            s.notes
        );
        // Mean: the background alone is ≥ 0.15 nits everywhere.
        assert!(mean > 0.15, "{backend:?}: mean {mean}");
        // The stone covers roughly a fifth of the frame; at least a tenth of that must
        // flash.
        assert!(sparkle > 0.02, "{backend:?}: sparkle fraction {sparkle}");
        // The old default (directional key and fill, no environment) leaves the clear
        // stone black against a black background: the regression this preset fixes.
        let (old, _) = render(
            &gem,
            &dir.join("none.exr"),
            backend,
            Studio::None,
            GroundMode::Off,
            1,
        );
        let old_mean = mean_lum(&old.data);
        eprintln!("{backend:?}: --studio none mean {old_mean}");
        assert!(
            old_mean < 0.01 * mean,
            "{backend:?}: none {old_mean} vs {mean}"
        );
    }
}

#[test]
fn ground_on_adds_a_lit_floor_below_the_model() {
    let dir = common::scratch_dir("studio_ground");
    let gem = bare_gem(&dir);
    // The bottom fifth of the frame lies below the stone (auto framing centres it).
    let bottom = |img: &ImageRgb| {
        let rows = (img.height * 4 / 5) as usize..img.height as usize;
        let px: Vec<glam::Vec3> = rows
            .flat_map(|y| (0..img.width as usize).map(move |x| (x, y)))
            .map(|(x, y)| img.data[y * img.width as usize + x])
            .collect();
        mean_lum(&px)
    };
    for studio in [Studio::Soft, Studio::Jeweller, Studio::Bright] {
        let (off, _) = render(
            &gem,
            &dir.join("off.exr"),
            Backend::Bvh,
            studio,
            GroundMode::Off,
            1,
        );
        let (on, s) = render(
            &gem,
            &dir.join("on.exr"),
            Backend::Bvh,
            studio,
            GroundMode::On,
            1,
        );
        let (b_off, b_on) = (bottom(&off), bottom(&on));
        eprintln!("{studio:?}: bottom rows {b_off} nits without floor, {b_on} with");
        assert!(
            s.notes.iter().any(|n| n.contains("--ground on")),
            "{:?}",
            s.notes
        );
        // A white (0.8) Lambertian floor under ≥ 4 lux of environment light alone has
        // radiance ≥ 0.8·4/π ≈ 1 nit; the ground below the horizon of the gradient is
        // 0.15 (soft), 0.004 (jeweller) and 1.5 (bright, where the key adds 8 lux and
        // the softboxes more). Ask for 30 % more than without.
        assert!(b_on > 1.3 * b_off, "{studio:?}: {b_on} vs {b_off}");
    }
}

#[test]
fn ground_auto_on_for_a_bare_stone_off_for_a_scene_with_a_floor() {
    let dir = common::scratch_dir("studio_auto");
    let bare = iris::load::load_scene(&bare_gem(&dir)).expect("load bare");
    let (add, note) = ground::decide(&bare, GroundMode::Auto);
    assert!(add, "{note:?}");
    let preview = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gems/round_diamond.glb");
    let with_floor = iris::load::load_scene(&preview).expect("load preview");
    let (add, note) = ground::decide(&with_floor, GroundMode::Auto);
    let note = Note::Floor(note).to_string();
    assert!(!add, "{note}");
    assert!(note.contains("surface of its own"), "{note}");
    // `on` adds one anyway; `off` never.
    assert!(ground::decide(&with_floor, GroundMode::On).0);
    assert!(!ground::decide(&bare, GroundMode::Off).0);
    // The auto floor is framed out of the camera's bounds: the scene bounds grow, the
    // subject bounds stay the stone's.
    let prepared = iris::prepare::prepare(
        &dir.join("bare_diamond.glb"),
        &iris::prepare::PrepareOptions {
            accel: Backend::Bvh,
            preview: PreviewOptions {
                ground: GroundMode::Auto,
                ..PreviewOptions::default()
            },
            ..Default::default()
        },
    )
    .expect("prepare");
    let note = prepared
        .notes
        .iter()
        .find(|n| matches!(n, Note::Floor(_)))
        .map(ToString::to_string)
        .unwrap_or_default();
    assert!(note.contains("white floor added"), "{note}");
    let scene = &prepared.scene;
    let size = |b: (glam::Vec3, glam::Vec3)| (b.1 - b.0).length();
    assert!(size(scene.bounds()) > 10.0 * size(scene.subject_bounds()));
    assert_eq!(
        scene.bounds().0.y,
        scene.subject_bounds().0.y,
        "floor touches the culet"
    );
}

#[test]
fn a_file_with_lights_keeps_them() {
    // The gem preview brings its own light (two emissive panels and an environment): the
    // default studio adds nothing (the authored note says why). An explicit `--studio
    // jeweller` asks for the studio: its two keys join the file's lights, which
    // stay.
    let dir = common::scratch_dir("studio_lit");
    let preview = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gems/round_diamond.glb");
    let prepared = |studio: Option<Studio>| {
        let opts = RenderOptions {
            size: Some((W, H)),
            accel: Backend::Bvh,
            preview: PreviewOptions {
                studio,
                ..Default::default()
            },
            ..RenderOptions::new(&preview, None)
        };
        iris::prepare::prepare(&preview, &opts.prepare_options(None)).expect("prepare")
    };
    let plain = prepared(None);
    let notes: Vec<String> = plain.notes().iter().map(ToString::to_string).collect();
    assert!(!notes.iter().any(|n| n.contains("studio `")), "{notes:?}");
    assert!(
        notes.iter().any(|n| n.contains("rendered as authored")),
        "{notes:?}"
    );
    let (_, s) = render(
        &preview,
        &dir.join("lit.exr"),
        Backend::Bvh,
        Studio::Jeweller,
        GroundMode::Auto,
        1,
    );
    assert!(
        s.notes
            .iter()
            .any(|n| n.contains("--studio jeweller: studio environment and 2 key light(s) added")),
        "{:?}",
        s.notes
    );
    let jeweller = prepared(Some(Studio::Jeweller));
    assert_eq!(
        jeweller.scene.lights().len(),
        plain.scene.lights().len() + 2
    );
    assert_eq!(
        jeweller.scene.area_lights().len(),
        plain.scene.area_lights().len(),
        "the file's emissive panels stay"
    );
}

#[test]
fn same_seed_same_image() {
    let dir = common::scratch_dir("studio_determinism");
    let gem = bare_gem(&dir);
    for studio in [Studio::Soft, Studio::Jeweller] {
        let (a, _) = render(
            &gem,
            &dir.join("a.exr"),
            Backend::Bvh,
            studio,
            GroundMode::Auto,
            7,
        );
        let (b, _) = render(
            &gem,
            &dir.join("b.exr"),
            Backend::Bvh,
            studio,
            GroundMode::Auto,
            7,
        );
        assert_eq!(a.data, b.data, "{studio:?}");
    }
}

#[test]
fn bad_names_are_clear_errors() {
    let e = Studio::parse("disco").unwrap_err().to_string();
    assert!(
        e.contains("disco") && e.contains("soft, jeweller, bright, tent or none"),
        "{e}"
    );
    let e = GroundMode::parse("maybe").unwrap_err().to_string();
    assert!(e.contains("auto, on or off"), "{e}");
    let dir = common::scratch_dir("studio_cli");
    let gem = bare_gem(&dir);
    let gem = gem.to_str().unwrap();
    for (flag, value, expect) in [
        ("--studio", "disco", "jeweller"),
        ("--ground", "maybe", "auto, on or off"),
    ] {
        let o = common::iris(
            &[
                "render", gem, "--size", "8x6", "--spp", "1", flag, value, "-o", "x.png",
            ],
            &dir,
        );
        assert!(!o.status.success(), "{flag} {value}");
        let err = common::stderr(&o);
        assert!(err.contains(expect), "{err}");
        assert!(
            !dir.join("x.png").exists(),
            "nothing written on a usage error"
        );
    }
    let o = common::iris(
        &[
            "render", gem, "--size", "8x6", "--spp", "1", "--studio", "Bright", "--ground", "on",
            "-o", "ok.png",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", common::stderr(&o));
    assert!(common::stderr(&o).contains("studio `bright`"));
}
