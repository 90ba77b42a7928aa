//! The picture's error ([`iris::output::display`]): what `iris render` judges a PNG by.
//! - Raw: the display estimate from two half images reads the picture's error against a
//!   reference of 16× the samples (another seed) within 1.5× either way, under ACES at
//!   automatic exposure and three stops brighter, clamped (clipping in the light's
//!   reflections and on the lit floor); the unit tests of [`iris::output::display`] check
//!   clipping and slopes by hand.
//! - Denoised, through `iris render` on the gallery's diamond: the report's `display_est`
//!   of the denoised PNG is not optimistic by more than 1.5× against its `display_rmse`
//!   (the written picture against a long reference's picture, bias included).
//! - The stop: a PNG stops on the display estimate and says so.

use crate::common;

use iris::camera::Camera;
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::output::display::Picture;
use iris::output::{Background, DisplayOptions, Exposure, ToneMap};
use iris::render::{Film, RenderSettings};
use iris::sampler::SamplerKind;

const W: u32 = 96;
const H: u32 = 64;

/// The path tracer's film of the caustic sphere's stage under its 60 cm area light with
/// the sphere made white Lambert: noise with light tails (next-event estimation to a large
/// light, no caustic), the case the half-buffer argument describes. (Through glass, paths
/// that find the light by chance are rare and bright: both halves of a few samples miss
/// most of them, an estimate from halves reads low there, and the time limit is the
/// safety net: `iris::app::budget`.) Independent samples: each half is a plain Monte Carlo
/// estimate, as a second seed is.
fn render(spp: u32, seed: u64) -> Film {
    let (mut desc, cam) = iris::assets::bench::caustic_sphere(Some(0.3));
    for m in &mut desc.materials {
        if m.transmission > 0.0 {
            *m = common::white_lambert();
        }
    }
    let scene = common::build_scene(desc);
    let s = RenderSettings {
        sampler: SamplerKind::Independent,
        ..common::render_settings((W, H), spp, seed, 0)
    };
    let integrator = Integrator::new(Method::Path, 16, &PhotonSettings::default()).unwrap();
    integrator
        .render_units(&scene, &Camera::new(&cam, W, H), &s, None, None)
        .unwrap()
        .0
}

#[test]
fn the_display_estimate_reads_the_pictures_error_against_a_reference() {
    let spp = 64;
    let film = render(spp, 3);
    let reference = render(16 * spp, 4).mean();
    let (a, b) = film.halves();
    let image = film.mean();
    let picture = |exposure, tonemap| {
        let display = DisplayOptions { exposure, tonemap };
        Picture::new(display, Background::Environment, None)
    };
    // ACES at automatic exposure, and the same picture three stops brighter and clamped:
    // the caustic and the light's reflections clip to white there.
    let aces = picture(Exposure::Auto, ToneMap::Aces);
    let bright = picture(Exposure::Ev(3.0), ToneMap::Clamp);
    let mut errors = Vec::new();
    for (name, pic) in [("aces", aces), ("clipped", bright)] {
        let est = pic.estimate(&a, &b).unwrap();
        // The reference's own noise adds 1/16 of the image's variance to the comparison.
        let actual = pic.error(&image, &reference).unwrap() / (1.0f64 + 1.0 / 16.0).sqrt();
        let ratio = est / actual;
        eprintln!("{name}: estimate {est:.5}, against the reference {actual:.5} ({ratio:.3})");
        assert!(
            (1.0 / 1.5..1.5).contains(&ratio),
            "{name}: estimate {est:.5} vs {actual:.5}"
        );
        errors.push((est, actual));
    }
    // The two pictures' errors differ (their slopes do), and each estimate follows its own.
    assert!((errors[1].1 / errors[0].1 - 1.0).abs() > 0.1, "{errors:?}");
}

#[cfg(feature = "denoise")]
/// `iris render` of `scene` at 160×90 to `out` with `spp` samples, seed `seed`, `denoise`,
/// and the report (with `reference`, if given); its summary.
fn render_file(
    scene: &std::path::Path,
    out: &std::path::Path,
    (spp, seed, denoise): (u32, u64, iris::denoise::DenoiseMode),
    reference: Option<&std::path::Path>,
) -> iris::app::RenderSummary {
    let mut opts = iris::app::RenderOptions {
        size: Some((160, 90)),
        spp,
        seed,
        threads: 2,
        quiet: true,
        denoise,
        ..iris::app::RenderOptions::new(scene, Some(out))
    };
    opts.measure.report = Some(out.with_extension("csv"));
    opts.measure.reference = reference.map(std::path::Path::to_path_buf);
    iris::app::render_command(&opts).expect("render")
}

#[cfg(feature = "denoise")]
#[test]
fn the_denoised_pngs_estimate_is_not_optimistic_against_a_reference() {
    // The gallery's diamond on the jeweller studio and floor (hybrid, spectral, denoised
    // PNG) at 32 spp, against its raw render at 16× the samples (another seed, written as
    // EXR for `--reference`): the report's last row has the picture's estimate and its
    // error against the reference's picture, the denoiser's blur included.
    use iris::denoise::DenoiseMode;
    let dir = common::scratch_dir("display_error_gem");
    let scene =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gems/round_diamond.glb");
    let reference = dir.join("reference.exr");
    render_file(&scene, &reference, (512, 1001, DenoiseMode::Off), None);
    let png = dir.join("diamond.png");
    let s = render_file(&scene, &png, (32, 1, DenoiseMode::Auto), Some(&reference));
    let last = s.rows.last().expect("a report row");
    let (est, actual) = (
        last.display_estimate.expect("the PNG's estimate"),
        last.display_error
            .expect("the PNG's error against the reference"),
    );
    eprintln!("denoised diamond at 32 spp: estimate {est:.5}, against the reference {actual:.5}");
    assert!(s.denoised.is_some(), "the PNG is denoised");
    assert!(
        est >= actual / 1.5,
        "optimistic: estimate {est:.5} vs {actual:.5}"
    );
    assert!(
        est <= 3.0 * actual,
        "far too pessimistic: {est:.5} vs {actual:.5}"
    );
    // The report carries both estimates: the linear one (`est_*`) and the picture's.
    let text = std::fs::read_to_string(png.with_extension("csv")).unwrap();
    assert!(text
        .lines()
        .next()
        .unwrap()
        .ends_with(",display_est,display_rmse"));
}
