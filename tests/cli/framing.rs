//! Automatic framing of files without a camera (issue 8, drop-in preview item 1): for a
//! gem, a flat plate and a long rod at 1e-4, 1 and 1e4 m, every `--view` frames the whole
//! model, centred, with its projected bounding box spanning a sensible fraction of the
//! image, measured two ways: by projecting the vertices with the camera, and from the
//! coverage (alpha) mask of the camera rays.

use crate::common;

use iris::accel::Backend;
use iris::app::{self, PreviewOptions, RenderOptions};
use iris::camera::Camera;
use iris::framing::{projected_box, View, FILL, VIEWS};
use iris::output::Background;
use iris::render::RenderSettings;
use iris::scene::Scene;
use std::path::Path;

/// A named test model: (name, positions, triangles).
type Model = (String, Vec<[f32; 3]>, Vec<[u32; 3]>);

/// The test models at `scale` metres.
fn models(scale: f32) -> Vec<Model> {
    let gem = iris::authoring::cuts::Cut::Round.mesh(f64::from(scale));
    let off = [0.3 * scale, -0.2 * scale, 0.1 * scale];
    let mut out = vec![(
        format!("gem@{scale}"),
        gem.positions
            .iter()
            .map(|p| [p.x + off[0], p.y + off[1], p.z + off[2]])
            .collect(),
        gem.indices.clone(),
    )];
    let (p, t) = common::cuboid([scale, 0.02 * scale, 0.7 * scale], off);
    out.push((format!("plate@{scale}"), p, t));
    let (p, t) = common::cuboid([2.0 * scale, 0.04 * scale, 0.04 * scale], off);
    out.push((format!("rod@{scale}"), p, t));
    out
}

fn settings(w: u32, h: u32) -> RenderSettings {
    RenderSettings::quiet_rgb((w, h), 1, 1, 2)
}

/// Bounding box of the covered pixels as fractions of the image: (span x, span y, centre
/// offset x, centre offset y).
fn mask_box(scene: &Scene, view: Option<View>, w: u32, h: u32) -> (f64, f64, f64, f64) {
    let (desc, note) =
        app::choose_camera_view(scene, None, view, w as f32 / h as f32).expect("camera");
    assert!(note.is_some(), "auto framing is announced");
    let cam = Camera::new(&desc, w, h);
    let s = settings(w, h);
    let pool = iris::render::thread_pool(&s).expect("pool");
    let cov = pool.install(|| iris::render::coverage::coverage(scene, &cam, &s, 1));
    let (mut x0, mut x1, mut y0, mut y1) = (u32::MAX, 0, u32::MAX, 0);
    for (i, a) in cov.alpha.iter().enumerate() {
        if *a > 0.0 {
            let (x, y) = (i as u32 % w, i as u32 / w);
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
    }
    assert!(x0 <= x1, "nothing covered");
    let (fw, fh) = (f64::from(w), f64::from(h));
    (
        f64::from(x1 - x0 + 1) / fw,
        f64::from(y1 - y0 + 1) / fh,
        (f64::from(x0 + x1 + 1) / 2.0 - fw / 2.0) / fw,
        (f64::from(y0 + y1 + 1) / 2.0 - fh / 2.0) / fh,
    )
}

#[test]
fn every_view_frames_gems_plates_and_rods_at_every_scale() {
    let dir = common::scratch_dir("framing_models");
    let (w, h) = (120u32, 90u32);
    for scale in [1e-4f32, 1.0, 1e4] {
        for (name, p, t) in models(scale) {
            let path = common::write_obj(&dir, &name, &p, &t);
            let (scene, _) = app::load(&path, Backend::Auto).expect("load");
            assert!(scene.cameras().is_empty());
            for view in [None].into_iter().chain(VIEWS.map(Some)) {
                // Projection of the vertices: exact fit, 80 % in the limiting direction.
                let (desc, _) =
                    app::choose_camera_view(&scene, None, view, w as f32 / h as f32).unwrap();
                let (lo, hi) =
                    projected_box(scene.positions(), &desc, w as f32 / h as f32).expect("in front");
                let span = 0.5 * (hi - lo).max_element();
                // f32 camera matrices at 1e4 m: 1e-3 of the frame is far below a pixel.
                assert!((span - FILL).abs() < 1e-3, "{name} {view:?}: {span}");
                // The mask: the covered pixels' box spans 60–90 % of the image in its
                // limiting direction (80 % ± 1 pixel of rasterisation expected), and is
                // centred within 3 % (a pixel and a half at 90 px).
                let (sx, sy, cx, cy) = mask_box(&scene, view, w, h);
                let fill = sx.max(sy);
                eprintln!("{name} {view:?}: mask fill {fill:.3} ({sx:.3} × {sy:.3})");
                assert!((0.6..=0.9).contains(&fill), "{name} {view:?}: fill {fill}");
                assert!(
                    (fill - FILL).abs() <= 2.0 / f64::from(h),
                    "{name} {view:?}: {fill}"
                );
                assert!(sx <= 0.9 && sy <= 0.9, "{name} {view:?}: {sx} {sy}");
                assert!(
                    cx.abs() < 0.03 && cy.abs() < 0.03,
                    "{name} {view:?}: off centre {cx} {cy}"
                );
            }
        }
    }
}

fn render_opts(scene: &Path, out: &Path) -> RenderOptions {
    RenderOptions {
        size: Some((80, 60)),
        spp: 2,
        max_depth: 16,
        seed: 3,
        threads: 2,
        quiet: true,
        ..RenderOptions::new(scene, Some(out))
    }
}

#[test]
fn a_file_with_no_camera_and_no_light_renders_a_lit_framed_model() {
    // A diffuse plate (the OBJ default material) with no camera and no light: the default
    // lights light it, the automatic camera frames it.
    let dir = common::scratch_dir("framing_render");
    let (p, t) = common::cuboid([1.0, 0.02, 0.7], [0.0, 0.0, 0.0]);
    let scene = common::write_obj(&dir, "plate", &p, &t);
    let out = dir.join("plate.png");
    let preview = PreviewOptions {
        view: None,
        background: Background::Transparent,
        ..Default::default()
    };
    let s = app::render_command(&RenderOptions {
        preview,
        ..render_opts(&scene, &out)
    })
    .expect("render");
    assert!(
        s.notes.iter().any(|n| n.contains("no camera")),
        "{:?}",
        s.notes
    );
    let img = image::open(&out).expect("png").to_rgba8();
    let covered: Vec<_> = img.pixels().filter(|p| p.0[3] == 255).collect();
    let frac = covered.len() as f64 / f64::from(80 * 60);
    // A plate seen from 35° above covers a good part of the frame (about a third).
    assert!(frac > 0.15, "covered fraction {frac}");
    let lit = covered
        .iter()
        .filter(|p| p.0[..3].iter().any(|&c| c > 20))
        .count();
    assert!(
        lit * 2 > covered.len(),
        "{lit} of {} covered pixels lit",
        covered.len()
    );
}

#[test]
fn framed_renders_are_deterministic() {
    let dir = common::scratch_dir("framing_determinism");
    let gem = iris::authoring::cuts::Cut::Round.mesh(1.0);
    let p: Vec<[f32; 3]> = gem.positions.iter().map(|v| v.to_array()).collect();
    let tris = gem.indices.clone();
    let scene = common::write_obj(&dir, "gem", &p, &tris);
    let mut bytes = Vec::new();
    for (i, threads) in [1usize, 2].into_iter().enumerate() {
        let out = dir.join(format!("gem{i}.png"));
        let mut opts = render_opts(&scene, &out);
        opts.threads = threads;
        opts.env = Some(Some(iris::light::env::Environment::Uniform {
            radiance: glam::Vec3::splat(0.7),
        }));
        let preview = PreviewOptions {
            view: Some(View::Top),
            background: Background::Transparent,
            ..Default::default()
        };
        app::render_command(&RenderOptions { preview, ..opts }).expect("render");
        bytes.push(std::fs::read(&out).expect("read"));
    }
    assert_eq!(
        bytes[0], bytes[1],
        "same seed, different threads: same bytes"
    );
}

#[test]
fn view_and_camera_together_are_a_usage_error() {
    let dir = common::scratch_dir("framing_conflict");
    let (p, t) = common::cuboid([1.0, 1.0, 1.0], [0.0, 0.0, 0.0]);
    let scene = common::write_obj(&dir, "cube", &p, &t);
    let (scene, _) = app::load(&scene, Backend::Auto).unwrap();
    let e = app::choose_camera_view(&scene, Some("0"), Some(View::Front), 1.0).unwrap_err();
    assert!(e.to_string().contains("--view front"), "{e}");
}
