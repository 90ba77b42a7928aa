//! SPPM's gather at a visible point: Σ f(wo, wiₚ) · Φₚ over the photons within r, with the
//! lanes bookkeeping of the photon pass ([`GatherLanes`], [`photon_term`]) and f per lane
//! at a rough dispersive interface reached with the lanes kept.
//!
//! Units: as [`photon_term`]; the caller divides the sum over the photons within r (world
//! units, metres) by π r².

use crate::bsdf::TransportMode;
use crate::integrator::path::VisiblePoint;
use crate::integrator::photon_pass::{photon_term, GatherLanes};
use crate::photon::grid::{in_disc, HashGrid};
use crate::photon::store::Photon;
use crate::shading::spectral_mis;
use crate::spectrum::Carrier;

/// Sum of f · Φ over the photons within `r` of a visible point and in its flattened disc
/// ([`crate::photon::grid::in_disc`]), in the visible point's lane order
/// ([`visible_term`]).
pub(super) fn gather<C: Carrier>(
    vp: &VisiblePoint<C>,
    photons: &[Photon],
    grid: &HashGrid,
    r: f32,
) -> C {
    let mut phi = C::ZERO;
    let lanes = GatherLanes::at(vp);
    grid.for_each_within(vp.p, r, |i, _d2| {
        let ph = &photons[i as usize];
        if in_disc(vp.p, vp.ng, ph.position(), r) {
            phi += visible_term(vp, lanes, ph);
        }
    });
    phi
}

/// [`photon_term`] at the visible point `vp` (lanes `lanes`, [`GatherLanes::at`]), with f
/// per lane, each with its own η, at a rough dispersive interface reached with the lanes
/// kept ([`VisiblePoint::etas`], [`spectral_mis::eval_lanes`]).
fn visible_term<C: Carrier>(vp: &VisiblePoint<C>, lanes: GatherLanes, ph: &Photon) -> C {
    let Some(etas) = &vp.etas else {
        return photon_term(&vp.bsdf, &vp.frame, vp.wo, lanes, ph);
    };
    let wi = vp.frame.to_local(ph.wi());
    let mode = TransportMode::Radiance;
    spectral_mis::eval_lanes(&vp.bsdf, etas, vp.wo, wi, mode).0 * lanes.power::<C>(ph)
}
