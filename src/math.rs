//! Small math shared by every module: rays, a deterministic random-number generator,
//! orthonormal frames, f64 complex numbers (for complex indices of refraction) and the one
//! normaliser for directions read from files and flags ([`unit_direction`]).
//! Directions are unit vectors unless stated; lengths in world units.

use glam::{DVec3, Vec3};

/// A ray `origin + t·dir`, valid for `t` in `[0, t_max)`.
///
/// Secondary rays are made only by the intersection layer ([`crate::interaction`]), which
/// offsets their origin; `t_min` is always 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Origin, world space.
    pub origin: Vec3,
    /// Direction (unit length for camera and scattered rays; `spawn_ray_to` uses the
    /// un-normalised segment so that `t_max` is a fraction of it).
    pub dir: Vec3,
    /// Exclusive upper bound of the ray parameter.
    pub t_max: f32,
    /// Distance (world units, whatever |dir|) along the ray's line between the surface it
    /// left and `origin`, which the intersection layer moved off that surface: the ray
    /// really starts this far before `origin`. Intersection ignores it; media count it
    /// ([`crate::shading::media`]), so the offset never skips a medium. 0 for camera rays
    /// and rays leaving a point in a medium.
    pub skipped: f32,
}

impl Ray {
    /// A primary ray (camera or test ray) with no upper bound.
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Ray {
            origin,
            dir,
            t_max: f32::INFINITY,
            skipped: 0.0,
        }
    }

    /// Whether the ray can be traced: finite origin, finite non-zero direction, `t_max` not
    /// NaN (+∞ is fine).
    #[inline]
    pub fn is_valid(&self) -> bool {
        self.origin.is_finite()
            && self.dir.is_finite()
            && self.dir != Vec3::ZERO
            && !self.t_max.is_nan()
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// PCG32 random-number generator (O'Neill 2014, "PCG: A Family of Simple Fast
/// Space-Efficient Statistically Good Algorithms for Random Number Generation"), seeded by
/// hashing, so each pixel/sample/pass gets an independent, reproducible stream.
#[derive(Debug, Clone)]
pub struct Rng {
    state: u64,
    inc: u64,
}

/// SplitMix64 finaliser: a strong 64-bit hash used to derive seeds (Steele et al. 2014).
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Rng {
    /// A generator for the stream identified by `keys` (e.g. seed, pixel x, pixel y, sample).
    pub fn new(keys: &[u64]) -> Self {
        let mut h = 0x243F_6A88_85A3_08D3u64;
        for &k in keys {
            h = mix64(h ^ k);
        }
        let mut rng = Rng {
            state: 0,
            inc: (mix64(h ^ 0xDEAD_BEEF) << 1) | 1,
        };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(h);
        rng.next_u32();
        rng
    }

    /// Next 32 random bits.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform float in `[0, 1)`.
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

/// An orthonormal frame around a unit normal (Duff et al. 2017, "Building an Orthonormal
/// Basis, Revisited", JCGT 6(1)).
#[derive(Debug, Clone, Copy)]
pub struct Frame {
    /// Tangent.
    pub s: Vec3,
    /// Bitangent.
    pub t: Vec3,
    /// Normal.
    pub n: Vec3,
}

impl Frame {
    /// Builds a frame whose `n` is the given unit vector.
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        Frame {
            s: Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
            t: Vec3::new(b, sign + n.y * n.y * a, -n.y),
            n,
        }
    }

    /// World → local.
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Local → world.
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// Why a vector given as a direction names none ([`unit_direction`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoDirection {
    /// Every component is zero.
    Zero,
    /// A component is NaN or infinite.
    NotFinite,
}

impl std::fmt::Display for NoDirection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            NoDirection::Zero => "is zero (a direction needs a non-zero component)",
            NoDirection::NotFinite => "is not finite (a component is NaN or infinite)",
        })
    }
}

/// The unit vector along `v`: the one normaliser for directions read from files, flags and
/// node transforms (an optic axis, a polarizer's axis, a light's or camera's direction).
/// `v` is first divided by its largest |component|, so its squared length lies in [1, 3]
/// and can neither overflow (3e38 in f32, 1e200 in f64) nor underflow (1e-30 in f32) on
/// the way; any finite non-zero `v` gives its direction, to f32 rounding. Zero and
/// non-finite vectors have no direction.
pub fn unit_direction(v: DVec3) -> Result<Vec3, NoDirection> {
    if !v.is_finite() {
        return Err(NoDirection::NotFinite);
    }
    let largest = v.abs().max_element();
    if largest == 0.0 {
        return Err(NoDirection::Zero);
    }
    let scaled = v / largest;
    Ok((scaled / scaled.length()).as_vec3())
}

/// A complex number in f64: just what complex indices of refraction n + ik and the
/// conductor Fresnel equations need (arithmetic, principal square root, |z|²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Complex {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl Complex {
    /// `re + i·im`.
    pub const fn new(re: f64, im: f64) -> Self {
        Complex { re, im }
    }

    /// A real number.
    pub const fn real(re: f64) -> Self {
        Complex { re, im: 0.0 }
    }

    /// |z|² = re² + im².
    pub fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }

    /// The principal square root (re ≥ 0, and im ≥ 0 when `self.im` ≥ 0): with
    /// r = |z|, √z = (√((r + re)/2), sign(im)·√((r − re)/2)), the form without cancellation
    /// for re < 0 (Press et al., Numerical Recipes, 3rd ed., §5.5).
    pub fn sqrt(self) -> Self {
        let r = self.norm_sqr().sqrt();
        if r == 0.0 {
            return Complex::real(0.0);
        }
        if self.re >= 0.0 {
            let a = ((r + self.re) * 0.5).sqrt();
            Complex::new(a, self.im / (2.0 * a))
        } else {
            let b = ((r - self.re) * 0.5).sqrt().copysign(self.im);
            Complex::new(self.im / (2.0 * b), b)
        }
    }
}

impl std::ops::Add for Complex {
    type Output = Complex;
    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }
}

impl std::ops::Sub for Complex {
    type Output = Complex;
    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }
}

impl std::ops::Mul for Complex {
    type Output = Complex;
    fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}

impl std::ops::Mul<f64> for Complex {
    type Output = Complex;
    fn mul(self, s: f64) -> Complex {
        Complex::new(self.re * s, self.im * s)
    }
}

impl std::ops::Div for Complex {
    type Output = Complex;
    /// z / w = z·w̄ / |w|² (NaN or ∞ for w = 0).
    fn div(self, o: Complex) -> Complex {
        let d = o.norm_sqr();
        Complex::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_normalise_without_overflow_or_underflow() {
        let diagonal = Vec3::new(1.0, 1.0, 0.0) / 2f32.sqrt();
        for v in [
            DVec3::new(3e38, 3e38, 0.0),
            DVec3::new(1e300, 1e300, 0.0),
            DVec3::new(1e-30, 1e-30, 0.0),
            DVec3::new(1e-320, 1e-320, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
        ] {
            let u = unit_direction(v).unwrap();
            assert!((u - diagonal).length() < 1e-7, "{v}: {u}");
        }
        assert_eq!(unit_direction(DVec3::ZERO), Err(NoDirection::Zero));
        assert_eq!(unit_direction(-DVec3::ZERO), Err(NoDirection::Zero));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let v = DVec3::new(1.0, bad, 0.0);
            assert_eq!(unit_direction(v), Err(NoDirection::NotFinite));
        }
    }

    #[test]
    fn rng_is_reproducible_and_uniform() {
        let mut a = Rng::new(&[1, 2, 3]);
        let mut b = Rng::new(&[1, 2, 3]);
        let mut c = Rng::new(&[1, 2, 4]);
        let xs: Vec<f32> = (0..10_000).map(|_| a.next_f32()).collect();
        assert!(xs
            .iter()
            .zip((0..).map(|_| b.next_f32()))
            .all(|(x, y)| *x == y));
        assert_ne!(xs[0], c.next_f32());
        let mean = xs.iter().sum::<f32>() / xs.len() as f32;
        assert!((mean - 0.5).abs() < 0.01, "mean {mean}");
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
    }

    #[test]
    fn frame_is_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.5, 0.8).normalize(),
        ] {
            let f = Frame::from_normal(n);
            assert!(f.s.dot(f.t).abs() < 1e-6 && f.s.dot(f.n).abs() < 1e-6);
            assert!((f.s.length() - 1.0).abs() < 1e-6 && (f.t.length() - 1.0).abs() < 1e-6);
            let v = Vec3::new(0.2, 0.7, -0.1);
            assert!((f.to_world(f.to_local(v)) - v).length() < 1e-6);
        }
    }

    /// √z squares back to z, and the root is the principal one (re ≥ 0, im with the sign
    /// of z's), including negative reals (gold's permittivity in the red is about −10 + 1i).
    #[test]
    fn complex_sqrt_is_the_principal_root() {
        for (re, im) in [
            (4.0, 0.0),
            (-9.0, 0.0),
            (-10.0, 1.2),
            (3.0, -4.0),
            (0.04, 9.0),
        ] {
            let z = Complex::new(re, im);
            let r = z.sqrt();
            let back = r * r;
            assert!(
                (back.re - re).abs() < 1e-12 && (back.im - im).abs() < 1e-12,
                "{z:?}"
            );
            assert!(r.re >= 0.0, "{z:?} -> {r:?}");
            assert!(r.im * im >= 0.0, "{z:?} -> {r:?}");
        }
        assert_eq!(Complex::new(-9.0, 0.0).sqrt(), Complex::new(0.0, 3.0));
        let q = Complex::new(1.0, 2.0) / Complex::new(3.0, -1.0);
        assert!(
            (q.re - 0.1).abs() < 1e-15 && (q.im - 0.7).abs() < 1e-15,
            "{q:?}"
        );
    }
}
