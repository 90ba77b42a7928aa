//! Candidates for *thin sheets*: triangles of a mesh with a face of the **same mesh** on
//! the opposite side within the merge distance ([`Triangle::merge_distance`], world units),
//! i.e. a slab thinner than the offset rule can resolve. [`super::contact`]
//! probes only these (besides faces near other meshes) so that a lone gem or glass does not
//! pay for the probe on every triangle; the probe then decides.
//!
//! A pair qualifies when the planes are anti-parallel — unit normals n and n' with
//! n' ≈ −n, bucketed on a 1/256 grid of the normal's components with the 27 neighbouring
//! cells searched (normals within ~4e-3 rad always meet) — their plane offsets `n·p` and
//! `n'·p'` satisfy |n·p + n'·p'| ≤ 2·merge distance, and their bounding boxes grown by the
//! merge distance overlap. Sheets whose sides are tilted by more than that (wedges thinner
//! than the merge distance) are not found and keep rendering as two faces.
//!
//! Cost: O(T log T) for T triangles (one sort per bucket and a binary search per triangle).

use super::triangle::{geometric_normal, Triangle};
use glam::{IVec3, Vec3};
use std::collections::HashMap;

/// One triangle's plane and box.
struct Plane {
    offset: f32,
    tri: u32,
    lo: Vec3,
    hi: Vec3,
}

/// Per triangle, whether it may face a triangle of its own mesh across a sheet thinner than
/// the merge distance. `keep(i)` filters the triangles considered (volumetric ones).
pub(super) fn sheet_candidates(tris: &[Triangle], keep: impl Fn(usize) -> bool) -> Vec<bool> {
    const GRID: f32 = 256.0;
    let key = |n: Vec3| (n * GRID).round().as_ivec3();
    let mut buckets: HashMap<(u32, IVec3), Vec<Plane>> = HashMap::new();
    let mut normals = vec![None; tris.len()];
    for (i, td) in tris.iter().enumerate() {
        if !keep(i) {
            continue;
        }
        let Some(n) = geometric_normal(td.p) else {
            continue;
        };
        normals[i] = Some(n);
        let [p0, p1, p2] = td.p;
        let half = td.merge_distance();
        buckets.entry((td.mesh, key(n))).or_default().push(Plane {
            offset: n.dot(p0),
            tri: i as u32,
            lo: p0.min(p1).min(p2) - half,
            hi: p0.max(p1).max(p2) + half,
        });
    }
    for b in buckets.values_mut() {
        b.sort_unstable_by(|a, b| a.offset.total_cmp(&b.offset).then(a.tri.cmp(&b.tri)));
    }
    let mut out = vec![false; tris.len()];
    for (i, td) in tris.iter().enumerate() {
        let Some(n) = normals[i] else {
            continue;
        };
        let [p0, p1, p2] = td.p;
        let half = td.merge_distance();
        let (lo, hi) = (p0.min(p1).min(p2), p0.max(p1).max(p2));
        // The opposite plane's offset n'·p' = −n·p (within 2·half).
        let target = -n.dot(p0);
        let k = key(-n);
        'cells: for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let Some(b) = buckets.get(&(td.mesh, k + IVec3::new(dx, dy, dz))) else {
                        continue;
                    };
                    let start = b.partition_point(|p| p.offset < target - 2.0 * half);
                    let hit = b[start..]
                        .iter()
                        .take_while(|p| p.offset <= target + 2.0 * half)
                        .any(|p| p.lo.cmple(hi).all() && lo.cmple(p.hi).all());
                    if hit {
                        out[i] = true;
                        break 'cells;
                    }
                }
            }
        }
    }
    out
}
