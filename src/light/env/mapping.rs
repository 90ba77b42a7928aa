//! Equirectangular (latitude–longitude) mapping between world directions and image
//! coordinates, in Iris's glTF world frame (right-handed, +Y up, −Z forward).
//!
//! With θ ∈ [0, π] the polar angle from +Y and φ ∈ (−π, π] the azimuth measured from −Z
//! towards +X:
//!
//! ```text
//! u = 0.5 + φ/(2π),  φ = atan2(dir.x, −dir.z)      u ∈ (0, 1]
//! v = θ/π,           θ = acos(dir.y)               v ∈ [0, 1]
//! dir = (sin θ sin φ, cos θ, −sin θ cos φ)
//! ```
//!
//! So the image centre (u = 0.5) looks along −Z, u = 0.75 along +X, the top row (v = 0) is
//! +Y (zenith) and the bottom row (v = 1) is −Y. Pixel column `x = ⌊u·W⌋`, row `y = ⌊v·H⌋`
//! (row 0 is the top row, as in [`crate::image::ImageRgb`]), clamped into the image.
//! The Jacobian is dω = 2π² sin θ du dv (derived for lat-long maps in pbrt-v3 §14.2.4;
//! pbrt-v4 §12.5.2 `ImageInfiniteLight` uses an equal-area octahedral map instead, but the
//! same sampling structure).
//!
//! [`dir_to_uv`] and [`uv_to_dir`] are exact inverses up to rounding, except that at the
//! poles (sin θ = 0) every u maps to the same direction.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Image coordinates (u, v) ∈ (0, 1] × [0, 1] of a unit world direction.
///
/// Non-unit input is not normalised; `dir.y` is clamped to [−1, 1] before `acos`.
#[inline]
pub fn dir_to_uv(dir: Vec3) -> Vec2 {
    let phi = dir.x.atan2(-dir.z);
    let theta = dir.y.clamp(-1.0, 1.0).acos();
    Vec2::new(0.5 + phi * (0.5 / PI), theta * (1.0 / PI))
}

/// The unit world direction of image coordinates (u, v); see the module doc.
#[inline]
pub fn uv_to_dir(uv: Vec2) -> Vec3 {
    let phi = 2.0 * PI * (uv.x - 0.5);
    let theta = PI * uv.y;
    let (sin_t, cos_t) = theta.sin_cos();
    let (sin_p, cos_p) = phi.sin_cos();
    Vec3::new(sin_t * sin_p, cos_t, -sin_t * cos_p)
}

/// sin θ of the direction at image coordinate v (≥ 0).
#[inline]
pub fn sin_theta_of_v(v: f32) -> f32 {
    (PI * v).sin().max(0.0)
}

/// The pixel (column, row) containing (u, v) in a `width` × `height` image, clamped.
#[inline]
pub fn uv_to_pixel(uv: Vec2, width: u32, height: u32) -> (u32, u32) {
    // `as u32` saturates (NaN → 0), so this never panics.
    let x = ((uv.x * width as f32) as u32).min(width.saturating_sub(1));
    let y = ((uv.y * height as f32) as u32).min(height.saturating_sub(1));
    (x, y)
}
