//! The Sobol' sequence in base 2, with pbrt-v4's three randomisations.
//!
//! Units and invariants:
//! - A point coordinate is computed as 32 bits `v` (a binary fraction, bit 31 = 1/2) by
//!   multiplying the index by the dimension's generator matrix over GF(2) (Sobol' 1967;
//!   matrices of Joe & Kuo 2008, [`super::sobol_table`]), then randomised, then mapped to
//!   `f32` by keeping its top 24 bits: every returned value is in `[0, 1)` exactly (no
//!   clamping, no rounding up to 1).
//! - Indices below `2^SOBOL_MATRIX_SIZE` (2^52) are distinct; higher bits are ignored.
//! - Dimension `d` must be below [`SOBOL_DIMENSIONS`] (64); it is reduced modulo that count
//!   otherwise, so a caller's bug degrades quality, never panics.
//! - The scramblers preserve the net structure: every elementary interval that holds one
//!   point unscrambled holds one point after XOR or Owen scrambling (Owen 1995).
//! - Dimensions 0 and 1, the 2D points of [`super::zsobol`], have fast paths equal to
//!   [`sobol_bits`] with the bits reversed, the order in which Owen scrambling works
//!   ([`owen_reversed`]): dimension 0 reversed is the index's low 32 bits (van der Corput),
//!   dimension 1 reversed is [`sobol_dim1_reversed`] (a subset-sum transform of the index).

use super::sobol_table::{SOBOL_DIMENSIONS, SOBOL_MATRICES, SOBOL_MATRIX_SIZE};

/// How a Sobol' coordinate is randomised (pbrt-v4 `RandomizeStrategy`, util/lowdiscrepancy.h).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scramble {
    /// The deterministic sequence (pbrt-v4 `NoRandomizer`).
    None,
    /// Random digit scrambling: XOR with a 32-bit key (pbrt-v4 `BinaryPermuteScrambler`;
    /// Kollig & Keller 2002, "Efficient multidimensional sampling").
    Xor(u32),
    /// Hash-based nested uniform (Owen) scrambling keyed by a seed (Burley 2020, "Practical
    /// Hash-based Owen Scrambling", JCGT 9(4); pbrt-v4 `FastOwenScrambler`).
    Owen(u32),
}

/// The unrandomised 32-bit Sobol' coordinate of point `index` in dimension `dim`:
/// `v = XOR of column k of the generator matrix over the set bits k of index`
/// (Sobol' 1967; Bratley & Fox 1988, Algorithm 659; pbrt-v4 `SobolSample`).
#[inline]
pub fn sobol_bits(index: u64, dim: usize) -> u32 {
    let columns = &SOBOL_MATRICES[dim % SOBOL_DIMENSIONS];
    let mut a = index & ((1u64 << SOBOL_MATRIX_SIZE) - 1);
    let mut v = 0u32;
    let mut k = 0;
    while a != 0 {
        // Skip runs of zero bits at once.
        let zeros = a.trailing_zeros() as usize;
        k += zeros;
        a >>= zeros;
        v ^= columns[k];
        a >>= 1;
        k += 1;
    }
    v
}

/// Burley's fast Owen scramble of a 32-bit binary fraction (Burley 2020, Sec. 3, listing
/// 3): reverse the bits so the most significant digit becomes the least significant, apply a
/// hash in which every output bit depends only on itself and lower input bits (a
/// Laine–Karras-style permutation: `+ seed`, `x ^= x * even`), and reverse back. Each digit is
/// therefore flipped by a function of the digits above it: a nested uniform scramble. The
/// multipliers are pbrt-v4's `FastOwenScrambler` constants (util/lowdiscrepancy.h).
#[inline]
pub fn fast_owen(v: u32, seed: u32) -> u32 {
    owen_reversed(v.reverse_bits(), seed).reverse_bits()
}

/// [`fast_owen`] on bit-reversed input and output: `fast_owen(v, seed) =
/// owen_reversed(v.reverse_bits(), seed).reverse_bits()`. Output bit `j` depends only on
/// input bits `0..=j`, so the low 24 bits of the result (the 24 bits a sample keeps, once
/// reversed) depend only on the low 24 bits of the input.
#[inline]
pub(super) fn owen_reversed(x: u32, seed: u32) -> u32 {
    let mut x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

/// Apply a randomisation to 32 Sobol' bits.
#[inline]
pub fn scramble_bits(v: u32, scramble: Scramble) -> u32 {
    match scramble {
        Scramble::None => v,
        Scramble::Xor(key) => v ^ key,
        Scramble::Owen(seed) => fast_owen(v, seed),
    }
}

/// A 32-bit binary fraction as `f32` in `[0, 1)`: its top 24 bits, which `f32` holds
/// exactly, times 2^-24 (so the largest value is `1 - 2^-24`).
#[inline]
pub fn bits_to_unit(v: u32) -> f32 {
    (v >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Coordinate `dim` of Sobol' point `index`, randomised by `scramble`, in `[0, 1)`.
#[inline]
pub fn sobol_sample(index: u64, dim: usize, scramble: Scramble) -> f32 {
    bits_to_unit(scramble_bits(sobol_bits(index, dim), scramble))
}

/// Sobol' dimension 0 of `index`: the van der Corput sequence, the index's low 32 bits
/// reversed (its generator matrix is the identity, `sobol_table`); equal to
/// `sobol_bits(index, 0)` at a fraction of the cost.
#[inline]
pub(super) fn van_der_corput(index: u64) -> u32 {
    (index as u32).reverse_bits()
}

/// `sobol_bits(index, 1)` with its bits reversed. Sobol' dimension 1's generator matrix is
/// the Pascal matrix mod 2: column `k` has bit `31 − j` set when C(k, j) is odd, i.e. when
/// `j & k == j` (Lucas's theorem; Joe & Kuo's second dimension, which the tests compare with
/// [`SOBOL_MATRICES`]). So bit `j` of the reversed coordinate is the XOR of the index bits
/// `k < SOBOL_MATRIX_SIZE` with `j & k == j`: the subset-sum (zeta) transform over GF(2),
/// computed one bit `b` of the position at a time by adding each position with bit `b` set
/// into the one without it (the fast zeta transform: Björklund, Husfeldt, Kaski &
/// Koivisto 2007, "Fourier meets Möbius: fast subset convolution", STOC). The `b = 5` step
/// comes first, folding positions 32..63 onto 0..31, since only `j < 32` is kept.
#[inline]
pub(super) fn sobol_dim1_reversed(index: u64) -> u32 {
    let x = index & ((1u64 << SOBOL_MATRIX_SIZE) - 1);
    let mut y = (x ^ (x >> 32)) as u32;
    y ^= (y >> 1) & 0x5555_5555;
    y ^= (y >> 2) & 0x3333_3333;
    y ^= (y >> 4) & 0x0f0f_0f0f;
    y ^= (y >> 8) & 0x00ff_00ff;
    y ^= (y >> 16) & 0x0000_ffff;
    y
}

/// `sobol_bits(index, 1)` from [`sobol_dim1_reversed`].
#[cfg(test)]
fn sobol_dim1(index: u64) -> u32 {
    sobol_dim1_reversed(index).reverse_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Does every elementary interval `[a/2^i, (a+1)/2^i) x [b/2^j, (b+1)/2^j)` with
    /// `i + j = m` hold exactly one of the `2^m` points (the (0, m, 2)-net property)?
    fn is_02_net(points: &[(u32, u32)], m: u32) -> bool {
        assert_eq!(points.len(), 1 << m);
        (0..=m).all(|i| {
            let mut seen = vec![false; 1 << m];
            points.iter().all(|&(x, y)| {
                let cell = if m == 0 {
                    0
                } else {
                    let cx = if i == 0 { 0 } else { (x >> (32 - i)) as usize };
                    let cy = if i == m {
                        0
                    } else {
                        (y >> (32 - (m - i))) as usize
                    };
                    (cx << (m - i)) | cy
                };
                !std::mem::replace(&mut seen[cell], true)
            })
        })
    }

    #[test]
    fn first_points_match_the_published_sequence() {
        // Joe & Kuo's reference generator (sobol.cc) enumerates points in Gray-code order
        // (Antonov & Saleev 1979): point n is our index n ^ (n >> 1). Its first 8 points of
        // dims 0, 1, 2, as published with the direction numbers.
        let d0 = [0.0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125];
        let d1 = [0.0, 0.5, 0.25, 0.75, 0.375, 0.875, 0.125, 0.625];
        let d2 = [0.0, 0.5, 0.25, 0.75, 0.625, 0.125, 0.875, 0.375];
        for n in 0..8u64 {
            let g = n ^ (n >> 1);
            let i = n as usize;
            assert_eq!(
                sobol_sample(g, 0, Scramble::None),
                d0[i],
                "dim 0, point {n}"
            );
            assert_eq!(
                sobol_sample(g, 1, Scramble::None),
                d1[i],
                "dim 1, point {n}"
            );
            assert_eq!(
                sobol_sample(g, 2, Scramble::None),
                d2[i],
                "dim 2, point {n}"
            );
        }
        // In plain index order (pbrt-v4's `SobolSample`, which this module follows), dim 0
        // is the van der Corput sequence.
        let vdc = [0.0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875];
        let d1_direct = [0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875];
        for i in 0..8u64 {
            assert_eq!(sobol_sample(i, 0, Scramble::None), vdc[i as usize]);
            assert_eq!(sobol_sample(i, 1, Scramble::None), d1_direct[i as usize]);
        }
    }

    #[test]
    fn dims_0_1_form_02_nets_unscrambled_xor_and_owen() {
        for m in 0..=10u32 {
            for scr in [
                (Scramble::None, Scramble::None),
                (Scramble::Xor(0x1234_5678), Scramble::Xor(0x9abc_def0)),
                (Scramble::Owen(7), Scramble::Owen(0xdead_beef)),
                (Scramble::Owen(0x8000_0001), Scramble::Owen(42)),
            ] {
                let pts: Vec<(u32, u32)> = (0..1u64 << m)
                    .map(|i| {
                        (
                            scramble_bits(sobol_bits(i, 0), scr.0),
                            scramble_bits(sobol_bits(i, 1), scr.1),
                        )
                    })
                    .collect();
                assert!(is_02_net(&pts, m), "m = {m}, {scr:?}");
            }
        }
    }

    #[test]
    fn every_dimension_is_stratified_in_1d() {
        // Each dimension is a (0,1)-sequence: any aligned block of 2^k points has one point
        // in each interval [j/2^k, (j+1)/2^k); checked for the first two blocks, k <= 12.
        for dim in 0..SOBOL_DIMENSIONS {
            for k in 0..=12u32 {
                for block in 0..2u64 {
                    for scr in [Scramble::None, Scramble::Owen(dim as u32 * 31 + 5)] {
                        let mut seen = vec![false; 1 << k];
                        for i in (block << k)..((block + 1) << k) {
                            let v = scramble_bits(sobol_bits(i, dim), scr);
                            let cell = if k == 0 { 0 } else { (v >> (32 - k)) as usize };
                            assert!(!seen[cell], "dim {dim}, k {k}, block {block}, {scr:?}");
                            seen[cell] = true;
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn owen_scrambling_changes_points_and_stays_below_one() {
        let mut differ = 0;
        for i in 0..1024u64 {
            let a = sobol_bits(i, 3);
            let b = scramble_bits(a, Scramble::Owen(99));
            differ += usize::from(a != b);
            let u = sobol_sample(i, 3, Scramble::Owen(99));
            assert!((0.0..1.0).contains(&u));
        }
        assert!(differ > 1000, "only {differ} of 1024 points moved");
        assert!(bits_to_unit(u32::MAX) < 1.0);
    }

    #[test]
    fn fast_paths_are_sobol_dimensions_0_and_1() {
        let mut rng = crate::math::Rng::new(&[3]);
        for _ in 0..10_000 {
            let i = (u64::from(rng.next_u32()) << 32) | u64::from(rng.next_u32());
            for index in [i, i >> 20, i >> 40] {
                assert_eq!(van_der_corput(index), sobol_bits(index, 0), "{index}");
                assert_eq!(sobol_dim1(index), sobol_bits(index, 1), "{index}");
            }
        }
    }
}
