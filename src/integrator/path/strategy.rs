//! What a method asks of its camera paths ([`Strategy`]), passed to the path vertex
//! ([`super::vertex`]) as a value it calls: where a path stops, what is gathered along
//! it, which hero orders its lanes, which of its light belongs to another estimator, and
//! whether it splits into its wavelengths. The vertex is generic over the strategy, so
//! each caller's code is monomorphised and runs as if written for it.
//!
//! The strategies live with their methods: the path tracer's is its [`Dispersion`] (here),
//! SPPM's and the photon map's stop at a visible point
//! ([`crate::integrator::sppm::VisiblePoints`]), the hybrid's split its paths with a
//! caustic map ([`crate::integrator::hybrid::CausticPaths`]).
//!
//! Units: radiance per unit path throughput, in the carrier's units.

use super::{Beam, Dispersion};
use crate::shading::Surface;
use crate::spectrum::Carrier;

/// What a camera path keeps at a rough dispersive interface in spectral transport.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RoughLanes {
    /// The hero only ([`crate::spectrum::Carrier::keep_hero`]).
    Hero,
    /// The 4 lanes with spectral MIS, the sample's lane 0 the hero
    /// ([`crate::shading::spectral_mis`]).
    Mis,
    /// The 4 lanes with spectral MIS, the hero the path's own, drawn at its first rough
    /// dispersive vertex ([`super::own_hero`]: SPPM's camera paths, whose photons share the
    /// sample's hero); a visible point there keeps the lanes, the gather evaluating f per
    /// lane.
    OwnHero,
}

/// The bounce history of a camera path at a vertex, as a strategy reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct History {
    /// Delta bounces since the last non-delta vertex (`None` before the first): ≥ 1 when
    /// light found now closes a D S+ L chain.
    pub since_diffuse: Option<u32>,
    /// The last non-delta vertex was a scattering event in a medium.
    pub last_in_medium: bool,
    /// No scattering event in a medium yet.
    pub clear: bool,
    /// No bounce and no BLEND pass-through yet: the vertex is seen directly.
    pub direct: bool,
    /// A non-delta bounce from this vertex would be followed (the depth limit allows it).
    pub continues: bool,
}

impl History {
    /// Light found now closes a chain a caustic map owns: ≥ 1 delta bounce since the last
    /// non-delta vertex, which was a scattering event in a medium (an M S+ L chain, the
    /// volume map's) or a surface before any (a D S+ L chain, the surface map's;
    /// [`crate::integrator::volume_map`] gives the split).
    pub fn closes_caustic(&self) -> bool {
        self.since_diffuse.unwrap_or(0) > 0 && (self.last_in_medium || self.clear)
    }

    /// The vertex is the path's first non-delta one, D₁, and the bounce from it would be
    /// followed: where a caustic map is gathered.
    pub fn first_diffuse(&self) -> bool {
        self.since_diffuse.is_none() && self.continues
    }
}

/// What a method asks of its camera paths (module docs). Every hook has the plain path
/// tracer's answer by default.
pub trait Strategy<C: Carrier>: Sync {
    /// Whether [`Strategy::stops_at`] may stop a path: such paths return their visible
    /// point, which the lanes ([`super::estimate_lanes`]) do not, so they run on single rays.
    const STOPS: bool = false;

    /// What the path keeps at rough dispersive interfaces.
    fn rough(&self) -> RoughLanes;

    /// Whether the path splits into its wavelengths at its first smooth dispersive interface
    /// ([`super::split`]; spectral transport only).
    fn splits(&self) -> bool;

    /// Whether light the path finds now (emission, the environment) belongs to another
    /// estimator, after the bounces `h`.
    fn leaves_light(&self, _h: &History) -> bool {
        false
    }

    /// Whether the path ends at the surface `s` as a visible point
    /// ([`super::VisiblePoint`]).
    fn stops_at(&self, _s: &Surface<C>) -> bool {
        false
    }

    /// Whether [`Strategy::gather`] may add something (another estimator shares the light
    /// at non-delta vertices).
    fn gathers(&self) -> bool {
        false
    }

    /// What another estimator adds at the non-delta vertex `s` after the bounces `h`, per
    /// unit throughput.
    fn gather(&self, _s: &Surface<C>, _lambda: &C::Lambda, _h: &History) -> Option<C> {
        None
    }

    /// What another estimator adds along the path's segments through media.
    fn beam(&self) -> Option<Beam<'_, C>> {
        None
    }
}

/// The plain path tracer: every path counted here, to Russian roulette or the depth
/// limit, keeping its wavelengths as the [`Dispersion`] says.
impl<C: Carrier> Strategy<C> for Dispersion {
    fn rough(&self) -> RoughLanes {
        if self.spectral_mis {
            RoughLanes::Mis
        } else {
            RoughLanes::Hero
        }
    }

    fn splits(&self) -> bool {
        self.split
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// The path tracer keeps its wavelengths as its dispersion setting says and counts all
    /// light itself.
    #[test]
    fn the_path_tracer_follows_its_dispersion() {
        let rough = |d: Dispersion| Strategy::<Vec3>::rough(&d);
        assert_eq!(rough(Dispersion::ALL), RoughLanes::Mis);
        assert_eq!(rough(Dispersion::HERO), RoughLanes::Hero);
        assert_eq!(rough(Dispersion::SPLIT), RoughLanes::Hero);
        assert!(Strategy::<Vec3>::splits(&Dispersion::SPLIT));
        assert!(!Strategy::<Vec3>::splits(&Dispersion::HERO));
        let h = History {
            since_diffuse: Some(2),
            last_in_medium: false,
            clear: true,
            direct: false,
            continues: true,
        };
        assert!(!Strategy::<Vec3>::leaves_light(&Dispersion::ALL, &h));
        const { assert!(!<Dispersion as Strategy<Vec3>>::STOPS) };
    }
}
