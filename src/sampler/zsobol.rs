//! Owen-scrambled Sobol' samples indexed per pixel in Morton order: pbrt-v4's
//! `ZSobolSampler` design (Ahmed & Wonka 2020, "Screen-Space Blue-Noise Diffusion of Monte
//! Carlo Sampling Error via Hierarchical Ordering of Pixels", SIGGRAPH Asia; pbrt-v4
//! src/pbrt/samplers.h), written anew in Rust.
//!
//! Invariants:
//! - The whole image shares one 2D Sobol' sequence (dims 0 and 1 of [`super::sobol`]).
//!   Pixel `(x, y)`'s sample `i` is Sobol' point `Z(x, y) · spp + i` with its base-4 digits
//!   permuted: each digit by one of the 24 permutations of {0,1,2,3}, chosen by hashing the
//!   digits above it with the dimension and seed. Because a digit's permutation depends only
//!   on higher digits, the map is a bijection that keeps aligned blocks aligned: a pixel's
//!   `spp` samples are one aligned block of the sequence (a (0, m, 2)-net, stratified), and
//!   neighbouring pixels (neighbouring Morton blocks) get complementary strata, which
//!   spreads the error as blue noise.
//! - Every value is a pure function of `(x, y, sample index, dimension, seed,
//!   samples_per_pixel, resolution)`, so an N-sample image is identical however its samples
//!   are split into rounds, threads or shards, provided `samples_per_pixel` and the
//!   resolution passed to [`ZSobol::new`] are the same for every part. The only state kept
//!   from one pixel sample to the next is a cache: the digit keys of the previous index,
//!   of which [`ZSobol::start_pixel_sample`] recomputes those the new index changes
//!   ([`digits`]).
//! - `samples_per_pixel` is the size of a pixel's block; it is rounded up to a power of two.
//!   Sample indices at or above it continue in further blocks placed above every pixel's
//!   digits (an extension of pbrt-v4, which requires `index < spp`): quality stays that of
//!   Sobol' blocks, and nothing aliases onto another pixel.
//! - The dimension counter advances by 1 per [`ZSobol::get_1d`] and 2 per
//!   [`ZSobol::get_2d`]; it is unbounded (each dimension only keys hashes), so path length
//!   is not limited by the 64 tabulated Sobol' dimensions.
//! - Values are in `[0, 1)`.
//!
//! Cost: starting a pixel sample hashes the changed digits (one `mix64` each: one or two
//! for the next sample of the same pixel); a draw hashes its dimension twice and permutes
//! eight digits per 256-bit vector ([`digits`]), and a 1D draw permutes only the digits
//! below bit 32, the bits Sobol' dimension 0 reads.

use super::sobol::{bits_to_unit, owen_reversed, sobol_dim1_reversed, van_der_corput};
use crate::math::mix64;
use digits::Digits;

mod digits;
#[cfg(test)]
mod reference_tests;

/// How [`ZSobol`] randomises each dimension (pbrt-v4 `RandomizeStrategy`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Randomize {
    /// Digit permutation of the index only; coordinates unscrambled (for tests).
    None,
    /// Random digit scrambling (XOR with a hashed key per dimension).
    Xor,
    /// Hash-based Owen scrambling (Burley 2020) per dimension: the default.
    Owen,
}

/// Spread the low 32 bits of `v` to the even bit positions of a `u64` (for Morton codes;
/// the classic magic-number interleave, e.g. pbrt-v4 `LeftShift2`).
#[inline]
fn spread_bits(v: u32) -> u64 {
    let mut x = u64::from(v);
    x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
    x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x << 2)) & 0x3333_3333_3333_3333;
    x = (x | (x << 1)) & 0x5555_5555_5555_5555;
    x
}

/// The Morton (Z-order) code of `(x, y)`: x in the even bits, y in the odd bits.
#[inline]
pub fn morton2(x: u32, y: u32) -> u64 {
    spread_bits(x) | (spread_bits(y) << 1)
}

/// Largest pixel block: 2^32 samples per pixel.
const MAX_SPP: u64 = 1 << 32;
/// Largest image side for distinct Morton codes: 65536 pixels (with [`MAX_SPP`], the
/// permuted digits fill the 64-bit index exactly).
const MAX_RES: u32 = 1 << 16;

/// `x >> n`, 0 when `n >= 64`.
#[inline]
fn shr(x: u64, n: u32) -> u64 {
    x.checked_shr(n).unwrap_or(0)
}

/// `x << n`, 0 when `n >= 64`.
#[inline]
fn shl(x: u64, n: u32) -> u64 {
    x.checked_shl(n).unwrap_or(0)
}

/// A per-pixel Sobol' sampler in Morton order. Cheap to copy: one per worker thread.
#[derive(Debug, Clone)]
pub struct ZSobol {
    randomize: Randomize,
    log2_spp: u32,
    /// Bits below the "block" part of the index: `2 log2(res) + log2_spp`.
    low_bits: u32,
    /// The index's block bits (at and above `low_bits`), which are not permuted.
    block_bits: u64,
    dimension: u32,
    /// `mix64(seed)`: the dimension keys' base.
    seed_mix: u64,
    /// The permuted digits' keys and values for the current pixel sample, set by
    /// [`ZSobol::start_pixel_sample`]; each dimension combines them with its own key.
    digits: Digits,
}

impl ZSobol {
    /// A sampler for an image of `resolution` = (width, height) pixels taking blocks of
    /// `samples_per_pixel` samples (rounded up to a power of two and clamped to
    /// `[1, 2^32]`), Owen scrambled and keyed by `seed`. Pixels must lie inside the
    /// resolution (clamped to 65536 a side) for their sequences to be disjoint.
    pub fn new(samples_per_pixel: u64, resolution: (u32, u32), seed: u64) -> Self {
        Self::with_randomize(samples_per_pixel, resolution, seed, Randomize::Owen)
    }

    /// As [`ZSobol::new`] with a chosen randomisation.
    pub fn with_randomize(
        samples_per_pixel: u64,
        resolution: (u32, u32),
        seed: u64,
        randomize: Randomize,
    ) -> Self {
        let spp = samples_per_pixel.clamp(1, MAX_SPP);
        let log2_spp = spp.next_power_of_two().trailing_zeros();
        let res = resolution.0.max(resolution.1).clamp(1, MAX_RES);
        let res = res.next_power_of_two();
        let log2_res = res.trailing_zeros();
        let seed_mix = mix64(seed);
        // Base-4 digits covering pixel and sample bits (pbrt-v4 `nBase4Digits`).
        let base4_digits = log2_res + log2_spp.div_ceil(2);
        ZSobol {
            randomize,
            log2_spp,
            low_bits: 2 * log2_res + log2_spp,
            block_bits: 0,
            dimension: 0,
            seed_mix,
            digits: Digits::new(base4_digits, log2_spp & 1, seed_mix),
        }
    }

    /// Samples per pixel block (a power of two).
    pub fn samples_per_pixel(&self) -> u64 {
        1 << self.log2_spp
    }

    /// Start sample `index` of pixel `(x, y)` at dimension 0.
    pub fn start_pixel_sample(&mut self, x: u32, y: u32, index: u64) {
        let block = index >> self.log2_spp;
        let within = index & ((1u64 << self.log2_spp) - 1);
        let local = (morton2(x, y) << self.log2_spp) | within;
        let morton_index = local | shl(block, self.low_bits);
        self.block_bits = shl(shr(morton_index, self.low_bits), self.low_bits);
        self.digits.set(morton_index);
        self.dimension = 0;
    }

    /// The next dimension to be drawn.
    pub fn dimension(&self) -> u32 {
        self.dimension
    }

    /// Jump to dimension `dim` (for a fixed dimension schedule: a bounce starts at its
    /// own dimension whatever the previous bounce drew).
    pub fn set_dimension(&mut self, dim: u32) {
        self.dimension = dim;
    }

    /// A 1D sample in `[0, 1)`; advances the dimension by 1.
    #[inline]
    pub fn get_1d(&mut self) -> f32 {
        let dim = self.dimension;
        self.dimension = dim.wrapping_add(1);
        // Sobol' dimension 0 reads the index's low 32 bits only, which the first two
        // vectors of digits (16 base-4 digits above the odd bit) cover.
        let index = self.sample_index_below(dim, 2);
        let hash = self.dimension_hash(dim) as u32;
        bits_to_unit(match self.randomize {
            Randomize::None => van_der_corput(index),
            Randomize::Xor => van_der_corput(index) ^ hash,
            // Dimension 0 bit-reversed is the index itself ([`super::sobol`]).
            Randomize::Owen => owen_reversed(index as u32, hash).reverse_bits(),
        })
    }

    /// A 2D sample in `[0, 1)^2` (Sobol' dims 0 and 1 of one permuted index); advances the
    /// dimension by 2.
    #[inline]
    pub fn get_2d(&mut self) -> [f32; 2] {
        self.get_2d_with(self.randomize)
    }

    /// [`ZSobol::get_2d`] with the randomisation `randomize` for this draw. A random digit
    /// shift ([`Randomize::Xor`]) keeps each coordinate of a pixel's 2^k first samples on a
    /// shifted regular grid of spacing 2^-k (Owen scrambling only keeps one per stratum):
    /// what a periodic use of the number needs (the hero wavelength's rotation,
    /// [`crate::spectrum::hero_number`]).
    #[inline]
    pub fn get_2d_with(&mut self, randomize: Randomize) -> [f32; 2] {
        let dim = self.dimension;
        self.dimension = dim.wrapping_add(2);
        let index = self.sample_index(dim);
        let hash = self.dimension_hash(dim);
        // Both coordinates bit-reversed, dimension 0 in the high half, so that one 64-bit
        // reversal restores both (dimension 0 to the low half).
        let (r0, r1) = (index as u32, sobol_dim1_reversed(index));
        let (r0, r1, xor) = match randomize {
            Randomize::None => (r0, r1, 0),
            Randomize::Xor => (r0, r1, hash),
            Randomize::Owen => (
                owen_reversed(r0, hash as u32),
                owen_reversed(r1, (hash >> 32) as u32),
                0,
            ),
        };
        let v = ((u64::from(r0) << 32) | u64::from(r1)).reverse_bits() ^ xor;
        [bits_to_unit(v as u32), bits_to_unit((v >> 32) as u32)]
    }

    /// The film position within the pixel: a 2D sample (pbrt-v4 `GetPixel2D`).
    pub fn get_pixel_2d(&mut self) -> [f32; 2] {
        self.get_2d()
    }

    /// A 64-bit key for dimension `dim` under this sampler's seed.
    #[inline]
    fn dimension_hash(&self, dim: u32) -> u64 {
        mix64(self.seed_mix ^ u64::from(dim))
    }

    /// The Sobol' index for dimension `dim`: every base-4 digit of the Morton index permuted
    /// by a permutation chosen from the digits above it (pbrt-v4 `GetSampleIndex`). With an
    /// odd `log2_spp` the lowest single bit is flipped by a hash instead.
    #[inline]
    fn sample_index(&self, dim: u32) -> u64 {
        self.sample_index_below(dim, u32::MAX)
    }

    /// [`ZSobol::sample_index`] with only the first `vectors` vectors of 8 base-4 digits
    /// permuted ([`digits`]): exact in its bits below `odd + 16·vectors`.
    #[inline]
    fn sample_index_below(&self, dim: u32, vectors: u32) -> u64 {
        let key = mix64(self.seed_mix ^ 0x5555_5555_5555_5555 ^ (u64::from(dim) << 32));
        self.block_bits | self.digits.permuted(key, vectors)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 32-bit coordinates of a pixel's samples `0..n` in one 2D dimension.
    fn pixel_points(s: &mut ZSobol, x: u32, y: u32, n: u64, dim: u32) -> Vec<(u32, u32)> {
        (0..n)
            .map(|i| {
                s.start_pixel_sample(x, y, i);
                s.set_dimension(dim);
                let [u, v] = s.get_2d();
                ((u * 16_777_216.0) as u32, (v * 16_777_216.0) as u32)
            })
            .collect()
    }

    /// One point in each of the `n` cells of every `2^i x 2^j` grid with `2^(i+j) = n`
    /// (coordinates as 24-bit integers).
    fn stratified(points: &[(u32, u32)]) -> bool {
        let m = points.len().trailing_zeros();
        (0..=m).all(|i| {
            let mut seen = vec![false; points.len()];
            points.iter().all(|&(x, y)| {
                let cx = (u64::from(x) << i >> 24) as usize;
                let cy = (u64::from(y) << (m - i) >> 24) as usize;
                !std::mem::replace(&mut seen[(cx << (m - i)) | cy], true)
            })
        })
    }

    #[test]
    fn morton_interleaves_x_in_even_bits() {
        assert_eq!(morton2(0, 0), 0);
        assert_eq!(morton2(1, 0), 1);
        assert_eq!(morton2(0, 1), 2);
        assert_eq!(morton2(3, 3), 15);
        assert_eq!(morton2(u32::MAX, 0), 0x5555_5555_5555_5555);
    }

    #[test]
    fn a_pixels_samples_are_stratified_for_every_power_of_two() {
        for log2 in 0..=10u32 {
            for randomize in [Randomize::None, Randomize::Xor, Randomize::Owen] {
                let mut s = ZSobol::with_randomize(1 << log2, (640, 480), 3, randomize);
                for (x, y, dim) in [(0, 0, 0), (17, 5, 2), (639, 479, 9)] {
                    let pts = pixel_points(&mut s, x, y, 1 << log2, dim);
                    assert!(
                        stratified(&pts),
                        "spp 2^{log2} {randomize:?} ({x},{y}) d{dim}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_stratification_check_rejects_random_points() {
        let mut rng = crate::math::Rng::new(&[1]);
        let pts: Vec<(u32, u32)> = (0..64)
            .map(|_| (rng.next_u32() >> 8, rng.next_u32() >> 8))
            .collect();
        assert!(!stratified(&pts));
    }

    #[test]
    fn prefixes_of_a_power_of_four_apart_are_stratified() {
        // The index permutation acts on base-4 digits (the lowest single bit for odd
        // log2 spp), so a prefix of 2^j samples is a whole block when log2 spp - j is even.
        let mut s = ZSobol::new(256, (64, 64), 11);
        for j in [0u32, 2, 4, 6, 8] {
            assert!(
                stratified(&pixel_points(&mut s, 9, 40, 1 << j, 4)),
                "prefix 2^{j}"
            );
        }
    }

    #[test]
    fn samples_past_the_block_continue_in_fresh_strata() {
        let mut s = ZSobol::new(16, (32, 32), 5);
        let all = pixel_points(&mut s, 3, 7, 64, 0);
        for block in all.chunks(16) {
            assert!(stratified(block));
        }
        let mut sorted = all.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), 64, "blocks repeat points");
    }

    #[test]
    fn neighbouring_pixels_get_different_samples() {
        let mut s = ZSobol::new(16, (64, 64), 1);
        let a = pixel_points(&mut s, 10, 10, 16, 0);
        for (x, y) in [(11, 10), (10, 11), (9, 10), (10, 9)] {
            let b = pixel_points(&mut s, x, y, 16, 0);
            assert!(a.iter().all(|p| !b.contains(p)), "({x},{y}) shares a point");
        }
    }

    #[test]
    fn dimensions_and_seeds_decorrelate() {
        let mut s = ZSobol::new(64, (64, 64), 1);
        let d0 = pixel_points(&mut s, 5, 5, 64, 0);
        let d2 = pixel_points(&mut s, 5, 5, 64, 2);
        assert_ne!(d0, d2);
        let mut t = ZSobol::new(64, (64, 64), 2);
        assert_ne!(d0, pixel_points(&mut t, 5, 5, 64, 0));
    }

    #[test]
    fn counter_advances_one_per_1d_and_two_per_2d() {
        let mut s = ZSobol::new(4, (8, 8), 0);
        s.start_pixel_sample(1, 2, 3);
        let a = s.get_1d();
        let b = s.get_2d();
        let c = s.get_1d();
        assert_eq!(s.dimension(), 4);
        s.start_pixel_sample(1, 2, 3);
        assert_eq!(s.get_1d(), a);
        s.set_dimension(1);
        assert_eq!(s.get_2d(), b);
        s.set_dimension(3);
        assert_eq!(s.get_1d(), c);
    }

    #[test]
    fn odd_and_huge_arguments_do_not_panic() {
        for spp in [0u64, 1, 3, 1 << 40, u64::MAX] {
            for res in [(0, 0), (1, 1), (70_000, 3), (u32::MAX, u32::MAX)] {
                let mut s = ZSobol::new(spp, res, u64::MAX);
                s.start_pixel_sample(u32::MAX, u32::MAX, u64::MAX);
                s.set_dimension(u32::MAX);
                let u = s.get_1d();
                let [v, w] = s.get_2d();
                assert!([u, v, w].iter().all(|x| (0.0..1.0).contains(x)));
            }
        }
    }
}
