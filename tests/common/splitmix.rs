//! A deterministic splitmix64 generator (Steele, Lea & Flood 2014, "Fast splittable
//! pseudorandom number generators") for the random rays of the acceleration tests and
//! benchmarks; benches/common includes this file too.

use glam::Vec3;

/// splitmix64 state.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in the box `[lo, hi)`.
    pub fn in_box(&mut self, lo: Vec3, hi: Vec3) -> Vec3 {
        lo + (hi - lo) * Vec3::new(self.f32(), self.f32(), self.f32())
    }

    /// Uniform on the unit sphere.
    pub fn unit_vector(&mut self) -> Vec3 {
        let z = 2.0 * self.f32() - 1.0;
        let phi = std::f32::consts::TAU * self.f32();
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}
