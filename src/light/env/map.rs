//! [`EnvMap`]: an equirectangular radiance image (mapping in [`super::mapping`]) with a
//! piecewise-constant importance-sampling distribution (pbrt-v4 §12.5.2 `ImageInfiniteLight`,
//! §A.5.2 `PiecewiseConstant2D`).
//!
//! - Texels are linear RGB radiance (W·sr⁻¹·m⁻² per unit, Rec.709 primaries), looked up
//!   with **nearest** (piecewise-constant) filtering, so eval, sample and pdf describe the
//!   same function exactly.
//! - Sampling density of texel (x, y) ∝ Y(texel) · ΔΩ(row y), with Y = 0.2126R + 0.7152G +
//!   0.0722B and ΔΩ the texel's exact solid angle (2π/W)(cos θ₀ − cos θ₁). In (u, v) this is
//!   the constant `Y · mean sin θ over the row`; the solid-angle pdf is
//!   `pdf_uv / (2π² sin θ)` with sin θ of the direction itself, and 0 where sin θ = 0.
//! - Black texels (Y = 0) get probability 0; their radiance is 0, so eval/pdf stay
//!   consistent (no floor is needed: every texel with any positive channel has Y > 0).
//! - Non-finite or negative channels are clamped to 0 when the map is built and counted in
//!   [`EnvMap::warnings`]. Maps must have 1 … 2^26 texels.

use super::distribution::PiecewiseConstant2D;
use super::mapping::{dir_to_uv, sin_theta_of_v, uv_to_dir, uv_to_pixel};
use crate::error::{LoadError, LoadErrorKind, Result};
use crate::image::ImageRgb;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;
use std::path::Path;

/// Largest environment map accepted, in texels (2^26 ≈ 67 M, e.g. 11585² or 16384 × 4096).
pub const MAX_TEXELS: u64 = 1 << 26;

/// Rec.709 relative luminance Y of linear RGB.
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// An equirectangular environment map with its sampling distribution.
#[derive(Debug, Clone)]
pub struct EnvMap {
    width: u32,
    height: u32,
    texels: Vec<Vec3>,
    dist: PiecewiseConstant2D,
    warnings: Vec<String>,
}

impl EnvMap {
    /// Builds a map from a linear RGB image; `source` names it in errors and warnings.
    ///
    /// Errors (naming `source`): zero-sized, more than [`MAX_TEXELS`] texels, or
    /// `data.len() != width * height`.
    pub fn from_image(img: ImageRgb, source: &Path) -> Result<Self> {
        let texels = img.width as u64 * img.height as u64;
        if texels == 0 {
            return Err(LoadError::new(
                source,
                "",
                LoadErrorKind::InvalidValue,
                format!("environment map is empty ({}×{})", img.width, img.height),
            )
            .into());
        }
        if texels > MAX_TEXELS {
            return Err(LoadError::new(
                source,
                "",
                LoadErrorKind::TooLarge,
                format!(
                    "environment map {}×{} exceeds the limit of {MAX_TEXELS} texels",
                    img.width, img.height
                ),
            )
            .into());
        }
        if img.data.len() as u64 != texels {
            return Err(LoadError::new(
                source,
                "",
                LoadErrorKind::MissingBuffer,
                format!(
                    "{} texels for a {}×{} map",
                    img.data.len(),
                    img.width,
                    img.height
                ),
            )
            .into());
        }
        let (w, h) = (img.width as usize, img.height as usize);
        let mut data = img.data;
        let mut clamped = 0usize;
        for c in &mut data {
            let fixed = Vec3::new(fix(c.x), fix(c.y), fix(c.z));
            if fixed != *c {
                clamped += 1;
                *c = fixed;
            }
        }
        let mut warnings = Vec::new();
        if clamped > 0 {
            warnings.push(format!(
                "{}: {clamped} environment texel(s) had NaN, infinite or negative values; \
                 clamped to 0",
                source.display()
            ));
        }
        // Mean of sin θ over row y: (cos θ₀ − cos θ₁) / Δθ, so the texel's weight in (u, v)
        // is proportional to its exact solid angle.
        let dtheta = PI / h as f32;
        let func: Vec<f32> = data
            .iter()
            .enumerate()
            .map(|(i, &c)| {
                let y = i / w;
                let (t0, t1) = (y as f32 * dtheta, (y + 1) as f32 * dtheta);
                let mean_sin = ((t0.cos() - t1.cos()) / dtheta).max(0.0);
                luminance(c) * mean_sin
            })
            .collect();
        let dist = PiecewiseConstant2D::new(&func, w, h);
        Ok(EnvMap {
            width: img.width,
            height: img.height,
            texels: data,
            dist,
            warnings,
        })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Problems fixed while loading (clamped texels), for the caller to report.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The (clamped) radiance of texel (x, y), row 0 = top = +Y.
    pub fn texel(&self, x: u32, y: u32) -> Vec3 {
        if x >= self.width || y >= self.height {
            return Vec3::ZERO;
        }
        self.texels[y as usize * self.width as usize + x as usize]
    }

    /// Radiance arriving from world direction `dir` (nearest texel).
    pub fn eval(&self, dir: Vec3) -> Vec3 {
        if !dir.is_finite() {
            return Vec3::ZERO;
        }
        let (x, y) = uv_to_pixel(dir_to_uv(dir), self.width, self.height);
        self.texel(x, y)
    }

    /// Solid-angle density with which [`EnvMap::sample`] produces `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        if !dir.is_finite() {
            return 0.0;
        }
        let uv = dir_to_uv(dir);
        let sin_t = sin_theta_of_v(uv.y);
        if sin_t <= 0.0 {
            return 0.0;
        }
        let (x, y) = uv_to_pixel(uv, self.width, self.height);
        let pdf_uv = self.dist.pdf_at(x as usize, y as usize);
        let pdf = pdf_uv / (2.0 * PI * PI * sin_t);
        if pdf.is_finite() {
            pdf
        } else {
            0.0
        }
    }

    /// Samples a direction ∝ luminance; returns (wi, radiance, solid-angle pdf), or `None`
    /// if the map is black or the sample lands on a pole / zero-probability texel.
    /// `radiance == eval(wi)` and `pdf == pdf(wi)` by construction.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        if self.dist.integral() <= 0.0 {
            return None;
        }
        let (uv, _) = self.dist.sample(u);
        let wi = uv_to_dir(uv);
        // Re-evaluate through the direction so a sample rounding onto a neighbouring
        // texel still reports exactly eval(wi) and pdf(wi).
        let pdf = self.pdf(wi);
        if pdf > 0.0 {
            Some((wi, self.eval(wi), pdf))
        } else {
            None
        }
    }

    /// ∫ Y(L(ω)) dω over the sphere (= mean luminance × 4π).
    pub fn luminance_integral(&self) -> f32 {
        (2.0 * std::f64::consts::PI * std::f64::consts::PI * self.dist.integral()) as f32
    }
}

/// A channel value made finite and non-negative.
#[inline]
fn fix(x: f32) -> f32 {
    if x.is_finite() && x > 0.0 {
        x
    } else {
        0.0
    }
}
