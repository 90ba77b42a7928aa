//! Every glTF/GLB and OBJ scene in the shared third-party assets renders (small, few
//! samples) on the default backend without NaN or infinite pixels, and not entirely black:
//! with `--method whitted` as the file is lit, and with `--method path` under a uniform
//! environment as well (so every BSDF, environment sampling and MIS run on every file), and
//! with `--method sppm` and `--method photon` under that environment (photons from every
//! light type, including the environment, through every file's materials). The same runs
//! cover the project's own assets/; a scene with scattering media renders with the two
//! methods that trace them, the path tracer and the hybrid. Every run's film guard counts 0
//! bad (NaN/inf) samples.

use crate::common;

use glam::Vec3;
use iris::accel::Backend;
use iris::app::{render_command, RenderOptions};
use iris::integrator::{Method, PhotonSettings};
use iris::light::env::Environment;
use iris::output::{read_exr, DisplayOptions};
use std::path::{Path, PathBuf};

#[test]
fn every_shared_scene_renders_finite_pixels() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let files = common::files_with_ext(&shared, &common::SCENE_EXTS);
    assert!(files.len() >= 20, "found only {} scenes", files.len());
    render_all(&files, "render_assets");
}

#[test]
fn every_project_asset_renders_finite_pixels() {
    let files = common::files_with_ext(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("assets"),
        &common::SCENE_EXTS,
    );
    assert!(files.len() >= 8, "found only {} scenes", files.len());
    render_all(&files, "render_project_assets");
}

/// Renders every file with every method (see the module docs) and checks the images and
/// the film's bad-sample count.
fn render_all(files: &[PathBuf], scratch: &str) {
    let dir = common::scratch_dir(scratch);
    let env = Some(Environment::Uniform {
        radiance: Vec3::splat(0.5),
    });
    let photons = |photons, passes| PhotonSettings {
        photons,
        passes,
        ..PhotonSettings::default()
    };
    let runs = [
        (Method::Whitted, 2, None, PhotonSettings::default()),
        (Method::Path, 4, env.clone(), PhotonSettings::default()),
        (Method::Sppm, 1, env.clone(), photons(4000, 2)),
        (Method::Photon, 1, env.clone(), photons(20_000, 1)),
    ];
    // Scenes with scattering media: the two methods that trace them (the others refuse,
    // `tests/optics/media.rs`).
    let media_runs = [
        (Method::Path, 4, env.clone(), PhotonSettings::default()),
        (Method::Hybrid, 2, env.clone(), photons(4000, 2)),
    ];
    for (i, scene) in files.iter().enumerate() {
        let desc = iris::load::load_scene(scene).expect("a project asset loads");
        let media = desc.fog.is_some() || desc.materials.iter().any(|m| m.scatter.is_some());
        let runs = if media {
            media_runs.to_vec()
        } else {
            runs.to_vec()
        };
        for (method, spp, env, photon) in runs {
            let out = dir.join(format!("{i}-{method:?}.exr"));
            let opts = RenderOptions {
                scene: scene.clone(),
                output: Some(out.clone()),
                size: Some((48, 36)),
                spp,
                method,
                max_depth: 64,
                time_limit: None,
                checkpoint: None,
                watch: false,
                photon,
                accel: Backend::Auto,
                seed: 1,
                sampler: Default::default(),
                threads: 2,
                camera: None,
                look_at: None,
                display: DisplayOptions::default(),
                quiet: true,
                spectral: Default::default(),
                polarization: Default::default(),
                polarizer: None,
                env: env.map(Some),
                fog: None,
                measure: Default::default(),
                preview: Default::default(),
                looks: Vec::new(),
                explain: false,
                // The EXR keeps the raw image; the denoised layer (auxiliary pass through
                // every asset's glass) must come out finite too.
                denoise: if iris::denoise::available() {
                    iris::denoise::DenoiseMode::On
                } else {
                    iris::denoise::DenoiseMode::Off
                },
                adaptive: Default::default(),
                spin: None,
                exr_copy: None,
                shard: None,
            };
            let summary =
                render_command(&opts).unwrap_or_else(|e| panic!("{}: {e}", scene.display()));
            if let Some(d) = &summary.denoised {
                let bad = d.data.iter().filter(|p| !p.is_finite()).count();
                assert_eq!(
                    bad,
                    0,
                    "{} {method:?}: non-finite denoised",
                    scene.display()
                );
            }
            assert_eq!(
                summary.stats.bad_samples,
                0,
                "{} {method:?}: NaN/inf samples",
                scene.display()
            );
            let img = read_exr(&out).unwrap();
            let bad = img.data.iter().filter(|p| !p.is_finite()).count();
            assert_eq!(
                bad,
                0,
                "{} {method:?}: {bad} non-finite pixels",
                scene.display()
            );
            assert!(
                img.data.iter().any(|p| p.max_element() > 0.0),
                "{} {method:?}: black image",
                scene.display()
            );
        }
    }
}
