//! The kernel against the scalar path tracer on every scene in the repository's assets/
//! that it takes (in RGB and in spectral transport, as each file is authored: its camera,
//! its lights, no drop-in studio or environment), with the bounds of [`super::tests`]'
//! agreement test over 8×8-pixel blocks.

use super::tests::{
    assert_agrees, assert_near_same_seed, kernel_image_through, scalar_image_through,
};
use super::tests::{settings, H, W};
use super::*;
use crate::accel::Backend;
use crate::render::RenderSettings;
use std::path::{Path, PathBuf};

/// The .glb files under `dir`, sorted.
fn scenes(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("assets/ is in the repository") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            out.extend(scenes(&path));
        } else if path.extension().is_some_and(|e| e == "glb") {
            out.push(path);
        }
    }
    out.sort();
    out
}

/// Every asset the kernel takes agrees with the scalar path tracer: per 8×8-pixel block and
/// channel (36 comparisons a scene) within 5 σ from the halves' variance, the image mean
/// within 4 standard errors, at 128 samples per pixel each; and at the same seed the
/// kernel's image is the scalar one up to float rounding (at most 7 of 768 pixels more than
/// 1e-4 apart, [`super::tests`]' bound), handed-over paths included. At least ten assets
/// qualify (lanes meeting their layered, textured, rough or dispersive materials hand over to the
/// scalar vertex), so a change that refuses them, or breaks what they need, fails here.
#[test]
fn every_asset_the_kernel_takes_agrees_with_the_scalar_path_tracer() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let mut taken = Vec::new();
    for path in scenes(&root) {
        let (scene, _) = crate::prepare::input::load(&path, Backend::Auto).expect("loads");
        let aspect = W as f32 / H as f32;
        let (desc, _) =
            crate::prepare::camera_choice::choose_camera(&scene, None, aspect).expect("a camera");
        let cam = Camera::new(&desc, W, H);
        // A file without lights is lit by the drop-in studio, which this test leaves out.
        let lit = !(scene.lights().is_empty()
            && scene.area_lights().is_empty()
            && scene.environment().is_none());
        if !lit || qualify(&scene, cam.is_perspective(), false).is_err() {
            continue;
        }
        let name = path
            .strip_prefix(&root)
            .unwrap_or(&path)
            .display()
            .to_string();
        for spectral in [false, true] {
            let at = |seed| RenderSettings {
                spectral,
                ..settings(128, seed)
            };
            let k = kernel_image_through(&scene, &cam, &at(31), 16);
            let s = scalar_image_through(&scene, &cam, &at(32));
            let same_seed = scalar_image_through(&scene, &cam, &at(31)).0;
            let what = format!("{name}, {}", if spectral { "spectral" } else { "RGB" });
            assert_agrees(&what, (&k, &s, 8), None);
            assert_near_same_seed(&what, (&k.0, &same_seed), spectral);
        }
        taken.push(name);
    }
    assert!(taken.len() >= 10, "the kernel takes only {taken:?}");
}
