//! The per-lane state of the kernel's camera paths: throughput and the bounce records
//! ([`Throughput`], `M` channels a lane, [`super::colour`]), one lane's record apart from
//! its throughput ([`Lane`], what a split sample's waiting sub-path restarts from), and
//! rays in structure-of-arrays form ([`Rays`]).
//!
//! Units: world space; throughput dimensionless per channel.

use super::colour::Channels;
use super::hits::{Hits, V3};

/// [`Throughput::since`] of a lane before its first non-delta bounce.
pub const NONE_YET: u32 = u32::MAX;

/// One lane's [`Throughput`] record apart from β.
#[derive(Debug, Clone, Copy, Default)]
pub struct Lane {
    eta_scale: f32,
    depth: u32,
    deltas: u32,
    prev_delta: bool,
    prev_pdf: f32,
    prev_p: [f32; 3],
    medium: u32,
    since: u32,
}

/// The per-lane state the bounces update: throughput, η scale, bounce counts, the
/// previous bounce (for the MIS weight of emission the path meets next, as the scalar
/// path's `Prev`) and the glass volume the path is in.
pub struct Throughput<const N: usize, const M: usize> {
    /// Throughput β.
    pub beta: Channels<N, M>,
    /// Product of η'² over the refractions (Russian roulette reads β · η scale).
    pub eta_scale: [f32; N],
    /// Non-delta bounces.
    pub depth: [u32; N],
    /// Delta bounces.
    pub deltas: [u32; N],
    /// The previous bounce was delta (or the ray is the camera's): no MIS.
    pub prev_delta: [bool; N],
    /// The previous bounce's BSDF pdf (solid angle).
    pub prev_pdf: [f32; N],
    /// The previous bounce's position.
    pub prev_p: V3<N>,
    /// The glass volume the path is in: its material index + 1, or 0 in air.
    pub medium: [u32; N],
    /// Delta bounces since the last non-delta one ([`NONE_YET`] before the first).
    pub since: [u32; N],
}

impl<const N: usize, const M: usize> Throughput<N, M> {
    /// No paths yet.
    pub fn new() -> Self {
        Throughput {
            beta: [[0.0; N]; M],
            eta_scale: [1.0; N],
            depth: [0; N],
            deltas: [0; N],
            prev_delta: [true; N],
            prev_pdf: [0.0; N],
            prev_p: [[0.0; N]; 3],
            medium: [0; N],
            since: [NONE_YET; N],
        }
    }

    /// Lane `i` starts a camera path: unit throughput, no bounce yet (none to weigh
    /// against), in air.
    pub fn restart(&mut self, i: usize) {
        (0..M).for_each(|c| self.beta[c][i] = 1.0);
        self.eta_scale[i] = 1.0;
        self.depth[i] = 0;
        self.deltas[i] = 0;
        self.prev_delta[i] = true;
        self.prev_pdf[i] = 0.0;
        self.medium[i] = 0;
        self.since[i] = NONE_YET;
    }

    /// Lane `i`'s state but its throughput.
    pub fn lane(&self, i: usize) -> Lane {
        Lane {
            eta_scale: self.eta_scale[i],
            depth: self.depth[i],
            deltas: self.deltas[i],
            prev_delta: self.prev_delta[i],
            prev_pdf: self.prev_pdf[i],
            prev_p: [0, 1, 2].map(|c| self.prev_p[c][i]),
            medium: self.medium[i],
            since: self.since[i],
        }
    }

    /// Sets lane `i`'s state but its throughput to `s`.
    pub fn set_lane(&mut self, i: usize, s: &Lane) {
        self.eta_scale[i] = s.eta_scale;
        self.depth[i] = s.depth;
        self.deltas[i] = s.deltas;
        self.prev_delta[i] = s.prev_delta;
        self.prev_pdf[i] = s.prev_pdf;
        (0..3).for_each(|c| self.prev_p[c][i] = s.prev_p[c]);
        self.medium[i] = s.medium;
        self.since[i] = s.since;
    }

    /// Where `on`, lane `i` records its bounce at `h`'s lane `i` with BSDF pdf `pdf`
    /// (`delta`: a delta bounce).
    #[inline(always)]
    pub fn bounced(&mut self, on: bool, h: &Hits<N, M>, i: usize, (pdf, delta): (f32, bool)) {
        self.prev_delta[i] = if on { delta } else { self.prev_delta[i] };
        self.prev_pdf[i] = if on { pdf } else { self.prev_pdf[i] };
        for c in 0..3 {
            self.prev_p[c][i] = if on { h.p[c][i] } else { self.prev_p[c][i] };
        }
    }
}

/// Rays in SoA form: origin, direction, `t_max`.
pub struct Rays<const N: usize> {
    /// Origin.
    pub o: V3<N>,
    /// Direction.
    pub d: V3<N>,
    /// Upper bound of t.
    pub t_max: [f32; N],
}

impl<const N: usize> Rays<N> {
    /// No rays yet.
    pub fn new() -> Self {
        Rays {
            o: [[0.0; N]; 3],
            d: [[0.0; N]; 3],
            t_max: [0.0; N],
        }
    }
}
