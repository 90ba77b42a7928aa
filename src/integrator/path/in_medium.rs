//! A camera path's vertex in a scattering medium ([`scatter`]): next-event estimation
//! through the phase function (MIS against phase sampling, power heuristic, as at
//! surfaces), then a direction sampled exactly from the phase function, so the throughput
//! keeps the free-flight weight σ_s e^(−σ_t t) / p_mix it got from
//! [`crate::shading::media::fly`] (pbrt-v4 `VolPathIntegrator`, §14.2).
//!
//! The vertex takes the bounce's scheduled dimensions like a surface vertex (light choice,
//! member and position; the phase direction in the BSDF-direction slot; roulette) and
//! counts against `max_depth` like a non-delta bounce. Directions are unit vectors in world
//! space.

use super::vertex::{next_event, pending, Next, Pending, Rules, Scatterer, Walk};
use crate::interaction::SurfaceHit;
use crate::math::Ray;
use crate::render::Context;
use crate::scene::Scene;
use crate::shading::media::Scattered;
use crate::spectrum::Carrier;

/// The vertex of `walk` at the scattering event `sc` on its ray: adds the light sample's
/// pending contribution and sets the walk's next ray (module docs).
pub(super) fn scatter<C: Carrier>(
    scene: &Scene,
    rules: &Rules<'_, C>,
    walk: &mut Walk<C>,
    sc: Scattered,
    ctx: &mut Context,
) -> (Option<Pending<C>>, Next) {
    let st = &mut walk.st;
    let wo = -walk.ray.dir.normalize();
    let at = Scatterer::Medium {
        hit: SurfaceHit::in_medium(sc.p, wo),
        phase: sc.phase,
        media: st.media,
    };
    let mut u = ctx.sample.bounce(st.vertex);
    let ls = next_event(scene, &at, &walk.lambda, true, &mut u, &mut ctx.rays);
    let nee = pending(st.beta, ls, None);
    if st.beta == C::ZERO {
        return (Some(nee), Next::End);
    }
    let (wi, pdf) = sc.phase.sample(wo, u.bsdf_direction());
    if pdf.is_nan() || pdf <= 0.0 || !st.advance_in_medium(sc.p, pdf, rules.max_depth, &mut u) {
        return (Some(nee), Next::End);
    }
    walk.ray = Ray::new(sc.p, wi);
    st.vertex += 1;
    st.direct = false;
    (Some(nee), Next::Trace)
}
