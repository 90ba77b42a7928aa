//! A spatial hash grid for fixed-radius neighbour search, rebuilt every SPPM pass
//! (Hachisuka & Jensen 2009, §4.1; hashing of Teschner, Heidelberger, Müller, Pomeranets,
//! Gross 2003, "Optimized Spatial Hashing for Collision Detection of Deformable Objects").
//!
//! Structure: cubic cells of side `2·radius`, so a query ball of radius `r ≤ radius` overlaps
//! at most 2 cells per axis (3 only when it straddles two boundaries after the tiny padding
//! below). Cell `(i, j, k)` goes to bucket `(i·73856093 ⊕ j·19349663 ⊕ k·83492791) mod B`
//! (Teschner et al. §4), `B = 2N` for `N` points. The points are sorted into the buckets by a
//! counting sort into CSR arrays (`starts`, `entries`); within a bucket they keep input order,
//! so the structure and every query's visiting order depend only on the input.
//!
//! Units and frames: world space, metres; radii in metres, reported distances squared (m²).
//! Reported indices index the `points` slice given to [`HashGrid::rebuild`].
//!
//! Invariants: points with a non-finite position are skipped. Cell coordinates saturate
//! (`f32 → i64` casts), which keeps them monotone in position, so huge coordinates stay
//! correct (they only share cells). A query with `r` above the build radius is still correct:
//! when it would cover more than 27 cells it scans every point. `rebuild` reuses the
//! allocations: with the same number of points the memory does not grow.

use super::store::Photon;
use glam::Vec3;
use rayon::prelude::*;

/// Teschner et al. 2003's three large primes.
const P: [u64; 3] = [73_856_093, 19_349_663, 83_492_791];
/// Bucket key of a skipped (non-finite) point.
const SKIP: u32 = u32::MAX;
/// At most this many cells are visited before falling back to a full scan (3 per axis).
const MAX_CELLS: usize = 27;

/// How far off a receiver's tangent plane a point within the gather radius `r` may lie and
/// still count, as a fraction of `r`: the density estimators (SPPM's gather, the hybrid's
/// caustic map, VCM's merging) count points in a flattened disc, not a ball, so that light
/// on a nearby parallel surface (a light panel 1 cm under a ceiling, the far side of a thin
/// wall) does not leak onto the receiver (a ball brightens SPPM's image of the Cornell box:
/// BENCHMARKS.md, "Figures behind choices in the code"). A curved surface of
/// radius R leaves its tangent plane by r²/2R within the disc: all of it counts while
/// r ≤ R/2.
pub const DISC_TOLERANCE: f32 = 0.25;

/// Whether point `q` lies within the gather disc of radius `r` around `p` with unit normal
/// `n` ([`DISC_TOLERANCE`]); the caller has already found it within `r` of `p`.
#[inline]
pub fn in_disc(p: Vec3, n: Vec3, q: Vec3, r: f32) -> bool {
    (q - p).dot(n).abs() <= DISC_TOLERANCE * r
}

/// Fixed-radius neighbour search over a point set (see the module documentation).
#[derive(Debug, Clone, Default)]
pub struct HashGrid {
    /// Build radius (metres) and the cell side and its inverse derived from it.
    radius: f32,
    cell: f32,
    inv_cell: f32,
    /// `starts[b]..starts[b + 1]` is bucket `b`'s range of `entries`.
    starts: Vec<u32>,
    /// Positions (copied for locality) and input indices, grouped by bucket.
    entries: Vec<([f32; 3], u32)>,
    /// Scratch: the bucket of each input point (or [`SKIP`]).
    keys: Vec<u32>,
}

impl HashGrid {
    /// An empty grid (no allocation until the first [`HashGrid::rebuild`]).
    pub fn new() -> HashGrid {
        HashGrid::default()
    }

    /// Rebuild over `points` for queries of radius up to `radius` (metres). A radius that is
    /// not finite and positive gives cells of side 1 m (queries stay correct).
    pub fn rebuild(&mut self, points: &[Photon], radius: f32) {
        self.rebuild_with(points.len(), |i| points[i].position(), radius);
    }

    /// [`HashGrid::rebuild`] over `n` points whose positions `position(i)` gives (any
    /// point type; reported indices are the `i`).
    pub fn rebuild_with(&mut self, n: usize, position: impl Fn(usize) -> Vec3 + Sync, radius: f32) {
        self.radius = radius;
        self.cell = if radius.is_finite() && radius > 0.0 {
            2.0 * radius
        } else {
            1.0
        };
        self.inv_cell = 1.0 / self.cell;
        let buckets = (2 * n).max(1);
        let inv = self.inv_cell;
        self.keys.clear();
        self.keys.resize(n, SKIP);
        self.keys.par_iter_mut().enumerate().for_each(|(i, key)| {
            let p = position(i);
            if p.is_finite() {
                *key = bucket(cell_of(p.to_array(), inv), buckets);
            }
        });
        // Counting sort (stable): counts, exclusive prefix sums, scatter, shift back.
        self.starts.clear();
        self.starts.resize(buckets + 1, 0);
        for &k in &self.keys {
            if k != SKIP {
                self.starts[k as usize + 1] += 1;
            }
        }
        for b in 0..buckets {
            self.starts[b + 1] += self.starts[b];
        }
        let kept = self.starts[buckets] as usize;
        self.entries.clear();
        self.entries.resize(kept, ([0.0; 3], 0));
        for (i, &k) in self.keys.iter().enumerate() {
            if k != SKIP {
                let slot = &mut self.starts[k as usize];
                self.entries[*slot as usize] = (position(i).to_array(), i as u32);
                *slot += 1;
            }
        }
        // Each start now holds its bucket's end (= the next bucket's start): shift right.
        for b in (1..=buckets).rev() {
            self.starts[b] = self.starts[b - 1];
        }
        self.starts[0] = 0;
    }

    /// Number of points stored (non-finite ones skipped).
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// True when no point is stored.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The radius given to the last [`HashGrid::rebuild`].
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// Bytes currently allocated by the grid's arrays (capacity, not length).
    pub fn capacity(&self) -> usize {
        self.starts.capacity() * std::mem::size_of::<u32>()
            + self.entries.capacity() * std::mem::size_of::<([f32; 3], u32)>()
            + self.keys.capacity() * std::mem::size_of::<u32>()
    }

    /// Call `f(index, d²)` for every stored point with `d² ≤ r²` from `p` (both in f32, as
    /// [`super::kdtree::dist2`] computes them), in a deterministic order. `r` should not exceed the build radius (larger is correct but slower). Nothing
    /// is reported for a NaN or negative `r` or a non-finite `p`.
    pub fn for_each_within(&self, p: Vec3, r: f32, mut f: impl FnMut(u32, f32)) {
        if r.is_nan() || r < 0.0 || !p.is_finite() || self.entries.is_empty() {
            return;
        }
        let r2 = r * r;
        let p = p.to_array();
        let mut visit = |range: std::ops::Range<usize>| {
            for &(q, i) in &self.entries[range] {
                let d2 = super::kdtree::dist2(p, q);
                if d2 <= r2 {
                    f(i, d2);
                }
            }
        };
        // Pad the cell range by a relative 1e-5 so float rounding of `p ± r` can never drop
        // a point that `d2 ≤ r2` accepts at the boundary.
        let rp = r * (1.0 + 1e-5);
        let lo = cell_of([p[0] - rp, p[1] - rp, p[2] - rp], self.inv_cell);
        let hi = cell_of([p[0] + rp, p[1] + rp, p[2] + rp], self.inv_cell);
        let span: [i64; 3] = std::array::from_fn(|a| hi[a].saturating_sub(lo[a]));
        // An overflowing r² accepts every point whose d² overflows too, cells or not.
        if r2 == f32::INFINITY || span.iter().any(|&s| s > 2) {
            visit(0..self.entries.len());
            return;
        }
        let buckets = self.starts.len() - 1;
        let mut list = [0u32; MAX_CELLS];
        let mut n = 0;
        for dz in 0..=span[2] {
            for dy in 0..=span[1] {
                for dx in 0..=span[0] {
                    let c = [lo[0] + dx, lo[1] + dy, lo[2] + dz];
                    list[n] = bucket(c, buckets);
                    n += 1;
                }
            }
        }
        // Distinct cells may share a bucket: visit each bucket once.
        let list = &mut list[..n];
        list.sort_unstable();
        let mut prev = None;
        for &b in list.iter() {
            if prev != Some(b) {
                prev = Some(b);
                visit(self.starts[b as usize] as usize..self.starts[b as usize + 1] as usize);
            }
        }
    }
}

/// Integer cell coordinates of a position (saturating casts keep them monotone).
#[inline]
fn cell_of(p: [f32; 3], inv_cell: f32) -> [i64; 3] {
    p.map(|x| (x * inv_cell).floor() as i64)
}

/// Teschner et al. 2003's hash of a cell, reduced to `buckets`.
#[inline]
fn bucket(c: [i64; 3], buckets: usize) -> u32 {
    let h = (c[0] as u64).wrapping_mul(P[0])
        ^ (c[1] as u64).wrapping_mul(P[1])
        ^ (c[2] as u64).wrapping_mul(P[2]);
    (h % buckets as u64) as u32
}

#[cfg(test)]
mod tests;
