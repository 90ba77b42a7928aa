//! Pure-Rust backend: an obvhs 8-wide compressed BVH (CWBVH) with our own watertight
//! triangle test.
//!
//! obvhs's node test clamps the entry distance to a hard-coded 1e-4 (in ray-parameter
//! units), which would drop hits closer than that: every hit on a 1e-4-scale model, and the
//! far face of a slab thinner than 1e-4 at any scale. We therefore build and traverse in a
//! *scaled* frame: positions and ray origins are multiplied by a power of two `s` chosen so
//! the largest coordinate magnitude is about 2^20. Multiplying by a power of two is exact
//! in floating point, so hits are bit-identical to the unscaled test (barring
//! over/underflow), and `t` scales by exactly `s`. The 1e-4 clamp then sits about 1e-10
//! below the scene's coordinate magnitude, far below f32 resolution (6e-8 relative).
//!
//! **Rays along an axis, and boxes a ray only touches.** A direction component that is zero
//! (or so small that its reciprocal overflows) has no finite inverse. An infinite one makes
//! obvhs's quantized slab test compute ∞ − ∞ = NaN for every node, and NaN is accepted, so
//! such a ray would visit the whole tree (correct, ~1000× slower). We pass a finite inverse
//! of magnitude [`BIG_INV`] instead (no overflow for any scaled coordinate, so nodes off the
//! ray are culled as usual). With a finite inverse a box whose face lies exactly on the
//! ray's constant coordinate gets distance 0 on that face, and obvhs's entry clamp (≥ 1e-4)
//! would cull it; rounding likewise culls boxes that a ray touches only at a corner or an
//! edge (a ray through a shared vertex). Every triangle's box is therefore padded by
//! [`BOX_PAD`] before the build (pbrt-v4 widens its slab test's far distance by 1 + 2γ₃ for
//! the same reason), which makes such faces strictly enclose the ray. tests/accel/accel_parity.rs
//! casts rays along the axes and coordinate-plane diagonals through rows of shared vertices
//! lying exactly on box faces, at scales 1e-4, 1 and 1e4, and compares with brute force.

use super::triangle::RayPrep;
use super::{HitList, RawHit};
use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray, RayHit};
use obvhs::BvhBuildParams;
use std::time::Duration;

/// Target magnitude of the largest coordinate in the scaled frame.
const TARGET_EXPONENT: i32 = 20;

/// Padding of every triangle's box in the scaled frame: 4 units where coordinates reach
/// 2^20–2^21, i.e. 2–4 × 10⁻⁶ of the scene's size (a few ulps of the slab test's distances).
const BOX_PAD: f32 = 4.0;

/// Largest inverse direction magnitude handed to obvhs: 2^80. Its node test multiplies the
/// inverse by node extents (≤ 2^23 in the scaled frame, times a quantized 255) and by
/// origin offsets; both products stay below f32::MAX (2^128) for origins within 2^47 of the
/// scene.
const BIG_INV: f32 = 1.2089258e24;

/// obvhs CWBVH over a scaled copy of the triangles, stored in BVH leaf order.
pub struct BvhAccel {
    bvh: CwBvh,
    /// Triangles in leaf order, in the scaled frame.
    tris: Vec<[Vec3; 3]>,
    /// Original triangle index for each leaf-order slot.
    prim_ids: Vec<u32>,
    /// Power-of-two scale from world to the BVH frame.
    scale: f32,
}

/// Power of two that brings `max_abs` to about 2^20 (1 for empty or zero scenes).
fn pow2_scale(max_abs: f32) -> f32 {
    if max_abs.is_nan() || max_abs <= 0.0 || !max_abs.is_finite() {
        return 1.0;
    }
    let e = max_abs.log2().floor() as i32;
    2f32.powi((TARGET_EXPONENT - e).clamp(-100, 100))
}

impl BvhAccel {
    /// Builds the BVH over world-space triangles (indices must be in range).
    pub fn build(positions: &[Vec3], indices: &[[u32; 3]]) -> Self {
        let max_abs = positions
            .iter()
            .fold(0f32, |m, p| m.max(p.abs().max_element()));
        let scale = pow2_scale(max_abs);
        let scaled: Vec<[Vec3; 3]> = indices
            .iter()
            .map(|t| t.map(|k| positions[k as usize] * scale))
            .collect();
        // Each triangle's box, padded by BOX_PAD scaled units so rounding in obvhs's slab
        // test cannot cull a box the ray only touches (a ray through a shared vertex or
        // along an edge of the box; pbrt-v4 widens tFar by 1 + 2γ₃ for the same reason).
        let boxes: Vec<Aabb> = scaled
            .iter()
            .map(|t| {
                let lo = t[0].min(t[1]).min(t[2]) - Vec3::splat(BOX_PAD);
                let hi = t[0].max(t[1]).max(t[2]) + Vec3::splat(BOX_PAD);
                Aabb::new(lo.into(), hi.into())
            })
            .collect();
        let mut build_time = Duration::ZERO;
        let bvh = if boxes.is_empty() {
            CwBvh::default()
        } else {
            obvhs::cwbvh::builder::build_cwbvh(
                &boxes,
                BvhBuildParams::medium_build(),
                &mut build_time,
            )
        };
        let tris = bvh
            .primitive_indices
            .iter()
            .map(|&i| scaled[i as usize])
            .collect();
        let prim_ids = bvh.primitive_indices.clone();
        BvhAccel {
            bvh,
            tris,
            prim_ids,
            scale,
        }
    }

    /// The obvhs ray in the scaled frame. A direction component without a finite inverse
    /// below [`BIG_INV`] gets ±`BIG_INV`, signed as obvhs orders the slab (`direction < 0`,
    /// so −0 counts as positive) — see the module docs.
    #[inline]
    fn ray(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Ray {
        let mut inv = Vec3A::from(dir).recip();
        for axis in 0..3 {
            if inv[axis].is_nan() || inv[axis].abs() > BIG_INV {
                inv[axis] = if dir[axis] < 0.0 { -BIG_INV } else { BIG_INV };
            }
        }
        Ray {
            origin: Vec3A::from(origin * self.scale),
            direction: dir.into(),
            inv_direction: inv,
            tmin: 0.0,
            tmax: t_max * self.scale,
        }
    }

    /// Closest hit in `[0, t_max)`.
    pub fn closest(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<RawHit> {
        if self.tris.is_empty() {
            return None;
        }
        let ray = self.ray(origin, dir, t_max);
        let prep = RayPrep::new(origin * self.scale, dir);
        let mut hit = RayHit::none();
        let mut uv = (0.0, 0.0);
        let found = self.bvh.ray_traverse(ray, &mut hit, |r, id| {
            let [a, b, c] = self.tris[id];
            match prep.intersect(a, b, c, r.tmax) {
                Some((t, u, v)) => {
                    uv = (u, v);
                    t
                }
                None => f32::INFINITY,
            }
        });
        if !found {
            return None;
        }
        Some(RawHit {
            t: hit.t / self.scale,
            prim: self.prim_ids[hit.primitive_id as usize],
            u: uv.0,
            v: uv.1,
        })
    }

    /// Any hit in `[0, t_max)`.
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        if self.tris.is_empty() {
            return false;
        }
        let ray = self.ray(origin, dir, t_max);
        let prep = RayPrep::new(origin * self.scale, dir);
        !self.bvh.ray_traverse_miss(ray, |r, id| {
            let [a, b, c] = self.tris[id];
            prep.intersect(a, b, c, r.tmax)
                .map_or(f32::INFINITY, |h| h.0)
        })
    }

    /// Every hit in `[0, t_max)` (up to [`super::MAX_HITS`]): the closure records each
    /// candidate and reports a miss, so traversal visits them all.
    pub fn all_hits(&self, origin: Vec3, dir: Vec3, t_max: f32) -> HitList {
        let mut out = HitList::default();
        if self.tris.is_empty() || t_max.is_nan() || t_max <= 0.0 {
            return out;
        }
        let ray = self.ray(origin, dir, t_max);
        let prep = RayPrep::new(origin * self.scale, dir);
        let mut hit = RayHit::none();
        self.bvh.ray_traverse(ray, &mut hit, |r, id| {
            let [a, b, c] = self.tris[id];
            if let Some((t, u, v)) = prep.intersect(a, b, c, r.tmax) {
                out.push(RawHit {
                    t: t / self.scale,
                    prim: self.prim_ids[id],
                    u,
                    v,
                });
            }
            f32::INFINITY
        });
        out
    }
}
