//! A lane whose path meets a material the kernel does not shade ([`Shade::Scalar`]:
//! layers, textures, films, anisotropy, rough or thin glass, …), or a vertex where
//! the method's strategy gathers another estimator, has that vertex shaded by the scalar
//! path tracer under the method's strategy ([`Vertex`], [`OnScalar`]: the path tracer's
//! or the hybrid's camera paths): its state becomes the scalar path's
//! ([`PathState`]) at the hit it just found, the scalar vertex runs once with the sample's
//! own numbers (read from the dimension the path's vertex count gives,
//! [`crate::sampler::schedule`]), its shadow ray traced at once, and the path comes back to
//! the kernel with the state the vertex left ([`Back::Goes`]); or it ends there
//! ([`Back::Ended`]). Where the kernel could not carry the state on — the sample split at
//! that vertex, the path inside two volumes at once, or seen through a cut-out — the
//! scalar path tracer follows it to its end ([`super::super::walk_on`]) and it ends.
//!
//! What carries over both ways ([`Handed`]): throughput and wavelengths (in spectral
//! transport), η scale, the non-delta and delta bounce counts (so the depth limit, the
//! delta cap and Russian roulette continue where they were), the vertex count, delta
//! bounces since the last non-delta one, the glass volume the lane is in (or air) and the
//! previous bounce's MIS record; the radiance gathered at the vertex goes back to the
//! lane's own. The hand-over happens before the kernel counts anything at the hit: the
//! scalar vertex takes the segment's absorption and the hit's emission.
//!
//! [`Shade::Scalar`]: super::features::Shade::Scalar

use super::super::own_hero::HeroOf;
use super::super::state::Prev;
use super::super::strategy::{History, Strategy};
use super::super::walk::{Next, Rules, Walk};
use super::super::{step, walk_on};
use crate::accel::RawHit;
use crate::math::Ray;
use crate::medium_stack::MediumStack;
use crate::render::Context;
use crate::scene::Scene;
use crate::shading::step::StepNumbers;
use crate::shading::{arrival, Event};
use crate::spectrum::Carrier;

/// What a lane's path carries into the scalar vertex, and back, besides its throughput
/// and wavelengths.
#[derive(Clone, Copy)]
pub struct Handed {
    /// Product of η'² over the refractions so far.
    pub eta_scale: f32,
    /// Non-delta bounces so far.
    pub depth: u32,
    /// Delta bounces so far.
    pub deltas: u32,
    /// Delta bounces since the last non-delta one (`None` before the first).
    pub since_diffuse: Option<u32>,
    /// The volumetric material the lane is inside (`None`: air).
    pub inside: Option<u32>,
    /// The previous bounce, for MIS of emission the path meets next.
    pub prev: Prev,
}

/// A path after its vertex on the scalar vertex.
pub enum Back<C: Carrier> {
    /// It ended (there, or followed to its end on the scalar path): the radiance gathered
    /// from the hit on, in the lane order of the wavelengths handed over.
    Ended(C),
    /// It goes on in the kernel.
    Goes {
        /// The radiance gathered at the vertex.
        l: C,
        /// Throughput and wavelengths after it.
        carried: (C, C::Lambda),
        /// The next ray.
        ray: Ray,
        /// The rest of the state.
        state: Handed,
    },
}

/// A lane's path at the hit the kernel hands to the scalar vertex.
pub struct Handing<C: Carrier> {
    /// Its state but throughput and wavelengths.
    pub handed: Handed,
    /// Its throughput and wavelengths (a split sample's sub-path keeps its own: it does
    /// not split again).
    pub carried: (C, C::Lambda),
    /// The ray that met the hit, and the hit.
    pub at: (Ray, RawHit),
}

impl<C: Carrier> Handing<C> {
    /// The lane's path with the state `handed`, throughput and wavelengths `carried`, at
    /// the hit `at`.
    pub fn new(handed: Handed, carried: (C, C::Lambda), at: (Ray, RawHit)) -> Self {
        Handing {
            handed,
            carried,
            at,
        }
    }
}

/// The scalar vertex under a method's strategy, as the kernel calls it for a lane (one
/// object per carrier `C`, so the kernel's loop is not instantiated per method).
pub trait Vertex<C: Carrier>: Sync {
    /// The vertex of `lane`'s path at its hit ([`vertex`]).
    fn vertex(&self, scene: &Scene, lane: Handing<C>, ctx: &mut Context) -> Back<C>;

    /// What the strategy gathers per unit throughput at a lane's Lambert or glossy vertex
    /// (one the kernel shades) at the hit of `at`, with the lane's wavelengths and the volume it is
    /// in (`None`: air), after the bounces `h` ([`Strategy::gather`]).
    fn gather(
        &self,
        scene: &Scene,
        at: (Ray, RawHit),
        lane: (C::Lambda, Option<u32>),
        h: &History,
    ) -> Option<C>;

    /// The bounce limit: non-delta bounces a path takes.
    fn max_depth(&self) -> u32;

    /// Whether a sample splits into its wavelengths at its first smooth dispersive glass
    /// ([`Strategy::splits`]).
    fn splits(&self) -> bool;

    /// Whether another estimator is gathered at non-delta vertices ([`Strategy::gathers`]):
    /// the kernel then asks [`Vertex::gather`] at its Lambert and glossy vertices (the scalar
    /// vertex gathers at those it hands over).
    fn gathers(&self) -> bool;

    /// Whether light a path finds after the bounces `h` is another estimator's
    /// ([`Strategy::leaves_light`]).
    fn leaves_light(&self, h: &History) -> bool;
}

/// The scalar vertex under `strategy` with the bounce limit `max_depth`: the path
/// tracer's ([`super::super::Dispersion`]) or a photon method's camera strategy.
pub struct OnScalar<S> {
    /// Non-delta bounces a path takes.
    pub max_depth: u32,
    /// What the method asks of its camera paths.
    pub strategy: S,
}

impl<C: Carrier, S: Strategy<C>> Vertex<C> for OnScalar<S> {
    fn vertex(&self, scene: &Scene, lane: Handing<C>, ctx: &mut Context) -> Back<C> {
        vertex(scene, (self.max_depth, &self.strategy), lane, ctx)
    }

    fn gather(
        &self,
        scene: &Scene,
        (ray, raw): (Ray, RawHit),
        (lambda, inside): (C::Lambda, Option<u32>),
        h: &History,
    ) -> Option<C> {
        let media = media(scene, inside);
        let at = arrival::<C>(
            scene,
            &ray,
            scene.lane_hit(&ray, Some(raw)),
            &media,
            &lambda,
        )?;
        let (mut beta, mut lam) = (C::ONE, lambda);
        match at.event(scene, media, &mut beta, &mut lam, &mut Drawn) {
            Event::Scatter(s) => self.strategy.gather(&s, &lambda, h),
            Event::PassThrough(_) => None,
        }
    }

    fn max_depth(&self) -> u32 {
        self.max_depth
    }

    fn splits(&self) -> bool {
        self.strategy.splits()
    }

    fn gathers(&self) -> bool {
        self.strategy.gathers()
    }

    fn leaves_light(&self, h: &History) -> bool {
        self.strategy.leaves_light(h)
    }
}

/// The vertex of `lane`'s path at its hit, on the scalar vertex under `strategy` with the
/// bounce limit `max_depth`, with `ctx`'s numbers (restarted for the lane's camera sample
/// by the caller; its ray count grows by the rays traced): what follows ([`Back`]).
fn vertex<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    (max_depth, strategy): (u32, &S),
    lane: Handing<C>,
    ctx: &mut Context,
) -> Back<C> {
    let Handing {
        handed,
        carried,
        at: (ray, raw),
    } = lane;
    let Some(hit) = scene.lane_hit(&ray, Some(raw)) else {
        return Back::Ended(C::ZERO);
    };
    let mut walk = Walk::<C>::new(ray, carried.1);
    let st = &mut walk.st;
    st.beta = carried.0;
    st.eta_scale = handed.eta_scale;
    st.depth = handed.depth;
    st.delta_depth = handed.deltas;
    st.vertex = handed.depth + handed.deltas;
    st.since_diffuse = handed.since_diffuse;
    st.direct = st.vertex == 0;
    st.prev = handed.prev;
    st.media = media(scene, handed.inside);
    st.meet = Some(hit);
    let rules = Rules {
        max_depth,
        strategy,
    };
    let next = step(scene, &rules, &mut walk, ctx, &mut None);
    if next == Next::Trace && returns(&walk) {
        let st = &walk.st;
        return Back::Goes {
            l: walk.l,
            carried: (st.beta, walk.lambda),
            ray: walk.ray,
            state: Handed {
                eta_scale: st.eta_scale,
                depth: st.depth,
                deltas: st.delta_depth,
                since_diffuse: st.since_diffuse,
                inside: st.media.iter().next(),
                prev: st.prev,
            },
        };
    }
    if next == Next::Trace || walk.next_branch() {
        walk_on(scene, &rules, &mut walk, ctx, &mut None);
    }
    Back::Ended(walk.radiance())
}

/// Whether the kernel can carry `walk` on after its vertex: the sample whole (not split
/// there), its lanes in the sample's order, at most one volume around it, its vertex
/// count the bounces' sum and seen directly only before the first vertex (no cut-out
/// passed through).
fn returns<C: Carrier>(walk: &Walk<C>) -> bool {
    let st = &walk.st;
    !walk.branches.is_split()
        && walk.hero == HeroOf::Sample
        && st.media.iter().nth(1).is_none()
        && st.vertex == st.depth + st.delta_depth
        && st.direct == (st.vertex == 0)
}

/// The media around a lane inside the volumetric material `inside` (`None`: air).
fn media(scene: &Scene, inside: Option<u32>) -> MediumStack {
    match inside {
        Some(m) => MediumStack::new().entered(m, scene.materials()[m as usize].desc.priority),
        None => MediumStack::new(),
    }
}

/// The step's numbers at a Lambert or glossy vertex the kernel shades, which reads none
/// that matters: it is not BLEND and has one layer ([`super::features::Shade`]), which
/// rough glass (transmission 1) takes whatever its layer number; the lane's own draws
/// passed over that number already ([`super::numbers`]).
struct Drawn;

impl StepNumbers for Drawn {
    fn alpha(&mut self) -> f32 {
        0.0
    }
    fn layer(&mut self) -> f32 {
        0.0
    }
    fn skip_layer(&mut self) {}
}
