//! A procedural sky for the environment-lit scenes, written as a Radiance RGBE (`.hdr`)
//! equirectangular map.
//!
//! Mapping: the one of [`crate::light::env::mapping`] — texel (x, y) of a W×H map has
//! u = (x + ½)/W, v = (y + ½)/H, polar angle θ = π v from +Y (top row = zenith) and
//! azimuth φ = 2π (u − ½) = atan2(dir.x, −dir.z) (image centre = −Z, φ = 90° = +X), so
//! `dir = (sin θ sin φ, cos θ, −sin θ cos φ)`. Elevation β = 90° − θ.
//!
//! Content (linear RGB radiance, the renderer's unit; see [`sky_radiance`]): a blue
//! gradient from a pale horizon to the zenith, a dark brown ground below the horizon,
//! four coloured panels standing on the horizon (they show up in reflections), and a small
//! very bright sun disc of angular radius [`SUN_RADIUS_DEG`] at [`SUN_ELEVATION_DEG`],
//! [`SUN_AZIMUTH_DEG`] with a faint glow around it. The sun's irradiance at normal
//! incidence is about 6× the sky's on a horizontal plane, so it casts sharp shadows and
//! caustics.
//!
//! Determinism: only `+ − × ÷ √` and [`sin_cos`] in `f64`; RGBE bytes by exact
//! power-of-two scaling (G. Ward, "Real Pixels", Graphics Gems II, 1991), scanlines
//! run-length encoded as in Radiance's `fwritecolrs` (B. Walter's `rgbe.c`), so the file
//! is bit-identical on every platform.

use crate::authoring::lathe::sin_cos;
use glam::{DVec3, Vec3};

/// Map width in texels (0.70° per texel).
pub const SKY_WIDTH: u32 = 512;
/// Map height in texels.
pub const SKY_HEIGHT: u32 = 256;
/// Sun elevation above the horizon, degrees.
pub const SUN_ELEVATION_DEG: f64 = 30.0;
/// Sun azimuth φ (0° = −Z, 90° = +X), degrees: the sun stands towards −X, −Z.
pub const SUN_AZIMUTH_DEG: f64 = -55.0;
/// Angular radius of the sun disc, degrees (≈ 14 texels).
pub const SUN_RADIUS_DEG: f64 = 1.2;
/// Radiance of the sun disc (warm white).
pub const SUN_RADIANCE: [f64; 3] = [10000.0, 9500.0, 8800.0];

const HORIZON: DVec3 = DVec3::new(0.8, 0.88, 1.0);
const ZENITH: DVec3 = DVec3::new(0.15, 0.3, 0.75);
const GROUND: DVec3 = DVec3::new(0.16, 0.13, 0.1);
/// Coloured panels: azimuth range, elevation range (degrees), radiance.
const PANELS: [(f64, f64, f64, f64, [f64; 3]); 4] = [
    (100.0, 118.0, 0.0, 9.0, [2.2, 0.25, 0.15]),
    (150.0, 160.0, 0.0, 15.0, [0.25, 1.8, 0.35]),
    (-160.0, -135.0, 0.0, 6.0, [0.2, 0.35, 2.4]),
    (20.0, 32.0, 0.0, 5.0, [2.0, 1.7, 0.2]),
];

/// Unit direction for polar angle θ and azimuth φ (radians).
fn direction(theta: f64, phi: f64) -> DVec3 {
    let (st, ct) = sin_cos(theta);
    let (sp, cp) = sin_cos(phi);
    DVec3::new(st * sp, ct, -st * cp)
}

/// The unit direction towards the centre of the sun disc.
pub fn sun_direction() -> Vec3 {
    let theta = (90.0 - SUN_ELEVATION_DEG).to_radians();
    direction(theta, SUN_AZIMUTH_DEG.to_radians()).as_vec3()
}

/// Radiance of texel (x, y) of the [`SKY_WIDTH`]×[`SKY_HEIGHT`] map.
pub fn sky_radiance(x: u32, y: u32) -> DVec3 {
    let u = (f64::from(x) + 0.5) / f64::from(SKY_WIDTH);
    let v = (f64::from(y) + 0.5) / f64::from(SKY_HEIGHT);
    let elevation = 90.0 - 180.0 * v;
    let azimuth = 360.0 * (u - 0.5);
    let mut c = if elevation >= 0.0 {
        let t = (elevation / 90.0).sqrt();
        HORIZON * (1.0 - t) + ZENITH * t
    } else {
        let w = (-elevation / 4.0).min(1.0);
        HORIZON * 0.5 * (1.0 - w) + GROUND * w
    };
    for (a0, a1, e0, e1, colour) in PANELS {
        if (a0..a1).contains(&azimuth) && (e0..e1).contains(&elevation) {
            c = DVec3::from_array(colour);
        }
    }
    let dir = direction(
        std::f64::consts::PI * v,
        2.0 * std::f64::consts::PI * (u - 0.5),
    );
    let sun = sun_direction().as_dvec3().normalize();
    let (_, cos_radius) = sin_cos(SUN_RADIUS_DEG.to_radians());
    let d = dir.dot(sun);
    if d >= cos_radius {
        return DVec3::from_array(SUN_RADIANCE);
    }
    // Glow ∝ k / (k + 1 − cos γ): ≈ 3.6 at the disc's edge, 0.5 at 10°, 0.06 at 30°.
    let k = 0.002;
    if elevation >= 0.0 {
        c += DVec3::new(4.0, 3.6, 3.0) * (k / (k + 1.0 - d));
    }
    c
}

/// The sky map as `.hdr` bytes.
pub fn sky_hdr() -> Vec<u8> {
    let texels: Vec<DVec3> = (0..SKY_HEIGHT)
        .flat_map(|y| (0..SKY_WIDTH).map(move |x| sky_radiance(x, y)))
        .collect();
    encode_hdr(SKY_WIDTH, SKY_HEIGHT, &texels)
}

/// Shared-exponent RGBE of a linear colour (components < 0 clamp to 0): mantissas
/// `⌊c · 256 / 2ᵉ⌋` with 2ᵉ⁻¹ ≤ max < 2ᵉ, exponent byte e + 128; black below 1e-32.
pub fn rgbe(c: DVec3) -> [u8; 4] {
    let c = c.max(DVec3::ZERO);
    let m = c.max_element();
    if m.is_nan() || m < 1e-32 {
        return [0; 4];
    }
    let m = m.min(1e38);
    // frexp by the exponent bits: m = f·2^e with f in [0.5, 1) (m is normal here).
    let e = ((m.to_bits() >> 52) & 0x7ff) as i64 - 1022;
    let scale = f64::from_bits(((1023 + 8 - e) as u64) << 52); // 2^(8 − e), exact
    let byte = |x: f64| (x.min(1e38) * scale).min(255.0) as u8;
    [byte(c.x), byte(c.y), byte(c.z), (e + 128) as u8]
}

/// A Radiance `.hdr` file (`#?RADIANCE`, `FORMAT=32-bit_rle_rgbe`, `-Y h +X w`) holding
/// `texels` (row-major, top row first). Scanlines 8 … 32767 wide are run-length encoded
/// per component; others are written flat.
pub fn encode_hdr(width: u32, height: u32, texels: &[DVec3]) -> Vec<u8> {
    let mut out = format!(
        "#?RADIANCE\n# CC0-1.0, generated by Iris\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n"
    )
    .into_bytes();
    let w = width as usize;
    for row in texels.chunks(w.max(1)).take(height as usize) {
        let px: Vec<[u8; 4]> = row.iter().map(|&c| rgbe(c)).collect();
        if !(8..=32767).contains(&w) {
            out.extend(px.iter().flatten());
            continue;
        }
        out.extend_from_slice(&[2, 2, (w >> 8) as u8, (w & 0xff) as u8]);
        for ch in 0..4 {
            let data: Vec<u8> = px.iter().map(|p| p[ch]).collect();
            rle(&data, &mut out);
        }
    }
    out
}

/// Radiance's per-component run-length code: a byte n > 128 repeats the next byte n − 128
/// times; n ≤ 128 copies the next n bytes. Runs shorter than 4 are sent as literals.
fn rle(data: &[u8], out: &mut Vec<u8>) {
    const MIN_RUN: usize = 4;
    let mut cur = 0;
    while cur < data.len() {
        let (mut beg, mut run, mut old_run) = (cur, 0usize, 0usize);
        while run < MIN_RUN && beg < data.len() {
            beg += run;
            old_run = run;
            run = 1;
            while beg + run < data.len() && run < 127 && data[beg] == data[beg + run] {
                run += 1;
            }
        }
        if old_run > 1 && old_run == beg - cur {
            out.extend_from_slice(&[128 + old_run as u8, data[cur]]);
            cur = beg;
        }
        while cur < beg {
            let n = (beg - cur).min(128);
            out.push(n as u8);
            out.extend_from_slice(&data[cur..cur + n]);
            cur += n;
        }
        if run >= MIN_RUN {
            out.extend_from_slice(&[128 + run as u8, data[beg]]);
            cur += run;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgbe_keeps_three_significant_bits_of_the_largest_component() {
        assert_eq!(rgbe(DVec3::ZERO), [0; 4]);
        assert_eq!(rgbe(DVec3::ONE), [128, 128, 128, 129]);
        assert_eq!(rgbe(DVec3::new(0.5, 0.25, 0.0)), [128, 64, 0, 128]);
        // Ward's decoding (m + 0.5)·2^(e−136) is within half a step (1/256 relative to
        // the largest component) of the input.
        for c in [
            DVec3::new(10000.0, 9500.0, 8800.0),
            DVec3::new(0.22, 0.38, 0.8),
        ] {
            let [r, g, b, e] = rgbe(c);
            let f = 2f64.powi(i32::from(e) - 136);
            let back = DVec3::new(f64::from(r), f64::from(g), f64::from(b)) * f + 0.5 * f;
            assert!(
                (back - c).abs().max_element() <= c.max_element() / 256.0,
                "{c} {back}"
            );
        }
    }

    #[test]
    fn rle_round_trips() {
        let data: Vec<u8> = (0..600u32)
            .map(|i| if i % 97 < 40 { 7 } else { (i * 31 % 251) as u8 })
            .collect();
        let mut enc = Vec::new();
        rle(&data, &mut enc);
        let mut dec = Vec::new();
        let mut i = 0;
        while i < enc.len() {
            let n = enc[i] as usize;
            if n > 128 {
                dec.extend(std::iter::repeat_n(enc[i + 1], n - 128));
                i += 2;
            } else {
                assert!(n > 0);
                dec.extend_from_slice(&enc[i + 1..i + 1 + n]);
                i += 1 + n;
            }
        }
        assert_eq!(dec, data);
        assert!(enc.len() < data.len(), "runs are compressed");
    }

    #[test]
    fn sky_reads_back_with_the_sun_where_it_should_be() {
        let dir = std::env::temp_dir().join(format!("iris_sky_{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("mkdir");
        let path = dir.join("sky.hdr");
        std::fs::write(&path, sky_hdr()).expect("write");
        let map = crate::light::env::load(&path).expect("load");
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!((map.width(), map.height()), (SKY_WIDTH, SKY_HEIGHT));
        // The brightest direction is the sun (within RGBE's 1/256 precision), and the
        // renderer's own mapping finds it there.
        let sun = map.eval(sun_direction());
        assert!((sun.x - 10000.0).abs() < 10000.0 / 128.0, "{sun}");
        let up = map.eval(Vec3::Y);
        assert!(up.z > up.x && up.z < 1.0, "zenith is blue: {up}");
        let down = map.eval(Vec3::NEG_Y);
        assert!(
            (down - GROUND.as_vec3()).abs().max_element() < 0.01,
            "{down}"
        );
    }
}
