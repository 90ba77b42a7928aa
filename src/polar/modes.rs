//! Choosing a crystal mode at an interface, for camera paths (backward) and photons
//! (forward) alike: each mode the light may be in is weighted by what its linear polarizer
//! passes of the light's Stokes vector (a photon's column) or of the analyzer's row (a camera
//! path's), and one is picked with probability w / Σw; the chosen vector becomes the
//! projected one, fully polarized along the mode's D field.
//!
//! Frames: a vector is given in the basis s (unit, ⊥ the light's direction of propagation
//! k_light); the mode's D field makes the angle ψ with s about k_light, and its polarizer is
//! [`super::stokes::linear_polarizer`]`(ψ)`, symmetric, so the row a·P and the column P·S
//! have the same entries.

use super::crystal::{Indicatrix, Mode, Which, BOTH};
use glam::Vec3;

/// Relative index difference below which the two modes are one (along an optic axis, or an
/// isotropic "crystal"): their phase difference over a stone is then a small fraction of a
/// wave, so the light keeps its polarization instead of splitting.
pub const DEGENERATE: f32 = 1e-5;

/// A mode the light may be in, with its projected vector and weight.
pub type Weighted = Option<(Which, Mode, ([f32; 4], f32))>;

/// The chosen mode, its projected vector and weight, and the weights' sum.
pub type Chosen = (Which, Mode, ([f32; 4], f32), f32);

/// The mode light is in inside a crystal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InMode {
    /// Which mode.
    pub which: Which,
    /// Its wave normal, along the path (camera path or photon).
    pub k: Vec3,
    /// Its D field direction.
    pub d: Vec3,
}

/// Which way the light travels along a mode's wave normal k: camera paths meet it against
/// the light ([`Travel::Against`], the light propagates along −k), photons with it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Travel {
    /// The light propagates along −k (a camera path following k).
    Against,
    /// The light propagates along k (a photon).
    Along,
}

impl Travel {
    /// The light's direction of propagation in `mode`.
    pub fn k_light(self, mode: &Mode) -> Vec3 {
        match self {
            Travel::Against => -mode.k,
            Travel::Along => mode.k,
        }
    }
}

/// The modes (slow, fast) the light may be in, each with the vector `through` it gives
/// (basis `s`) projected on the mode's polarization ([`project`]). Degenerate modes
/// ([`DEGENERATE`]) are one wave whose vector is not projected: projecting it on an
/// arbitrary basis would depolarize light travelling along an optic axis.
pub fn split(
    modes: [Option<Mode>; 2],
    through: impl Fn(&Mode) -> [f32; 4],
    s: Vec3,
    travel: Travel,
) -> [Weighted; 2] {
    if let [Some(slow), Some(fast)] = modes {
        if slow.n - fast.n < DEGENERATE * slow.n {
            let a = through(&slow);
            return [Some((Which::Slow, slow, (a, a[0].max(0.0)))), None];
        }
    }
    let mut out = [None, None];
    for (i, (m, w)) in modes.iter().zip(BOTH).enumerate() {
        out[i] = m.map(|mode| (w, mode, project(&through(&mode), &mode, s, travel)));
    }
    out
}

/// The vector `v` (basis s ⊥ the light's direction) through the mode's linear polarizer:
/// P·v and its weight w = (P·v)₀ ≥ 0.
pub fn project(v: &[f32; 4], mode: &Mode, s: Vec3, travel: Travel) -> ([f32; 4], f32) {
    let y = travel.k_light(mode).cross(s);
    let psi = mode.d.dot(y).atan2(mode.d.dot(s));
    let (sin2, cos2) = (2.0 * psi).sin_cos();
    let w = (0.5 * (v[0] + v[1] * cos2 + v[2] * sin2)).max(0.0);
    ([w, w * cos2, w * sin2, 0.0], w)
}

/// The mode of light met travelling inside a crystal along the ray direction `ray` in no
/// known mode — a camera or a light inside the crystal, or a path leaving a surface that
/// is not the crystal's inside it — chosen with `u` as [`choose`] does: each mode whose
/// ray runs along `ray` ([`Indicatrix::mode_along_ray`]) weighted by what its linear
/// polarizer passes of `v` (basis `s` ⊥ `ray`), the polarizer along the mode's E field,
/// which is ⊥ the ray as `v`'s basis is. Returns the choice with the chosen vector in the
/// basis of the second value, ⊥ the mode's wave normal: fully polarized along its D field
/// (E along the ray is D along the wave normal), or `v` unchanged in `s` when the two
/// modes are one ([`DEGENERATE`]: no walk-off, no split).
pub fn along_ray(
    c: &Indicatrix,
    ray: Vec3,
    (v, s): (&[f32; 4], Vec3),
    travel: Travel,
    u: f32,
) -> Option<(Chosen, Vec3)> {
    let modes = BOTH.map(|w| c.mode_along_ray(ray, w));
    if modes[0].n - modes[1].n < DEGENERATE * modes[0].n {
        let w = v[0].max(0.0);
        let one = [Some((Which::Slow, modes[0], (*v, w))), None];
        return choose(&one, u).map(|c| (c, s));
    }
    let weighted = BOTH.map(|w| {
        let mode = modes[usize::from(w == Which::Fast)];
        // The projection in the ray's frame: the mode's E field in place of D, the ray in
        // place of the wave normal.
        let seen = Mode {
            k: ray,
            d: super::stokes::transverse(c.e_field(mode.d), ray),
            ..mode
        };
        let (_, weight) = project(v, &seen, s, travel);
        Some((w, mode, ([weight, weight, 0.0, 0.0], weight)))
    });
    let chosen = choose(&weighted, u)?;
    Some((chosen, chosen.1.d))
}

/// Picks one of the weighted modes with probability w / Σw using `u`; returns it with Σw.
pub fn choose(weighted: &[Weighted; 2], u: f32) -> Option<Chosen> {
    let total: f32 = weighted.iter().flatten().map(|(_, _, (_, w))| *w).sum();
    if total.is_nan() || total <= 0.0 {
        return None;
    }
    let mut acc = 0.0;
    let mut last = None;
    for (w, mode, p) in weighted.iter().flatten() {
        acc += p.1;
        last = Some((*w, *mode, *p, total));
        if u * total < acc {
            break;
        }
    }
    last
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polar::crystal::calcite;
    use crate::polar::stokes::{linear_polarizer, mul};

    fn calcite_mode(which: Which) -> Mode {
        calcite().mode(Vec3::new(1.0, 0.0, 1.0).normalize(), which)
    }

    #[test]
    fn projection_is_the_polarizer_along_d_for_either_travel() {
        // Unpolarized light splits half and half whichever way it travels, and the
        // projection equals the polarizer matrix at the angle of D from s about k_light.
        for travel in [Travel::Against, Travel::Along] {
            let mode = calcite_mode(Which::Fast);
            let k = travel.k_light(&mode);
            let s = k.any_orthonormal_vector();
            let (p, w) = project(&[1.0, 0.0, 0.0, 0.0], &mode, s, travel);
            assert!((w - 0.5).abs() < 1e-6, "{w}");
            let psi = mode.d.dot(k.cross(s)).atan2(mode.d.dot(s));
            let expect = mul(&linear_polarizer(psi), &[1.0, 0.0, 0.0, 0.0]);
            for i in 0..4 {
                assert!((p[i] - expect[i]).abs() < 1e-5, "{p:?} {expect:?}");
            }
        }
    }

    #[test]
    fn choices_follow_the_weights() {
        let w = [
            Some((Which::Slow, calcite_mode(Which::Slow), ([0.3; 4], 0.3))),
            Some((Which::Fast, calcite_mode(Which::Fast), ([0.1; 4], 0.1))),
        ];
        assert_eq!(choose(&w, 0.74).unwrap().0, Which::Slow);
        assert_eq!(choose(&w, 0.76).unwrap().0, Which::Fast);
        assert!((choose(&w, 0.1).unwrap().3 - 0.4).abs() < 1e-6);
        assert!(choose(&[None, None], 0.5).is_none());
    }
}
