//! A lane whose path meets a material the kernel does not shade ([`Shade::Scalar`]:
//! layers, textures, specular or metal lobes, rough or thin glass, …) hands its path over
//! to the scalar path tracer ([`finish`]): its state becomes the scalar path's
//! ([`PathState`]) at the hit it just found, and [`super::super::walk_on`] follows it to
//! its end on single rays with the sample's own numbers, read from the dimension the
//! path's vertex count gives ([`crate::sampler::schedule`]).
//!
//! What carries over: the radiance so far (the caller keeps it and adds the rest),
//! throughput and wavelengths (in spectral transport), η scale, the non-delta and delta bounce counts (so the depth limit, the
//! delta cap and Russian roulette continue where they were), the vertex count, delta
//! bounces since the last non-delta one, the glass volume the lane is in (or air) and the
//! previous bounce's MIS record. The hand-over happens before the kernel counts anything
//! at the hit: the scalar vertex takes the segment's absorption and the hit's emission.
//!
//! [`Shade::Scalar`]: super::features::Shade::Scalar

use super::super::state::Prev;
use super::super::walk::{Rules, Walk};
use super::super::{walk_on, Dispersion};
use crate::accel::RawHit;
use crate::math::Ray;
use crate::medium_stack::MediumStack;
use crate::render::Context;
use crate::scene::Scene;
use crate::spectrum::Carrier;

/// What a lane's path carries into the scalar vertex besides its throughput and
/// wavelengths.
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

/// The rest of the path whose ray `ray` met `raw` with the state `handed`, throughput
/// `beta` and wavelengths `lambda` (a split sample's sub-path keeps its own: it does not
/// split again): the radiance it gathers from there on, in the lane order of `lambda`,
/// under the path tracer's `max_depth` and `dispersion`, with `ctx`'s numbers (restarted
/// for the lane's camera sample by the caller; its ray count grows by the rays traced).
pub fn finish<C: Carrier>(
    scene: &Scene,
    (max_depth, dispersion): (u32, &Dispersion),
    handed: &Handed,
    (beta, lambda): (C, C::Lambda),
    (ray, raw): (Ray, RawHit),
    ctx: &mut Context,
) -> C {
    let Some(hit) = scene.lane_hit(&ray, Some(raw)) else {
        return C::ZERO;
    };
    let mut walk = Walk::<C>::new(ray, lambda);
    let st = &mut walk.st;
    st.beta = beta;
    st.eta_scale = handed.eta_scale;
    st.depth = handed.depth;
    st.delta_depth = handed.deltas;
    st.vertex = handed.depth + handed.deltas;
    st.since_diffuse = handed.since_diffuse;
    st.direct = st.vertex == 0;
    st.prev = handed.prev;
    if let Some(m) = handed.inside {
        let priority = scene.materials()[m as usize].desc.priority;
        st.media = MediumStack::new().entered(m, priority);
    }
    st.meet = Some(hit);
    let rules = Rules {
        max_depth,
        strategy: dispersion,
    };
    walk_on(scene, &rules, &mut walk, ctx, &mut None);
    walk.radiance()
}
