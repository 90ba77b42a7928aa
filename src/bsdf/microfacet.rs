//! Isotropic Trowbridge–Reitz (GGX) microfacet distribution: normal distribution `D`,
//! Smith masking `Λ`/`G1` and height-correlated `G`, visible-normal (VNDF) sampling and its
//! pdf; and [`Distribution`], the masking terms and visible-normal density every GGX
//! distribution (this one, [`super::anisotropic::GgxAniso`]) derives from its `D` and `Λ`.
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

/// A GGX-family distribution of microfacet normals given by its `D` and its Smith `Λ`;
/// the masking terms and the density of visible normals follow from those two (Heitz 2014,
/// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs").
pub trait Distribution {
    /// Normal distribution D(wm); 0 for wm.z ≤ 0.
    fn d(&self, wm: Vec3) -> f32;

    /// Smith Λ(w); 0 at grazing.
    fn lambda(&self, w: Vec3) -> f32;

    /// Smith masking G1(w) = 1/(1 + Λ(w)) (Heitz 2014, eq. 43).
    #[inline]
    fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking-shadowing G2(wo, wi) = 1/(1 + Λ(wo) + Λ(wi))
    /// (Heitz 2014, eq. 99).
    #[inline]
    fn g(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Density of visible normals D_w(wm) = G1(w)/|cos θ_w| · D(wm) · |w·wm|
    /// (Heitz 2014, eq. 38 / Heitz 2018, eq. 1): the pdf of the distribution's
    /// `sample_visible`.
    #[inline]
    fn pdf_visible(&self, w: Vec3, wm: Vec3) -> f32 {
        if w.z == 0.0 {
            return 0.0;
        }
        self.g1(w) / w.z.abs() * self.d(wm) * w.dot(wm).abs()
    }
}

impl Distribution for Ggx {
    /// Normal distribution D(wm), normalised so that ∫ D(wm) cos θm dωm = 1
    /// (Walter et al. 2007, eq. 33, written as α²/(π (cos²θ (α²−1) + 1)²)). 0 for wm.z ≤ 0.
    #[inline]
    fn d(&self, wm: Vec3) -> f32 {
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
    fn lambda(&self, w: Vec3) -> f32 {
        let cos2 = w.z * w.z;
        let sin2 = w.x * w.x + w.y * w.y;
        let tan2 = sin2 / cos2;
        if !tan2.is_finite() {
            return 0.0;
        }
        ((1.0 + self.alpha * self.alpha * tan2).sqrt() - 1.0) * 0.5
    }
}

impl Ggx {
    /// Samples a microfacet normal visible from `w` (from `−w` when `w.z < 0`) with density
    /// [`Distribution::pdf_visible`] (Heitz 2018, "Sampling the GGX Distribution of Visible
    /// Normals", JCGT 7(4), Listing 1). `u` ∈ [0,1)².
    pub fn sample_visible(&self, w: Vec3, u: Vec2) -> Vec3 {
        let a = self.alpha;
        let frame = visible_frame(a, a, w);
        // Section 4.2: parameterisation of the projected area.
        let r = u.x.sqrt();
        let phi = 2.0 * PI * u.y;
        let p1 = r * phi.cos();
        let mut p2 = r * phi.sin();
        let s = 0.5 * (1.0 + frame.0.z);
        p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * p2;
        visible_normal(a, a, frame, p1, p2)
    }
}

/// The first steps of visible-normal sampling (Heitz 2018, Listing 1) for the stretch
/// (`ax`, `ay`): the view direction `w` in the hemisphere configuration, faced to +z
/// (section 3.2), and an orthonormal basis (t1, t2) around it (section 4.1). Returns
/// (wh, t1, t2).
pub(super) fn visible_frame(ax: f32, ay: f32, w: Vec3) -> (Vec3, Vec3, Vec3) {
    let mut wh = Vec3::new(ax * w.x, ay * w.y, w.z).normalize();
    if wh.z < 0.0 {
        wh = -wh;
    }
    let t1 = if wh.z < 0.99999 {
        Vec3::Z.cross(wh).normalize()
    } else {
        Vec3::X
    };
    (wh, t1, wh.cross(t1))
}

/// The last steps of visible-normal sampling (Heitz 2018, Listing 1): the point (p1, p2)
/// of the projected area reprojected onto the hemisphere of `frame` (section 4.3) and
/// transformed back to the ellipsoid configuration of the stretch (`ax`, `ay`) (section
/// 3.4).
pub(super) fn visible_normal(
    ax: f32,
    ay: f32,
    (wh, t1, t2): (Vec3, Vec3, Vec3),
    p1: f32,
    p2: f32,
) -> Vec3 {
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * wh;
    Vec3::new(ax * nh.x, ay * nh.y, nh.z.max(1e-6)).normalize()
}
