//! KHR_texture_transform on every textured material property, end to end through the
//! `iris` binary (EXR out, no denoising; scenes in `textured/features.rs`): a file whose
//! texture carries a transform must render like the same file whose image has the
//! transform baked into its texels ([`texture::bake`]: the same function of uv, exactly),
//! and unlike the file with the untransformed image (so each test can fail).
//!
//! The texture is an 8 × 8 block image (the top-left quadrant on, [`quadrant`]); the
//! transforms are an offset of (2, 1) texels, a quarter turn, a scale of 2 (the baked image
//! is then 16 × 16: the source tiled and turned) and all three at once
//! ([`texture::COMBINED`]). The base colour (read through the one lookup that applies the
//! transform today) is the control, with each part of the transform alone; every other
//! property on the flat quad gets the combination. On the reflector, whose ceiling image
//! photon density estimation blurs, the quadrant moves at its own size instead
//! ([`texture::QUARTER_SHIFT`]: offset and quarter turn).
//!
//! Unit of comparison: the means of 8 × 8-pixel blocks of the 64 × 64 image, per channel,
//! relative to the feature's contrast (the largest spread of one channel's block means over
//! the baked render). Each file renders with its own seed (transformed 1, baked 2,
//! untransformed 3) and the baked file once more with seed 4, so agreement is agreement
//! within noise, not sample correlation. A test asserts, with the measured values in its
//! messages:
//! - noise: baked (seed 4) against baked (seed 2) within half the tolerance, so the
//!   tolerance holds at least twice the seed-to-seed noise of the render settings;
//! - visible: untransformed against baked at least half the contrast apart (measured 1.07
//!   to 1.14 on the flat quad, where the quadrant and its moved image differ over whole
//!   blocks, 0.73 on the reflector);
//! - moved: transformed against baked within the tolerance.
//!
//! Tolerances, from the seed-to-seed noise (largest block difference over channels, as a
//! fraction of the contrast) measured with these settings:
//! - [`TOL`] = 0.1 for the flat quad, path tracer and SPPM. Noise: 5e-5 to 2e-4 (a
//!   directional light through next-event estimation; only pixel-filter positions vary),
//!   0.02 for iridescence at 64 spp (spectral transport: wavelength noise; 0.038 at 16 spp).
//! - [`TOL_REFLECTOR`] = 0.15 for the reflector under SPPM (16 passes of 20 000 photons).
//!   Noise: 0.03 to 0.04 (photon density noise).

use crate::common;
use crate::features;
use crate::render;
use crate::texture;

use features::*;
use render::{contrast, max_diff, render};
use serde_json::json;
use texture::{bake, blocks, Transform, COMBINED, QUARTER_SHIFT};

/// Texels per side of the source images.
const N: u32 = 8;
const SIZE: &str = "64x64";

/// Tolerance on the flat quad (see the module doc).
const TOL: f64 = 0.1;
/// Tolerance on the reflector (see the module doc).
const TOL_REFLECTOR: f64 = 0.15;

/// The path tracer, 16 samples per pixel.
const PATH: &[&str] = &["--method", "path", "--spp", "16"];
/// The path tracer, 64 samples per pixel (spectral features).
const PATH_64: &[&str] = &["--method", "path", "--spp", "64"];
/// SPPM, 16 passes of one photon per pixel.
const SPPM: &[&str] = &["--method", "sppm", "--passes", "16"];
/// SPPM, 16 passes of 20 000 photons.
const SPPM_REFLECTOR: &[&str] = &["--method", "sppm", "--passes", "16", "--photons", "20000"];

/// An offset of (2, 1) texels of the 8-texel source.
const OFFSET: Transform = Transform {
    offset: [0.25, 0.125],
    rotation: 0.0,
    scale: [1.0, 1.0],
};
/// A quarter turn (counter-clockwise in the image) about the texture origin.
const ROTATION: Transform = Transform {
    offset: [0.0, 0.0],
    rotation: std::f32::consts::FRAC_PI_2,
    scale: [1.0, 1.0],
};
/// Scale 2: the source repeats twice across the quad.
const SCALE: Transform = Transform {
    offset: [0.0, 0.0],
    rotation: 0.0,
    scale: [2.0, 2.0],
};

/// The top-left quadrant of an `N`-texel image.
fn quadrant(x: u32, y: u32) -> bool {
    x < N / 2 && y < N / 2
}

/// What one feature's three renders measured: the largest block difference, relative to
/// the feature's contrast, of the transformed file and of the untransformed file from the
/// baked one, and of the baked file from itself with another seed (the noise).
#[derive(Debug)]
struct Measured {
    moved: f64,
    plain: f64,
    noise: f64,
    contrast: f64,
}

/// A name for transform `t` and render flags `args` (scratch directories, messages).
fn label(t: &Transform, args: &[&str]) -> String {
    let part = |on: bool, s: &'static str| if on { s } else { "" };
    format!(
        "{}{}{}_{}",
        part(t.offset != [0.0, 0.0], "o"),
        part(t.rotation != 0.0, "r"),
        part(t.scale != [1.0, 1.0], "s"),
        args[1]
    )
}

/// Writes `f`'s three files for transform `t` (the baked image `baked_size` texels wide)
/// and renders them with `args` (method and sample counts).
fn measure(f: &Feature, t: &Transform, baked_size: u32, args: &[&str]) -> Measured {
    let dir = common::scratch_dir(&format!("texture_transform_{}_{}", f.name, label(t, args)));
    let source = blocks(N, quadrant, f.on, f.off);
    let baked = bake(&source, t, baked_size);
    let moved = json!({"index": 0, "extensions": {"KHR_texture_transform": t.json(None)}});
    let files = [
        f.stage
            .doc((f.material)(moved), source.clone())
            .write(&dir, "moved"),
        f.stage
            .doc((f.material)(json!({"index": 0})), baked)
            .write(&dir, "baked"),
        f.stage
            .doc((f.material)(json!({"index": 0})), source)
            .write(&dir, "plain"),
    ];
    let run = |file: &std::path::Path, out: &str, seed: &str| -> render::Image {
        let mut a = vec!["--size", SIZE, "--seed", seed];
        a.extend_from_slice(args);
        let img = render(file, out, &a);
        assert!(img.finite(), "{}: {out} has non-finite pixels", f.name);
        img
    };
    let moved = run(&files[0], "moved", "1").blocks(8);
    let baked = run(&files[1], "baked", "2").blocks(8);
    let plain = run(&files[2], "plain", "3").blocks(8);
    let again = run(&files[1], "baked_again", "4").blocks(8);
    let c = contrast(&baked);
    Measured {
        moved: max_diff(&moved, &baked) / c,
        plain: max_diff(&plain, &baked) / c,
        noise: max_diff(&again, &baked) / c,
        contrast: c,
    }
}

/// Asserts that the transform moved `f`'s feature like the bake did (within `tol` of the
/// contrast), that the feature is visible (untransformed differs from baked by at least
/// half the contrast) and that the seed-to-seed noise stays below `tol / 2`.
fn check(f: &Feature, t: &Transform, baked_size: u32, args: &[&str], tol: f64) {
    let m = measure(f, t, baked_size, args);
    let method = label(t, args);
    eprintln!("{} {method}: {m:?}", f.name);
    assert!(
        m.noise <= tol / 2.0,
        "{} ({method}): seed-to-seed noise {:.4} of the contrast {:.4} exceeds half the tolerance {tol}",
        f.name, m.noise, m.contrast
    );
    assert!(
        m.plain >= 0.5,
        "{} ({method}): the feature is not visible: the untransformed file differs from the baked one by only {:.4} of the contrast {:.4}",
        f.name, m.plain, m.contrast
    );
    assert!(
        m.moved <= tol,
        "{} ({method}): the transformed file differs from the baked one by {:.4} of the contrast {:.4} (tolerance {tol}; untransformed: {:.4}, noise: {:.4})",
        f.name, m.moved, m.contrast, m.plain, m.noise
    );
}

#[test]
fn base_colour_offset() {
    check(&BASE_COLOUR, &OFFSET, N, PATH, TOL);
}

#[test]
fn base_colour_rotation() {
    check(&BASE_COLOUR, &ROTATION, N, PATH, TOL);
}

#[test]
fn base_colour_scale() {
    check(&BASE_COLOUR, &SCALE, 2 * N, PATH, TOL);
}

#[test]
fn base_colour_combined() {
    check(&BASE_COLOUR, &COMBINED, 2 * N, PATH, TOL);
}

#[test]
fn clearcoat_factor() {
    check(&CLEARCOAT, &COMBINED, 2 * N, PATH, TOL);
}

#[test]
fn sheen_colour() {
    check(&SHEEN, &COMBINED, 2 * N, PATH, TOL);
}

/// The sheen under SPPM: read at the visible points, whose direct light SPPM estimates
/// itself (photons count from their first bounce on, and nothing here bounces light back
/// to the quad).
#[test]
fn sheen_colour_sppm() {
    check(&SHEEN, &COMBINED, 2 * N, SPPM, TOL);
}

#[test]
fn diffuse_transmission_strength() {
    check(&DIFFUSE_TRANSMISSION, &COMBINED, 2 * N, PATH, TOL);
}

#[test]
fn iridescence_thickness() {
    check(&IRIDESCENCE, &COMBINED, 2 * N, PATH_64, TOL);
}

#[test]
fn anisotropy_direction_and_strength() {
    check(&ANISOTROPY, &COMBINED, 2 * N, PATH, TOL);
}

/// Photons leaving a textured reflector: the pattern on the ceiling is drawn by photons
/// the anisotropic metal reflected, so the texture is read where photons bounce.
#[test]
fn anisotropy_reflector_sppm() {
    check(
        &ANISOTROPY_REFLECTOR,
        &QUARTER_SHIFT,
        N,
        SPPM_REFLECTOR,
        TOL_REFLECTOR,
    );
}
