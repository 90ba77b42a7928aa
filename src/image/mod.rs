//! Images as numbers, below everything that makes, stores or measures them: the linear
//! [`ImageRgb`], a film's exact content ([`ExactImage`] of fixed-point sums, [`fixed`]),
//! per-pixel [`Coverage`] (alpha and escaped radiance), the sRGB transfer functions
//! ([`srgb`]) and the distances between images ([`metrics`]: against a reference, or
//! estimated from two half images). It imports nothing of the renderer: `render` fills
//! these types and estimates its error with [`metrics`], `output` writes and reads them as
//! files, `measure` records the distances, textures decode with [`srgb`].
//!
//! Conventions: pixels are row-major, top row first, pixel (x, y) at `y * width + x`;
//! colours are **linear** RGB with Rec.709/sRGB primaries (scene-referred radiance, any
//! scale) unless a function says it takes or gives sRGB-encoded values.

pub mod coverage;
pub mod exact;
pub mod fixed;
pub mod metrics;
pub mod srgb;

pub use coverage::Coverage;
pub use exact::ExactImage;
use glam::Vec3;

/// A linear RGB image (Rec.709/sRGB primaries), row-major, top row first.
///
/// Invariant expected by the writers: `data.len() == width * height` (checked, not trusted).
#[derive(Debug, Clone, PartialEq)]
pub struct ImageRgb {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` linear RGB pixels; pixel (x, y) is at `y * width + x`.
    pub data: Vec<Vec3>,
}

impl ImageRgb {
    /// The pixel-wise mean of this image and `other` (this image's size; `other` holds at
    /// least as many pixels): the full image of two half images.
    pub fn mean_with(&self, other: &ImageRgb) -> ImageRgb {
        ImageRgb {
            width: self.width,
            height: self.height,
            data: (self.data.iter().zip(&other.data))
                .map(|(x, y)| 0.5 * (*x + *y))
                .collect(),
        }
    }

    /// A black image of the given size.
    pub fn new(width: u32, height: u32) -> Self {
        ImageRgb {
            width,
            height,
            data: vec![Vec3::ZERO; width as usize * height as usize],
        }
    }

    /// The pixel at column `x`, row `y` (row 0 is the top), if inside the image.
    pub fn get(&self, x: u32, y: u32) -> Option<Vec3> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.data
            .get(y as usize * self.width as usize + x as usize)
            .copied()
    }
}
