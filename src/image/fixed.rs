//! Exact, order-free accumulation of the film: per pixel and half, each linear RGB
//! channel is summed as a fixed-point integer, so the sum of a set of samples does not
//! depend on the order they were added in (integer addition is associative). A render cut
//! into shards ([`crate::app::shard`]) and merged ([`crate::app::merge`]) therefore has
//! exactly the sums, and so bit for bit the image, of one render of all the samples.
//!
//! ## Format
//! A value v (radiance, W·sr⁻¹·m⁻², as f64) becomes the integer trunc(v · 2^[`FRAC_BITS`])
//! in an `i128`. Multiplying by a power of two is exact in binary floating point, and
//! truncation toward zero is a pure function of v, so a sample's integer is the same
//! whichever machine, thread or shard adds it. Back to floating point, a sum s is
//! `(s as f64) · 2^-FRAC_BITS` (rounded to nearest once, by the conversion).
//!
//! ## Range and resolution (why they suffice)
//! - Resolution: 2⁻⁶⁰ ≈ 8.7·10⁻¹⁹ per addition. An f32 image value is read to 2⁻²⁴
//!   relative; a pixel of 10⁻¹⁰ nits after 10⁶ samples has lost at most 10⁶ · 8.7·10⁻¹⁹ =
//!   8.7·10⁻¹³ to truncation, under a thousandth of its f32 step.
//! - Range: one addition is at most [`LIMIT`] = 2⁴⁰ ≈ 1.1·10¹² per channel (larger values
//!   are refused by the film's guard, [`crate::render::guard::admit`], like NaN: no light Iris
//!   renders comes near it; the sun is about 2·10⁹ nits). A pixel's half receives at most
//!   2²⁵ additions (SPPM: `--passes` ≤ 10⁷ < 2²⁴, two additions a pass; every other method
//!   ≤ 2²⁰ units, one each), so |sum| ≤ 2⁴⁰ · 2²⁵ · 2⁶⁰ = 2¹²⁵ < 2¹²⁷: no `i128` overflow.
//!   Additions wrap anyway ([`i128::wrapping_add`]), which stays associative.
//!
//! Memory: 96 bytes per pixel (two halves × three channels × 16 bytes), against 48 for the
//! f64 sums it replaced.

use glam::{DVec3, Vec3};

/// Fractional bits of the fixed-point format.
pub const FRAC_BITS: i32 = 60;

/// The largest magnitude of one channel of one addition: 2⁴⁰ (see the module docs).
pub const LIMIT: f64 = (1u64 << 40) as f64;

/// A linear RGB sum in fixed point (see the module docs).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FixedRgb(pub [i128; 3]);

/// 2^FRAC_BITS and its inverse, exact powers of two.
const SCALE: f64 = (1u64 << FRAC_BITS) as f64;
const INV_SCALE: f64 = 1.0 / SCALE;

impl FixedRgb {
    /// Zero.
    pub const ZERO: FixedRgb = FixedRgb([0; 3]);

    /// The fixed-point value of `v` (finite, each |component| ≤ [`LIMIT`]; the film's guard
    /// ensures it. Outside that the conversion saturates, it never wraps).
    #[inline]
    pub fn from_dvec3(v: DVec3) -> FixedRgb {
        debug_assert!(v.is_finite() && v.abs().max_element() <= LIMIT, "{v}");
        FixedRgb([
            (v.x * SCALE) as i128,
            (v.y * SCALE) as i128,
            (v.z * SCALE) as i128,
        ])
    }

    /// The value in floating point (each component rounded once).
    #[inline]
    pub fn to_dvec3(self) -> DVec3 {
        DVec3::new(
            self.0[0] as f64 * INV_SCALE,
            self.0[1] as f64 * INV_SCALE,
            self.0[2] as f64 * INV_SCALE,
        )
    }

    /// `self / n` as f32 RGB (0 units give 0): the one mean formula of the film and of a
    /// merge, so both give the same bits from the same sums.
    #[inline]
    pub fn mean(self, n: u64) -> Vec3 {
        (self.to_dvec3() / n.max(1) as f64).as_vec3()
    }
}

impl std::ops::Add for FixedRgb {
    type Output = FixedRgb;

    /// Componentwise, wrapping: associative and commutative.
    #[inline]
    fn add(self, o: FixedRgb) -> FixedRgb {
        let [a, b, c] = self.0;
        let [x, y, z] = o.0;
        FixedRgb([a.wrapping_add(x), b.wrapping_add(y), c.wrapping_add(z)])
    }
}

/// A pixel's two halves (units of even and odd absolute index).
pub type PixelSums = [FixedRgb; 2];

/// Units of even and of odd absolute index in `first..first + n`.
pub fn parity_counts(first: u64, n: u64) -> [u64; 2] {
    let even = (first + n).div_ceil(2) - first.div_ceil(2);
    [even, n - even]
}

/// The mean of both halves of a pixel holding `n` units.
#[inline]
pub fn pixel_mean(s: &PixelSums, n: u64) -> Vec3 {
    (s[0] + s[1]).mean(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_do_not_depend_on_the_order_of_additions() {
        // Values whose f64 sums do depend on the order.
        let vals: Vec<DVec3> = (0..200)
            .map(|i| {
                let x = (i as f64 * 0.618_033_988_749_895).fract();
                let big = if i % 2 == 0 { 1e11 } else { 1e-3 };
                DVec3::new(x * big, x * 1e-9, -x * 3.7)
            })
            .collect();
        let sum = |order: &mut dyn Iterator<Item = &DVec3>| {
            order.fold(FixedRgb::ZERO, |s, v| s + FixedRgb::from_dvec3(*v))
        };
        let forward = sum(&mut vals.iter());
        let backward = sum(&mut vals.iter().rev());
        let (a, b) = vals.split_at(77);
        let split = sum(&mut b.iter()) + sum(&mut a.iter());
        assert_eq!(forward, backward);
        assert_eq!(forward, split);
        let f64_sum = |v: &[DVec3]| v.iter().map(|v| v.x).sum::<f64>();
        let f64_fwd = f64_sum(&vals);
        // The premise: f64 partial sums (shards) do not add up to the sequential sum.
        let differs = (1..vals.len())
            .filter(|&k| f64_sum(&vals[..k]) + f64_sum(&vals[k..]) != f64_fwd)
            .count();
        assert!(differs > 10, "{differs}");
        assert!((forward.to_dvec3().x - f64_fwd).abs() < 1e-4 * f64_fwd.abs().max(1.0) * 1e-6);
    }

    #[test]
    fn conversion_is_exact_for_f32_values_above_the_resolution() {
        for v in [1.0f32, 0.1, 3.0e-7, 1234.567, -2.5, (1u64 << 40) as f32] {
            let f = FixedRgb::from_dvec3(DVec3::splat(v as f64));
            assert_eq!(f.to_dvec3().x, v as f64, "{v}");
            assert_eq!(f.mean(1).x, v);
        }
        // Below 2^-60 a value truncates to zero, toward zero on both sides.
        let tiny = FixedRgb::from_dvec3(DVec3::new(1e-19, -1e-19, 2f64.powi(-60)));
        assert_eq!(tiny.0, [0, 0, 1]);
    }

    #[test]
    fn the_worst_case_sum_does_not_overflow() {
        // 2^25 additions of the largest admitted value, by doubling.
        let mut s = FixedRgb::from_dvec3(DVec3::splat(LIMIT));
        for _ in 0..25 {
            s = s + s;
        }
        assert_eq!(s.to_dvec3().x, LIMIT * (1u64 << 25) as f64);
        assert!(s.0[0] > 0);
    }

    #[test]
    fn parity_counts_split_any_range() {
        assert_eq!(parity_counts(0, 0), [0, 0]);
        assert_eq!(parity_counts(0, 1), [1, 0]);
        assert_eq!(parity_counts(0, 5), [3, 2]);
        assert_eq!(parity_counts(3, 1), [0, 1]);
        assert_eq!(parity_counts(3, 4), [2, 2]);
        assert_eq!(parity_counts(7, 3), [1, 2]);
        for first in 0..9 {
            for n in 0..9 {
                let even = (first..first + n).filter(|k| k % 2 == 0).count() as u64;
                assert_eq!(parity_counts(first, n), [even, n - even]);
            }
        }
    }
}
