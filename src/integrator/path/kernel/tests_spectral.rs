//! The kernel in spectral transport (4 wavelengths a lane) against the scalar path tracer:
//! equal at the same seed up to float rounding (the same wavelengths, the same numbers, the
//! scalar path's own colour conversions), on clear glass and on dispersive glass where each
//! sample splits into its wavelengths (the sub-paths as the lane's refill), and with the
//! split off (the hero only); in expectation at other seeds; shards merge exactly.

use super::super::Dispersion;
use super::tests::{
    assert_agrees, build, camera, desc, differing_pixels, kernel_image, lambert_floor, path_rules,
    path_vertex, same_seed_difference, scalar_image, settings, H, W,
};
use super::{estimate_at, qualify};
use crate::accel::Backend;
use crate::image::{ExactImage, ImageRgb};
use crate::integrator::Integrator;
use crate::render::{render_batches, Film, Job, Kernel, Prepass, RenderSettings, Starts};
use crate::scene::desc::SceneDesc;
use crate::scene::Scene;
use glam::Vec3;
use std::ops::Range;

/// The test scene with its sphere dispersive: KHR_materials_dispersion 20/Abbe for an Abbe
/// number of 20 (a flint; η 1.5 at the d line).
fn dispersive() -> SceneDesc {
    let mut d = desc(lambert_floor());
    d.materials[1].dispersion = 1.0;
    d
}

/// `spp` samples at `seed`, spectral.
fn spectral(spp: u32, seed: u64) -> RenderSettings {
    RenderSettings {
        spectral: true,
        ..settings(spp, seed)
    }
}

/// The kernel's image equals the scalar one at the same seed up to rounding (as
/// `the_kernel_equals_the_scalar_path_tracer_at_the_same_seed` argues; at most 7 of 768
/// pixels differ by more than 1e-4 relative), in spectral transport on the clear sphere
/// and on the dispersive one, with both samplers.
#[test]
fn the_spectral_kernel_equals_the_scalar_path_tracer_at_the_same_seed() {
    let mut counts = Vec::new();
    for (name, d) in [
        ("clear", desc(lambert_floor())),
        ("dispersive", dispersive()),
    ] {
        let scene = build(d, Backend::Auto);
        assert!(qualify(&scene, true, true).is_ok_and(|t| t.spectral));
        for sampler in crate::sampler::SamplerKind::ALL {
            let s = RenderSettings {
                sampler,
                ..spectral(16, 11)
            };
            counts.push((name, sampler, same_seed_difference(&scene, &s)));
        }
    }
    assert!(
        counts.iter().all(|c| c.2 <= 7),
        "pixels that differ (scene, sampler, count): {counts:?}"
    );
}

/// The kernel's film through the test camera with `dispersion` (the samples `range`; all:
/// `None`).
fn film(
    scene: &Scene,
    s: &RenderSettings,
    dispersion: Dispersion,
    range: Option<Range<u64>>,
) -> Film {
    let tables = qualify(scene, true, s.spectral).expect("qualifies");
    let path = path_vertex(64, dispersion);
    let rules = path_rules(&path, s.spectral);
    let estimate = |starts: &Starts, jobs: &[Job], out: &mut [Vec3]| {
        estimate_at(16, &tables, scene, (starts, jobs), &rules, out)
    };
    let (film, _) =
        render_batches(&camera(), s, range, Prepass::now(), None, estimate).expect("kernel render");
    film
}

/// The scalar path tracer's image with `dispersion`.
fn scalar(scene: &Scene, s: &RenderSettings, dispersion: Dispersion) -> ImageRgb {
    let path = Integrator::Path {
        max_depth: 64,
        dispersion,
        polarization: None,
    };
    let s = &RenderSettings {
        kernel: Kernel::Scalar,
        ..s.clone()
    };
    let (film, _) = path
        .render_units(scene, &camera(), s, None, None)
        .expect("scalar render");
    film.mean()
}

/// With the split off (the hero only past a dispersive interface, ×4 on it) the kernel's
/// image is the scalar one at the same seed up to rounding; and it is not the split image
/// (the hero-only estimator has other noise: some pixel differs), so the test sees which
/// estimator ran.
#[test]
fn keeping_the_hero_only_equals_the_scalar_path_tracer() {
    let scene = build(dispersive(), Backend::Auto);
    let s = spectral(16, 5);
    let hero = film(&scene, &s, Dispersion::HERO, None).mean();
    let n = differing_pixels(&hero, &scalar(&scene, &s, Dispersion::HERO));
    assert!(n <= 7, "{n} pixels differ from the scalar hero-only image");
    let split = film(&scene, &s, Dispersion::ALL, None).mean();
    assert!(
        differing_pixels(&hero, &split) > 7,
        "the split changed nothing"
    );
}

/// On the dispersive sphere, the kernel's image agrees in expectation with the scalar path
/// tracer's at another seed (the bounds of [`super::tests`]' agreement test, 4×4-pixel
/// blocks), and the sphere's caustic carries colour (its channels differ somewhere by more
/// than 10 %: the sub-paths' wavelengths go their own ways).
#[test]
fn dispersive_glass_agrees_with_the_scalar_path_tracer() {
    let scene = build(dispersive(), Backend::Auto);
    let k = kernel_image(&scene, &spectral(256, 41), 16);
    let s = scalar_image(&scene, &spectral(256, 42));
    assert_agrees("dispersive sphere", (&k, &s, 4), None);
    let coloured = k.0.data.iter().any(|p| {
        let grey = p.x.min(p.y).min(p.z);
        p.max_element() > 0.05 && p.max_element() > 1.1 * grey.max(0.0) + 1e-3
    });
    assert!(coloured, "no colour anywhere");
}

/// Shards of a spectral kernel render with split samples merge into the whole bit for
/// bit (a sample's sub-paths run on its lane, whatever the batch).
#[test]
fn spectral_shards_merge_into_the_whole() {
    let scene = build(dispersive(), Backend::Auto);
    let s = spectral(9, 3);
    let whole = film(&scene, &s, Dispersion::ALL, None);
    let mut merged = ExactImage::new(W, H);
    for range in [5..9, 0..4, 4..5] {
        merged.add(&film(&scene, &s, Dispersion::ALL, Some(range)).exact());
    }
    assert_eq!(merged, whole.exact());
}
