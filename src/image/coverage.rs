//! Per-pixel coverage of a rendered image: the fraction α of a pixel's camera samples whose
//! primary ray hits a surface, and the mean environment radiance (linear RGB) its escaped
//! primary rays saw. The coverage pass fills it ([`crate::render::coverage`]); `--background`
//! composites with it ([`crate::output::background`] states the formulas).
//!
//! Invariant expected by the writers: `alpha.len() == escaped.len() == width · height`
//! (checked, not trusted).

use glam::Vec3;

/// Per-pixel coverage of an image (row-major, top row first; see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Coverage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// α ∈ [0, 1] per pixel.
    pub alpha: Vec<f32>,
    /// Mean environment radiance of the escaped primary rays per pixel (linear RGB).
    pub escaped: Vec<Vec3>,
}
