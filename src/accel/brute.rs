//! Brute-force reference: tests every triangle. Used by the parity tests as ground truth
//! for the BVH and Embree backends; far too slow to render with.

use super::triangle::RayPrep;
use super::{HitList, RawHit};
use glam::Vec3;

/// Closest hit in `[0, t_max)` over all triangles.
pub fn closest(
    positions: &[Vec3],
    indices: &[[u32; 3]],
    origin: Vec3,
    dir: Vec3,
    t_max: f32,
) -> Option<RawHit> {
    let prep = RayPrep::new(origin, dir);
    let mut best: Option<RawHit> = None;
    let mut t_best = t_max;
    for (i, tri) in indices.iter().enumerate() {
        let [a, b, c] = tri.map(|k| positions[k as usize]);
        if let Some((t, u, v)) = prep.intersect(a, b, c, t_best) {
            t_best = t;
            best = Some(RawHit {
                t,
                prim: i as u32,
                u,
                v,
            });
        }
    }
    best
}

/// Every hit in `[0, t_max)` over all triangles (up to [`super::MAX_HITS`]).
pub fn all_hits(
    positions: &[Vec3],
    indices: &[[u32; 3]],
    origin: Vec3,
    dir: Vec3,
    t_max: f32,
) -> HitList {
    let prep = RayPrep::new(origin, dir);
    let mut out = HitList::default();
    for (i, tri) in indices.iter().enumerate() {
        let [a, b, c] = tri.map(|k| positions[k as usize]);
        if let Some((t, u, v)) = prep.intersect(a, b, c, t_max) {
            out.push(RawHit {
                t,
                prim: i as u32,
                u,
                v,
            });
        }
    }
    out
}
