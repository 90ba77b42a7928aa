//! Anisotropic Trowbridge–Reitz (GGX) microfacets for KHR_materials_anisotropy: the
//! distribution `D`, Smith `Λ` with the direction-dependent roughness, visible-normal
//! sampling (Heitz 2018) and its pdf; plus [`Microfacet`], the closed choice between this
//! and the isotropic [`Ggx`] that the glTF and conductor lobes use.
//!
//! Frame: local shading frame, z = macro-surface normal, **x = the anisotropy direction**
//! (the tangent rotated by `anisotropyRotation` and the texture's direction), y = the
//! bitangent. `alpha_x` is the roughness along x, `alpha_y` along y. `wm.z ≥ 0`; other
//! directions may lie in either hemisphere. Densities are per unit solid angle.
//!
//! Formulas (Heitz 2014, "Understanding the Masking-Shadowing Function in
//! Microfacet-Based BRDFs", eqs. 85–86):
//! D(wm) = 1/(π α_x α_y ((x/α_x)² + (y/α_y)² + z²)²),
//! Λ(w) = (√(1 + (α_x² x² + α_y² y²)/z²) − 1)/2; with α_x = α_y = α both reduce to the
//! isotropic forms of [`Ggx`].

use super::microfacet::{visible_frame, visible_normal, Distribution, Ggx};
use super::SMOOTH_ALPHA;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// GGX with roughness `alpha_x` along the frame's x axis and `alpha_y` along y (both > 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GgxAniso {
    /// Roughness along x (the anisotropy direction).
    pub alpha_x: f32,
    /// Roughness along y.
    pub alpha_y: f32,
}

impl Distribution for GgxAniso {
    /// D(wm) (see the module doc); 0 for wm.z ≤ 0.
    #[inline]
    fn d(&self, wm: Vec3) -> f32 {
        if wm.z <= 0.0 {
            return 0.0;
        }
        let (ax, ay) = (self.alpha_x, self.alpha_y);
        let t = (wm.x / ax).powi(2) + (wm.y / ay).powi(2) + wm.z * wm.z;
        1.0 / (PI * ax * ay * t * t)
    }

    /// Smith Λ(w) (see the module doc); 0 at grazing.
    #[inline]
    fn lambda(&self, w: Vec3) -> f32 {
        let a2 = (self.alpha_x * w.x).powi(2) + (self.alpha_y * w.y).powi(2);
        let t = a2 / (w.z * w.z);
        if !t.is_finite() {
            return 0.0;
        }
        ((1.0 + t).sqrt() - 1.0) * 0.5
    }
}

impl GgxAniso {
    /// The KHR_materials_anisotropy roughnesses from the isotropic α and the strength s:
    /// α_x = mix(α, 1, s²), α_y = α (the extension's "Implementation" section).
    pub fn khr(alpha: f32, strength: f32) -> Self {
        let s2 = strength.clamp(0.0, 1.0).powi(2);
        GgxAniso {
            alpha_x: alpha + (1.0 - alpha) * s2,
            alpha_y: alpha,
        }
    }

    /// A microfacet normal visible from `w` (from `−w` when `w.z < 0`) with density
    /// [`Distribution::pdf_visible`]: Heitz 2018, JCGT 7(4), Listing 1, with the stretch
    /// (α_x, α_y).
    pub fn sample_visible(&self, w: Vec3, u: Vec2) -> Vec3 {
        let (ax, ay) = (self.alpha_x, self.alpha_y);
        let frame = visible_frame(ax, ay, w);
        let r = u.x.sqrt();
        let phi = 2.0 * PI * u.y;
        let p1 = r * phi.cos();
        let s = 0.5 * (1.0 + frame.0.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
        visible_normal(ax, ay, frame, p1, p2)
    }
}

/// The microfacet distribution of a reflection lobe: isotropic (the common case, computed
/// exactly as before anisotropy existed) or anisotropic.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Microfacet {
    /// Isotropic GGX.
    Iso(Ggx),
    /// Anisotropic GGX in the anisotropy frame.
    Aniso(GgxAniso),
}

impl Microfacet {
    /// Isotropic for strength 0 (bit-identical to [`Ggx`]), else [`GgxAniso::khr`] with α
    /// at least [`SMOOTH_ALPHA`] (an anisotropic lobe is never a delta).
    pub fn khr(alpha: f32, strength: f32) -> Self {
        if strength > 0.0 {
            Microfacet::Aniso(GgxAniso::khr(alpha.max(SMOOTH_ALPHA), strength))
        } else {
            Microfacet::Iso(Ggx { alpha })
        }
    }

    /// Visible-normal sample.
    #[inline]
    pub fn sample_visible(&self, w: Vec3, u: Vec2) -> Vec3 {
        match self {
            Microfacet::Iso(g) => g.sample_visible(w, u),
            Microfacet::Aniso(g) => g.sample_visible(w, u),
        }
    }
}

impl Distribution for Microfacet {
    #[inline]
    fn d(&self, wm: Vec3) -> f32 {
        match self {
            Microfacet::Iso(g) => g.d(wm),
            Microfacet::Aniso(g) => g.d(wm),
        }
    }

    #[inline]
    fn lambda(&self, w: Vec3) -> f32 {
        match self {
            Microfacet::Iso(g) => g.lambda(w),
            Microfacet::Aniso(g) => g.lambda(w),
        }
    }
}

impl From<Ggx> for Microfacet {
    fn from(g: Ggx) -> Self {
        Microfacet::Iso(g)
    }
}
