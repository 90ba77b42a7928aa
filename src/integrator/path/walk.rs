//! A camera path between its vertices ([`Walk`]), the rules its vertices follow
//! ([`Rules`]), what a vertex leaves for its shadow ray ([`Pending`]) and what follows a
//! vertex ([`Next`]): the state [`super::vertex`] and [`super::in_medium`] step, on single
//! rays and in lanes ([`super::lanes`]).
//!
//! Units: radiance in the carrier's units (W·m⁻²·sr⁻¹ per wavelength, or linear RGB);
//! rays in world space, metres.

use super::light_sample::NextEvent;
use super::own_hero::HeroOf;
use super::split::Branches;
use super::state::PathState;
use crate::interaction::SurfaceHit;
use crate::math::Ray;
use crate::scene::Scene;
use crate::shading::media::{self, Through};
use crate::spectrum::Carrier;

/// How a render's camera paths run: the depth limit and what the method asks of them.
pub(super) struct Rules<'s, S> {
    /// Non-delta bounces per path.
    pub max_depth: u32,
    /// The method's decisions ([`Strategy`]).
    pub strategy: &'s S,
}

/// A camera path between two vertices: the radiance so far, the ray to trace next and
/// the state the bounce rules read.
pub(super) struct Walk<C: Carrier> {
    /// Radiance gathered so far.
    pub l: C,
    /// The ray to trace next.
    pub ray: Ray,
    /// The path's wavelengths (the hero only past a smooth dispersive interface).
    pub lambda: C::Lambda,
    /// Throughput, media, bounce counts.
    pub st: PathState<C>,
    /// The sub-paths of a path split into its wavelengths ([`super::split`]).
    pub(super) branches: Branches<C>,
    /// Whose hero orders the lanes of `l`, `lambda` and `st.beta` ([`super::own_hero`]).
    pub(super) hero: HeroOf,
}

impl<C: Carrier> Walk<C> {
    /// A path leaving the camera along `ray` at the wavelengths `lambda`.
    pub fn new(ray: Ray, lambda: C::Lambda) -> Self {
        Walk {
            l: C::ZERO,
            ray,
            lambda,
            st: PathState::new(ray.origin),
            branches: Branches::new(),
            hero: HeroOf::Sample,
        }
    }

    /// Ends the current (sub-)path and, if the path was split and a lane waits, sets the
    /// walk to that lane's sub-path and returns true ([`super::split`]).
    pub fn next_branch(&mut self) -> bool {
        let (l, ray, lambda) = (&mut self.l, &mut self.ray, &mut self.lambda);
        self.branches.next(l, ray, lambda, &mut self.st)
    }

    /// The sample's radiance (in the sample's lane order) once [`Self::next_branch`]
    /// returned false.
    pub fn radiance(&self) -> C {
        self.hero.to_sample(self.branches.radiance(self.l))
    }

    /// Adds light `e` found along the path unless it is another estimator's (`leaves`).
    #[inline]
    pub(super) fn add_unless(&mut self, e: Option<C>, leaves: bool) {
        if let (Some(e), false) = (e, leaves) {
            self.l += e;
        }
    }

    /// Passes through the uncovered part of a BLEND surface at `hit` along `next`.
    #[inline]
    pub(super) fn pass_through(
        &mut self,
        next: Ray,
        hit: SurfaceHit,
    ) -> (Option<Pending<C>>, Next) {
        self.ray = next;
        self.st.from = Some(hit);
        self.st.direct = false;
        (None, Next::Trace)
    }
}

/// What a vertex adds once its shadow ray is answered: `beta × value` (zero if blocked),
/// then the caustic map's gather.
pub(super) struct Pending<C: Carrier> {
    /// The shadow ray of next-event estimation (`None`: nothing to trace, `value` is zero).
    pub shadow: Option<Ray>,
    /// In a scene with media: where the shadow ray starts; it is then traced alone for its
    /// transmittance ([`Pending::resolve_traced`]), not in a packet.
    pub through: Option<Through>,
    beta: C,
    value: C,
    gather: Option<C>,
}

impl<C: Carrier> Pending<C> {
    /// Adds the vertex's light to `l`, `blocked` being the shadow ray's answer (a scene
    /// without media).
    #[inline]
    pub fn resolve(self, blocked: bool, l: &mut C) {
        let v = if blocked { C::ZERO } else { self.value };
        self.add(v, l);
    }

    /// Traces the shadow ray (through its media, [`media::shadow`]) and adds the vertex's
    /// light to `l`.
    pub fn resolve_traced(self, scene: &Scene, lambda: &C::Lambda, rays: &mut u64, l: &mut C) {
        let v = self.transmitted(scene, lambda, rays);
        self.add(v, l);
    }

    /// Traces the shadow ray (through its media, [`media::shadow`]): the light sample's
    /// value past it, per unit throughput (zero if blocked or without a shadow ray).
    pub fn transmitted(&self, scene: &Scene, lambda: &C::Lambda, rays: &mut u64) -> C {
        match (self.shadow, self.through) {
            (Some(r), Some(t)) => self.value * media::shadow::<C>(scene, &r, t, lambda, rays),
            (Some(r), None) if !scene.occluded(&r) => self.value,
            _ => C::ZERO,
        }
    }

    #[inline]
    fn add(&self, v: C, l: &mut C) {
        *l += self.beta * v;
        if let Some(g) = self.gather {
            *l += g;
        }
    }
}

/// What follows a vertex.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Next {
    /// Trace the walk's (new) ray.
    Trace,
    /// The path is over (perhaps at a visible point, [`Strategy::stops_at`]).
    End,
}

/// A light sample at throughput `beta`, with the gather to add after it.
pub(super) fn pending<C: Carrier>(beta: C, ls: NextEvent<C>, gather: Option<C>) -> Pending<C> {
    Pending {
        shadow: ls.shadow,
        through: ls.through,
        beta,
        value: ls.value,
        gather,
    }
}
