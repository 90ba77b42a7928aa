//! The Halton sequence with Owen scrambling, indexed by one global counter: for photon
//! emission, where a photon's number (not a pixel) is the index (pbrt-v4 SPPM draws its
//! photon paths from Halton over the photon index, src/pbrt/cpu/integrators.cpp).
//!
//! Invariants:
//! - Dimension `d` is the radical inverse in base `PRIMES[d]` (Halton 1960), `d` below
//!   [`HALTON_DIMENSIONS`] (reduced modulo that count otherwise: never a panic).
//! - Owen scrambling permutes each digit by a hash of the digits above it (pbrt-v4
//!   `OwenScrambledRadicalInverse`, util/lowdiscrepancy.h), so the first `b^k` points of a
//!   base-`b` dimension still fall one in each interval `[j/b^k, (j+1)/b^k)`.
//! - Digits are taken down to `2^-53` (f64), then rounded to `f32` in `[0, 1)`.
//! - Every value is a pure function of `(index, dim, seed)`.

use crate::math::mix64;

/// Number of Halton dimensions (one prime base each).
pub const HALTON_DIMENSIONS: usize = 64;

/// The first 64 primes: the bases of the Halton dimensions.
pub const PRIMES: [u32; HALTON_DIMENSIONS] = [
    2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89, 97,
    101, 103, 107, 109, 113, 127, 131, 137, 139, 149, 151, 157, 163, 167, 173, 179, 181, 191, 193,
    197, 199, 211, 223, 227, 229, 233, 239, 241, 251, 257, 263, 269, 271, 277, 281, 283, 293, 307,
    311,
];

/// The largest `f32` below 1.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// Element `i` of a pseudo-random permutation of `0..len` chosen by `key` (Kensler 2013,
/// "Correlated Multi-Jittered Sampling", Pixar TM 13-01, `permute`; pbrt-v4
/// `PermutationElement`). Every step is a bijection on the low bits under mask `w`, and
/// cycle-walking (`while i >= len`) restricts it to `0..len`. `len` must be at least 1.
pub fn permutation_element(mut i: u32, len: u32, key: u32) -> u32 {
    let len = len.max(1);
    let mut w = len - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= key;
        i = i.wrapping_mul(0xe170_893d);
        i ^= key >> 16;
        i ^= (i & w) >> 4;
        i ^= key >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= key >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | key >> 27);
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if i < len {
            break;
        }
    }
    ((u64::from(i) + u64::from(key)) % u64::from(len)) as u32
}

/// Radical inverse of `a` in base `PRIMES[dim]`: the digits of `a` mirrored about the
/// radix point, `Σ d_k b^-(k+1)` (Halton 1960). `owen = Some(hash)` permutes digit `k` by
/// [`permutation_element`] keyed on `hash` and the already-reversed higher digits (Owen
/// 1995; pbrt-v4 `OwenScrambledRadicalInverse`).
pub fn radical_inverse(dim: usize, mut a: u64, owen: Option<u32>) -> f32 {
    let base = u64::from(PRIMES[dim % HALTON_DIMENSIONS]);
    let inv_base = 1.0 / base as f64;
    let mut inv_base_m = 1.0f64;
    let mut reversed = 0u64;
    // Stop once a digit weighs under 2^-53: `reversed` stays below 2^53 * base.
    while inv_base_m > f64::EPSILON / 2.0 {
        let next = a / base;
        let mut digit = (a - next * base) as u32;
        if let Some(hash) = owen {
            let digit_hash = mix64(u64::from(hash) ^ reversed) as u32;
            digit = permutation_element(digit, base as u32, digit_hash);
        }
        reversed = reversed * base + u64::from(digit);
        inv_base_m *= inv_base;
        a = next;
    }
    ((reversed as f64 * inv_base_m) as f32).min(ONE_MINUS_EPSILON)
}

/// Coordinate `dim` of Owen-scrambled Halton point `index` under `seed`, in `[0, 1)`.
pub fn halton_sample(index: u64, dim: usize, seed: u64) -> f32 {
    let hash = mix64(mix64(seed) ^ (dim as u64)) as u32;
    radical_inverse(dim, index, Some(hash))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unscrambled_values_are_the_radical_inverse() {
        let b2 = [0.0, 0.5, 0.25, 0.75, 0.125];
        let b3 = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0 / 9.0, 4.0 / 9.0, 7.0 / 9.0];
        for (i, &want) in b2.iter().enumerate() {
            assert_eq!(radical_inverse(0, i as u64, None), want);
        }
        for (i, &want) in b3.iter().enumerate() {
            assert!(
                (radical_inverse(1, i as u64, None) - want).abs() < 1e-7,
                "{i}"
            );
        }
    }

    #[test]
    fn permutation_element_is_a_permutation() {
        for len in [1u32, 2, 3, 5, 7, 16, 31, 100, 311] {
            for key in [0u32, 1, 0xdead_beef, 12345] {
                let mut seen = vec![false; len as usize];
                for i in 0..len {
                    let p = permutation_element(i, len, key) as usize;
                    assert!(
                        !std::mem::replace(&mut seen[p], true),
                        "len {len} key {key}"
                    );
                }
            }
        }
    }

    #[test]
    fn owen_halton_stays_stratified_per_base() {
        for (dim, &base) in PRIMES.iter().enumerate().take(12) {
            let base = u64::from(base);
            let mut n = 1u64;
            while n * base <= 2048 {
                n *= base;
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let u = halton_sample(i, dim, 7);
                    assert!((0.0..1.0).contains(&u));
                    let cell = ((u as f64 * n as f64) as usize).min(n as usize - 1);
                    assert!(!std::mem::replace(&mut seen[cell], true), "dim {dim} n {n}");
                }
            }
        }
    }
}
