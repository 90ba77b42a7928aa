//! A camera path's vertex in a scattering medium ([`scatter`]): next-event estimation
//! through the phase function (MIS against phase sampling, power heuristic, as at
//! surfaces), then a direction sampled exactly from the phase function, so the throughput
//! keeps the free-flight weight σ_s e^(−σ_t t) / p_mix it got from
//! [`crate::shading::media::fly`] (pbrt-v4 `VolPathIntegrator`, §14.2).
//!
//! The vertex takes the bounce's scheduled dimensions like a surface vertex (light choice,
//! member and position; the phase direction in the BSDF-direction slot; roulette); its
//! bounce limits and the walk's coarse scale are [`super::state`]'s. A vertex in a
//! surface's offset band leaves it as the band says ([`crate::interaction::BandPoint`]:
//! its rays from the surface's offset origin, or meeting the surface untraced), its shadow
//! ray too ([`media::shadow_from`]). Directions are unit vectors in world space.

use super::light_sample::{next_event, Scatterer};
use super::strategy::Strategy;
use super::walk::{pending, Next, Pending, Rules, Walk};
use crate::interaction::{Leave, SurfaceHit};
use crate::math::Ray;
use crate::render::Context;
use crate::scene::Scene;
use crate::shading::media::{self, Ends, Scattered};
use crate::shading::Arrival;
use crate::spectrum::Carrier;

/// Before the surface `at` its ray reached (`None` if it escaped; `met`: reached untraced,
/// [`super::state::PathState::meet`]): the media checked where the ray leaves a point of a
/// medium ([`media::starting`]), the volume caustic map's beam estimate along the segment
/// ([`super::Strategy::beam`], in a chromatic medium after keeping the hero only),
/// then free flight ([`media::fly`]); `Some` with the vertex's outcome if the path scatters
/// in the medium, else the path has met the surface (a new run).
pub(super) fn fly<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    rules: &Rules<'_, S>,
    walk: &mut Walk<C>,
    (at, met): (Option<&Arrival<'_, C>>, bool),
    ctx: &mut Context,
) -> Option<(Option<Pending<C>>, Next)> {
    let st = &mut walk.st;
    let t_hit = at.map_or(f32::INFINITY, |a| a.hit.t);
    if st.run > 0 && st.from.is_none() && !met {
        st.media = media::starting(scene, st.media, at.map(|a| (&a.hit, &a.coincident)));
    }
    if let Some(beam) = rules.strategy.beam() {
        let values = (&mut st.beta, &mut walk.lambda);
        media::keep_hero_in(scene, &walk.ray, t_hit, &st.media, values);
        if let Some(seg) = media::segment(scene, &walk.ray, t_hit, &st.media) {
            walk.l += st.beta * beam(&walk.ray, &seg, &walk.lambda);
        }
    }
    let scale = st.scale();
    let values = (&mut st.beta, &mut walk.lambda);
    let ends = Ends {
        from: st.from.as_ref(),
        meets: at.map(|a| &a.hit),
    };
    let mut u = ctx.sample.bounce(st.vertex);
    let flight = (&walk.ray, ends);
    let Some(sc) = media::fly(scene, flight, &st.media, scale, values, u.rng()) else {
        st.met_surface();
        return None;
    };
    Some(scatter(scene, rules.max_depth, walk, sc, ctx))
}

/// At the surface `at`: if it only changes the medium ([`media::cross_matched`]), the walk
/// crosses it without a bounce (MIS state kept) and `true` is returned.
pub(super) fn cross<C: Carrier>(scene: &Scene, walk: &mut Walk<C>, at: &Arrival<'_, C>) -> bool {
    let st = &mut walk.st;
    let crossed = media::cross_matched::<C>(scene, &at.hit, &at.coincident, st.media, &walk.lambda);
    match crossed {
        Some(after) => {
            walk.ray = at.hit.spawn_ray(-at.hit.wo);
            st.from = Some(at.hit);
            st.media = after;
            true
        }
        None => false,
    }
}

/// The vertex of `walk` at the scattering event `sc` on its ray: adds the light sample's
/// pending contribution and sets the walk's next ray (module docs).
fn scatter<C: Carrier>(
    scene: &Scene,
    max_depth: u32,
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
    let mut ls = next_event(scene, &at, &walk.lambda, true, &mut u, &mut ctx.rays);
    if let (Some(shadow), Some(through)) = (ls.shadow, ls.through) {
        let through = media::Through {
            scale: st.event_scale(),
            from_point: true,
            ..through
        };
        let (r, through, band) = media::shadow_from::<C>(scene, &sc, shadow, through, &walk.lambda);
        (ls.shadow, ls.through, ls.value) = (Some(r), Some(through), ls.value * band);
    }
    let nee = pending(st.beta, ls, None);
    if st.beta == C::ZERO {
        return (Some(nee), Next::End);
    }
    let (wi, pdf) = sc.phase.sample(wo, u.bsdf_direction());
    if pdf.is_nan() || pdf <= 0.0 || !st.advance_in_medium(sc.p, pdf, max_depth, &mut u) {
        return (Some(nee), Next::End);
    }
    match sc.leave(wi) {
        Leave::Ray(r) => {
            walk.ray = r;
            st.from = sc.band.map(|b| *b.surface());
        }
        Leave::Meets { hit, distance } => {
            walk.ray = Ray {
                t_max: distance,
                ..Ray::new(sc.p, wi)
            };
            (st.from, st.meet) = (None, Some(hit));
        }
    }
    st.vertex += 1;
    st.direct = false;
    (Some(nee), Next::Trace)
}
