//! A lane whose path meets a material the kernel does not shade ([`Shade::Scalar`]:
//! layers, textures, specular or metal lobes, rough or thin glass, …) hands its path over
//! to the scalar path tracer ([`finish`]): its state becomes the scalar path's
//! ([`PathState`]) at the hit it just found, and [`super::super::walk_on`] follows it to
//! its end on single rays with the sample's own numbers, read from the dimension the
//! path's vertex count gives ([`crate::sampler::schedule`]).
//!
//! What carries over: the radiance so far (the caller keeps it and adds the rest),
//! throughput, η scale, the non-delta and delta bounce counts (so the depth limit, the
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
use glam::Vec3;

/// What a lane's path carries into the scalar vertex.
pub struct Handed {
    /// Throughput.
    pub beta: Vec3,
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

/// The rest of the path whose ray `ray` met `raw` with the state `handed`: the radiance
/// it gathers from there on, under the path tracer's `max_depth` and `dispersion`, with
/// `ctx`'s numbers (restarted for the lane's camera sample by the caller; its ray count
/// grows by the rays traced).
pub fn finish(
    scene: &Scene,
    (max_depth, dispersion): (u32, &Dispersion),
    handed: &Handed,
    (ray, raw): (Ray, RawHit),
    ctx: &mut Context,
) -> Vec3 {
    let Some(hit) = scene.lane_hit(&ray, Some(raw)) else {
        return Vec3::ZERO;
    };
    let mut walk = Walk::<Vec3>::new(ray, ());
    let st = &mut walk.st;
    st.beta = handed.beta;
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
