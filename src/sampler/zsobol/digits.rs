//! The digit permutation of [`super::ZSobol`]'s sample index (pbrt-v4 `GetSampleIndex`),
//! laid out so that one dimension permutes eight base-4 digits per 256-bit vector.
//!
//! The index `m` (pixel Morton code, sample bits, block above) has `count` permuted base-4
//! digits and, when `log2 spp` is odd, one single bit below them. Digit `i` counts from the
//! bottom: with `odd` = `log2 spp mod 2`, digit 0 of an odd layout is bit 0 and digit
//! `i ≥ odd` covers bits `2i − odd` and `2i − odd + 1`. The formulas (bit-identical to
//! pbrt-v4's design as written in this crate):
//! - Digit `i`'s key is `k_i = ⌊mix64((m >> (2i + 2 − odd)) ⊕ seed_mix) / 2^32⌋`: a hash of
//!   the digits above it and the seed (SplitMix64's finaliser, [`mix64`]). It depends on
//!   the pixel sample only, so [`Digits::set`] computes it once per pixel sample, and only
//!   for the digits at or below the highest bit that changed since the previous one
//!   (consecutive samples of a pixel change one or two digits).
//! - In a dimension with the 64-bit key `K`, digit `i` takes permutation
//!   `p = ⌊24·h / 2^32⌋` of the 24 in [`PERMUTATIONS`], where `h` is the high 32 bits of
//!   `(k_i ⊕ K)·M mod 2^64`, `M` = 0x9E37_79B9_7F4A_7C15 (a multiply-shift range reduction,
//!   Lemire 2019, "Fast random integer generation in an interval", ACM TOMACS 29(1)).
//!   The single bit of an odd layout is flipped by the top bit of the same `h` for `k_0`.
//! - `h` from 32-bit products, so eight digits fit one vector: with `a = k_i ⊕ K_lo`,
//!   `(k_i ⊕ K) = K_hi·2^32 + a` and the schoolbook product of two-word numbers (Knuth,
//!   TAOCP vol. 2, §4.3.1) gives `h = ⌊a·M_lo / 2^32⌋ + a·M_hi + K_hi·M_lo (mod 2^32)`;
//!   the last term is one per dimension.
//! - `⌊24h / 2^32⌋ = ⌊3h / 2^29⌋ = 3·⌊h / 2^29⌋ + ⌊3·(h mod 2^29) / 2^29⌋`, all in 32 bits
//!   (`3·(h mod 2^29) < 2^31`).
//! - The permuted digit `PERMUTATIONS[p][d]` is bits `2p, 2p + 1` of the 48-bit column
//!   `T_d` ([`COLUMNS`]); a digit's slot holds `T_d`'s low and high 32-bit words, read by a
//!   variable shift of `2p mod 32` in the word that `p ≥ 16` selects. Slots past `count`
//!   hold zero words and so add nothing.
//!
//! Invariant: after [`Digits::set`]`(m)`, every slot below `count` holds the key and the
//! column of `m`'s digit, exactly as a fresh computation would, whatever index was set
//! before.

use crate::math::mix64;

/// The 24 permutations of four base-4 digits (pbrt-v4 `ZSobolSampler::GetSampleIndex`).
pub(super) const PERMUTATIONS: [[u8; 4]; 24] = [
    [0, 1, 2, 3],
    [0, 1, 3, 2],
    [0, 2, 1, 3],
    [0, 2, 3, 1],
    [0, 3, 2, 1],
    [0, 3, 1, 2],
    [1, 0, 2, 3],
    [1, 0, 3, 2],
    [1, 2, 0, 3],
    [1, 2, 3, 0],
    [1, 3, 2, 0],
    [1, 3, 0, 2],
    [2, 1, 0, 3],
    [2, 1, 3, 0],
    [2, 0, 1, 3],
    [2, 0, 3, 1],
    [2, 3, 0, 1],
    [2, 3, 1, 0],
    [3, 1, 2, 0],
    [3, 1, 0, 2],
    [3, 2, 1, 0],
    [3, 2, 0, 1],
    [3, 0, 2, 1],
    [3, 0, 1, 2],
];

/// `COLUMNS[d]` holds `PERMUTATIONS[p][d]` in bits `2p, 2p + 1`, for all 24 `p`.
const COLUMNS: [u64; 4] = {
    let mut t = [0u64; 4];
    let mut d = 0;
    while d < 4 {
        let mut p = 0;
        while p < 24 {
            t[d] |= (PERMUTATIONS[p][d] as u64) << (2 * p);
            p += 1;
        }
        d += 1;
    }
    t
};

/// The range reduction's multiplier `M` and its 32-bit halves.
const MUL: u64 = 0x9E37_79B9_7F4A_7C15;
const MUL_LO: u32 = MUL as u32;
const MUL_HI: u32 = (MUL >> 32) as u32;

/// Digits permuted per vector.
const LANES: usize = 8;
/// Vectors of digits in a 64-bit index (32 base-4 digits).
const VECTORS: usize = 4;

/// The per-pixel-sample digit keys and columns of a [`super::ZSobol`], slot `s` (digit
/// `s + odd`) in lane `s mod 8` of vector `s / 8`.
#[derive(Debug, Clone)]
pub(super) struct Digits {
    /// 1 when `log2 spp` is odd (a single bit below the base-4 digits), else 0.
    odd: u32,
    /// Base-4 digits permuted: slots `0..count`.
    count: u32,
    /// `mix64(seed)`.
    seed_mix: u64,
    /// The index the slots describe.
    index: u64,
    /// `keys[i]` = `k_i`, digit `i`'s key (slot `s` reads `keys[s + odd]`; one spare entry
    /// keeps the last vector of an odd layout in bounds).
    keys: [u32; LANES * VECTORS + 1],
    /// The low 32 bits of the slot's digit's column (read when `p < 16`), 0 past `count`.
    low: [[u32; LANES]; VECTORS],
    /// The high 16 bits of the slot's digit's column (read when `p ≥ 16`), 0 past `count`.
    high: [[u32; LANES]; VECTORS],
}

impl Digits {
    /// The digits of index 0 for `base4_digits` digits in all (the single bit of an odd
    /// layout included, as pbrt-v4 `nBase4Digits` counts it).
    pub(super) fn new(base4_digits: u32, odd: u32, seed_mix: u64) -> Self {
        let mut d = Digits {
            odd,
            count: base4_digits - odd,
            seed_mix,
            index: 0,
            keys: [0; LANES * VECTORS + 1],
            low: [[0; LANES]; VECTORS],
            high: [[0; LANES]; VECTORS],
        };
        d.refresh(0, u64::BITS + 2);
        d
    }

    /// Vectors holding permuted digits: the largest `vectors` argument of
    /// [`Digits::permuted`] that does any work.
    pub(super) fn vectors(&self) -> u32 {
        self.count.div_ceil(LANES as u32)
    }

    /// Describe index `m`, recomputing only the slots whose digits changed.
    #[inline]
    pub(super) fn set(&mut self, m: u64) {
        let changed = u64::BITS - (m ^ self.index).leading_zeros();
        self.refresh(m, changed);
    }

    /// Describe index `m`, which differs from the described one only in its `changed`
    /// lowest bits.
    fn refresh(&mut self, m: u64, changed: u32) {
        self.index = m;
        let odd = self.odd;
        // Digit i's key reads bits from 2i + 2 - odd up: stale when that is below `changed`.
        let stale_keys = ((changed + odd).saturating_sub(1) / 2).min(self.count + odd);
        for i in 0..stale_keys {
            let higher = m.checked_shr(2 * i + 2 - odd).unwrap_or(0);
            self.keys[i as usize] = (mix64(higher ^ self.seed_mix) >> 32) as u32;
        }
        // Slot s's digit is at bits 2s + odd, 2s + odd + 1.
        let stale_digits = changed.saturating_sub(odd).div_ceil(2).min(self.count);
        let digits = m >> odd;
        let low = self.low.as_flattened_mut();
        let high = self.high.as_flattened_mut();
        for s in 0..stale_digits as usize {
            let column = COLUMNS[(digits >> (2 * s) & 3) as usize];
            low[s] = column as u32;
            high[s] = (column >> 32) as u32;
        }
    }

    /// The permuted index below its block bits in the dimension with key `key`, computing
    /// the first `vectors` vectors of slots (digits below `odd + 8·vectors`); the bits above
    /// them are 0. `vectors ≥` [`Digits::vectors`] gives every bit.
    #[inline]
    pub(super) fn permuted(&self, key: u64, vectors: u32) -> u64 {
        let key_lo = key as u32;
        let key_term = ((key >> 32) as u32).wrapping_mul(MUL_LO);
        let mut digits = 0u64;
        let odd = self.odd as usize;
        for v in 0..(vectors.min(self.vectors()) as usize) {
            let Some(keys) = self.keys[odd + LANES * v..].first_chunk() else {
                break;
            };
            let bits = permute_lanes(keys, &self.low[v], &self.high[v], key_lo, key_term);
            digits |= u64::from(bits) << (16 * v);
        }
        let mut index = digits << self.odd;
        if self.odd == 1 {
            let flip = (u64::from(self.keys[0]) ^ key).wrapping_mul(MUL) >> 63;
            index |= (self.index & 1) ^ flip;
        }
        index
    }
}

/// Eight permuted digits, slot `l`'s at bits `2l, 2l + 1` (the module docs' formulas, one
/// slot per vector lane).
#[inline(always)]
fn permute_lanes(
    keys: &[u32; LANES],
    low: &[u32; LANES],
    high: &[u32; LANES],
    key_lo: u32,
    key_term: u32,
) -> u32 {
    let mut bits = [0u32; LANES];
    for l in 0..LANES {
        let p = permutation_of(product_high(keys[l], key_lo, key_term));
        // All ones when p ≥ 16.
        let upper = (15u32.wrapping_sub(p) as i32 >> 31) as u32;
        let word = low[l] ^ ((low[l] ^ high[l]) & upper);
        // Placed 2 bits higher than its slot, so that no lane shifts by 0 and all eight
        // lanes compile to the same vector instructions.
        bits[l] = ((word >> ((2 * p) & 31)) & 3) << (2 * l + 2);
    }
    bits.iter().fold(0, |acc, b| acc | b) >> 2
}

/// `h`, the high 32 bits of `(k ⊕ K)·M mod 2^64`, from 32-bit products: `key_lo` is
/// `K mod 2^32`, `key_term` is `K_hi·M_lo mod 2^32` (module docs).
#[inline(always)]
fn product_high(k: u32, key_lo: u32, key_term: u32) -> u32 {
    let a = k ^ key_lo;
    let carry = ((u64::from(a) * u64::from(MUL_LO)) >> 32) as u32;
    carry
        .wrapping_add(a.wrapping_mul(MUL_HI))
        .wrapping_add(key_term)
}

/// `⌊24h / 2^32⌋` in 32-bit arithmetic (module docs).
#[inline(always)]
fn permutation_of(h: u32) -> u32 {
    3 * (h >> 29) + ((3 * (h & 0x1FFF_FFFF)) >> 29)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_hold_every_permutation() {
        for (p, perm) in PERMUTATIONS.iter().enumerate() {
            for d in 0..4 {
                assert_eq!((COLUMNS[d] >> (2 * p)) & 3, u64::from(perm[d]));
            }
        }
        assert!(COLUMNS.iter().all(|c| c >> 48 == 0));
    }

    #[test]
    fn the_product_from_32_bit_halves_is_the_64_bit_product() {
        let mut rng = crate::math::Rng::new(&[17]);
        let edges = [
            0u32,
            1,
            0x1FFF_FFFF,
            0x2000_0000,
            0xAAAA_AAAA,
            0xAAAA_AAAB,
            u32::MAX,
        ];
        let mut cases: Vec<(u32, u64)> = Vec::new();
        for &k in &edges {
            for &hi in &edges {
                for &lo in &edges {
                    cases.push((k, u64::from(hi) << 32 | u64::from(lo)));
                }
            }
        }
        cases.extend((0..200_000).map(|_| {
            let k = rng.next_u32();
            (
                k,
                u64::from(rng.next_u32()) << 32 | u64::from(rng.next_u32()),
            )
        }));
        for (k, key) in cases {
            let full = (u64::from(k) ^ key).wrapping_mul(MUL) >> 32;
            let key_term = ((key >> 32) as u32).wrapping_mul(MUL_LO);
            let h = product_high(k, key as u32, key_term);
            assert_eq!(u64::from(h), full, "k {k:#x} key {key:#x}");
        }
    }

    #[test]
    fn the_permutation_index_is_the_64_bit_range_reduction() {
        let mut rng = crate::math::Rng::new(&[18]);
        // Around every boundary ⌈j·2^32/24⌉ between two permutations, and at random.
        let boundaries = (0..=24u64).flat_map(|j| {
            let b = (j << 32).div_ceil(24);
            (b.saturating_sub(2)..b + 2).filter(|&h| h <= u64::from(u32::MAX))
        });
        let random = (0..200_000).map(|_| u64::from(rng.next_u32()));
        for h in boundaries.chain(random) {
            assert_eq!(
                u64::from(permutation_of(h as u32)),
                (h * 24) >> 32,
                "h {h:#x}"
            );
        }
    }
}
