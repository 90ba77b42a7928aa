//! The per-pixel memory a render needs by method, checked against
//! [`crate::render::PIXEL_MEMORY_BUDGET`] before anything is allocated.
//! Units: bytes.

use super::Method;
use crate::error::{Error, Result};
use glam::Vec3;

/// Bytes each pixel costs `method`: the accumulation buffers, the images handed to
/// observers and writers, coverage and the output's encoding, and what its declaration
/// adds ([`super::capability::Capabilities::pixel_bytes`]: SPPM's per-pixel visible point).
pub fn bytes_per_pixel(method: Method) -> u64 {
    use std::mem::size_of;
    let common = size_of::<crate::image::fixed::PixelSums>() + 3 * size_of::<Vec3>() + 16 + 8;
    (common + method.caps().pixel_bytes) as u64
}

/// Rejects a `width × height` image whose per-pixel buffers for `method` would exceed
/// [`crate::render::PIXEL_MEMORY_BUDGET`] (SPPM needs several times what the other methods need).
pub fn check_memory(width: u32, height: u32, method: Method) -> Result<()> {
    let per = bytes_per_pixel(method);
    let pixels = u64::from(width) * u64::from(height);
    let budget = crate::render::PIXEL_MEMORY_BUDGET;
    if pixels.saturating_mul(per) > budget {
        return Err(Error::Usage(format!(
            "--size {width}x{height}: --method {} needs {per} bytes per pixel, {:.1} GiB for \
             this image, over the {} GiB budget (at most {} pixels)",
            method.name(),
            (pixels * per) as f64 / (1u64 << 30) as f64,
            budget >> 30,
            budget / per
        )));
    }
    Ok(())
}
