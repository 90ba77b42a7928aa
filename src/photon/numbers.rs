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

/// The digit permutations of one base-`B` dimension: `N = digits(B)` permutations of
/// `0..B`, one per digit position, and the scale `B^-N` (computed by `N` divisions, so the
/// values equal the digit-by-digit recurrence of pbrt-v4's `ScrambledRadicalInverse`).
#[derive(Debug, Clone)]
struct Dimension<const B: usize, const N: usize> {
    perms: [[u8; B]; N],
    scale: f64,
}

impl<const B: usize, const N: usize> Dimension<B, N> {
    /// The permutations of dimension `d` for `seed` (each from [`permutation_element`]
    /// keyed by a hash of the seed, the dimension and the digit position).
    fn new(seed: u64, d: u64) -> Self {
        const { assert!(N == digits(B as u64)) };
        let mut perms = [[0u8; B]; N];
        let mut scale = 1.0f64;
        for (k, perm) in perms.iter_mut().enumerate() {
            let key = mix64(mix64(seed) ^ (d << 32 | k as u64)) as u32;
            for (i, p) in perm.iter_mut().enumerate() {
                *p = permutation_element(i as u32, B as u32, key) as u8;
            }
            scale /= B as f64;
        }
        Dimension { perms, scale }
    }

    /// The radical inverse of `a` in base `B` with digit position `k` mapped through
    /// `perms[k]` (pbrt-v4 `ScrambledRadicalInverse`): trailing zero digits are permuted
    /// too, so the low digits are random.
    #[inline]
    fn get(&self, mut a: u64) -> f32 {
        let mut reversed = 0u64;
        for perm in &self.perms {
            let next = a / B as u64;
            let digit = (a - next * B as u64) as usize;
            reversed = reversed * B as u64 + u64::from(perm[digit]);
            a = next;
        }
        ((reversed as f64 * self.scale) as f32).min(ONE_MINUS_EPSILON)
    }
}

/// Dimension 0, base 2: a permutation of {0, 1} is the identity or the swap, so the
/// scrambled radical inverse of the 31 kept digits is the index's bits reversed, XOR a
/// mask of the swapped positions.
#[derive(Debug, Clone)]
struct Base2 {
    /// Bit `30 − k` set where digit position `k` is swapped.
    flips: u32,
}

impl Base2 {
    /// Digit positions kept in base 2.
    const N: u32 = digits(2) as u32;

    fn new(seed: u64) -> Self {
        let mut flips = 0;
        for k in 0..Self::N {
            let key = mix64(mix64(seed) ^ u64::from(k)) as u32;
            if permutation_element(0, 2, key) == 1 {
                flips |= 1 << (Self::N - 1 - k);
            }
        }
        Base2 { flips }
    }

    #[inline]
    fn get(&self, a: u64) -> f32 {
        let kept = (a as u32) & ((1 << Self::N) - 1);
        let reversed = (kept.reverse_bits() >> (32 - Self::N)) ^ self.flips;
        // 2^-N by N halvings is exact, as is the product.
        ((f64::from(reversed) * 0.5f64.powi(Self::N as i32)) as f32).min(ONE_MINUS_EPSILON)
    }
}

/// Digit permutations of the emission dimensions for one seed.
#[derive(Debug, Clone)]
pub struct PhotonNumbers {
    d0: Base2,
    d1: Dimension<3, 20>,
    d2: Dimension<5, 13>,
    d3: Dimension<7, 11>,
    d4: Dimension<11, 9>,
}

impl PhotonNumbers {
    /// The permutations for `seed`.
    pub fn new(seed: u64) -> PhotonNumbers {
        PhotonNumbers {
            d0: Base2::new(seed),
            d1: Dimension::new(seed, 1),
            d2: Dimension::new(seed, 2),
            d3: Dimension::new(seed, 3),
            d4: Dimension::new(seed, 4),
        }
    }

    /// The five numbers of photon `index`.
    #[inline]
    pub fn get(&self, index: u64) -> [f32; 5] {
        [
            self.d0.get(index),
            self.d1.get(index),
            self.d2.get(index),
            self.d3.get(index),
            self.d4.get(index),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The digit-by-digit definition: every base's permutations in one vector, a division
    /// of the scale per digit (the reference the tables above must equal bit for bit).
    fn reference(seed: u64, index: u64) -> [f32; 5] {
        std::array::from_fn(|d| {
            let b = u64::from(BASES[d]);
            let mut a = index;
            let (mut reversed, mut scale) = (0u64, 1.0f64);
            for k in 0..digits(b) {
                let key = mix64(mix64(seed) ^ ((d as u64) << 32 | k as u64)) as u32;
                let next = a / b;
                let digit = (a - next * b) as u32;
                let p = permutation_element(digit, b as u32, key);
                reversed = reversed * b + u64::from(p);
                scale /= b as f64;
                a = next;
            }
            ((reversed as f64 * scale) as f32).min(ONE_MINUS_EPSILON)
        })
    }

    #[test]
    fn tables_equal_the_digit_by_digit_definition() {
        let mut rng = crate::math::Rng::new(&[3]);
        for seed in [0, 1, 7, u64::MAX] {
            let nums = PhotonNumbers::new(seed);
            let edges = [0, 1, 2, 3, (1 << 31) - 1, 1 << 31, (1 << 32) + 5, u64::MAX];
            let random = (0..2000).map(|_| {
                let v = u64::from(rng.next_u32()) << 32 | u64::from(rng.next_u32());
                v >> (rng.next_u32() % 64)
            });
            for i in edges.into_iter().chain(random) {
                let (got, want) = (nums.get(i), reference(seed, i));
                assert_eq!(
                    got.map(f32::to_bits),
                    want.map(f32::to_bits),
                    "seed {seed} i {i}"
                );
            }
        }
    }

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
