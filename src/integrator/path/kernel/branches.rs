//! A lane's camera sample split into its wavelengths at its first smooth dispersive
//! interface, in spectral transport ([`Branches`]): the scalar path tracer's split
//! ([`crate::integrator::path::split`], where the estimator and its unbiasedness are
//! argued) with the waiting sub-paths as the lane's own refill. Sub-path 0 continues at
//! once; when a sub-path ends, the lane takes the next waiting one (sample lanes 1, 2, 3
//! in this order, those whose throughput at the split is not 0) before a new job: its state
//! is the split vertex's, its throughput that lane's alone, its wavelengths the sample's
//! rotated so that the lane's is the hero ([`Carrier::lane_as_hero`]), and it redoes the
//! split vertex from its event on, with the hit kept from the split (what arrived there
//! was counted before the split). The sample's radiance is what it gathered before the
//! split plus each sub-path's lane 0 in its own lane.
//!
//! Without the split (`Dispersion::split` off) the path keeps its hero wavelength only
//! there ([`Carrier::keep_hero`], ×1/w₀ on lane 0).
//!
//! A lane's sub-paths run one after the other with the sample's own stream, as the scalar
//! loop runs them, so a sample's numbers and its estimate are the scalar path's.

use super::colour::{lane, set_lane, take, Channels};
use super::state::{Lane, Throughput};
use crate::accel::RawHit;
use crate::spectrum::{Carrier, Lambdas, SampledSpectrum, N_LAMBDA};

/// The split samples of `N` lanes carrying `M` channels (used in spectral transport,
/// `M` = 4).
pub struct Branches<const N: usize, const M: usize> {
    /// Each lane's sample wavelengths as drawn (lane 0 the hero).
    pub sample: [Lambdas; N],
    /// The lane's sample was split.
    split: [bool; N],
    /// The sample lane the lane's current sub-path carries.
    carrying: [usize; N],
    /// Radiance gathered before the split and by finished sub-paths, in sample lane order.
    done: [[f32; M]; N],
    /// The throughput of each sample lane at the split vertex, before its event.
    beta: [[f32; M]; N],
    /// The sample lanes still waiting (bit `k` for lane `k`).
    waiting: [u8; N],
    /// The ray that reached the split vertex (origin, direction) and its hit.
    ray: [([f32; 3], [f32; 3]); N],
    hit: [Option<RawHit>; N],
    /// The path's state at the split vertex.
    state: [Lane; N],
}

/// A waiting sub-path a lane takes: the ray to its (known) hit at the split vertex.
pub struct Resumed {
    /// Origin and direction of the ray that reached the split vertex.
    pub ray: ([f32; 3], [f32; 3]),
    /// Its hit.
    pub hit: Option<RawHit>,
}

impl<const N: usize, const M: usize> Branches<N, M> {
    /// No lane split.
    pub fn new() -> Self {
        Branches {
            sample: std::array::from_fn(|_| super::colour::unset()),
            split: [false; N],
            carrying: [0; N],
            done: [[0.0; M]; N],
            beta: [[0.0; M]; N],
            waiting: [0; N],
            ray: [([0.0; 3], [0.0; 3]); N],
            hit: [None; N],
            state: [Lane::default(); N],
        }
    }

    /// Lane `i` starts a sample at the wavelengths `sample`.
    pub fn start(&mut self, i: usize, sample: Lambdas) {
        self.sample[i] = sample;
        self.split[i] = false;
        self.waiting[i] = 0;
    }

    /// Splits lane `i`'s sample at its dispersive vertex, reached along `ray` meeting
    /// `hit`: its radiance `l` so far is kept, the waiting lanes recorded, and the lane
    /// goes on as sub-path 0 (throughput lane 0's alone, wavelengths marked as its
    /// sub-path's, no radiance yet).
    pub fn split(
        &mut self,
        i: usize,
        (ray, hit): (([f32; 3], [f32; 3]), Option<RawHit>),
        (st, l, lam): (
            &mut Throughput<N, M>,
            &mut Channels<N, M>,
            &mut [Lambdas; N],
        ),
    ) {
        let b = lane(&st.beta, i);
        self.done[i] = lane(l, i);
        self.beta[i] = b;
        self.waiting[i] = (1..M.min(N_LAMBDA)).fold(0, |w, k| w | (u8::from(b[k] != 0.0) << k));
        (self.ray[i], self.hit[i]) = (ray, hit);
        self.state[i] = st.lane(i);
        self.split[i] = true;
        self.carrying[i] = 0;
        set_lane(&mut st.beta, i, only(b[0]));
        set_lane(l, i, [0.0; M]);
        lam[i] = SampledSpectrum::lane_as_hero(&self.sample[i], 0);
    }

    /// Lane `i`'s current sub-path ended with radiance `l`: adds it to the sample's and,
    /// when a sample lane waits, sets the lane to its sub-path (state, throughput,
    /// wavelengths, `since`) and returns the ray to its split vertex. `None`: the sample is
    /// done ([`Self::radiance`]).
    pub fn next(
        &mut self,
        i: usize,
        (st, l, lam): (
            &mut Throughput<N, M>,
            &mut Channels<N, M>,
            &mut [Lambdas; N],
        ),
    ) -> Option<Resumed> {
        if !self.split[i] {
            return None;
        }
        self.done[i][self.carrying[i]] += l[0][i];
        set_lane(l, i, [0.0; M]);
        let k = (1..M.min(N_LAMBDA)).find(|&k| self.waiting[i] & (1 << k) != 0)?;
        self.waiting[i] &= !(1 << k);
        self.carrying[i] = k;
        st.set_lane(i, &self.state[i]);
        set_lane(&mut st.beta, i, only(self.beta[i][k]));
        lam[i] = SampledSpectrum::lane_as_hero(&self.sample[i], k);
        Some(Resumed {
            ray: self.ray[i],
            hit: self.hit[i],
        })
    }

    /// Lane `i`'s sample radiance, in sample lane order, once [`Self::next`] returned
    /// `None`: `l` itself without a split.
    pub fn radiance(&self, i: usize, l: &Channels<N, M>) -> [f32; M] {
        if self.split[i] {
            self.done[i]
        } else {
            lane(l, i)
        }
    }
}

/// `v` in channel 0, the others 0.
fn only<const M: usize>(v: f32) -> [f32; M] {
    std::array::from_fn(|c| if c == 0 { v } else { 0.0 })
}

/// Lane `i` keeps only its hero wavelength at a dispersive vertex ([`Carrier::keep_hero`]).
pub fn keep_hero<const N: usize, const M: usize>(
    i: usize,
    st: &mut Throughput<N, M>,
    lam: &mut [Lambdas; N],
) {
    let b = SampledSpectrum::from_lanes(take(lane(&st.beta, i))).keep_hero(&mut lam[i]);
    set_lane(&mut st.beta, i, take(b.to_lanes()));
}
