//! Isotropic Trowbridge–Reitz (GGX) microfacet distribution: normal distribution `D`,
//! Smith masking `Λ`/`G1` and height-correlated `G`, visible-normal (VNDF) sampling and its
//! pdf.
//!
//! Frame: local shading frame, z = macro-surface normal; `wm` (a microfacet normal) always has
//! `wm.z ≥ 0`. Directions are unit vectors pointing away from the surface and may lie in
//! either hemisphere (Λ depends on tan²θ only). `alpha` is the GGX roughness (glTF:
//! perceptual roughness²). Densities are per unit solid angle.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// GGX distribution with isotropic roughness `alpha` (> 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ggx {
    /// GGX α (width of the slope distribution).
    pub alpha: f32,
}

impl Ggx {
    /// Normal distribution D(wm), normalised so that ∫ D(wm) cos θm dωm = 1
    /// (Walter et al. 2007, eq. 33, written as α²/(π (cos²θ (α²−1) + 1)²)). 0 for wm.z ≤ 0.
    #[inline]
    pub fn d(&self, wm: Vec3) -> f32 {
        if wm.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let t = wm.z * wm.z * (a2 - 1.0) + 1.0;
        a2 / (PI * t * t)
    }

    /// Smith Λ(w) for GGX (Heitz 2014, "Understanding the Masking-Shadowing Function", eq. 72):
    /// (√(1 + α² tan²θ) − 1)/2. 0 at grazing (tan θ = ∞), where every cosine factor is 0.
    #[inline]
    pub fn lambda(&self, w: Vec3) -> f32 {
        let cos2 = w.z * w.z;
        let sin2 = w.x * w.x + w.y * w.y;
        let tan2 = sin2 / cos2;
        if !tan2.is_finite() {
            return 0.0;
        }
        ((1.0 + self.alpha * self.alpha * tan2).sqrt() - 1.0) * 0.5
    }

    /// Smith masking G1(w) = 1/(1 + Λ(w)) (Heitz 2014, eq. 43).
    #[inline]
    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking-shadowing G2(wo, wi) = 1/(1 + Λ(wo) + Λ(wi))
    /// (Heitz 2014, eq. 99).
    #[inline]
    pub fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Density of visible normals D_w(wm) = G1(w)/|cos θ_w| · D(wm) · |w·wm|
    /// (Heitz 2014, eq. 38 / Heitz 2018, eq. 1); this is the pdf of [`Ggx::sample_visible`].
    #[inline]
    pub fn pdf_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        if w.z == 0.0 {
            return 0.0;
        }
        self.g1(w) / w.z.abs() * self.d(wm) * w.dot(wm).abs()
    }

    /// Samples a microfacet normal visible from `w` (from `−w` when `w.z < 0`) with density
    /// [`Ggx::pdf_visible`] (Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
    /// JCGT 7(4), Listing 1). `u` ∈ [0,1)².
    pub fn sample_visible(&self, w: Vec3, u: Vec2) -> Vec3 {
        let a = self.alpha;
        // Section 3.2: transform the view direction to the hemisphere configuration.
        let mut wh = Vec3::new(a * w.x, a * w.y, w.z).normalize();
        if wh.z < 0.0 {
            wh = -wh;
        }
        // Section 4.1: orthonormal basis.
        let t1 = if wh.z < 0.99999 {
            Vec3::Z.cross(wh).normalize()
        } else {
            Vec3::X
        };
        let t2 = wh.cross(t1);
        // Section 4.2: parameterisation of the projected area.
        let r = u.x.sqrt();
        let phi = 2.0 * PI * u.y;
        let p1 = r * phi.cos();
        let mut p2 = r * phi.sin();
        let s = 0.5 * (1.0 + wh.z);
        p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * p2;
        // Section 4.3: reprojection onto the hemisphere.
        let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * wh;
        // Section 3.4: transform the normal back to the ellipsoid configuration.
        Vec3::new(a * nh.x, a * nh.y, nh.z.max(1e-6)).normalize()
    }
}
