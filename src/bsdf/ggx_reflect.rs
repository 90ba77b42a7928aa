//! GGX reflection shared by the conductor, the glTF BRDF and its layers: the half vector of
//! a reflection pair, the Cook–Torrance term without Fresnel, and sampling and pdf of a
//! visible normal's reflection.
//!
//! Frame: local shading frame, z = normal; two-sided reflection (|cos θ|), `None` or 0 when
//! `wo` and `wi` are not in the same hemisphere. Densities are per unit solid angle.

use super::anisotropic::Microfacet;
use super::microfacet::Distribution;
use super::same_hemisphere;
use crate::optics::reflect;
use glam::{Vec2, Vec3};

/// Half vector of a reflection pair, faced to +z (`None` when degenerate or not a
/// reflection).
#[inline]
pub(super) fn half_reflect(wo: Vec3, wi: Vec3) -> Option<Vec3> {
    if !same_hemisphere(wo, wi) {
        return None;
    }
    let wm = (wo + wi).normalize_or_zero();
    if wm == Vec3::ZERO {
        return None;
    }
    Some(if wm.z < 0.0 { -wm } else { wm })
}

/// Cook–Torrance specular term D·G2/(4|cos θo||cos θi|) without Fresnel (Walter 2007,
/// eq. 20), and |wo·wm| for the Fresnel term.
#[inline]
pub(super) fn ggx_spec(ggx: impl Into<Microfacet>, wo: Vec3, wi: Vec3) -> Option<(f32, f32)> {
    let ggx: Microfacet = ggx.into();
    let wm = half_reflect(wo, wi)?;
    let s = ggx.d(wm) * ggx.g(wo, wi) / (4.0 * wo.z.abs() * wi.z.abs());
    Some((s, wo.dot(wm).abs()))
}

/// pdf of reflecting a visible normal: D_wo(wm)/(4|wo·wm|) (Walter 2007, eq. 14;
/// Heitz 2018, eq. 17).
#[inline]
pub(super) fn ggx_reflect_pdf(ggx: impl Into<Microfacet>, wo: Vec3, wi: Vec3) -> f32 {
    let ggx: Microfacet = ggx.into();
    match half_reflect(wo, wi) {
        Some(wm) => ggx.pdf_visible(wo, wm) / (4.0 * wo.dot(wm).abs()),
        None => 0.0,
    }
}

/// Reflects `wo` about a visible normal; `None` when it lands under the surface.
#[inline]
pub(super) fn ggx_reflect_sample(ggx: impl Into<Microfacet>, wo: Vec3, u: Vec2) -> Option<Vec3> {
    let ggx: Microfacet = ggx.into();
    if wo.z == 0.0 {
        return None;
    }
    let wi = reflect(wo, ggx.sample_visible(wo, u));
    same_hemisphere(wo, wi).then_some(wi)
}
