//! The photon map: a balanced kd-tree over stored [`Photon`]s with k-nearest and radius
//! queries (Jensen 2001, "Realistic Image Synthesis Using Photon Mapping", §6.3 / appendix
//! B, with the implicit median layout of Wald 2004 and Bentley 1975).
//!
//! Layout: the photons are reordered in place. The subtree of a range `[lo, hi)` of
//! [`PhotonMap::photons`] has its node at `m = lo + (hi - lo) / 2`, the left subtree in
//! `[lo, m)` (coordinates ≤ the node's on the split axis) and the right one in `[m + 1, hi)`
//! (≥). Ranges of at most [`LEAF`] photons are leaves, scanned linearly. The split axis (the
//! widest axis of the range's points) is kept in one byte per photon, so the map costs 33
//! bytes per photon.
//!
//! Units and frames: world space, metres; distances are returned squared (m²). Indices
//! returned by the queries index [`PhotonMap::photons`] (the reordered array), not the input.
//!
//! Invariants: photons with a non-finite position are dropped at build. The tree, and so
//! every query result and index, depends only on the input (never on the number of rayon
//! threads: subtrees are independent and built by the same sequential code). kNN ties are
//! broken by index: the result is the `k` smallest `(d², index)` pairs.

use super::store::Photon;
use glam::Vec3;

/// Ranges of at most this many photons are not split (linear scan at query time).
pub const LEAF: usize = 8;
/// Subtrees larger than this are built in parallel with `rayon::join`.
const PAR_THRESHOLD: usize = 16 * 1024;
/// Traversal stack depth: each level at least halves a range, so 64 covers any `usize` size.
const STACK: usize = 64;

/// Squared distance between a query point and a stored position, in the one float order all
/// queries (and the tests' brute force) use: `dx² + dy² + dz²`.
#[inline]
pub fn dist2(p: [f32; 3], q: [f32; 3]) -> f32 {
    let (dx, dy, dz) = (q[0] - p[0], q[1] - p[1], q[2] - p[2]);
    dx * dx + dy * dy + dz * dz
}

/// A kd-tree photon map (see the module documentation for the layout).
#[derive(Debug, Clone, Default)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// Split axis (0, 1, 2) of the node stored at the same index; unused inside leaves.
    axes: Vec<u8>,
}

impl PhotonMap {
    /// Build the tree from `photons` (reordered in place; non-finite positions dropped).
    pub fn build(mut photons: Vec<Photon>) -> PhotonMap {
        photons.retain(|ph| ph.position().is_finite());
        let mut axes = vec![0u8; photons.len()];
        build_range(&mut photons, &mut axes);
        PhotonMap { photons, axes }
    }

    /// The stored photons, in tree order (the indices the queries return).
    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// Number of photons stored.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// True when no photon is stored.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// The photon at tree index `i`, if any.
    pub fn get(&self, i: usize) -> Option<&Photon> {
        self.photons.get(i)
    }

    /// Bytes of heap memory per stored photon (photon + split-axis byte), for reports.
    pub fn bytes_per_photon() -> usize {
        std::mem::size_of::<Photon>() + 1
    }

    /// The at most `k` nearest photons to `p` with `d² ≤ max_r2`, written to `out` (cleared
    /// first, in no particular order) as `(d², index)`. Returns the largest `d²` found, or 0
    /// when none. Ties are broken by the smaller index. `out` is used as the bounded max-heap,
    /// so a reused `out` makes the query allocation-free.
    pub fn knn(&self, p: Vec3, k: usize, max_r2: f32, out: &mut Vec<(f32, u32)>) -> f32 {
        out.clear();
        // `!(max_r2 >= 0)` would read better but trips clippy; NaN and negatives find nothing.
        if k == 0 || max_r2.is_nan() || max_r2 < 0.0 || !p.is_finite() {
            return 0.0;
        }
        let mut heap = Heap { v: out, k };
        self.walk(p.to_array(), max_r2, |i, d2, r2| {
            heap.offer(d2, i);
            if heap.full() {
                heap.top().0
            } else {
                r2
            }
        });
        // The max-heap's root holds the largest d².
        heap.v.first().map_or(0.0, |e| e.0)
    }

    /// Call `f(photon, d²)` for every photon with `d² ≤ r2` from `p`, in a deterministic
    /// order. Nothing is reported for a NaN or negative `r2` or a non-finite `p`.
    pub fn for_each_within(&self, p: Vec3, r2: f32, mut f: impl FnMut(&Photon, f32)) {
        self.for_each_index_within(p, r2, |i, d2| f(&self.photons[i as usize], d2));
    }

    /// As [`PhotonMap::for_each_within`], reporting the photon's index instead.
    pub fn for_each_index_within(&self, p: Vec3, r2: f32, mut f: impl FnMut(u32, f32)) {
        if r2.is_nan() || r2 < 0.0 || !p.is_finite() {
            return;
        }
        self.walk(p.to_array(), r2, |i, d2, r2| {
            f(i, d2);
            r2
        });
    }

    /// The one traversal of both queries: calls `visit(index, d², r²)` for every photon with
    /// `d² ≤ r²` from `p`, where r² starts at `r2` and becomes what `visit` returns (a kNN
    /// query shrinks it as its heap fills; the radius query keeps it). Visits the node of a
    /// range, then its near side, then its far side while the splitting plane is within r
    /// (equal distance is kept: a tie with a smaller index may still win a kNN query).
    #[inline]
    fn walk(&self, p: [f32; 3], mut r2: f32, mut visit: impl FnMut(u32, f32, f32) -> f32) {
        let mut stack = [(0u32, 0u32, 0f32); STACK];
        let mut sp = 0;
        let (mut lo, mut hi) = (0usize, self.photons.len());
        loop {
            if hi - lo <= LEAF {
                for i in lo..hi {
                    let d2 = dist2(p, self.photons[i].pos_array());
                    if d2 <= r2 {
                        r2 = visit(i as u32, d2, r2);
                    }
                }
            } else {
                let m = lo + (hi - lo) / 2;
                let q = self.photons[m].pos_array();
                let d2 = dist2(p, q);
                if d2 <= r2 {
                    r2 = visit(m as u32, d2, r2);
                }
                let axis = self.axes[m] as usize;
                let diff = p[axis] - q[axis];
                let ((nlo, nhi), (flo, fhi)) = if diff < 0.0 {
                    ((lo, m), (m + 1, hi))
                } else {
                    ((m + 1, hi), (lo, m))
                };
                let plane2 = diff * diff;
                if plane2 <= r2 && fhi > flo {
                    stack[sp] = (flo as u32, fhi as u32, plane2);
                    sp += 1;
                }
                (lo, hi) = (nlo, nhi);
                continue;
            }
            // Pop the next far subtree that can still hold something closer.
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                let (a, b, plane2) = stack[sp];
                if plane2 <= r2 {
                    (lo, hi) = (a as usize, b as usize);
                    break;
                }
            }
        }
    }
}

/// A bounded binary max-heap on `(d², index)` (lexicographic), stored in the caller's `Vec`.
struct Heap<'a> {
    v: &'a mut Vec<(f32, u32)>,
    k: usize,
}

/// Strict lexicographic order on `(d², index)`; d² is never NaN here.
#[inline]
fn less(a: (f32, u32), b: (f32, u32)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

impl Heap<'_> {
    #[inline]
    fn full(&self) -> bool {
        self.v.len() >= self.k
    }

    #[inline]
    fn top(&self) -> (f32, u32) {
        self.v[0]
    }

    /// Insert `(d2, i)` if the heap has room or it beats the current maximum.
    #[inline]
    fn offer(&mut self, d2: f32, i: u32) {
        let e = (d2, i);
        if !self.full() {
            self.v.push(e);
            let mut c = self.v.len() - 1;
            while c > 0 {
                let parent = (c - 1) / 2;
                if less(self.v[parent], self.v[c]) {
                    self.v.swap(parent, c);
                    c = parent;
                } else {
                    break;
                }
            }
        } else if less(e, self.v[0]) {
            self.v[0] = e;
            let n = self.v.len();
            let mut c = 0;
            loop {
                let (l, r) = (2 * c + 1, 2 * c + 2);
                let mut big = c;
                if l < n && less(self.v[big], self.v[l]) {
                    big = l;
                }
                if r < n && less(self.v[big], self.v[r]) {
                    big = r;
                }
                if big == c {
                    break;
                }
                self.v.swap(c, big);
                c = big;
            }
        }
    }
}

/// Build the subtree of `photons` (the whole range) in place; `axes` is the matching slice.
fn build_range(photons: &mut [Photon], axes: &mut [u8]) {
    let n = photons.len();
    if n <= LEAF {
        return;
    }
    let axis = widest_axis(photons);
    let m = n / 2;
    photons.select_nth_unstable_by(m, |a, b| {
        a.pos_array()[axis].total_cmp(&b.pos_array()[axis])
    });
    axes[m] = axis as u8;
    let (left, rest) = photons.split_at_mut(m);
    let right = &mut rest[1..];
    let (aleft, arest) = axes.split_at_mut(m);
    let aright = &mut arest[1..];
    if n > PAR_THRESHOLD {
        rayon::join(|| build_range(left, aleft), || build_range(right, aright));
    } else {
        build_range(left, aleft);
        build_range(right, aright);
    }
}

/// The axis of largest extent of the points' bounding box (ties: lowest axis).
fn widest_axis(photons: &[Photon]) -> usize {
    let mut lo = Vec3::INFINITY;
    let mut hi = Vec3::NEG_INFINITY;
    for ph in photons {
        let p = ph.position();
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let e = hi - lo;
    if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    }
}

#[cfg(test)]
pub(crate) mod tests;
