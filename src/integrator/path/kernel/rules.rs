//! What a method asks of the kernel's camera paths ([`Rules`]): the scalar vertex under
//! the method's strategy ([`Vertex`]: the path tracer's [`crate::integrator::path::Dispersion`],
//! or the hybrid's camera paths sharing light with a caustic map), in the carrier the
//! lanes hold, and the wavelengths every path starts with when the method fixes them (a
//! photon pass's). The kernel's loop is generic over the channels only; the strategy is
//! one object, asked once per batch what it changes ([`Vertex::gathers`]) and per lane
//! where it does.
//!
//! A strategy that gathers another estimator at non-delta vertices (the hybrid's caustic
//! map at the first one, D₁) has such a vertex shaded by the scalar vertex, which gathers,
//! and the lane comes back; the light a lane then finds closing a chain the map owns (D S+
//! L: ≥ 1 delta bounce since the last non-delta vertex) is not counted, as the scalar
//! vertex does not count it ([`crate::integrator::path::History::closes_caustic`]).

use super::handoff::Vertex;
use super::state::{Throughput, NONE_YET};
use crate::accel::packet::LaneMask;
use crate::integrator::path::History;
use crate::spectrum::{Carrier, Lambdas, SampledSpectrum};
use glam::Vec3;

/// The method's camera paths as the kernel runs them, in the lanes' carrier.
#[derive(Clone, Copy)]
pub enum Rules<'a> {
    /// Linear RGB.
    Rgb(&'a dyn Vertex<Vec3>),
    /// 4 wavelengths a lane; `Some`: every path starts with these (a photon pass's),
    /// otherwise each draws its own from its sample.
    Spectral(&'a dyn Vertex<SampledSpectrum>, Option<Lambdas>),
}

impl Rules<'_> {
    /// The lanes carry 4 wavelengths.
    pub fn spectral(&self) -> bool {
        matches!(self, Rules::Spectral(..))
    }

    /// The bounce limit.
    pub fn max_depth(&self) -> u32 {
        match self {
            Rules::Rgb(v) => v.max_depth(),
            Rules::Spectral(v, _) => v.max_depth(),
        }
    }

    /// A sample splits into its wavelengths at its first smooth dispersive glass.
    pub fn splits(&self) -> bool {
        match self {
            Rules::Rgb(v) => v.splits(),
            Rules::Spectral(v, _) => v.splits(),
        }
    }

    /// Another estimator is gathered at non-delta vertices.
    pub fn gathers(&self) -> bool {
        match self {
            Rules::Rgb(v) => v.gathers(),
            Rules::Spectral(v, _) => v.gathers(),
        }
    }

    /// The wavelengths every path starts with, if the method fixes them.
    pub fn fixed(&self) -> Option<Lambdas> {
        match self {
            Rules::Rgb(_) => None,
            Rules::Spectral(_, l) => *l,
        }
    }

    /// Of the lanes `on` (with the bounce records `st`), those whose light found now is
    /// another estimator's: none unless the strategy gathers one.
    pub fn leaving<const N: usize, const M: usize>(
        &self,
        on: LaneMask,
        st: &Throughput<N, M>,
    ) -> LaneMask {
        if !self.gathers() {
            return 0;
        }
        let mut leaves = 0;
        for i in crate::accel::packet::lanes(on) {
            let h = History {
                since_diffuse: (st.since[i] != NONE_YET).then_some(st.since[i]),
                last_in_medium: false,
                clear: true,
                direct: st.depth[i] + st.deltas[i] == 0,
                continues: st.depth[i] + 1 < self.max_depth(),
            };
            let leaves_light = match self {
                Rules::Rgb(v) => v.leaves_light(&h),
                Rules::Spectral(v, _) => v.leaves_light(&h),
            };
            leaves |= u32::from(leaves_light) << i;
        }
        leaves
    }

    /// Of the lanes `on`, those at their first non-delta vertex where the strategy gathers:
    /// the scalar vertex's.
    pub fn gathered<const N: usize, const M: usize>(
        &self,
        on: LaneMask,
        st: &Throughput<N, M>,
    ) -> LaneMask {
        if !self.gathers() {
            return 0;
        }
        crate::accel::packet::lanes(on)
            .filter(|&i| st.since[i] == NONE_YET)
            .fold(0, |m, i| m | (1 << i))
    }
}

/// The carriers the kernel's lanes hold: [`Rules`] from a strategy's scalar vertex in
/// that carrier.
pub trait Carried: Carrier {
    /// The rules for `vertex`, every path starting at `lambda` if given.
    fn rules(vertex: &dyn Vertex<Self>, lambda: Option<Self::Lambda>) -> Rules<'_>;
}

impl Carried for Vec3 {
    fn rules(vertex: &dyn Vertex<Vec3>, _: Option<()>) -> Rules<'_> {
        Rules::Rgb(vertex)
    }
}

impl Carried for SampledSpectrum {
    fn rules(vertex: &dyn Vertex<SampledSpectrum>, lambda: Option<Lambdas>) -> Rules<'_> {
        Rules::Spectral(vertex, lambda)
    }
}
