//! One vertex of a camera path ([`vertex`]), written once for the scalar loop
//! ([`super::trace`]) and the lanes ([`super::lanes`]): what arrived along the path's ray
//! (emission with MIS, the environment on escape), next-event estimation, the caustic
//! map's gather, the BSDF sample and the bounce rules. The shadow ray of next-event
//! estimation is not traced here: the vertex returns it as [`Pending`], so the lanes can
//! trace all their shadow rays as one packet; [`Pending::resolve`] then adds to the
//! radiance exactly what the scalar loop adds, in the same order.
//!
//! Units: radiance in the carrier's units (linear RGB or per-wavelength spectral
//! radiance); frames as in [`crate::shading::step`].

use super::light_sample::{next_event, NextEvent, Scatterer};
use super::own_hero::{self, HeroOf};
use super::split::Branches;
use super::state::{PathState, Prev};
use super::{CausticSplit, Gather, StopAt, VisiblePoint};
use crate::bsdf::TransportMode;
use crate::math::Ray;
use crate::render::Context;
use crate::scene::Scene;
use crate::shading::media::Through;
use crate::shading::{lights, media, Arrival, Event};
use crate::spectrum::Carrier;
use glam::Vec3;

/// Power heuristic with β = 2.
pub(super) fn mis(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 {
        a2 / (a2 + b2)
    } else {
        0.0
    }
}

/// How a render's camera paths run: the depth limit, where they stop, how they share
/// transport with a caustic map, and spectral MIS at rough dispersive interfaces.
#[derive(Clone, Copy)]
pub(super) struct Rules<'a, C: Carrier> {
    /// Non-delta bounces per path.
    pub max_depth: u32,
    /// Where a path ends ([`StopAt`]).
    pub stop: StopAt,
    /// The share of a caustic map ([`CausticSplit`]).
    pub split: CausticSplit<'a, C>,
    /// What the path keeps at rough dispersive interfaces ([`RoughLanes`]).
    pub rough: RoughLanes,
    /// Split the path into its wavelengths at its first smooth dispersive interface
    /// ([`super::split`]).
    pub wavelength_split: bool,
}

impl<'a, C: Carrier> Rules<'a, C> {
    /// The rules for `max_depth`, `stop` and `split`, keeping wavelengths as `dispersion`
    /// says where it applies: spectral MIS without a caustic map (whose gather pairs the
    /// path's hero with its photons'), with the path's own hero when it stops at a visible
    /// point ([`RoughLanes::OwnHero`]); the split only with [`StopAt::Never`]
    /// ([`super::split::applies`]).
    pub fn new(
        max_depth: u32,
        dispersion: super::Dispersion,
        stop: StopAt,
        split: CausticSplit<'a, C>,
    ) -> Self {
        Rules {
            max_depth,
            stop,
            split,
            rough: match (dispersion.spectral_mis, stop, &split) {
                (false, _, _)
                | (
                    _,
                    _,
                    CausticSplit::Map(_) | CausticSplit::Mixed { .. } | CausticSplit::Volume { .. },
                ) => RoughLanes::Hero,
                (true, StopAt::Never, CausticSplit::None) => RoughLanes::Mis,
                (true, StopAt::Diffuse, CausticSplit::None) => RoughLanes::OwnHero,
            },
            wavelength_split: super::split::applies::<C>(dispersion.split, stop),
        }
    }
}

/// What a camera path keeps at a rough dispersive interface in spectral transport.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum RoughLanes {
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
    branches: Branches<C>,
    /// Whose hero orders the lanes of `l`, `lambda` and `st.beta` ([`super::own_hero`]).
    hero: HeroOf,
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
        let v = match (self.shadow, self.through) {
            (Some(r), Some(t)) => self.value * media::shadow::<C>(scene, &r, t, lambda, rays),
            (Some(r), None) if !scene.occluded(&r) => self.value,
            _ => C::ZERO,
        };
        self.add(v, l);
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
    /// The path is over (with [`StopAt::Diffuse`], perhaps at a visible point).
    End,
}

/// The environment seen along an escaped ray, times `beta`, MIS-weighted against the light
/// sampling of the previous bounce (the light sampler's probability of the environment);
/// `None` without an environment.
pub(super) fn escaped<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    prev: &Prev,
    beta: C,
    lambda: &C::Lambda,
) -> Option<C> {
    let env = scene.environment()?;
    let d = ray.dir.normalize();
    let w = if prev.delta {
        1.0
    } else {
        mis(prev.pdf, lights::environment_pdf(scene, d))
    };
    Some(beta * C::illuminant(env.eval(d), lambda) * w)
}

/// Emission of the surface arrived at (its emitting side only), times `beta`, MIS-weighted
/// like [`escaped`] with the probability of the emissive group; `None` if it does not emit
/// toward the path.
pub(super) fn emitted<C: Carrier>(
    scene: &Scene,
    at: &Arrival<'_, C>,
    prev: &Prev,
    beta: C,
    lambda: &C::Lambda,
) -> Option<C> {
    let (hit, mat) = (&at.hit, at.mat);
    if at.sp.emissive == Vec3::ZERO || !(hit.front_face || mat.desc.double_sided) {
        return None;
    }
    let w = if prev.delta {
        1.0
    } else {
        mis(prev.pdf, lights::area_pdf(scene, hit.prim, prev.p, hit.p))
    };
    Some(beta * C::emitted(at.sp.emissive, mat.emitter_shape(), lambda) * w)
}

/// The caustic map's gather at a path's first non-delta vertex under `split`: the whole
/// map, or with [`CausticSplit::Mixed`] the part for a vertex seen `direct`ly or through
/// delta bounces.
fn split_gather<'a, C: Carrier>(split: CausticSplit<'a, C>, direct: bool) -> Option<Gather<'a, C>> {
    match split {
        CausticSplit::None => None,
        CausticSplit::Map(g) | CausticSplit::Volume { surface: g, .. } => Some(g),
        CausticSplit::Mixed { through, direct: d } => {
            if direct {
                d
            } else {
                Some(through)
            }
        }
    }
}

/// The vertex of `walk` at `arrival` (its ray's hit; `None` if the ray escaped): adds what
/// arrives there to `walk.l`, samples the next direction into `walk.ray`, and returns the
/// next-event estimate waiting for its shadow ray, and what follows; a path that stops at
/// its first diffuse-like vertex ([`StopAt::Diffuse`]) writes it to `visible` and ends. Each hit is the shared
/// step ([`crate::shading::arrive`], [`Arrival::event`]); emission is counted on arrival,
/// before BLEND coverage is decided; `rules.split` hands the caustic paths to a caustic
/// map ([`CausticSplit`]).
#[inline(always)]
pub(super) fn vertex<C: Carrier>(
    scene: &Scene,
    rules: &Rules<'_, C>,
    walk: &mut Walk<C>,
    arrival: Option<Arrival<'_, C>>,
    ctx: &mut Context,
    visible: &mut Option<VisiblePoint<C>>,
) -> (Option<Pending<C>>, Next) {
    // A sub-path redoing its split vertex: what arrived there is counted.
    let resume = std::mem::take(&mut walk.branches.resume);
    let caustic = walk.st.closes_caustic(&rules.split) || resume;
    let met = walk.st.meet.take();
    if scene.has_media() && !resume {
        let at = (arrival.as_ref(), met.is_some());
        if let Some(scattered) = super::in_medium::fly(scene, rules, walk, at, ctx) {
            return scattered;
        }
    }
    let st = &mut walk.st;
    let Some(at) = &arrival else {
        let e = escaped(scene, &walk.ray, &st.prev, st.beta, &walk.lambda);
        if let (Some(e), false) = (e, caustic) {
            walk.l += e;
        }
        return (None, Next::End);
    };
    if !resume {
        st.beta *= at.transmittance;
    }
    if let (Some(e), false) = (emitted(scene, at, &st.prev, st.beta, &walk.lambda), caustic) {
        walk.l += e;
    }
    if scene.has_media() && super::in_medium::cross(scene, walk, at) {
        return (None, Next::Trace);
    }
    let st = &mut walk.st;
    let mut u = ctx.sample.bounce(st.vertex);
    let before = (rules.wavelength_split && !C::is_hero_only(&walk.lambda)).then_some(st.beta);
    let ev = if rules.rough != RoughLanes::Hero {
        at.event_lanes(scene, st.media, &mut st.beta, &mut walk.lambda, &mut u)
    } else {
        at.event(scene, st.media, &mut st.beta, &mut walk.lambda, &mut u)
    };
    // By reference: the surface stays where `event` built it.
    let s = match &ev {
        Event::PassThrough(next) => {
            walk.ray = *next;
            st.from = Some(at.hit);
            st.direct = false;
            return (None, Next::Trace);
        }
        Event::Scatter(s) => s,
    };
    // The event kept the hero only at a smooth dispersive interface: split instead.
    if let (Some(beta), true) = (before, C::is_hero_only(&walk.lambda) && s.bsdf.is_delta()) {
        let split = (beta, &mut walk.lambda);
        walk.branches.split(&mut walk.l, st, (walk.ray, met), split);
    }
    let lambda = &walk.lambda;
    if rules.stop == StopAt::Diffuse && s.bsdf.is_diffuse_like() {
        let ls = next_event(
            scene,
            &Scatterer::Surface(s),
            lambda,
            false,
            &mut u,
            &mut ctx.rays,
        );
        *visible = Some(VisiblePoint {
            p: s.hit.p,
            ng: s.hit.ng,
            frame: s.frame,
            wo: s.wo,
            bsdf: s.bsdf,
            beta: st.beta,
            lambda: *lambda,
            hit: s.hit,
            etas: s.lane_etas(),
            hero: walk.hero,
        });
        return (Some(pending(st.beta, ls, None)), Next::End);
    }
    let own = (rules.rough == RoughLanes::OwnHero)
        .then(|| {
            let values = [&mut st.beta, &mut walk.l];
            own_hero::draw(s, &mut walk.hero, &mut walk.lambda, values, &mut u)
        })
        .flatten();
    let s = own.as_ref().unwrap_or(s);
    let lambda = &walk.lambda;
    let mut nee = None;
    if !s.bsdf.is_delta() {
        let ls = next_event(
            scene,
            &Scatterer::Surface(s),
            lambda,
            true,
            &mut u,
            &mut ctx.rays,
        );
        let first = st.since_diffuse.is_none();
        let gather = split_gather(rules.split, st.direct)
            .filter(|_| first && st.depth + 1 < rules.max_depth)
            .map(|gather| st.beta * gather(s, lambda));
        nee = Some(pending(st.beta, ls, gather));
    }
    let uc = u.bsdf_lobe();
    let ud = u.bsdf_direction_if(s.bsdf.samples_direction());
    let Some(bs) = s.sample_mis(uc, ud, TransportMode::Radiance, &mut walk.lambda) else {
        return (nee, Next::End);
    };
    if !st.advance(s, &bs, rules.max_depth, &mut u) {
        return (nee, Next::End);
    }
    walk.ray = s.spawn(bs.wi);
    st.from = Some(s.hit);
    st.vertex += 1;
    st.direct = false;
    (nee, Next::Trace)
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
