//! Stokes vectors, Mueller matrices and the analyzer a camera path carries.
//!
//! Conventions (Born & Wolf, *Principles of Optics*, 7th ed., §1.4.2; Chipman, Lam & Young,
//! *Polarized Light and Optical Systems*, 2018, ch. 6): light propagating along the unit
//! vector `k` has its Stokes vector S = (S0, S1, S2, S3) measured in a basis (x, y) of the
//! plane ⊥ k with y = k × x: S0 the intensity, S1 = I_x − I_y, S2 = I_{+45°} − I_{−45°}
//! (+45° along (x + y)/√2), S3 the circular part. A Mueller matrix maps the Stokes vector of
//! light before an interaction (in the incident basis) to the one after it (in the outgoing
//! basis).
//!
//! A camera path is traced against the light, so it carries a ROW vector instead: the
//! [`Analyzer`] a with a · S the signal the pixel records from light of Stokes vector S
//! arriving along the path's current segment. At the camera a = (1, 0, 0, 0) (no filter) or
//! the first row of a linear polarizer; every interaction multiplies it on the right,
//! a ← a · M, so that after the last one a · S_light is the pixel's value for that path.
//! Unpolarized light (S = L·(1, 0, 0, 0)) then contributes L·a0.

use glam::Vec3;

/// A Stokes vector (S0, S1, S2, S3), or an analyzer row in the same basis.
pub type Stokes = [f32; 4];

/// A 4×4 Mueller matrix, rows first: `m[i][j]` multiplies S_j into S'_i.
pub type Mueller = [[f32; 4]; 4];

/// The identity (no change of polarization).
pub const IDENTITY: Mueller = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// The ideal depolarizer: keeps the intensity, forgets the polarization (a Lambertian
/// surface's normalized Mueller matrix).
pub const DEPOLARIZER: Mueller = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 0.0, 0.0, 0.0],
];

/// Row vector times matrix: (a · M)_j = Σ_i a_i M_ij.
#[inline]
pub fn row_mul(a: &Stokes, m: &Mueller) -> Stokes {
    std::array::from_fn(|j| (0..4).map(|i| a[i] * m[i][j]).sum())
}

/// Matrix times column vector: (M · S)_i = Σ_j M_ij S_j.
#[inline]
pub fn mul(m: &Mueller, s: &Stokes) -> Stokes {
    std::array::from_fn(|i| (0..4).map(|j| m[i][j] * s[j]).sum())
}

/// Matrix product A · B.
pub fn mat_mul(a: &Mueller, b: &Mueller) -> Mueller {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// Every entry times `s`.
pub fn scaled(m: &Mueller, s: f32) -> Mueller {
    m.map(|row| row.map(|v| v * s))
}

/// The rotation of the basis by `phi` (radians) about the direction of propagation,
/// x' = cos φ x + sin φ y: S' = R(φ) S with S1' = cos 2φ S1 + sin 2φ S2,
/// S2' = −sin 2φ S1 + cos 2φ S2 (Chipman et al. 2018, eq. 6.43). An analyzer row
/// transforms the same way (R is orthogonal, a' = a R(φ)ᵀ).
#[inline]
pub fn rotate(s: &Stokes, phi: f32) -> Stokes {
    let (sin2, cos2) = (2.0 * phi).sin_cos();
    [
        s[0],
        cos2 * s[1] + sin2 * s[2],
        -sin2 * s[1] + cos2 * s[2],
        s[3],
    ]
}

/// An ideal linear polarizer with its transmission axis at `psi` (radians) from the basis'
/// x (Chipman et al. 2018, eq. 6.31): ½·[[1, c, s, 0], [c, c², cs, 0], [s, cs, s², 0],
/// [0, 0, 0, 0]] with c = cos 2ψ, s = sin 2ψ.
pub fn linear_polarizer(psi: f32) -> Mueller {
    let (s, c) = (2.0 * psi).sin_cos();
    [
        [0.5, 0.5 * c, 0.5 * s, 0.0],
        [0.5 * c, 0.5 * c * c, 0.5 * c * s, 0.0],
        [0.5 * s, 0.5 * c * s, 0.5 * s * s, 0.0],
        [0.0, 0.0, 0.0, 0.0],
    ]
}

/// The degree of polarization √(S1² + S2² + S3²)/S0 (0 for S0 = 0).
pub fn degree(s: &Stokes) -> f32 {
    if s[0] <= 0.0 {
        return 0.0;
    }
    (s[1] * s[1] + s[2] * s[2] + s[3] * s[3]).sqrt() / s[0]
}

/// A unit vector ⊥ `k` (any; deterministic).
pub fn perpendicular(k: Vec3) -> Vec3 {
    k.any_orthonormal_vector()
}

/// The angle φ that rotates the basis x (⊥ k) into x' (⊥ k) about k, for [`rotate`]:
/// x' = cos φ x + sin φ (k × x).
pub fn angle_between(x: Vec3, x_new: Vec3, k: Vec3) -> f32 {
    let y = k.cross(x);
    x_new.dot(y).atan2(x_new.dot(x))
}

/// What a camera path's segment records of light arriving along it: the analyzer row `a`
/// in the basis `x` ⊥ `k`, `k` the direction the light propagates along the segment
/// (minus the path's direction; inside a birefringent crystal the wave normal, which is
/// what the polarization is transverse to).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Analyzer {
    /// The row vector.
    pub a: Stokes,
    /// The basis' x (unit, ⊥ `k`).
    pub x: Vec3,
    /// The light's direction of propagation (unit).
    pub k: Vec3,
}

impl Analyzer {
    /// A camera with no filter looking along `dir` (the light travels along −dir).
    pub fn open(dir: Vec3, up: Vec3) -> Analyzer {
        let k = -dir.normalize();
        Analyzer {
            a: [1.0, 0.0, 0.0, 0.0],
            x: transverse(up, k),
            k,
        }
    }

    /// A camera looking along `dir` through an ideal linear polarizer whose transmission
    /// axis is at `angle` (radians) from the image's horizontal `right`, counter-clockwise
    /// toward the image's up as the viewer sees it.
    pub fn polarizer(dir: Vec3, right: Vec3, up: Vec3, angle: f32) -> Analyzer {
        let k = -dir.normalize();
        let axis = (right * angle.cos() + up * angle.sin()).normalize();
        // The first row of a polarizer along x: ½(1, 1, 0, 0).
        let x = transverse(axis, k);
        Analyzer {
            a: [0.5, 0.5, 0.0, 0.0],
            x,
            k,
        }
    }

    /// The same analyzer in the basis `x_new` (⊥ `k`).
    pub fn in_basis(&self, x_new: Vec3) -> Analyzer {
        let phi = angle_between(self.x, x_new, self.k);
        Analyzer {
            a: rotate(&self.a, phi),
            x: x_new,
            k: self.k,
        }
    }

    /// After an interaction with Mueller matrix `m` given in the incident basis `x_in` ⊥
    /// `k_in` and the outgoing basis `x_out` ⊥ `self.k` (the light's directions before and
    /// after it), divided by the probability `p` with which the interaction was chosen:
    /// the analyzer of the segment before it.
    pub fn through(&self, m: &Mueller, x_out: Vec3, x_in: Vec3, k_in: Vec3, p: f32) -> Analyzer {
        let a = row_mul(&self.in_basis(x_out).a, m);
        Analyzer {
            a: a.map(|v| v / p),
            x: x_in,
            k: k_in,
        }
    }

    /// The signal from unpolarized light of unit intensity: a0.
    pub fn unpolarized(&self) -> f32 {
        self.a[0]
    }
}

/// Light as a photon carries it: the Stokes vector `s` normalized to s₀ = 1 (the photon's
/// scalar weight carries the intensity) in the basis `x` ⊥ `k`, `k` the direction it
/// propagates (inside a birefringent crystal the wave normal).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// The Stokes vector, s₀ = 1.
    pub s: Stokes,
    /// The basis' x (unit, ⊥ `k`).
    pub x: Vec3,
    /// The direction of propagation (unit).
    pub k: Vec3,
}

impl Light {
    /// Unpolarized light propagating along `k`.
    pub fn unpolarized(k: Vec3) -> Light {
        let k = k.normalize();
        Light {
            s: [1.0, 0.0, 0.0, 0.0],
            x: perpendicular(k),
            k,
        }
    }

    /// The same light's Stokes vector in the basis `x_new` (⊥ `k`).
    pub fn in_basis(&self, x_new: Vec3) -> Stokes {
        rotate(&self.s, angle_between(self.x, x_new, self.k))
    }

    /// The light after an interaction with Mueller matrix `m` given in the incident basis
    /// `x_in` (⊥ `self.k`) and the outgoing basis `x_out` ⊥ `k_out`, normalized, with the
    /// intensity factor (M·S)₀ ≥ 0; `None` when nothing passes.
    pub fn after(&self, m: &Mueller, x_in: Vec3, x_out: Vec3, k_out: Vec3) -> Option<(Light, f32)> {
        let out = mul(m, &self.in_basis(x_in));
        Light::normalized(out, x_out, k_out)
    }

    /// The light of Stokes vector `s` (any s₀ > 0) in the basis `x` ⊥ `k`, normalized, with
    /// its s₀; `None` unless s₀ is positive and finite.
    pub fn normalized(s: Stokes, x: Vec3, k: Vec3) -> Option<(Light, f32)> {
        let i = s[0];
        (i > 0.0 && i.is_finite()).then(|| {
            let light = Light {
                s: s.map(|v| v / i),
                x,
                k,
            };
            (light, i)
        })
    }
}

/// The unit vector along the part of `v` ⊥ `k`, or any unit vector ⊥ `k` when `v` has
/// none.
pub fn transverse(v: Vec3, k: Vec3) -> Vec3 {
    let t = v - k * v.dot(k);
    let len = t.length();
    if len > 1e-6 {
        t / len
    } else {
        perpendicular(k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn malus_law_between_two_ideal_polarizers() {
        // Unpolarized light through a polarizer at 0 and one at θ: I = ½ cos²θ.
        for deg in [0.0f32, 15.0, 30.0, 45.0, 60.0, 90.0] {
            let th = deg.to_radians();
            let s = mul(&linear_polarizer(0.0), &[1.0, 0.0, 0.0, 0.0]);
            let s = mul(&linear_polarizer(th), &s);
            assert!(close(s[0], 0.5 * th.cos().powi(2), 1e-6), "{deg}: {}", s[0]);
        }
    }

    #[test]
    fn a_rotated_polarizer_is_the_polarizer_at_the_rotated_angle() {
        // Light polarized at 30° in the x basis is at 30° − φ in the basis rotated by φ.
        let s = mul(&linear_polarizer(30f32.to_radians()), &[1.0, 0.0, 0.0, 0.0]);
        let r = rotate(&s, 10f32.to_radians());
        let expect = mul(&linear_polarizer(20f32.to_radians()), &[1.0, 0.0, 0.0, 0.0]);
        for i in 0..4 {
            assert!(close(r[i], expect[i], 1e-6), "{r:?} vs {expect:?}");
        }
    }

    #[test]
    fn the_analyzer_row_gives_what_the_column_product_gives() {
        // a · (M S) = (a · M) · S for a polarizer, a rotation and a retarder-like matrix.
        let m = mat_mul(&linear_polarizer(0.3), &DEPOLARIZER);
        let s = [1.0, 0.2, -0.4, 0.5];
        let a = linear_polarizer(1.1)[0];
        let left: f32 = (0..4).map(|i| a[i] * mul(&m, &s)[i]).sum();
        let right: f32 = (0..4).map(|i| row_mul(&a, &m)[i] * s[i]).sum();
        assert!(close(left, right, 1e-6));
    }

    #[test]
    fn basis_angles_are_measured_about_the_direction_of_travel() {
        let k = Vec3::Z;
        assert!(close(
            angle_between(Vec3::X, Vec3::Y, k),
            std::f32::consts::FRAC_PI_2,
            1e-6
        ));
        let v = Vec3::new(1.0, 1.0, 0.0).normalize();
        assert!(close(
            angle_between(Vec3::X, v, k),
            std::f32::consts::FRAC_PI_4,
            1e-6
        ));
        assert!(close(degree(&linear_polarizer(0.7)[0]), 1.0, 1e-6));
    }
}
