//! The hybrid's camera paths ([`CausticPaths`]): the path tracer's loop sharing light
//! transport with a caustic photon map, Jensen's caustic map in Heckbert's notation. A
//! path's light end L S+ D (a caustic light, at least one delta bounce, a non-delta
//! vertex) is the map's; the path tracer counts every other path. The vertex asks this
//! strategy ([`Strategy`]) whether light it finds is the map's and what the map adds at
//! its first non-delta vertex D₁.
//!
//! Units: radiance per unit path throughput, in the carrier's units.

use crate::integrator::path::{Beam, Dispersion, History, RoughLanes, Strategy};
use crate::shading::Surface;
use crate::spectrum::Carrier;

/// A caustic map's gather at a camera vertex: reflected radiance toward its `wo`
/// ([`crate::integrator::caustic::CausticMap::density`]).
pub type Gather<'a, C> = &'a (dyn Fn(&Surface<C>, &<C as Carrier>::Lambda) -> C + Sync);

/// How the caustic map's share is gathered.
#[derive(Clone, Copy)]
pub enum CausticSplit<'a, C: Carrier> {
    /// At the path's first non-delta vertex, if its BSDF-sampled bounce would be followed,
    /// `gather(surface, lambda)` adds the map's reflected radiance (times the path
    /// throughput), and emission found by BSDF sampling after any non-delta bounce followed
    /// by ≥ 1 delta bounces is dropped (exactly the paths the map counts), the environment's
    /// radiance seen by a ray escaping after D S+ included (the environment is a caustic
    /// light).
    Map(Gather<'a, C>),
    /// As `Map`, but D₁ gathers with `through` if the camera reached it through ≥ 1 delta
    /// bounce or BLEND pass-through, with `direct` if it is seen directly (`None`: nothing);
    /// light tracing counts the rest ([`crate::integrator::light_trace`], which proves the
    /// split).
    Mixed {
        /// The gather at a D₁ seen through delta bounces (the whole map).
        through: Gather<'a, C>,
        /// The gather at a D₁ seen directly (the photons light tracing does not splat).
        direct: Option<Gather<'a, C>>,
    },
    /// As `Map` in a scene with media, where a path's first non-delta vertex may be a
    /// scattering event: `surface` gathers at a surface D₁, and `beam` adds the volumetric
    /// caustic map's estimate along every segment through a medium before the first
    /// non-delta vertex ([`crate::integrator::volume_map`] proves the split). An M S+ L chain
    /// is always the volume map's, a D S+ L chain the surface map's only while the path has
    /// not scattered in a medium.
    Volume {
        /// The surface map's gather at D₁.
        surface: Gather<'a, C>,
        /// The volume map's beam estimate.
        beam: Beam<'a, C>,
    },
}

/// The hybrid's camera-path strategy: the caustic map's `split`, the wavelengths kept as
/// `dispersion` says except spectral MIS (under the sample's hero it would tie the
/// camera's hero to the photons' hero, [`crate::integrator::path::HeroOf`]).
#[derive(Clone, Copy)]
pub struct CausticPaths<'a, C: Carrier> {
    /// The caustic map's share.
    pub split: CausticSplit<'a, C>,
    /// What the paths keep at dispersive interfaces (the split only).
    pub dispersion: Dispersion,
}

impl<'a, C: Carrier> CausticPaths<'a, C> {
    /// The map's gather at a non-delta vertex after the bounces `h`: at D₁ if the bounce
    /// from it would be followed, the whole map, or with [`CausticSplit::Mixed`] the part
    /// for a D₁ seen directly or through delta bounces.
    fn gather_at(&self, h: &History) -> Option<Gather<'a, C>> {
        let gather = match self.split {
            CausticSplit::Map(g) | CausticSplit::Volume { surface: g, .. } => Some(g),
            CausticSplit::Mixed { through, direct } => {
                if h.direct {
                    direct
                } else {
                    Some(through)
                }
            }
        };
        gather.filter(|_| h.first_diffuse())
    }
}

impl<C: Carrier> Strategy<C> for CausticPaths<'_, C> {
    fn rough(&self) -> RoughLanes {
        RoughLanes::Hero
    }

    fn splits(&self) -> bool {
        self.dispersion.split
    }

    /// Light closing a D S+ L chain is the map's (module docs; with media, see
    /// [`CausticSplit::Volume`]).
    fn leaves_light(&self, h: &History) -> bool {
        h.closes_caustic()
    }

    fn gathers(&self) -> bool {
        true
    }

    fn gather(&self, s: &Surface<C>, lambda: &C::Lambda, h: &History) -> Option<C> {
        self.gather_at(h).map(|g| g(s, lambda))
    }

    fn beam(&self) -> Option<Beam<'_, C>> {
        match self.split {
            CausticSplit::Volume { beam, .. } => Some(beam),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn history(since_diffuse: Option<u32>, direct: bool) -> History {
        History {
            since_diffuse,
            last_in_medium: false,
            clear: true,
            direct,
            continues: true,
        }
    }

    /// Light found after a non-delta vertex and ≥ 1 delta bounces (read from the light: L
    /// S+ D) is left to the photons; light seen directly, through delta bounces only, or
    /// straight after a non-delta vertex is the path tracer's. After scattering in a
    /// medium a surface's D S+ L chain is the path tracer's again, an M S+ L chain the
    /// volume map's.
    #[test]
    fn light_specular_diffuse_is_left_to_photons() {
        let map = |_: &Surface<Vec3>, _: &()| Vec3::ONE;
        let paths = CausticPaths {
            split: CausticSplit::Map(&map),
            dispersion: Dispersion::SPLIT,
        };
        let leaves = |h: History| Strategy::<Vec3>::leaves_light(&paths, &h);
        assert!(leaves(history(Some(1), false)));
        assert!(leaves(history(Some(3), false)));
        assert!(!leaves(history(None, true)));
        assert!(!leaves(history(None, false)));
        assert!(!leaves(history(Some(0), false)));
        let scattered = |last_in_medium| History {
            last_in_medium,
            clear: false,
            ..history(Some(1), false)
        };
        assert!(!leaves(scattered(false)));
        assert!(leaves(scattered(true)));
    }

    /// The map is gathered at the first non-delta vertex only, and only when the bounce
    /// from it would be followed; in mixed mode a D₁ seen directly takes the `direct`
    /// gather (none with light tracing alone), one seen through delta bounces the whole map.
    #[test]
    fn the_map_is_gathered_at_the_first_diffuse_vertex() {
        let whole = |_: &Surface<Vec3>, _: &()| Vec3::ONE;
        let later = |_: &Surface<Vec3>, _: &()| Vec3::splat(2.0);
        let (whole, later): (Gather<Vec3>, Gather<Vec3>) = (&whole, &later);
        let at = |split, h: History| {
            let paths = CausticPaths {
                split,
                dispersion: Dispersion::HERO,
            };
            paths.gather_at(&h).map(|g| g as *const _ as *const ())
        };
        let (whole_p, later_p) = (
            Some(whole as *const _ as *const ()),
            Some(later as *const _ as *const ()),
        );
        let map = CausticSplit::Map(whole);
        assert_eq!(at(map, history(None, true)), whole_p);
        assert_eq!(at(map, history(None, false)), whole_p);
        assert_eq!(at(map, history(Some(0), false)), None);
        let last = History {
            continues: false,
            ..history(None, true)
        };
        assert_eq!(at(map, last), None);
        let mixed = |direct| CausticSplit::Mixed {
            through: whole,
            direct,
        };
        assert_eq!(at(mixed(None), history(None, true)), None);
        assert_eq!(at(mixed(Some(later)), history(None, true)), later_p);
        assert_eq!(at(mixed(Some(later)), history(None, false)), whole_p);
    }

    /// The hybrid keeps the hero at rough dispersive interfaces, splits as its dispersion
    /// says and never stops a path.
    #[test]
    fn hybrid_paths_keep_the_hero_and_never_stop() {
        let map = |_: &Surface<Vec3>, _: &()| Vec3::ONE;
        let paths = |dispersion| CausticPaths {
            split: CausticSplit::Map(&map),
            dispersion,
        };
        assert_eq!(
            Strategy::<Vec3>::rough(&paths(Dispersion::ALL)),
            RoughLanes::Hero
        );
        assert!(Strategy::<Vec3>::splits(&paths(Dispersion::SPLIT)));
        assert!(!Strategy::<Vec3>::splits(&paths(Dispersion::HERO)));
        const { assert!(!<CausticPaths<Vec3> as Strategy<Vec3>>::STOPS) };
        assert!(Strategy::<Vec3>::beam(&paths(Dispersion::SPLIT)).is_none());
    }
}
