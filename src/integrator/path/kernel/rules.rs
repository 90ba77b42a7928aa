//! What a method asks of the kernel's camera paths ([`Rules`]): the scalar vertex under
//! the method's strategy ([`Vertex`]: the path tracer's [`crate::integrator::path::Dispersion`],
//! or the hybrid's camera paths sharing light with a caustic map), in the carrier the
//! lanes hold, and the wavelengths every path starts with when the method fixes them (a
//! photon pass's). The kernel's loop is generic over the channels only; the strategy is
//! one object, asked once per batch what it changes ([`Vertex::gathers`]) and per lane
//! where it does.
//!
//! A strategy that gathers another estimator at non-delta vertices (the hybrid's caustic
//! map at the first one, D₁) gathers it there through the scalar vertex's surface
//! ([`Vertex::gather`]; at a Lambert or glossy vertex, which the kernel then shades on)
//! or, at a material the kernel hands over, in the scalar vertex; the light a lane finds closing a
//! chain the map owns (D S+ L: ≥ 1 delta bounce since the last non-delta vertex) is not
//! counted, as the scalar vertex does not count it
//! ([`crate::integrator::path::History::closes_caustic`]).

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

    /// Where the method shares the light with another estimator (a strategy that
    /// [`Rules::gathers`]), of the `alive` lanes (with the bounce records `st`) and the
    /// Lambert and glossy lanes `rough` among them: those at their first non-delta vertex,
    /// where the strategy gathers, and those whose light found now is the other
    /// estimator's.
    pub fn shared<const N: usize, const M: usize>(
        &self,
        (rough, alive): (LaneMask, LaneMask),
        st: &Throughput<N, M>,
    ) -> (LaneMask, LaneMask) {
        let (mut gathered, mut leaving) = (0, 0);
        let max_depth = self.max_depth();
        for i in crate::accel::packet::lanes(alive) {
            let h = history(st, i, max_depth);
            let first = h.since_diffuse.is_none() && rough & (1 << i) != 0;
            gathered |= u32::from(first) << i;
            let leaves = match self {
                Rules::Rgb(v) => v.leaves_light(&h),
                Rules::Spectral(v, _) => v.leaves_light(&h),
            };
            leaving |= u32::from(leaves) << i;
        }
        (gathered, leaving)
    }
}

/// Lane `i`'s bounces as a strategy reads them, from its records `st` under the bounce
/// limit `max_depth` (the kernel's paths never scatter in a medium).
pub fn history<const N: usize, const M: usize>(
    st: &Throughput<N, M>,
    i: usize,
    max_depth: u32,
) -> History {
    History {
        since_diffuse: (st.since[i] != NONE_YET).then_some(st.since[i]),
        last_in_medium: false,
        clear: true,
        direct: st.depth[i] + st.deltas[i] == 0,
        continues: st.depth[i] + 1 < max_depth,
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
