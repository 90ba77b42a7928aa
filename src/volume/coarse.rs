//! Long random walks in dense media, coarse-grained ([`Scale`]).
//!
//! A path that enters an optically thick medium of single-scattering albedo 1 takes a
//! random walk whose length has a heavy tail: the share still inside after n scattering
//! events falls only as n^(−1/2) (the walk's depth is a symmetric random walk, whose
//! survival on a half-line falls so whatever its steps: Sparre Andersen 1954), and a walk
//! that must cross an optical depth τ takes ~τ² events. Simulated event by event, a depth
//! limit loses that tail (a white medium renders dark) and a camera inside thick fog never
//! gets out (black).
//!
//! So a walk is exact for its first [`FINE_EVENTS`] events since it last met a surface
//! (`run`); after that each event scatters in a coarse-grained copy of the media: σ_t and
//! σ_s divided by k (same albedo, same phase function), k doubling every
//! [`EVENTS_PER_DOUBLING`] events. The coarse walk is the fine walk scaled up by k in space,
//! and in the diffusion limit one coarse event stands for k² fine ones (mean squared
//! displacement per event ∝ step²), so each coarse event's weight also carries the
//! absorption of k² − 1 more fine events, albedo^(k² − 1) per lane (the similarity of
//! diffusion; a non-absorbing medium keeps weight 1). The mean step stays about 1/26 of the
//! root-mean-square radius the walk has already explored (√(8 · `EVENTS_PER_DOUBLING` / 3)
//! steps of exponential length), so the walk only coarsens where it has shown the medium
//! to be thick around it, and it reaches any boundary within ~`EVENTS_PER_DOUBLING` ·
//! log₂(τ) events. Energy is kept exactly for albedo 1; what the approximation changes is
//! where the tail's light leaves the medium, by about the coarse step, for the light still
//! inside after `FINE_EVENTS` events (~1/√`FINE_EVENTS` of what enters). Shadow rays of next-event estimation at a
//! coarse event see the same coarse media up to the first surface, so next-event estimation
//! and phase sampling estimate the same thing there (MIS stays consistent).
//!
//! A walk meeting a surface (an index-matched boundary, glass, an object inside the medium)
//! starts a new run at the fine scale. [`MAX_RUN`] bounds a run (a medium closed by mirrors
//! never lets it out).

use super::medium::Coeffs;
use crate::spectrum::Carrier;

/// Events of a run simulated exactly before the walk coarsens.
pub const FINE_EVENTS: u32 = 1024;

/// Events per doubling of the coarse scale.
pub const EVENTS_PER_DOUBLING: u32 = 256;

/// Largest log₂ of the coarse scale (k ≤ 2⁶⁴).
const MAX_DOUBLINGS: u32 = 64;

/// Most scattering events in one run (the walk ends there).
pub const MAX_RUN: u32 = 2 * FINE_EVENTS + EVENTS_PER_DOUBLING * MAX_DOUBLINGS;

/// The coarse-graining scale k ≥ 1 of a walk's event (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale(f32);

impl Scale {
    /// The exact walk (k = 1).
    pub const FINE: Scale = Scale(1.0);

    /// The scale after `run` events since the walk last met a surface.
    pub fn after(run: u32) -> Scale {
        match run.checked_sub(FINE_EVENTS) {
            None => Scale::FINE,
            Some(n) => {
                let doublings = (n as f32 / EVENTS_PER_DOUBLING as f32).min(MAX_DOUBLINGS as f32);
                Scale(doublings.exp2())
            }
        }
    }

    /// k.
    pub fn k(self) -> f32 {
        self.0
    }

    /// The coarse coefficients: σ_t / k, σ_s / k.
    pub fn coeffs<C: Carrier>(self, c: Coeffs<C>) -> Coeffs<C> {
        if self == Scale::FINE {
            return c;
        }
        let inv = 1.0 / self.0;
        Coeffs {
            sigma_t: c.sigma_t * inv,
            sigma_s: c.sigma_s * inv,
        }
    }

    /// The extra weight of a scattering event at this scale in a medium with (fine)
    /// coefficients `c`: albedo^(k² − 1) per lane (1 where σ_t is 0).
    pub fn event_weight<C: Carrier>(self, c: &Coeffs<C>) -> C {
        if self == Scale::FINE {
            return C::ONE;
        }
        let power = self.0 * self.0 - 1.0;
        let (t, s) = (c.sigma_t.to_lanes(), c.sigma_s.to_lanes());
        C::from_lanes(std::array::from_fn(|j| {
            if t[j] > 0.0 {
                (s[j] / t[j]).min(1.0).powf(power)
            } else {
                1.0
            }
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn the_scale_doubles_after_the_fine_events() {
        assert_eq!(Scale::after(0), Scale::FINE);
        assert_eq!(Scale::after(FINE_EVENTS), Scale::FINE);
        assert_eq!(Scale::after(FINE_EVENTS + EVENTS_PER_DOUBLING).k(), 2.0);
        assert_eq!(Scale::after(FINE_EVENTS + 3 * EVENTS_PER_DOUBLING).k(), 8.0);
        assert_eq!(Scale::after(MAX_RUN).k(), 2f32.powi(64));
    }

    /// A coarse event of scale k weighs like k² fine events: albedo^(k²−1) on top of the
    /// flight's albedo; a non-absorbing lane keeps 1, an empty lane 1.
    #[test]
    fn a_coarse_event_absorbs_like_k_squared_fine_ones() {
        let c = Coeffs {
            sigma_t: Vec3::new(2.0, 1.0, 0.0),
            sigma_s: Vec3::new(1.8, 1.0, 0.0),
        };
        let w = Scale(4.0).event_weight(&c);
        assert!((w.x - 0.9f32.powi(15)).abs() < 1e-6, "{w}");
        assert_eq!((w.y, w.z), (1.0, 1.0));
        let coarse = Scale(4.0).coeffs(c);
        assert_eq!(coarse.sigma_t, Vec3::new(0.5, 0.25, 0.0));
        assert_eq!(Scale(2f32.powi(64)).event_weight(&c).x, 0.0);
    }
}
