//! The studio's procedural environment: a vertical grey gradient with soft-edged
//! rectangular "softboxes", as an equirectangular [`EnvMap`] built in memory (so it is
//! importance-sampled like any `--env` map).
//!
//! - Map: [`WIDTH`]×[`HEIGHT`] texels (0.35° each, so the narrowest strip, 4° wide, spans
//!   about 11 texels), the mapping of [`crate::light::env::mapping`]; each texel holds the
//!   radiance at its centre direction.
//! - Gradient (nits): `ground` below the horizon, blending to `horizon` over the first 5°
//!   below it; above the horizon from `horizon` to `zenith` with √(elevation/90°), as in
//!   [`crate::assets::sky`].
//! - Softbox: centred at (elevation, azimuth) in the studio convention of [`super`]; a
//!   point at angular offsets (Δel, Δaz·cos el) is inside when both are within the half
//!   sizes. The edge is feathered over the outer [`FEATHER`] of each half size (a linear
//!   ramp on each axis), so reflections of it in a polished facet show a soft border. Its
//!   radiance replaces the gradient where it is the larger.

use super::PresetSpec;
use crate::image::ImageRgb;
use crate::light::env::{uv_to_dir, EnvMap, Environment};
use glam::{Vec2, Vec3};
use std::path::Path;

/// Map width, texels.
pub const WIDTH: u32 = 1024;
/// Map height, texels.
pub const HEIGHT: u32 = 512;
/// Fraction of each half size over which a softbox fades out (from 1 at (1 − FEATHER)·h
/// to 0 at (1 + FEATHER)·h).
pub const FEATHER: f32 = 0.25;

/// A rectangular area light painted into the environment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Softbox {
    /// Centre elevation above the horizon, degrees.
    pub elevation: f32,
    /// Centre azimuth from the camera side (+ = camera-right), degrees.
    pub azimuth: f32,
    /// Half width along the horizon (angle on the sky), degrees.
    pub half_width: f32,
    /// Half height, degrees.
    pub half_height: f32,
    /// Radiance inside, nits (white).
    pub radiance: f32,
}

impl Softbox {
    /// A softbox (angles in degrees, radiance in nits).
    pub const fn new(
        elevation: f32,
        azimuth: f32,
        half_width: f32,
        half_height: f32,
        radiance: f32,
    ) -> Self {
        Softbox {
            elevation,
            azimuth,
            half_width,
            half_height,
            radiance,
        }
    }

    /// Coverage in [0, 1] of the direction at `elevation`, `azimuth` (degrees).
    pub fn coverage(&self, elevation: f32, azimuth: f32) -> f32 {
        let mut da = (azimuth - self.azimuth).rem_euclid(360.0);
        if da > 180.0 {
            da -= 360.0;
        }
        let dx = da.abs() * elevation.to_radians().cos();
        let dy = (elevation - self.elevation).abs();
        ramp(dx, self.half_width) * ramp(dy, self.half_height)
    }
}

/// 1 inside (1 − FEATHER)·h, 0 beyond (1 + FEATHER)·h, linear between.
fn ramp(d: f32, h: f32) -> f32 {
    let (a, b) = ((1.0 - FEATHER) * h, (1.0 + FEATHER) * h);
    ((b - d) / (b - a)).clamp(0.0, 1.0)
}

/// The gradient's radiance at `elevation` degrees: [below, horizon, zenith] in nits.
pub fn gradient(g: [f32; 3], elevation: f32) -> f32 {
    if elevation >= 0.0 {
        let t = (elevation / 90.0).min(1.0).sqrt();
        g[1] + (g[2] - g[1]) * t
    } else {
        let w = (-elevation / 5.0).min(1.0);
        g[1] + (g[0] - g[1]) * w
    }
}

/// Radiance (nits, grey) arriving from studio direction (`elevation`, `azimuth`) degrees.
pub fn radiance(spec: &PresetSpec, elevation: f32, azimuth: f32) -> f32 {
    let base = gradient(spec.gradient, elevation);
    spec.softboxes.iter().fold(base, |l, b| {
        let c = b.coverage(elevation, azimuth);
        l.max(base + (b.radiance - base) * c)
    })
}

/// The preset's environment for a camera at world azimuth `cam_azimuth` (radians, see
/// [`super::camera_azimuth`]).
pub fn environment(spec: &PresetSpec, cam_azimuth: f32) -> Environment {
    let mut data = Vec::with_capacity((WIDTH * HEIGHT) as usize);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let uv = Vec2::new(
                (x as f32 + 0.5) / WIDTH as f32,
                (y as f32 + 0.5) / HEIGHT as f32,
            );
            let d = uv_to_dir(uv);
            let elevation = d.y.clamp(-1.0, 1.0).asin().to_degrees();
            let azimuth = (d.x.atan2(d.z) - cam_azimuth).to_degrees();
            data.push(Vec3::splat(radiance(spec, elevation, azimuth)));
        }
    }
    let img = ImageRgb {
        width: WIDTH,
        height: HEIGHT,
        data,
    };
    // The image is finite, non-negative and of a valid size by construction.
    match EnvMap::from_image(img, Path::new("studio environment")) {
        Ok(m) => Environment::Map(m),
        Err(_) => Environment::Uniform {
            radiance: Vec3::splat(spec.gradient[1]),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::super::{studio_direction, Studio};
    use super::*;

    #[test]
    fn softboxes_appear_where_placed() {
        for preset in [Studio::Soft, Studio::Jeweller, Studio::Bright, Studio::Tent] {
            let spec = preset.spec().unwrap();
            let cam_az = 0.7f32;
            let env = environment(&spec, cam_az);
            for b in spec.softboxes {
                let d = studio_direction(b.elevation, b.azimuth, cam_az);
                let l = env.eval(d).x;
                // Nearest-texel lookup at the box centre: exactly the box's radiance.
                assert_eq!(l, b.radiance, "{preset:?} {b:?}");
            }
            // Straight down is the gradient's ground value.
            assert_eq!(env.eval(-Vec3::Y).x, spec.gradient[0]);
        }
    }

    #[test]
    fn feathered_edges() {
        let b = Softbox::new(0.0, 0.0, 10.0, 10.0, 5.0);
        assert_eq!(b.coverage(0.0, 7.0), 1.0);
        assert!((b.coverage(0.0, 10.0) - 0.5).abs() < 1e-6);
        assert_eq!(b.coverage(0.0, 13.0), 0.0);
        assert_eq!(b.coverage(0.0, 350.0), b.coverage(0.0, -10.0));
    }
}
