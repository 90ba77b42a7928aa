//! One vertex of a camera path ([`vertex`]), written once for the scalar loop
//! ([`super::trace`]) and the lanes ([`super::lanes`]), in the order light meets it: the
//! medium before the hit ([`super::in_medium`]), the light arriving (emission with MIS, the
//! environment on escape), the surface's event, next-event estimation, the BSDF sample and
//! the bounce rules. What differs between methods (where a path stops, what another
//! estimator gathers or owns of its light, which hero orders its lanes, whether it splits
//! into its wavelengths) is asked of the caller's [`Strategy`]. The shadow ray of
//! next-event estimation is not traced here: the vertex returns it as [`Pending`] ([`super::walk`]), so the
//! lanes can trace all their shadow rays as one packet; [`Pending::resolve`] then adds to
//! the radiance exactly what the scalar loop adds, in the same order.
//!
//! Units: radiance in the carrier's units (linear RGB or per-wavelength spectral
//! radiance); frames as in [`crate::shading::step`].

use super::light_sample::{mis, next_event, Scatterer};
use super::own_hero;
use super::state::Prev;
use super::strategy::{History, RoughLanes, Strategy};
use super::walk::{pending, Next, Pending, Rules, Walk};
use super::VisiblePoint;
use crate::bsdf::TransportMode;
use crate::interaction::SurfaceHit;
use crate::math::Ray;
use crate::render::Context;
use crate::sampler::Bounce;
use crate::scene::Scene;
use crate::shading::{lights, Arrival, Event, Surface};
use crate::spectrum::Carrier;
use glam::Vec3;

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

/// The vertex of `walk` at `arrival` (its ray's hit; `None` if it escaped), in the order
/// light meets it: the medium before the hit, the light arriving (the environment on
/// escape, emission with MIS on arrival, before BLEND coverage is decided), the surface's
/// event ([`crate::shading::arrive`], [`Arrival::event`]), next-event estimation and the
/// strategy's gather, then the BSDF sample and the bounce rules. Adds what arrives to
/// `walk.l`, sets `walk.ray` to the next ray, and returns the next-event estimate waiting
/// for its shadow ray and what follows; a path the strategy stops
/// ([`Strategy::stops_at`]) writes its visible point to `visible` and ends.
#[inline(always)]
pub(super) fn vertex<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    rules: &Rules<'_, S>,
    walk: &mut Walk<C>,
    arrival: Option<Arrival<'_, C>>,
    ctx: &mut Context,
    visible: &mut Option<VisiblePoint<C>>,
) -> (Option<Pending<C>>, Next) {
    // A sub-path redoing its split vertex: what arrived there is counted.
    let resume = std::mem::take(&mut walk.branches.resume);
    let h = walk.st.history(rules.max_depth);
    let leaves = resume || rules.strategy.leaves_light(&h);
    let met = walk.st.meet.take();
    if scene.has_media() && !resume {
        let at = (arrival.as_ref(), met.is_some());
        if let Some(scattered) = super::in_medium::fly(scene, rules, walk, at, ctx) {
            return scattered;
        }
    }
    let Some(at) = &arrival else {
        let e = escaped(scene, &walk.ray, &walk.st.prev, walk.st.beta, &walk.lambda);
        walk.add_unless(e, leaves);
        return (None, Next::End);
    };
    if !resume {
        walk.st.beta *= at.transmittance;
    }
    let e = emitted(scene, at, &walk.st.prev, walk.st.beta, &walk.lambda);
    walk.add_unless(e, leaves);
    if scene.has_media() && super::in_medium::cross(scene, walk, at) {
        return (None, Next::Trace);
    }
    let mut u = ctx.sample.bounce(walk.st.vertex);
    let rough = rules.strategy.rough();
    let ev = event(scene, rules, walk, (at, met), rough, &mut u);
    // By reference: the surface stays where `event` built it.
    let s = match &ev {
        Event::PassThrough(next) => return walk.pass_through(*next, at.hit),
        Event::Scatter(s) => s,
    };
    if rules.strategy.stops_at(s) {
        return stop(scene, walk, s, (&mut u, &mut ctx.rays), visible);
    }
    let own = (rough == RoughLanes::OwnHero)
        .then(|| {
            let values = [&mut walk.st.beta, &mut walk.l];
            own_hero::draw(s, &mut walk.hero, &mut walk.lambda, values, &mut u)
        })
        .flatten();
    let s = own.as_ref().unwrap_or(s);
    let (strategy, rays) = (rules.strategy, &mut ctx.rays);
    let nee = (!s.bsdf.is_delta()).then(|| light(scene, strategy, walk, (s, &h), &mut u, rays));
    (nee, bounce(rules.max_depth, walk, s, &mut u))
}

/// The surface's event at `at` (reached along the walk's ray, untraced if `met`) for a path
/// keeping `rough` at rough dispersive interfaces; where the event kept the hero only at a
/// smooth dispersive interface and the strategy splits, the path splits into its
/// wavelengths instead ([`super::split`]).
#[inline(always)]
fn event<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    rules: &Rules<'_, S>,
    walk: &mut Walk<C>,
    (at, met): (&Arrival<'_, C>, Option<SurfaceHit>),
    rough: RoughLanes,
    u: &mut Bounce<'_>,
) -> Event<C> {
    let st = &mut walk.st;
    let splits = C::SPECTRAL && rules.strategy.splits();
    let before = (splits && !C::is_hero_only(&walk.lambda)).then_some(st.beta);
    let ev = if rough != RoughLanes::Hero {
        at.event_lanes(scene, st.media, &mut st.beta, &mut walk.lambda, u)
    } else {
        at.event(scene, st.media, &mut st.beta, &mut walk.lambda, u)
    };
    if let (Some(beta), Event::Scatter(s)) = (before, &ev) {
        if C::is_hero_only(&walk.lambda) && s.bsdf.is_delta() {
            let split = (beta, &mut walk.lambda);
            walk.branches.split(&mut walk.l, st, (walk.ray, met), split);
        }
    }
    ev
}

/// The path ends at the visible point `s`: its direct light is estimated with full weight
/// (BSDF sampling does not continue) and the point is written to `visible`.
fn stop<C: Carrier>(
    scene: &Scene,
    walk: &Walk<C>,
    s: &Surface<C>,
    (u, rays): (&mut Bounce<'_>, &mut u64),
    visible: &mut Option<VisiblePoint<C>>,
) -> (Option<Pending<C>>, Next) {
    let (st, lambda) = (&walk.st, &walk.lambda);
    let ls = next_event(scene, &Scatterer::Surface(s), lambda, false, u, rays);
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
    (Some(pending(st.beta, ls, None)), Next::End)
}

/// Next-event estimation at the non-delta vertex `s` reached after the bounces `h`, with
/// the strategy's gather there to add after it.
#[inline(always)]
fn light<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    strategy: &S,
    walk: &Walk<C>,
    (s, h): (&Surface<C>, &History),
    u: &mut Bounce<'_>,
    rays: &mut u64,
) -> Pending<C> {
    let (st, lambda) = (&walk.st, &walk.lambda);
    let ls = next_event(scene, &Scatterer::Surface(s), lambda, true, u, rays);
    let gather = strategy.gather(s, lambda, h).map(|g| st.beta * g);
    pending(st.beta, ls, gather)
}

/// Samples the BSDF at `s` and follows the sample: the walk's next ray, or the end of the
/// path (no sample, the bounce limits, Russian roulette).
#[inline(always)]
fn bounce<C: Carrier>(
    max_depth: u32,
    walk: &mut Walk<C>,
    s: &Surface<C>,
    u: &mut Bounce<'_>,
) -> Next {
    let st = &mut walk.st;
    let uc = u.bsdf_lobe();
    let ud = u.bsdf_direction_if(s.bsdf.samples_direction());
    let Some(bs) = s.sample_mis(uc, ud, TransportMode::Radiance, &mut walk.lambda) else {
        return Next::End;
    };
    if !st.advance(s, &bs, max_depth, u) {
        return Next::End;
    }
    walk.ray = s.spawn(bs.wi);
    st.from = Some(s.hit);
    st.vertex += 1;
    st.direct = false;
    Next::Trace
}
