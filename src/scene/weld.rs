//! Welding vertices by position within a tolerance: the one rule every closedness test
//! uses (the winding repair's connectivity, [`crate::scene::winding`]; the check that
//! scattering media and crystals have closed surfaces, `scene::validate`). Positions are
//! world-space metres as in [`crate::scene::desc::MeshDesc`].
//!
//! **The tolerance.** Two vertices are one corner when every coordinate differs by at
//! most ε = [`WELD_SCALE`] × D, with D the larger of the welded points' bounding-box
//! diagonal and their largest coordinate magnitude (both in f64). Why 2⁻²⁰:
//! - *f32 precision.* A vertex written in f32 carries a rounding error of up to 2⁻²⁴ of its
//!   largest coordinate per operation; generators and exporters that compute a seam or a
//!   pole with sin and cos in f32 (sin(2π) = −1.7·10⁻⁷, not 0) leave copies about 2⁻²²
//!   of the radius apart. ε is 8 roundings of the largest coordinate and at least 4× the
//!   seam error of a sphere (whose diagonal is 3.5 radii), so such copies weld.
//! - *Genuinely separate vertices.* ε is 2⁻⁶ of the distance within which the intersection
//!   layer already crosses two surfaces as one (`MERGE_SCALE`, 2⁻¹⁴ of the coordinate
//!   magnitude, [`crate::interaction`]) and 2⁻² of its ray offset (2⁻¹⁸): the two faces of
//!   a slab thinner than ε are one interface to every ray anyway, and anything the renderer
//!   tells apart stays apart.
//!
//! **The rule.** Points are taken in order; each joins the lowest-indexed earlier
//! *representative* within ε (max norm), or becomes one. Representatives are never within
//! ε of each other, so the welding does not chain along a row of close points. A hash grid
//! of cells 2ε wide holds the representatives; a point within ε of p lies, on each axis, in
//! p's cell or the neighbour on the side of the cell's middle p is on, so 8 cells are
//! searched and points straddling a cell border are found. A cell holds at most 8
//! representatives: O(n) in all. Non-finite points weld to nothing. The result depends only
//! on the input (no hashing order, no threads).

use crate::math::mix64;
use glam::{DVec3, Vec3};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// ε / D (module docs): 2⁻²⁰ ≈ 9.5·10⁻⁷.
pub const WELD_SCALE: f64 = 1.0 / (1u32 << 20) as f64;

/// Corner ids of welded points.
#[derive(Debug, Clone, PartialEq)]
pub struct Welded {
    /// Per point, the index of its representative (the first point of its corner).
    pub corner: Vec<u32>,
    /// The tolerance ε used, in the points' units (0 when all finite points coincide).
    pub tolerance: f64,
}

/// ε for `points` (module docs): [`WELD_SCALE`] × the larger of their bounding-box
/// diagonal and their largest coordinate magnitude; non-finite points are ignored.
pub fn tolerance(points: &[Vec3]) -> f64 {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for p in points.iter().filter(|p| p.is_finite()) {
        lo = lo.min(p.as_dvec3());
        hi = hi.max(p.as_dvec3());
    }
    if lo.x > hi.x {
        return 0.0;
    }
    let magnitude = lo.abs().max(hi.abs()).max_element();
    WELD_SCALE * (hi - lo).length().max(magnitude)
}

/// Welds `points` within [`tolerance`] (module docs).
pub fn weld(points: &[Vec3]) -> Welded {
    let eps = tolerance(points);
    let cell = 2.0 * eps;
    let mut grid: HashMap<u64, Vec<u32>, BuildHasherDefault<Premixed>> =
        HashMap::with_capacity_and_hasher(points.len(), BuildHasherDefault::default());
    let mut corner = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        if !p.is_finite() {
            corner.push(i as u32);
            continue;
        }
        let p = p.as_dvec3();
        // The cell of p and, per axis, the neighbour on the side p is nearer: a point
        // within ε of p (cells are 2ε wide) lies in one of these 2 × 2 × 2 cells.
        let (k, near) = if cell > 0.0 {
            let u = p / cell;
            let k = u.floor();
            (k, (u - k).cmplt(DVec3::splat(0.5)))
        } else {
            (DVec3::ZERO, glam::BVec3::FALSE)
        };
        let k = k.to_array().map(|c| c as i64);
        let near = [near.x, near.y, near.z].map(|lower| if lower { -1 } else { 0 });
        let mut found: Option<u32> = None;
        for d in 0..8 {
            let c = std::array::from_fn(|a| k[a] + near[a] + ((d >> a) & 1));
            let Some(reps) = grid.get(&cell_key(c)) else {
                continue;
            };
            for &r in reps {
                let q = points[r as usize].as_dvec3();
                if (q - p).abs().max_element() <= eps && found.is_none_or(|f| r < f) {
                    found = Some(r);
                }
            }
        }
        corner.push(found.unwrap_or_else(|| {
            grid.entry(cell_key(k)).or_default().push(i as u32);
            i as u32
        }));
    }
    Welded {
        corner,
        tolerance: eps,
    }
}

/// A grid cell's hash key: its three indices mixed by SplitMix64 ([`mix64`]). Two cells
/// sharing a key only add candidates, each checked by distance, so a collision costs time,
/// never a wrong weld.
fn cell_key([x, y, z]: [i64; 3]) -> u64 {
    mix64(x as u64 ^ mix64(y as u64 ^ mix64(z as u64)))
}

/// The hasher of keys already mixed by [`cell_key`]: the key itself.
#[derive(Default)]
struct Premixed(u64);

impl Hasher for Premixed {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = mix64(self.0 ^ u64::from(b));
        }
    }

    fn write_u64(&mut self, v: u64) {
        self.0 = v;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn copies_within_the_tolerance_weld_and_others_do_not() {
        // A unit-size cloud: ε ≈ 2⁻²⁰ × √3.
        let eps = WELD_SCALE * 3f64.sqrt();
        let a = Vec3::new(0.5, 0.25, 0.0);
        let near = a + Vec3::new(0.6 * eps as f32, -0.6 * eps as f32, 0.0);
        let far = a + Vec3::new(3.0 * eps as f32, 0.0, 0.0);
        let w = weld(&[Vec3::ZERO, Vec3::ONE, a, near, far, -Vec3::ZERO]);
        assert!((w.tolerance - eps).abs() < 1e-12, "{}", w.tolerance);
        assert_eq!(w.corner, vec![0, 1, 2, 2, 4, 0]);
    }

    #[test]
    fn points_straddling_cell_borders_weld() {
        let w0 = weld(&[Vec3::ZERO, Vec3::ONE]);
        let cell = 2.0 * w0.tolerance;
        // Just either side of a cell border, 0.2 ε apart on every axis.
        let border = (1000.0 * cell) as f32;
        let d = (0.1 * w0.tolerance) as f32;
        let p = Vec3::splat(border - d);
        let q = Vec3::splat(border + d);
        let w = weld(&[Vec3::ZERO, Vec3::ONE, p, q]);
        assert_eq!(w.corner[3], 2, "{:?}", w.corner);
    }

    #[test]
    fn welding_does_not_chain_and_skips_non_finite_points() {
        let eps = weld(&[Vec3::ZERO, Vec3::ONE]).tolerance as f32;
        let step = Vec3::new(0.7 * eps, 0.0, 0.0);
        let base = Vec3::splat(0.5);
        let points = [
            Vec3::ZERO,
            Vec3::ONE,
            base,
            base + step,
            base + 2.0 * step,
            Vec3::NAN,
            Vec3::NAN,
        ];
        let w = weld(&points);
        // base + 2·step is 1.4 ε from the representative `base`: a corner of its own.
        assert_eq!(w.corner, vec![0, 1, 2, 2, 4, 5, 6]);
        assert_eq!(weld(&[Vec3::ONE; 3]).corner, vec![0, 0, 0]);
        assert_eq!(weld(&[Vec3::ZERO; 2]).corner, vec![0, 0]);
    }
}
