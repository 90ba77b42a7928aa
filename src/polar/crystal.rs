//! Light in an anisotropic crystal: the two modes a wave normal admits (index, the
//! direction of D, the ray direction), and refraction into a mode across a plane
//! interface.
//!
//! Frame and units: world space; the crystal's principal axes are the orthonormal columns of
//! `axes` with principal indices `n` (x, y, z) at the path's wavelength. Uniaxial crystals
//! have n_x = n_y = n_o and z = the optic axis c with n_z = n_e. Directions are unit vectors.
//!
//! Physics (Born & Wolf, *Principles of Optics*, 7th ed., §15.2–15.3; Yariv & Yeh, *Optical
//! Waves in Crystals*, 1984, ch. 4): for a wave normal k the allowed D fields are the
//! eigenvectors of the impermeability tensor η = ε⁻¹ = R·diag(1/n_x², 1/n_y², 1/n_z²)·Rᵀ
//! projected on the plane ⊥ k; the eigenvalues are 1/n². The two modes' D vectors are
//! orthogonal. The electric field is E ∝ η·D and the energy (ray) direction is
//! S ∝ E × (k × E) = k |E|² − E (E·k): for a uniaxial crystal the extraordinary ray leaves
//! the wave normal by the walk-off angle ρ with tan(θ + ρ) = (n_o/n_e)² tan θ, θ the angle
//! from the optic axis. At an interface the tangential part of n·k is conserved (the phase
//! matching that gives Snell's law), so each mode's wave normal solves |t + ξ n̂| = n(k̂)
//! for ξ, which [`Indicatrix::refract`] finds by fixed-point iteration.

use glam::{Mat3, Vec3};

/// A crystal's indicatrix (index ellipsoid) at one wavelength: principal axes (world
/// columns) and principal indices. The crystal itself, its indices as functions of λ, is
/// [`crate::spectrum::crystals::Crystal`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Indicatrix {
    /// Principal axes x, y, z as columns (orthonormal, world space).
    pub axes: Mat3,
    /// Principal indices along x, y, z.
    pub n: [f32; 3],
}

/// Which of a wave normal's two modes: the slow one (the larger index) or the fast one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Which {
    /// The larger index (the extraordinary mode of a positive uniaxial crystal, the
    /// ordinary one of a negative crystal).
    Slow,
    /// The smaller index.
    Fast,
}

/// Both modes.
pub const BOTH: [Which; 2] = [Which::Slow, Which::Fast];

/// One mode of a wave normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode {
    /// Its refractive index (phase index along the wave normal).
    pub n: f32,
    /// The wave normal k (unit).
    pub k: Vec3,
    /// The unit D field direction (⊥ k).
    pub d: Vec3,
    /// The unit ray (energy) direction, on the side of k.
    pub ray: Vec3,
}

impl Indicatrix {
    /// η·v: the impermeability tensor applied to `v`.
    fn impermeability(&self, v: Vec3) -> Vec3 {
        let local = self.axes.transpose() * v;
        let scaled = Vec3::new(
            local.x / (self.n[0] * self.n[0]),
            local.y / (self.n[1] * self.n[1]),
            local.z / (self.n[2] * self.n[2]),
        );
        self.axes * scaled
    }

    /// The mode `which` of the wave normal `k` (unit).
    pub fn mode(&self, k: Vec3, which: Which) -> Mode {
        let u = k.any_orthonormal_vector();
        let v = k.cross(u);
        let (eu, ev) = (self.impermeability(u), self.impermeability(v));
        let (a, b, c) = (u.dot(eu), u.dot(ev), v.dot(ev));
        let mean = 0.5 * (a + c);
        let half = (0.25 * (a - c) * (a - c) + b * b).sqrt();
        // The slow mode has the larger index: the smaller eigenvalue 1/n².
        let lambda_slow = mean - half;
        // Its eigenvector, from whichever row of (B − λI) is better conditioned.
        let (r1, r2) = (
            Vec3::new(b, lambda_slow - a, 0.0),
            Vec3::new(lambda_slow - c, b, 0.0),
        );
        let e = if r1.length_squared() >= r2.length_squared() {
            r1
        } else {
            r2
        };
        let d_slow = if e.length_squared() > 1e-24 {
            (u * e.x + v * e.y).normalize()
        } else {
            u
        };
        let (lambda, d) = match which {
            Which::Slow => (lambda_slow, d_slow),
            Which::Fast => (mean + half, k.cross(d_slow)),
        };
        let e_field = self.impermeability(d);
        let ray = k * e_field.length_squared() - e_field * e_field.dot(k);
        let ray = if ray.length_squared() > 0.0 {
            ray.normalize()
        } else {
            k
        };
        Mode {
            n: 1.0 / lambda.max(1e-12).sqrt(),
            k,
            d,
            ray,
        }
    }

    /// The crystal whose principal indices are the reciprocals 1/n_x, 1/n_y, 1/n_z: its
    /// impermeability is this crystal's permittivity ε = R·diag(n_x², n_y², n_z²)·Rᵀ.
    fn dual(&self) -> Indicatrix {
        Indicatrix {
            axes: self.axes,
            n: self.n.map(|n| 1.0 / n),
        }
    }

    /// The mode `which` whose ray (energy) direction is `s` (unit): the inverse of the
    /// walk-off, for light met travelling inside the crystal along a known ray (a camera or
    /// a light inside it). The ray equations are the wave equations with k ↔ s, D ↔ E and
    /// n_i ↔ 1/n_i (Born & Wolf §15.2.2): the E fields a ray direction s admits are the
    /// D fields of the [`Indicatrix::dual`] crystal for the wave normal s, and its ray index
    /// n_r = n cos ρ the reciprocal of the dual's index, so the dual's slow mode is this
    /// crystal's fast one. Then D = ε·E, and k is the unit part of s ⊥ D (k, s, D and E lie
    /// in one plane, with D ⊥ k and E ⊥ s).
    pub fn mode_along_ray(&self, s: Vec3, which: Which) -> Mode {
        let dual = self.dual();
        let dual_which = match which {
            Which::Slow => Which::Fast,
            Which::Fast => Which::Slow,
        };
        let e = dual.mode(s, dual_which).d;
        let d = dual.impermeability(e).normalize_or(e);
        let k = (s - d * s.dot(d)).normalize_or(s);
        self.mode(if k.dot(s) > 0.0 { k } else { -k }, which)
    }

    /// The direction of the E field (unit) of a mode whose D field is along `d`: E ∝ η·D.
    pub fn e_field(&self, d: Vec3) -> Vec3 {
        self.impermeability(d).normalize_or(d)
    }

    /// The mode `which` of the wave refracted or reflected into the crystal across a plane
    /// with unit normal `into` (pointing into the crystal) whose tangential wave vector is
    /// `t` (⊥ `into`, |t| = n_i sin θ_i): k̂ ∝ t + ξ·into with ξ = √(n(k̂)² − |t|²).
    /// `None` when the mode is evanescent (|t| ≥ n(k̂)).
    pub fn refract(&self, t: Vec3, into: Vec3, which: Which) -> Option<Mode> {
        let t2 = t.length_squared();
        let mut k = (t + into * (self.n[1] * self.n[1] - t2).max(1e-6).sqrt()).normalize();
        let mut mode = self.mode(k, which);
        for _ in 0..12 {
            let xi2 = mode.n * mode.n - t2;
            if xi2 <= 0.0 {
                return None;
            }
            let next = (t + into * xi2.sqrt()).normalize();
            // Converged to f32 precision (the map contracts by about the birefringence).
            let done = (next - k).length_squared() < 1e-13;
            k = next;
            mode = self.mode(k, which);
            if done {
                break;
            }
        }
        (mode.n * mode.n > t2).then_some(mode)
    }

    /// The absorption coefficient of a mode whose D field is along `d`, from the
    /// coefficients `sigma` for light polarized along the principal axes x, y, z:
    /// σ = Σ_i σ_i (d·a_i)² (the imaginary part of the dielectric tensor projected on the
    /// field, valid for weak absorption; Born & Wolf §15.6).
    pub fn absorption(&self, d: Vec3, sigma: [f32; 3]) -> f32 {
        let local = self.axes.transpose() * d;
        sigma[0] * local.x * local.x + sigma[1] * local.y * local.y + sigma[2] * local.z * local.z
    }
}

/// Calcite at 589 nm, its optic axis along z: n_o = 1.6584, n_e = 1.4864 (the unit tests'
/// uniaxial crystal).
#[cfg(test)]
pub(crate) fn calcite() -> Indicatrix {
    Indicatrix {
        axes: Mat3::IDENTITY,
        n: [1.6584, 1.6584, 1.4864],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniaxial_modes_have_the_ordinary_and_extraordinary_indices() {
        let c = calcite();
        for deg in [0.0f32, 20.0, 45.0, 70.0, 90.0] {
            let th = deg.to_radians();
            let k = Vec3::new(th.sin(), 0.0, th.cos());
            let slow = c.mode(k, Which::Slow);
            let fast = c.mode(k, Which::Fast);
            // Negative crystal: the ordinary wave is the slow one.
            assert!((slow.n - 1.6584).abs() < 1e-5, "{deg}: {}", slow.n);
            let ne = 1.0 / ((th.cos() / 1.6584).powi(2) + (th.sin() / 1.4864).powi(2)).sqrt();
            assert!((fast.n - ne).abs() < 1e-5, "{deg}: {} vs {ne}", fast.n);
            assert!(slow.d.dot(fast.d).abs() < 1e-5 && slow.d.dot(k).abs() < 1e-5);
            // The ordinary D is ⊥ the optic axis (except along it, where any is).
            if deg > 0.0 {
                assert!(slow.d.z.abs() < 1e-5, "{:?}", slow.d);
            }
        }
    }

    #[test]
    fn the_extraordinary_ray_walks_off_by_the_textbook_angle() {
        // tan(θ + ρ) = (n_o/n_e)² tan θ; at θ = 45° calcite's ρ is 6.2°.
        let c = calcite();
        for deg in [10.0f32, 45.0, 60.0] {
            let th = deg.to_radians();
            let k = Vec3::new(th.sin(), 0.0, th.cos());
            let e = c.mode(k, Which::Fast);
            let o = c.mode(k, Which::Slow);
            assert!(o.ray.dot(k) > 1.0 - 1e-6, "ordinary ray along k");
            let ray_angle = e.ray.x.atan2(e.ray.z);
            let expect = ((1.6584f32 / 1.4864).powi(2) * th.tan()).atan();
            assert!(
                (ray_angle - expect).abs() < 1e-4,
                "{deg}: {ray_angle} vs {expect}"
            );
            if deg == 45.0 {
                assert!(((ray_angle - th).to_degrees() - 6.23).abs() < 0.05);
            }
        }
    }

    #[test]
    fn refraction_into_each_mode_conserves_the_tangential_wave_vector() {
        let mut c = calcite();
        c.axes = Mat3::from_rotation_y(0.6) * Mat3::from_rotation_x(0.3);
        let d = Vec3::new(0.5, 0.0, -0.8).normalize();
        let into = -Vec3::Z;
        let t = d - Vec3::Z * d.z; // outside n = 1
        for which in BOTH {
            let m = c.refract(t, into, which).unwrap();
            let tang = m.k * m.n - into * (m.k * m.n).dot(into);
            assert!((tang - t).length() < 1e-5, "{which:?}: {tang} vs {t}");
            assert!((c.mode(m.k, which).n - m.n).abs() < 1e-6);
        }
    }

    #[test]
    fn the_mode_along_a_ray_walks_off_onto_that_ray() {
        // Calcite with a tilted axis and a biaxial crystal: for rays in several directions,
        // each mode found along the ray has that ray as its own ray direction, and its
        // index is the mode's index for its wave normal.
        let mut cal = calcite();
        cal.axes = Mat3::from_rotation_y(0.6) * Mat3::from_rotation_x(0.3);
        let biaxial = Indicatrix {
            axes: Mat3::from_rotation_z(0.4),
            n: [1.654, 1.672, 1.690],
        };
        for c in [cal, biaxial] {
            for s in [
                Vec3::new(1.0, 0.0, 1.0),
                Vec3::new(0.3, -0.5, 0.8),
                Vec3::new(-0.9, 0.2, 0.1),
            ] {
                let s = s.normalize();
                for which in BOTH {
                    let m = c.mode_along_ray(s, which);
                    assert!((m.ray - s).length() < 1e-4, "{which:?}: {} vs {s}", m.ray);
                    assert!((c.mode(m.k, which).n - m.n).abs() < 1e-6);
                }
                let (slow, fast) = (
                    c.mode_along_ray(s, Which::Slow),
                    c.mode_along_ray(s, Which::Fast),
                );
                assert!(slow.n >= fast.n, "{} < {}", slow.n, fast.n);
                // The two E fields of one ray are orthogonal (they split unpolarized light
                // half and half).
                assert!(c.e_field(slow.d).dot(c.e_field(fast.d)).abs() < 1e-4);
            }
        }
        // Calcite at 45° from the axis: the extraordinary wave normal lies at θ with
        // tan θ = (n_e/n_o)² tan 45° (Born & Wolf §15.3.3), the ordinary one along the ray.
        let c = calcite();
        let s = Vec3::new(1.0, 0.0, 1.0).normalize();
        let e = c.mode_along_ray(s, Which::Fast);
        let theta = e.k.x.atan2(e.k.z);
        assert!((theta - (1.4864f32 / 1.6584).powi(2).atan()).abs() < 1e-4);
        assert!((c.mode_along_ray(s, Which::Slow).k - s).length() < 1e-5);
    }

    #[test]
    fn biaxial_indices_lie_between_the_principal_ones() {
        // Peridot-like: n_α 1.654, n_β 1.672, n_γ 1.690.
        let c = Indicatrix {
            axes: Mat3::IDENTITY,
            n: [1.654, 1.672, 1.690],
        };
        let k = Vec3::new(0.3, 0.5, 0.8).normalize();
        let (s, f) = (c.mode(k, Which::Slow), c.mode(k, Which::Fast));
        assert!(f.n >= 1.654 - 1e-5 && f.n <= 1.672 + 1e-5, "{}", f.n);
        assert!(s.n >= 1.672 - 1e-5 && s.n <= 1.690 + 1e-5, "{}", s.n);
        // Along x the two modes are n_β (D ∥ y) and n_γ (D ∥ z).
        let (s, f) = (c.mode(Vec3::X, Which::Slow), c.mode(Vec3::X, Which::Fast));
        assert!((s.n - 1.690).abs() < 1e-5 && s.d.z.abs() > 0.9999);
        assert!((f.n - 1.672).abs() < 1e-5 && f.d.y.abs() > 0.9999);
    }

    #[test]
    fn absorption_follows_the_field_direction() {
        let c = calcite();
        let sigma = [10.0, 10.0, 2.0];
        assert!((c.absorption(Vec3::X, sigma) - 10.0).abs() < 1e-5);
        assert!((c.absorption(Vec3::Z, sigma) - 2.0).abs() < 1e-5);
        let d = Vec3::new(1.0, 0.0, 1.0).normalize();
        assert!((c.absorption(d, sigma) - 6.0).abs() < 1e-5);
    }
}
