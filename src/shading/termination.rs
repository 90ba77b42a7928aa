//! How a path ends, written once for every tracer (the path tracer's and the polarized
//! path tracer's camera paths, photons, VCM's light and camera subpaths, the Whitted
//! tracer's branches): Russian roulette ([`roulette`], [`throughput_roulette`]) and the
//! cap on delta bounces ([`delta_bounce`], [`Bounces`]).
//!
//! Russian roulette (Arvo & Kirk 1990, "Particle Transport and Image Synthesis"; pbrt-v4
//! §14.1.5): a path continues with probability p ∈ (0, 1] and its weight is divided by p,
//! so its expectation is kept: E[1{u < p} · w / p] = w. What p is stays with each tracer
//! (the throughput's largest lane, its change over a bounce, a branch's weight over a
//! threshold); which random numbers a roulette reads is part of each tracer's
//! determinism, so [`Draw`] keeps the two rules in use.
//!
//! Delta bounces (smooth mirrors and dielectrics) do not use up a path's `max_depth` budget
//! of non-delta bounces, so a gem's internal reflections are not cut short; at most
//! [`MAX_DELTA_BOUNCES`] of them end a path.

use crate::spectrum::Carrier;

/// Most delta (specular) bounces on one camera or photon path.
pub const MAX_DELTA_BOUNCES: u32 = 1024;

/// Counts one delta bounce on `count`: `false` once the path has more than
/// [`MAX_DELTA_BOUNCES`] (it ends there).
pub fn delta_bounce(count: &mut u32) -> bool {
    *count += 1;
    *count <= MAX_DELTA_BOUNCES
}

/// A photon's or subpath's bounces so far: non-delta ones against its `max_depth`, delta
/// ones against [`MAX_DELTA_BOUNCES`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Bounces {
    /// Non-delta bounces (surface or medium).
    pub depth: u32,
    /// Delta bounces.
    pub deltas: u32,
}

impl Bounces {
    /// Counts one bounce (`delta` or not): `false` when the path ends there (`max_depth`
    /// non-delta bounces reached, or past [`MAX_DELTA_BOUNCES`] delta ones).
    pub fn bounce(&mut self, delta: bool, max_depth: u32) -> bool {
        if delta {
            delta_bounce(&mut self.deltas)
        } else {
            self.depth += 1;
            self.depth < max_depth
        }
    }
}

/// When a roulette reads its random number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Draw {
    /// Unless the path surely ends (p ≤ 0): a number also when it surely survives
    /// (p ≥ 1). Photons and light subpaths (one number of their own stream per bounce),
    /// VCM's camera subpaths and the Whitted tracer's branches.
    UnlessDead,
    /// Only while survival is not sure (p < 1; a NaN p ends the path without one): the
    /// path tracer's camera paths (their scheduled roulette dimension).
    UnlessSure,
}

/// Russian roulette with survival probability `p` (module docs): `Some(min(p, 1))`, the
/// number to divide the path's weight by, when it survives; `None` when it ends. A drawn
/// number `u()` ∈ [0, 1) survives when u < p; without one (as `draw` says) the path
/// survives when p ≥ 1. A NaN or non-positive `p` never survives.
pub fn roulette(p: f32, draw: Draw, u: impl FnOnce() -> f32) -> Option<f32> {
    let drawn = match draw {
        Draw::UnlessDead => p > 0.0 || p.is_nan(),
        Draw::UnlessSure => p < 1.0,
    };
    let survives = if drawn { u() < p } else { p >= 1.0 };
    survives.then(|| p.min(1.0))
}

/// Throughput Russian roulette from `old` to `new` (Jensen 2001 §5.1, "Realistic Image
/// Synthesis Using Photon Mapping"): survival min(1, max(new)/max(old)) (0 when `old`
/// carries nothing), [`Draw::UnlessDead`]; a survivor keeps its power, `new / p`.
pub fn throughput_roulette<C: Carrier>(old: C, new: C, u: impl FnOnce() -> f32) -> Option<C> {
    let before = old.max_element();
    let p = if before > 0.0 {
        (new.max_element() / before).min(1.0)
    } else {
        0.0
    };
    roulette(p, Draw::UnlessDead, u).map(|p| new / p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rng;
    use glam::Vec3;

    /// Roulette keeps the expectation: over many paths of weight w rouletted with p, the
    /// mean of the survivors' w / p is w (p = 0.3: 200 000 paths, 4σ ≈ 0.0068 relative),
    /// and a p of 1 or more keeps every path at its weight.
    #[test]
    fn roulette_keeps_the_expectation() {
        let mut rng = Rng::new(&[5, 0x77]);
        for draw in [Draw::UnlessDead, Draw::UnlessSure] {
            let (n, w, p) = (200_000, 2.5f64, 0.3f32);
            let mut sum = 0.0;
            for _ in 0..n {
                if let Some(q) = roulette(p, draw, || rng.next_f32()) {
                    sum += w / f64::from(q);
                }
            }
            let mean = sum / f64::from(n);
            assert!((mean / w - 1.0).abs() < 0.0068, "{draw:?}: {mean}");
            assert_eq!(roulette(1.0, draw, || 0.999_999), Some(1.0));
            assert_eq!(roulette(3.0, draw, || 0.5), Some(1.0));
        }
        let new = Vec3::new(0.2, 0.1, 0.05);
        let mut sum = Vec3::ZERO;
        for _ in 0..200_000 {
            if let Some(v) = throughput_roulette(Vec3::ONE, new, || rng.next_f32()) {
                assert_eq!(v.max_element(), 1.0);
                sum += v;
            }
        }
        let mean = sum / 200_000.0;
        assert!(
            (mean / new - Vec3::ONE).abs().max_element() < 0.02,
            "{mean}"
        );
    }

    /// Which numbers each rule reads: `UnlessDead` none at p ≤ 0 and one at p ≥ 1,
    /// `UnlessSure` one at p ≤ 0 and none at p ≥ 1 or NaN; NaN and p ≤ 0 never survive.
    #[test]
    fn the_draw_rules_read_their_numbers() {
        let reads = |p: f32, draw| {
            let mut n = 0;
            let out = roulette(p, draw, || {
                n += 1;
                0.0
            });
            (out, n)
        };
        assert_eq!(reads(0.0, Draw::UnlessDead), (None, 0));
        assert_eq!(reads(1.0, Draw::UnlessDead), (Some(1.0), 1));
        assert_eq!(reads(f32::NAN, Draw::UnlessDead), (None, 1));
        assert_eq!(reads(0.0, Draw::UnlessSure), (None, 1));
        assert_eq!(reads(-1.0, Draw::UnlessSure), (None, 1));
        assert_eq!(reads(1.0, Draw::UnlessSure), (Some(1.0), 0));
        assert_eq!(reads(f32::NAN, Draw::UnlessSure), (None, 0));
        assert_eq!(reads(0.5, Draw::UnlessSure), (Some(0.5), 1));
    }

    /// The delta cap ends a path at its 1025th delta bounce; non-delta bounces end it at
    /// `max_depth`, and neither count touches the other.
    #[test]
    fn bounces_are_capped() {
        let mut b = Bounces::default();
        for _ in 0..MAX_DELTA_BOUNCES {
            assert!(b.bounce(true, 2));
        }
        assert!(!b.bounce(true, 2));
        assert!(b.bounce(false, 3));
        assert!(b.bounce(false, 3));
        assert!(!b.bounce(false, 3));
        assert_eq!(
            b,
            Bounces {
                depth: 3,
                deltas: MAX_DELTA_BOUNCES + 1
            }
        );
    }
}
