//! A film's exact content outside the film: per pixel (row-major, top row first) the
//! fixed-point sums of its two halves ([`super::fixed`]) and the units in each half. It is
//! what a shard's partial image stores ([`crate::output::partial`]) and what a merge adds
//! up ([`ExactImage::add`]); its mean and halves follow the film's formulas
//! ([`super::Film::mean`], [`super::Film::halves`]), so equal sums give equal bits.
//!
//! Invariant: `sums.len() == units.len() == width · height`. Half h of a pixel holds the
//! units of absolute index ≡ h (mod 2). Values are linear RGB radiance.

use super::fixed::{pixel_mean, FixedRgb, PixelSums};
use super::ImageRgb;
use glam::Vec3;

/// Exact per-pixel sums and unit counts of an image (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ExactImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Per pixel, the sums of half 0 (even units) and half 1 (odd units).
    pub sums: Vec<PixelSums>,
    /// Per pixel, the units in half 0 and in half 1.
    pub units: Vec<[u64; 2]>,
}

/// The two halves' means of a pixel with `units` in each half (an empty half gives 0;
/// callers handle that case first).
#[inline]
pub fn half_means(s: &PixelSums, units: [u64; 2]) -> (Vec3, Vec3) {
    (s[0].mean(units[0]), s[1].mean(units[1]))
}

impl ExactImage {
    /// An empty image: no units anywhere.
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        ExactImage {
            width,
            height,
            sums: vec![[FixedRgb::ZERO; 2]; n],
            units: vec![[0; 2]; n],
        }
    }

    /// Adds `other`'s sums and units pixel by pixel (the sizes must match: the caller
    /// checked them; a mismatch adds the common prefix only).
    pub fn add(&mut self, other: &ExactImage) {
        for (s, o) in self.sums.iter_mut().zip(&other.sums) {
            *s = [s[0] + o[0], s[1] + o[1]];
        }
        for (u, o) in self.units.iter_mut().zip(&other.units) {
            *u = [u[0] + o[0], u[1] + o[1]];
        }
    }

    /// The image `f(sums, units)` of every pixel.
    fn image(&self, f: impl Fn(&PixelSums, [u64; 2]) -> Vec3) -> ImageRgb {
        ImageRgb {
            width: self.width,
            height: self.height,
            data: self
                .sums
                .iter()
                .zip(&self.units)
                .map(|(s, u)| f(s, *u))
                .collect(),
        }
    }

    /// The mean of every pixel's units.
    pub fn mean(&self) -> ImageRgb {
        self.image(|s, u| pixel_mean(s, u[0] + u[1]))
    }

    /// The two halves' means; when some pixel has an empty half, both are the mean (the
    /// film's rule).
    pub fn halves(&self) -> (ImageRgb, ImageRgb) {
        if self.units.iter().any(|u| u.contains(&0)) {
            let m = self.mean();
            return (m.clone(), m);
        }
        let a = self.image(|s, u| half_means(s, u).0);
        let b = self.image(|s, u| half_means(s, u).1);
        (a, b)
    }

    /// The fewest and the most units a pixel holds ((0, 0) for an empty image).
    pub fn unit_span(&self) -> (u64, u64) {
        let n = self.units.iter().map(|u| u[0] + u[1]);
        (n.clone().min().unwrap_or(0), n.max().unwrap_or(0))
    }

    /// Units over all pixels.
    pub fn pixel_units(&self) -> u64 {
        self.units.iter().map(|u| u[0] + u[1]).sum()
    }
}
