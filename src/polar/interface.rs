//! Where a path meets the smooth surface of a birefringent crystal, the geometry both
//! directions of travel share (camera paths against the light, photons with it): which side
//! it comes from, the modes on the crystal side, the directions and the reflectance that
//! decides reflect-or-refract.
//!
//! Frames: world space; `n` is the surface's outward unit normal, `d` the path's unit
//! direction outside, a mode's wave normal `k` inside. Phase matching across the surface
//! (the tangential wave vector t is conserved) gives every direction
//! ([`super::crystal::Indicatrix::refract`]). The reflectance R̄ is the unpolarized Fresnel
//! reflectance with the mean index of the modes that propagate (outside) or the mode's
//! own index (inside); 1 when nothing propagates beyond (total reflection).

use super::crystal::{Indicatrix, Mode, BOTH};
use super::modes::InMode;
use crate::optics::fresnel_dielectric;
use glam::Vec3;

/// A path at a crystal surface.
#[derive(Debug, Clone, Copy)]
pub enum Meeting {
    /// Arriving from outside.
    Outside(Outside),
    /// Arriving from inside, in a mode.
    Inside(Inside),
}

/// A path arriving from outside along `d`.
#[derive(Debug, Clone, Copy)]
pub struct Outside {
    /// cos θ between −d and the normal (> 0).
    pub cos1: f32,
    /// The mirror direction.
    pub reflected: Vec3,
    /// The modes (slow, fast) on the crystal side; `None` where evanescent.
    pub modes: [Option<Mode>; 2],
    /// The reflectance R̄.
    pub r_mean: f32,
    /// The index whose Fresnel matrix the reflection takes: the modes' mean, or the mean
    /// principal index under total reflection (for its retardance).
    pub n_reflect: f32,
}

/// A path inside in a mode, arriving at the surface from within.
#[derive(Debug, Clone, Copy)]
pub struct Inside {
    /// The mode's index along its wave normal.
    pub n_mode: f32,
    /// cos θ between the wave normal and the normal (> 0).
    pub cos_k: f32,
    /// The direction refracted out, `None` under total internal reflection.
    pub out: Option<Vec3>,
    /// The modes (slow, fast) reflected inside; `None` where evanescent.
    pub reflected: [Option<Mode>; 2],
    /// The reflectance R̄.
    pub r_mean: f32,
}

/// How a path along `d` (unit) meets a crystal surface with outward unit normal `n`,
/// `n_out` the index outside, the path in mode `state` inside (`None`: outside). `None`
/// when the two disagree (a path inside leaving through the surface from outside).
pub fn meet(
    c: &Indicatrix,
    (n, n_out): (Vec3, f32),
    d: Vec3,
    state: Option<InMode>,
) -> Option<Meeting> {
    match state {
        Some(inside) if d.dot(n) > 0.0 => Inside::new(c, (n, n_out), inside).map(Meeting::Inside),
        _ if d.dot(n) < 0.0 => Some(Meeting::Outside(Outside::new(c, (n, n_out), d))),
        _ => None,
    }
}

impl Outside {
    fn new(c: &Indicatrix, (n, n1): (Vec3, f32), d: Vec3) -> Outside {
        let cos1 = -d.dot(n);
        let t = (d + n * cos1) * n1;
        let modes = BOTH.map(|w| c.refract(t, -n, w));
        let (sum, count) = modes
            .iter()
            .flatten()
            .fold((0.0, 0.0), |(s, k), m| (s + m.n, k + 1.0));
        let n_mean = (count > 0.0).then(|| sum / count);
        Outside {
            cos1,
            reflected: d + n * (2.0 * cos1),
            modes,
            r_mean: n_mean.map_or(1.0, |nm| fresnel_dielectric(cos1, nm / n1)),
            n_reflect: n_mean.unwrap_or((c.n[0] + c.n[1] + c.n[2]) / 3.0),
        }
    }
}

impl Inside {
    fn new(c: &Indicatrix, (n, n2): (Vec3, f32), inside: InMode) -> Option<Inside> {
        let k = inside.k;
        let n_mode = c.mode(k, inside.which).n;
        let cos_k = k.dot(n);
        if cos_k <= 0.0 {
            return None;
        }
        let t = (k - n * cos_k) * n_mode;
        let t2 = t.length_squared();
        let out = (t2 < n2 * n2).then(|| (t + n * (n2 * n2 - t2).sqrt()) / n2);
        Some(Inside {
            n_mode,
            cos_k,
            out,
            reflected: BOTH.map(|w| c.refract(t, -n, w)),
            r_mean: out.map_or(1.0, |_| fresnel_dielectric(cos_k, n2 / n_mode)),
        })
    }
}
