//! [`ZSobol`] against a straightforward reference: the sample index computed digit by digit
//! (a full `mix64` per digit, the permutation table read per digit) and the coordinates by
//! the general Sobol' matrix product ([`sobol_sample`]) and [`Scramble`], for random
//! configurations, pixels, sample indices (in and past the block, consecutive and
//! scattered) and dimensions.

use super::digits::PERMUTATIONS;
use super::*;
use crate::math::Rng;
use crate::sampler::sobol::{sobol_sample, Scramble};

/// The configuration of a sampler, as [`ZSobol::with_randomize`] derives it.
struct Reference {
    log2_spp: u32,
    log2_res: u32,
    seed_mix: u64,
}

impl Reference {
    fn new(samples_per_pixel: u64, resolution: (u32, u32), seed: u64) -> Self {
        let spp = samples_per_pixel.clamp(1, 1 << 32).next_power_of_two();
        let res = resolution.0.max(resolution.1).clamp(1, 1 << 16);
        Reference {
            log2_spp: spp.trailing_zeros(),
            log2_res: res.next_power_of_two().trailing_zeros(),
            seed_mix: mix64(seed),
        }
    }

    /// The Morton index of sample `k` of pixel `(x, y)`: the pixel's bits interleaved one
    /// at a time, the sample's below, its block above every pixel's bits.
    fn morton_index(&self, x: u32, y: u32, k: u64) -> u64 {
        let mut z = 0u64;
        for b in 0..32 {
            z |= u64::from(x >> b & 1) << (2 * b) | u64::from(y >> b & 1) << (2 * b + 1);
        }
        let low_bits = 2 * self.log2_res + self.log2_spp;
        let within = k & ((1u64 << self.log2_spp) - 1);
        let block = (k >> self.log2_spp).checked_shl(low_bits).unwrap_or(0);
        (z << self.log2_spp | within) | block
    }

    /// The permuted index of sample `k` of pixel `(x, y)` in dimension `dim`.
    fn sample_index(&self, x: u32, y: u32, k: u64, dim: u32) -> u64 {
        let m = self.morton_index(x, y, k);
        let key = mix64(self.seed_mix ^ 0x5555_5555_5555_5555 ^ (u64::from(dim) << 32));
        let odd = self.log2_spp & 1;
        let low_bits = 2 * self.log2_res + self.log2_spp;
        let mut index = if low_bits >= 64 {
            0
        } else {
            m >> low_bits << low_bits
        };
        let hash_of_digits_above = |shift: u32| {
            let higher = m.checked_shr(shift).unwrap_or(0);
            (u64::from((mix64(higher ^ self.seed_mix) >> 32) as u32) ^ key)
                .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        };
        let base4_digits = self.log2_res + self.log2_spp.div_ceil(2);
        for i in odd..base4_digits {
            let shift = 2 * i - odd;
            let digit = ((m >> shift) & 3) as usize;
            let p = (((hash_of_digits_above(shift + 2) >> 32) * 24) >> 32) as usize;
            index |= u64::from(PERMUTATIONS[p][digit]) << shift;
        }
        if odd == 1 {
            index |= (m & 1) ^ (hash_of_digits_above(1) >> 63);
        }
        index
    }

    /// Coordinate `coordinate` (Sobol' dimension 0 or 1) of the sample in dimension `dim`.
    fn value(&self, (x, y, k): (u32, u32, u64), dim: u32, coordinate: usize, r: Randomize) -> f32 {
        let hash = mix64(self.seed_mix ^ u64::from(dim));
        let key = (hash >> (32 * coordinate)) as u32;
        let scramble = match r {
            Randomize::None => Scramble::None,
            Randomize::Xor => Scramble::Xor(key),
            Randomize::Owen => Scramble::Owen(key),
        };
        sobol_sample(self.sample_index(x, y, k, dim), coordinate, scramble)
    }
}

/// A random configuration: samples per pixel and resolution covering the extremes.
fn configuration(rng: &mut Rng) -> (u64, (u32, u32)) {
    let wide = |rng: &mut Rng| u64::from(rng.next_u32()) << 32 | u64::from(rng.next_u32());
    let spp = match rng.next_u32() % 6 {
        0 => 1,
        1 => 1 << 32,
        2 | 3 => 1 << (rng.next_u32() % 33),
        4 => u64::from(rng.next_u32() % 5000),
        _ => wide(rng),
    };
    let side = |rng: &mut Rng| match rng.next_u32() % 4 {
        0 => 1,
        1 => 65_536,
        2 => rng.next_u32() % 70_000,
        _ => rng.next_u32(),
    };
    (spp, (side(rng), side(rng)))
}

#[test]
fn sampler_matches_the_reference() {
    let mut rng = Rng::new(&[30, 2]);
    let wide = |rng: &mut Rng| u64::from(rng.next_u32()) << 32 | u64::from(rng.next_u32());
    for _ in 0..1500 {
        let (spp, res) = configuration(&mut rng);
        let seed = wide(&mut rng);
        let reference = Reference::new(spp, res, seed);
        for randomize in [Randomize::None, Randomize::Xor, Randomize::Owen] {
            let mut z = ZSobol::with_randomize(spp, res, seed, randomize);
            let (mut x, mut y, mut k) = (0u32, 0u32, 0u64);
            for _ in 0..12 {
                // Consecutive samples of a pixel (what renders do), or a jump anywhere.
                match rng.next_u32() % 4 {
                    0 => k = k.wrapping_add(1),
                    1 => k = k.wrapping_add(u64::from(rng.next_u32() % 9)),
                    _ => {
                        x = rng.next_u32() % res.0.max(1);
                        y = rng.next_u32() % res.1.max(1);
                        k = match rng.next_u32() % 3 {
                            0 => wide(&mut rng) % spp.max(1),
                            1 => wide(&mut rng) % spp.max(1).saturating_mul(8),
                            _ => wide(&mut rng),
                        };
                    }
                }
                z.start_pixel_sample(x, y, k);
                for _ in 0..4 {
                    let dim = match rng.next_u32() % 3 {
                        0 => rng.next_u32() % 600,
                        1 => rng.next_u32(),
                        _ => u32::MAX - rng.next_u32() % 3,
                    };
                    let at = (x, y, k);
                    let what = format!("spp {spp} res {res:?} {at:?} dim {dim} {randomize:?}");
                    assert_eq!(
                        z.sample_index(dim),
                        reference.sample_index(x, y, k, dim),
                        "{what}"
                    );
                    z.set_dimension(dim);
                    let u = z.get_1d();
                    assert_eq!(u, reference.value(at, dim, 0, randomize), "{what}");
                    assert_eq!(z.dimension(), dim.wrapping_add(1));
                    z.set_dimension(dim);
                    let [u, v] = z.get_2d();
                    assert_eq!(u, reference.value(at, dim, 0, randomize), "{what}");
                    assert_eq!(v, reference.value(at, dim, 1, randomize), "{what}");
                    for mode in [Randomize::None, Randomize::Xor, Randomize::Owen] {
                        z.set_dimension(dim);
                        let [u, v] = z.get_2d_with(mode);
                        assert_eq!(u, reference.value(at, dim, 0, mode), "{what} {mode:?}");
                        assert_eq!(v, reference.value(at, dim, 1, mode), "{what} {mode:?}");
                    }
                }
            }
        }
    }
}

#[test]
fn the_reference_maps_a_pixels_block_onto_an_aligned_block() {
    // Guards the oracle itself: a pixel's 64 samples go to 64 distinct indices forming one
    // aligned block of 64 (the digit permutation keeps aligned blocks aligned), in an order
    // that depends on the dimension.
    let reference = Reference::new(64, (8, 8), 5);
    let mut orders = Vec::new();
    for dim in [0, 7, 1000] {
        let order: Vec<u64> = (0..64)
            .map(|k| reference.sample_index(3, 6, k, dim))
            .collect();
        let mut sorted = order.clone();
        sorted.sort_unstable();
        let base = sorted[0];
        assert_eq!(base % 64, 0, "dim {dim}");
        assert!(sorted.iter().zip(base..).all(|(&a, b)| a == b), "dim {dim}");
        orders.push(order);
    }
    assert!(orders[0] != orders[1] && orders[1] != orders[2]);
    // x in the even bits and y in the odd bits above the 6 sample bits, the block above
    // the 6 pixel bits.
    assert_eq!(reference.morton_index(1, 0, 0), 1 << 6);
    assert_eq!(reference.morton_index(0, 1, 0), 1 << 7);
    assert_eq!(reference.morton_index(0, 0, 64), 1 << 12);
}
