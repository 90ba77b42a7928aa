//! A texture reference's `texCoord` (glTF 2.0 §5.22) and the KHR_texture_transform
//! `texCoord` override select the texture coordinate set, on every textured property of
//! the flat quad (`textured/features.rs`), end to end through the `iris` binary.
//!
//! The quad carries two sets: TEXCOORD_0 and TEXCOORD_1 = TEXCOORD_0 mirrored in u. The
//! texture is the 8 × 8 block image with its top-left quadrant on, so reading TEXCOORD_1
//! shows the feature in the top-right quadrant. Files, each with its own seed:
//! - `set1` (seed 1): the reference `{"index": 0, "texCoord": 1}`;
//! - `override` (seed 3): `{"index": 0, "extensions": {"KHR_texture_transform":
//!   {"texCoord": 1}}}` (the identity transform, its texCoord overriding the default 0);
//! - `reference` (seeds 2 and 5): one set, TEXCOORD_0 mirrored, `{"index": 0}`;
//! - `set0` (seed 4): both sets, `{"index": 0}`: what reading TEXCOORD_0 gives.
//!
//! Comparison and tolerances as in `texture_transform.rs` (8 × 8-pixel block means per
//! channel, relative to the reference's contrast): `set1` and `override` within
//! [`TOL`] = 0.1 of the reference, `set0` at least 0.5 away (the feature is visible and
//! the test can fail), and the reference against itself at another seed within `TOL / 2`
//! (measured seed-to-seed noise: below 2e-4, iridescence 0.02 at 64 spp).

use crate::common;
use crate::features;
use crate::render;
use crate::texture;

use features::*;
use render::{contrast, max_diff, render};
use serde_json::{json, Value};

const N: u32 = 8;
const TOL: f64 = 0.1;

/// Renders `f` from the four files of the module doc with `spp` samples per pixel and
/// checks them.
fn check(f: &Feature, spp: &str) {
    let Stage::Flat(light) = f.stage else {
        panic!("{}: texCoord tests use the flat quad", f.name)
    };
    let dir = common::scratch_dir(&format!("texture_coords_{}", f.name));
    let image = texture::blocks(N, |x, y| x < N / 2 && y < N / 2, f.on, f.off);
    let write = |name: &str, info: Value, uv0, uv1| {
        flat((f.material)(info), image.clone(), light, uv0, uv1).write(&dir, name)
    };
    let override_1 = json!({"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1}}});
    let files = [
        write(
            "set1",
            json!({"index": 0, "texCoord": 1}),
            UV0,
            Some(UV0_MIRRORED),
        ),
        write("reference", json!({"index": 0}), UV0_MIRRORED, None),
        write("override", override_1, UV0, Some(UV0_MIRRORED)),
        write("set0", json!({"index": 0}), UV0, Some(UV0_MIRRORED)),
    ];
    let run = |i: usize, out: &str, seed: &str| {
        let img = render(
            &files[i],
            out,
            &[
                "--size", "64x64", "--method", "path", "--spp", spp, "--seed", seed,
            ],
        );
        assert!(img.finite(), "{}: {out} has non-finite pixels", f.name);
        img.blocks(8)
    };
    let set1 = run(0, "set1", "1");
    let reference = run(1, "reference", "2");
    let over = run(2, "override", "3");
    let set0 = run(3, "set0", "4");
    let again = run(1, "reference_again", "5");
    let c = contrast(&reference);
    let d = |a: &[[f64; 3]]| max_diff(a, &reference) / c;
    let (d1, d_over, d0, noise) = (d(&set1), d(&over), d(&set0), d(&again));
    eprintln!(
        "{}: set1 {d1:.4}, override {d_over:.4}, set0 {d0:.4}, noise {noise:.4} (contrast {c:.4})",
        f.name
    );
    assert!(
        noise <= TOL / 2.0,
        "{}: seed-to-seed noise {noise:.4} of the contrast {c:.4} exceeds half the tolerance {TOL}",
        f.name
    );
    assert!(
        d0 >= 0.5,
        "{}: the feature is not visible: reading TEXCOORD_0 differs from reading TEXCOORD_1 by only {d0:.4} of the contrast {c:.4}",
        f.name
    );
    assert!(
        d1 <= TOL,
        "{}: texCoord 1 does not read TEXCOORD_1: it differs from the reference by {d1:.4} of the contrast {c:.4} (tolerance {TOL}; reading TEXCOORD_0: {d0:.4})",
        f.name
    );
    assert!(
        d_over <= TOL,
        "{}: the KHR_texture_transform texCoord 1 does not read TEXCOORD_1: it differs from the reference by {d_over:.4} of the contrast {c:.4} (tolerance {TOL}; reading TEXCOORD_0: {d0:.4})",
        f.name
    );
}

#[test]
fn base_colour() {
    check(&BASE_COLOUR, "16");
}

#[test]
fn clearcoat_factor() {
    check(&CLEARCOAT, "16");
}

#[test]
fn sheen_colour() {
    check(&SHEEN, "16");
}

#[test]
fn diffuse_transmission_strength() {
    check(&DIFFUSE_TRANSMISSION, "16");
}

#[test]
fn iridescence_thickness() {
    check(&IRIDESCENCE, "64");
}

/// Mirroring u flips the UV tangent, and with it the bitangent: the anisotropy axis, and
/// so the render, is the same whichever set defines the tangent.
#[test]
fn anisotropy_direction_and_strength() {
    check(&ANISOTROPY, "16");
}
