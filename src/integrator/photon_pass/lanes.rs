//! How a camera path's lanes meet a photon's at a gather ([`GatherLanes`]) and the photon
//! term f(wo, wiₚ) · Φₚ ([`photon_term`]) every photon gather reads: SPPM's visible points,
//! the hybrid's caustic and volume maps.
//!
//! Units: a photon's power Φₚ is flux per lane in the lights' units
//! ([`crate::photon::store`]), f the BSDF in sr⁻¹. Lanes: the photons carry the pass's
//! wavelengths in the pass's order; a camera path may carry them rotated, and the photon's
//! power is rotated into the path's order before the product.

use crate::bsdf::{Bsdf, TransportMode};
use crate::integrator::path::{HeroOf, VisiblePoint};
use crate::math::Frame;
use crate::photon::store::Photon;
use crate::spectrum::{rotate_lanes, Carrier};
use glam::Vec3;

/// How a camera path's lanes meet the photons' at a gather (the hero-wavelength
/// bookkeeping of [`photon_term`]), decided once per camera vertex.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::integrator) enum GatherLanes {
    /// The pass's lane order; `hero_only`: the camera path kept only the pass's hero.
    Pass { hero_only: bool },
    /// A sub-path of a split camera sample carrying the sample's lane i alone
    /// ([`Carrier::sub_path`]), its lanes rotated by i.
    SubPath(usize),
    /// An SPPM camera path with its own hero k (drawn at its first rough dispersive vertex,
    /// independently of the photons' hero: [`HeroOf::Own`]), its lanes rotated by k.
    OwnHero(usize),
}

impl GatherLanes {
    /// The lanes of a camera path at wavelengths `lambda` (in the pass's order unless a
    /// sub-path).
    pub fn of<C: Carrier>(lambda: &C::Lambda) -> Self {
        match C::sub_path(lambda) {
            Some(i) => GatherLanes::SubPath(i),
            None => GatherLanes::Pass {
                hero_only: C::is_hero_only(lambda),
            },
        }
    }

    /// The lanes of a visible point: its path's own hero if it drew one, else as
    /// [`Self::of`] its wavelengths.
    pub fn at<C: Carrier>(vp: &VisiblePoint<C>) -> Self {
        match vp.hero {
            HeroOf::Own(k) => GatherLanes::OwnHero(usize::from(k)),
            HeroOf::Sample => Self::of::<C>(&vp.lambda),
        }
    }

    /// The power of `ph` in the camera path's lane order, with the bookkeeping's factor
    /// ([`photon_term`]).
    pub(in crate::integrator) fn power<C: Carrier>(self, ph: &Photon) -> C {
        match self {
            GatherLanes::SubPath(k) | GatherLanes::OwnHero(k) => {
                C::from_lanes(rotate_lanes(ph.power(), k))
            }
            GatherLanes::Pass { hero_only } => {
                let c = C::from_lanes(ph.power());
                if hero_only && ph.flags() & Photon::HERO_ONLY != 0 {
                    c / 4.0
                } else {
                    c
                }
            }
        }
    }
}

/// f(wo, wiₚ) · Φₚ of the photon `ph` at a camera vertex (`bsdf` in `frame`, `wo` toward
/// the camera, its lanes `lanes`), with the hero-wavelength bookkeeping:
/// - when both the camera path and the photon kept only the pass's hero (each then carries
///   4× the hero lane, for the same uniformly chosen hero), the product is divided by 4
///   once;
/// - a sub-path of a split camera sample ([`GatherLanes::SubPath`],
///   [`crate::integrator::path`]'s split) carries the sample's lane i alone at weight 1,
///   its lanes rotated by i: the photon's lanes are rotated the same way, and nothing is
///   divided (the sub-path was traced with probability 1, so no selection is shared with
///   the photon's hero: E[β̂ᵢ · Φ̂ᵢ] = βᵢ Φᵢ for independent unbiased factors);
/// - a path with its own hero ([`GatherLanes::OwnHero`]) likewise: its lanes are rotated
///   by its hero k and its hero is independent of the photon's, so nothing is divided,
///   also when it later kept its own hero only (`crate::integrator::path`'s `own_hero`
///   gives the argument).
pub(in crate::integrator) fn photon_term<C: Carrier>(
    bsdf: &Bsdf<C>,
    frame: &Frame,
    wo: Vec3,
    lanes: GatherLanes,
    ph: &Photon,
) -> C {
    let wi = frame.to_local(ph.wi());
    bsdf.eval(wo, wi, TransportMode::Radiance) * lanes.power::<C>(ph)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{Lambdas, SampledSpectrum, SampledWavelengths};

    /// The gather's hero bookkeeping: ÷4 once when the camera path and the photon both kept
    /// the pass's hero; a split sample's sub-path i sees the photon's lanes rotated by i and
    /// is never divided; a path with its own hero k sees them rotated by k, never divided.
    #[test]
    fn photon_term_matches_lanes_and_hero_bookkeeping() {
        type S = SampledSpectrum;
        let albedo = S::new([1.0; 4]);
        let bsdf = Bsdf::Lambert { albedo };
        let frame = Frame::from_normal(Vec3::Z);
        let f = std::f32::consts::FRAC_1_PI;
        let power = [1.0, 2.0, 3.0, 4.0];
        let all = Photon::new(Vec3::ZERO, Vec3::Z, power, 0);
        let hero = Photon::new(Vec3::ZERO, Vec3::Z, power, Photon::HERO_ONLY);
        let whole = Lambdas::new(SampledWavelengths::sample_visible(0.3));
        let term = |lanes: GatherLanes, ph: &Photon| {
            photon_term::<S>(&bsdf, &frame, Vec3::Z, lanes, ph).values()
        };
        let of = |l: &Lambdas| GatherLanes::of::<S>(l);
        let close = |a: [f32; 4], b: [f32; 4]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6);
        assert!(close(term(of(&whole), &hero), power.map(|p| p * f)));
        let mut collapsed = whole;
        let _ = S::new([1.0; 4]).keep_hero(&mut collapsed);
        assert!(close(
            term(of(&collapsed), &hero),
            power.map(|p| p * f / 4.0)
        ));
        assert!(close(term(of(&collapsed), &all), power.map(|p| p * f)));
        for i in 0..4 {
            let sub = S::lane_as_hero(&collapsed, i);
            let want: [f32; 4] = std::array::from_fn(|j| power[(j + i) % 4] * f);
            assert!(close(term(of(&sub), &hero), want), "sub-path {i}");
            assert!(
                close(term(GatherLanes::OwnHero(i), &hero), want),
                "own hero {i}"
            );
        }
    }
}
