//! The five uniform numbers a photon is emitted from (light, point 2D, direction 2D), as a
//! low-discrepancy sequence over the photon index: Halton dimensions 0–4 (bases 2, 3, 5, 7,
//! 11; Halton 1960) randomized by random digit permutations, one permutation of the base's
//! digits per dimension and digit position (pbrt-v4 `HaltonSampler` with
//! `RandomizeStrategy::PermuteDigits`, `DigitPermutation` and `ScrambledRadicalInverse` in
//! util/lowdiscrepancy.h; pbrt-v4 SPPM draws its photon paths from Halton over the photon
//! index, src/pbrt/cpu/integrators.cpp).
//!
//! Why not [`crate::sampler::halton::halton_sample`] (Owen scrambling): it hashes every digit
//! down to 2^-53, about 5 µs per photon for the five dimensions, as long as tracing a photon;
//! the permutation tables here are built once per seed and a photon's numbers then cost a
//! table look-up per digit (bases are compile-time constants, so no division).
//!
//! Invariants: every number is in [0, 1) and a pure function of `(index, seed)`; each
//! dimension keeps the Halton stratification (the first `b^k` indices fall one in each
//! interval `[j/b^k, (j+1)/b^k)`), since each digit position is permuted bijectively.
//! Digits are kept while `b^n < 2^32` (beyond f32 resolution).

use crate::math::mix64;
use crate::sampler::halton::permutation_element;

/// The bases of the five emission dimensions.
pub const BASES: [u32; 5] = [2, 3, 5, 7, 11];

/// The largest `f32` below 1.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// Digit positions kept for base `b`: the `n` with `b^n < 2^32 ≤ b^(n+1)`.
const fn digits(b: u64) -> usize {
    let (mut n, mut m) = (0, 1u64);
    while m * b < 1 << 32 {
        m *= b;
        n += 1;
    }
    n
}

/// Digit permutations of the emission dimensions for one seed.
#[derive(Debug, Clone)]
pub struct PhotonNumbers {
    /// Per dimension, `digits(b)` permutations of `0..b` back to back.
    perms: [Vec<u8>; 5],
}

impl PhotonNumbers {
    /// The permutations for `seed` (each from [`permutation_element`] keyed by a hash of the
    /// seed, the dimension and the digit position).
    pub fn new(seed: u64) -> PhotonNumbers {
        let perms = std::array::from_fn(|d| {
            let b = BASES[d];
            let n = digits(b as u64);
            let mut p = Vec::with_capacity(n * b as usize);
            for k in 0..n {
                let key = mix64(mix64(seed) ^ ((d as u64) << 32 | k as u64)) as u32;
                p.extend((0..b).map(|i| permutation_element(i, b, key) as u8));
            }
            p
        });
        PhotonNumbers { perms }
    }

    /// The five numbers of photon `index`.
    pub fn get(&self, index: u64) -> [f32; 5] {
        [
            scrambled::<2>(index, &self.perms[0]),
            scrambled::<3>(index, &self.perms[1]),
            scrambled::<5>(index, &self.perms[2]),
            scrambled::<7>(index, &self.perms[3]),
            scrambled::<11>(index, &self.perms[4]),
        ]
    }
}

/// The radical inverse of `a` in base `B` with digit position `k` mapped through
/// `perm[k·B..(k+1)·B]` (pbrt-v4 `ScrambledRadicalInverse`): trailing zero digits are
/// permuted too, so the low digits are random.
fn scrambled<const B: u64>(mut a: u64, perm: &[u8]) -> f32 {
    let n = digits(B);
    let mut reversed = 0u64;
    let mut scale = 1.0f64;
    for k in 0..n {
        let next = a / B;
        let digit = (a - next * B) as usize;
        let p = perm.get(k * B as usize + digit).copied().unwrap_or(0);
        reversed = reversed * B + u64::from(p);
        scale /= B as f64;
        a = next;
    }
    ((reversed as f64 * scale) as f32).min(ONE_MINUS_EPSILON)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_dimension_stays_stratified() {
        let nums = PhotonNumbers::new(7);
        for (d, &b) in BASES.iter().enumerate() {
            let b = u64::from(b);
            let mut n = 1u64;
            while n * b <= 4096 {
                n *= b;
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let u = nums.get(i)[d];
                    assert!((0.0..1.0).contains(&u));
                    let cell = ((u as f64 * n as f64) as usize).min(n as usize - 1);
                    assert!(!std::mem::replace(&mut seen[cell], true), "dim {d} n {n}");
                }
            }
        }
    }

    #[test]
    fn seeds_give_different_points() {
        let (a, b) = (PhotonNumbers::new(1), PhotonNumbers::new(2));
        let same = (0..100).filter(|&i| a.get(i) == b.get(i)).count();
        assert!(same < 5, "{same}");
        assert_eq!(a.get(12345), PhotonNumbers::new(1).get(12345));
    }
}
