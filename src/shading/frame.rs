//! The shading frame at a hit: the local frame of the outward shading normal every BSDF
//! works in ([`shading_frame`]), turned about the normal to the brushing direction where
//! the material is anisotropic (KHR_materials_anisotropy, [`crate::material::anisotropy`]).
//!
//! Tangent frame (world space, unit vectors): the tangent T is the glTF `TANGENT` attribute
//! interpolated with the hit's barycentrics when all three vertices carry one (w gives the
//! bitangent's sign), else the triangle's UV tangent ∂p/∂u from its positions and
//! TEXCOORD_0 (constant per triangle, bitangent sign +1, as the glTF sample viewer does
//! without tangents; equal to MikkTSpace's on flat triangles up to its vertex averaging).
//! T is made orthogonal to the shading normal n (Gram–Schmidt), B = w·(n × T). The
//! anisotropy direction (d_x, d_y) in that tangent space gives the BSDF frame
//! x = normalize(d_x T + d_y B), y = n × x, z = n. Without UVs or tangents (or with a
//! degenerate UV map) the frame is [`Frame::from_normal`]'s, deterministic; the loader
//! warns once per file. Isotropic materials always use [`Frame::from_normal`].

use crate::interaction::SurfaceHit;
use crate::material::AnisotropyPoint;
use crate::math::Frame;
use crate::scene::Scene;
use glam::{Vec2, Vec3};

/// The BSDF frame at `hit` (see the module doc): [`Frame::from_normal`] unless the point is
/// anisotropic.
pub fn shading_frame(scene: &Scene, hit: &SurfaceHit, aniso: &AnisotropyPoint) -> Frame {
    let n = hit.ns;
    let plain = Frame::from_normal(n);
    if aniso.strength <= 0.0 {
        return plain;
    }
    let (t, sign) = tangent(scene, hit).unwrap_or((plain.s, 1.0));
    anisotropy_frame(n, t, sign, aniso.direction).unwrap_or(plain)
}

/// The BSDF frame for unit normal `n`, tangent `t` (any length, not parallel to `n`),
/// bitangent sign `sign` and tangent-space direction `dir`: x = normalize(dir.x T + dir.y B)
/// with T = `t` made orthogonal to `n` and B = sign·(n × T); y = n × x. `None` when
/// degenerate.
pub fn anisotropy_frame(n: Vec3, t: Vec3, sign: f32, dir: Vec2) -> Option<Frame> {
    let t = (t - n * n.dot(t)).try_normalize()?;
    let b = n.cross(t) * sign;
    let x = (t * dir.x + b * dir.y).try_normalize()?;
    Some(Frame {
        s: x,
        t: n.cross(x),
        n,
    })
}

/// The surface tangent and bitangent sign at `hit`: the interpolated TANGENT attribute,
/// else the triangle's ∂p/∂u; `None` without either (or with a degenerate UV map).
pub fn tangent(scene: &Scene, hit: &SurfaceHit) -> Option<(Vec3, f32)> {
    let idx = scene
        .triangles()
        .get(hit.prim as usize)?
        .vertices
        .map(|i| i as usize);
    let v = scene.vertices();
    let p = idx.map(|i| v.positions[i]);
    if !v.tangents.is_empty() {
        let ts = idx.map(|i| v.tangents[i]);
        if ts.iter().all(|t| t.w != 0.0) {
            let [w0, w1, w2] = barycentrics(p, hit.p);
            let t = ts[0].truncate() * w0 + ts[1].truncate() * w1 + ts[2].truncate() * w2;
            let sign = if ts[0].w < 0.0 { -1.0 } else { 1.0 };
            if let Some(t) = t.try_normalize() {
                return Some((t, sign));
            }
        }
    }
    uv_tangent(p, idx.map(|i| v.uvs[i])).map(|t| (t, 1.0))
}

/// ∂p/∂u of a triangle from its positions and texture coordinates (pbrt-v4 §6.5.3 "Partial
/// derivatives"): with e₁ = p₁ − p₀, e₂ = p₂ − p₀ and the UV differences,
/// ∂p/∂u = (Δv₂ e₁ − Δv₁ e₂)/(Δu₁Δv₂ − Δv₁Δu₂). `None` when the UV map is degenerate.
pub fn uv_tangent(p: [Vec3; 3], uv: [Vec2; 3]) -> Option<Vec3> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let (d1, d2) = (uv[1] - uv[0], uv[2] - uv[0]);
    let det = d1.x * d2.y - d1.y * d2.x;
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    ((e1 * d2.y - e2 * d1.y) / det).try_normalize()
}

/// Barycentric weights of `q` (on the triangle's plane) for vertices `p`.
fn barycentrics(p: [Vec3; 3], q: Vec3) -> [f32; 3] {
    let n = (p[1] - p[0]).cross(p[2] - p[0]);
    let area = n.length_squared();
    if area == 0.0 || !area.is_finite() {
        return [1.0 / 3.0; 3];
    }
    let w1 = (q - p[0]).cross(p[2] - p[0]).dot(n) / area;
    let w2 = (p[1] - p[0]).cross(q - p[0]).dot(n) / area;
    [1.0 - w1 - w2, w1, w2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uv_tangent_is_dp_du() {
        // u grows along +X, v along +Z (any scale, any triangle of the map).
        let p = [
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 3.0),
        ];
        let uv = [Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)];
        assert!((uv_tangent(p, uv).unwrap() - Vec3::X).length() < 1e-6);
        // Swapped parametrisation: u along +Z.
        let uv = [Vec2::ZERO, Vec2::new(0.0, 1.0), Vec2::new(1.0, 0.0)];
        assert!((uv_tangent(p, uv).unwrap() - Vec3::Z).length() < 1e-6);
        assert!(uv_tangent(p, [Vec2::ZERO; 3]).is_none());
        let w = barycentrics(p, Vec3::new(0.5, 0.0, 1.5));
        assert!((w[0] - 0.25).abs() < 1e-6 && (w[1] - 0.25).abs() < 1e-6);
    }

    #[test]
    fn rotation_turns_the_frame_about_the_normal() {
        let aniso = |rotation: f32| {
            let desc = crate::material::AnisotropyDesc {
                strength: 0.5,
                rotation,
                texture: None,
            };
            desc.at(&crate::material::TextureContext::new(
                &[],
                Default::default(),
            ))
        };
        let n = Vec3::Y;
        // Tangent +X, bitangent sign +1: B = n × T = −Z.
        let f0 = anisotropy_frame(n, Vec3::X, 1.0, aniso(0.0).direction).unwrap();
        assert!((f0.s - Vec3::X).length() < 1e-6);
        let f1 = anisotropy_frame(
            n,
            Vec3::X,
            1.0,
            aniso(std::f32::consts::FRAC_PI_2).direction,
        )
        .unwrap();
        assert!((f1.s - Vec3::NEG_Z).length() < 1e-6, "{:?}", f1.s);
        // The bitangent sign mirrors it; the frame stays right-handed with z = n.
        let f2 = anisotropy_frame(
            n,
            Vec3::X,
            -1.0,
            aniso(std::f32::consts::FRAC_PI_2).direction,
        )
        .unwrap();
        assert!((f2.s - Vec3::Z).length() < 1e-6);
        for f in [f0, f1, f2] {
            assert!((f.s.cross(f.t) - f.n).length() < 1e-6);
        }
        assert_eq!(aniso(0.0).strength, 0.5);
    }
}
