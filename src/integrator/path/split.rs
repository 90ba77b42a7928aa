//! Splitting a camera path into its wavelengths at its first smooth dispersive interface.
//!
//! In spectral transport a camera sample carries 4 wavelengths (lane 0 the hero,
//! [`crate::spectrum::Lambdas`]). At a smooth dispersive interface each wavelength has its
//! own refracted direction, a delta distribution, so one direction cannot serve the 4
//! lanes. (At a rough one the path tracer keeps the 4 lanes with spectral MIS,
//! [`crate::shading::spectral_mis`]; without spectral MIS it keeps the hero only there, as
//! before: splitting is for the smooth case.) Collapsing keeps the hero alone ([`Carrier::keep_hero`], pbrt-v4
//! `SampledWavelengths::TerminateSecondary`; Wilkie et al. 2014, "Hero Wavelength Spectral
//! Sampling", §5): an unbiased estimator, but past that vertex every sample carries one
//! wavelength, so a colourless stone shows colour noise. Splitting continues each lane
//! instead, as its own sub-path at its own wavelength: sub-path `i` restarts the vertex
//! with the lanes rotated so that λᵢ is its hero ([`Carrier::lane_as_hero`]), so its
//! BSDF uses ηᵢ, samples its own reflect/refract choice and direction, and does its own
//! next-event estimation there.
//!
//! Unbiasedness. The film's estimate of a colour channel is
//! (1/4)·Σᵢ c̄(λᵢ)·Lᵢ/p(λᵢ) ([`crate::spectrum::SampledSpectrum::to_xyz`]), so it suffices
//! that each lane's value Lᵢ be an unbiased estimate of the radiance at λᵢ given λᵢ. Up to
//! the split vertex x, lane i holds Lᵢ⁽⁰⁾ (what was gathered) and βᵢ (the throughput), both
//! unbiased for λᵢ (with spectral MIS at earlier rough vertices βᵢ is lane i's one-sample
//! MIS weight, unbiased per lane, Wilkie et al. §4). Sub-path i estimates the radiance
//! leaving x toward the camera at λᵢ, Lᵢ(x), with the ordinary single-wavelength path
//! tracer, unbiased given x and λᵢ; it is traced with probability 1, so
//! E[Lᵢ⁽⁰⁾ + βᵢ·L̂ᵢ(x)] = E[Lᵢ⁽⁰⁾ + βᵢ·Lᵢ(x)]: the lane's full path integral. No factor
//! is needed — the 4 of the collapse (1/w₀ with spectral MIS) compensates for the 3 lanes
//! it drops, and here none is dropped. (pbrt-v4 collapses instead and documents that
//! splitting is the alternative; Wilkie et al. §5 discuss both: the split costs up to
//! 4 sub-paths after the split vertex, the collapse's colour noise is what it removes.)
//! The sub-paths reuse the sample's numbers for their vertices (common random numbers:
//! every lane is still sampled exactly as a single-wavelength path, so each is unbiased;
//! the lanes' errors are correlated, which keeps the colour noise low where the lanes'
//! paths nearly agree). Later dispersive vertices of a sub-path find it hero-only and
//! need nothing more.
//!
//! Order and determinism: the sub-path of lane 0 continues at once; lanes 1, 2, 3 wait in
//! a fixed-size queue ([`Branches`], no allocation) and are traced one after the other,
//! each re-tracing the ray that reached the split vertex (the same hit) and redoing that
//! vertex from its BSDF on ([`Branches::resume`]: what arrived there was counted before
//! the split). A lane whose throughput is 0 is not traced. The scalar loop and the lanes
//! run the same sequence per sample, so their estimates agree bit for bit.
//!
//! Where: camera paths whose strategy splits ([`super::Strategy::splits`]: the path
//! tracer's and the hybrid's, when [`super::Dispersion::split`] is on, the default; off
//! for comparisons). The hybrid's sub-paths gather its caustic map in their own lane
//! order with the photons' lanes rotated to match, and without the collapse's ÷4
//! (`crate::integrator::photon_pass::photon_term` gives the argument). SPPM's and the photon map's
//! visible points keep the collapse: a pass stores one visible point per pixel.

use super::state::PathState;
use crate::interaction::SurfaceHit;
use crate::math::Ray;
use crate::spectrum::{Carrier, N_LAMBDA};
use glam::Vec3;

/// A lane waiting for its sub-path.
#[derive(Clone, Copy)]
struct Branch<C: Carrier> {
    /// The sample's lane it carries.
    lane: usize,
    /// Its wavelengths ([`Carrier::lane_as_hero`]).
    lambda: C::Lambda,
    /// The path state at the split vertex, with this lane's throughput alone in lane 0.
    st: PathState<C>,
}

/// The sub-paths of a split sample: the lane the walk carries now, the radiance of the
/// finished ones, and the waiting ones.
pub(super) struct Branches<C: Carrier> {
    /// The sample's lane that the walk's lane 0 carries (0 before a split).
    lane: usize,
    /// The sample's radiance gathered before the split and by finished sub-paths, in the
    /// sample's lane order.
    done: C,
    /// The ray that reached the split vertex.
    ray: Ray,
    /// Lanes 1–3, taken in this order.
    waiting: [Option<Branch<C>>; N_LAMBDA - 1],
    /// A split happened.
    split: bool,
    /// The walk is a waiting lane just taken: its first vertex is the split vertex again,
    /// whose arrival (emission, transmittance) was counted before the split.
    pub resume: bool,
}

impl<C: Carrier> Branches<C> {
    /// No split yet.
    pub fn new() -> Self {
        Branches {
            lane: 0,
            done: C::ZERO,
            ray: Ray::new(Vec3::ZERO, Vec3::Z),
            waiting: [None; N_LAMBDA - 1],
            split: false,
            resume: false,
        }
    }

    /// Splits the path that reached its vertex along `ray` (untraced, meeting `met`, if
    /// [`PathState::meet`] took it there) with radiance `l` and state
    /// `st`, whose throughput was `beta` before the event kept the hero only; `lambda` are
    /// the path's wavelengths. The walk continues as lane 0's sub-path (`l` and `st.beta`
    /// become lane 0's alone, at weight 1, and `lambda` is marked as its sub-path's,
    /// [`Carrier::sub_path`]); lanes 1–3 wait.
    pub fn split(
        &mut self,
        l: &mut C,
        st: &mut PathState<C>,
        (ray, met): (Ray, Option<SurfaceHit>),
        (beta, lambda): (C, &mut C::Lambda),
    ) {
        let b = beta.to_lanes();
        let lane_only = |v: f32| C::from_lanes([v, 0.0, 0.0, 0.0]);
        for (k, w) in self.waiting.iter_mut().enumerate() {
            let lane = k + 1;
            *w = (b[lane] != 0.0).then(|| Branch {
                lane,
                lambda: C::lane_as_hero(lambda, lane),
                st: PathState {
                    beta: lane_only(b[lane]),
                    meet: met,
                    ..*st
                },
            });
        }
        st.beta = lane_only(b[0]);
        *lambda = C::lane_as_hero(lambda, 0);
        self.done = std::mem::replace(l, C::ZERO);
        self.ray = ray;
        self.lane = 0;
        self.split = true;
    }

    /// Ends the current sub-path, whose radiance is `l` (in its lane 0): adds it to the
    /// sample's and, if a lane waits, sets `ray`, `lambda` and `st` to its sub-path and
    /// returns true. Without a split, false at once.
    pub fn next(
        &mut self,
        l: &mut C,
        ray: &mut Ray,
        lambda: &mut C::Lambda,
        st: &mut PathState<C>,
    ) -> bool {
        if !self.split {
            return false;
        }
        let mut d = self.done.to_lanes();
        d[self.lane] += l.to_lanes()[0];
        self.done = C::from_lanes(d);
        *l = C::ZERO;
        let Some(b) = self.waiting.iter_mut().find_map(Option::take) else {
            return false;
        };
        (self.lane, *ray, *lambda, *st) = (b.lane, self.ray, b.lambda, b.st);
        self.resume = true;
        true
    }

    /// Whether the sample was split.
    pub fn is_split(&self) -> bool {
        self.split
    }

    /// The sample's radiance once [`Self::next`] returned false: `l` without a split.
    pub fn radiance(&self, l: C) -> C {
        if self.split {
            self.done
        } else {
            l
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{Lambdas, SampledSpectrum, SampledWavelengths};

    /// The sample's lanes after a split: what was gathered before, plus each sub-path's
    /// lane 0 in its own lane; a lane with zero throughput is not traced; each sub-path
    /// starts from the split vertex's ray with its lane's throughput and wavelengths.
    #[test]
    fn sub_paths_add_into_their_lanes() {
        type S = SampledSpectrum;
        let lambda = Lambdas::new(SampledWavelengths::sample_visible(0.3));
        let ray = Ray::new(Vec3::new(1.0, 2.0, 3.0), Vec3::X);
        let mut st = PathState::<S>::new(Vec3::ZERO);
        st.vertex = 5;
        let mut l = S::new([1.0, 2.0, 3.0, 4.0]);
        let mut b = Branches::<S>::new();
        b.split(
            &mut l,
            &mut st,
            (ray, None),
            (S::new([0.5, 0.0, 0.25, 1.0]), &mut lambda.clone()),
        );
        assert_eq!((l, st.beta), (S::ZERO, S::new([0.5, 0.0, 0.0, 0.0])));
        let (mut r, mut lam) = (Ray::new(Vec3::ZERO, Vec3::Y), lambda);
        let mut taken = Vec::new();
        for v in [10.0, 20.0, 30.0] {
            l = S::new([v, 0.0, 0.0, 0.0]);
            if !b.next(&mut l, &mut r, &mut lam, &mut st) {
                break;
            }
            assert!(b.resume);
            b.resume = false;
            assert_eq!((r.origin, st.vertex), (ray.origin, 5));
            assert_eq!(lam.wl.hero(), lambda.wl.lambda(b.lane));
            assert!(lam.hero_only);
            taken.push((b.lane, st.beta.values()));
        }
        assert_eq!(
            taken,
            vec![(2, [0.25, 0.0, 0.0, 0.0]), (3, [1.0, 0.0, 0.0, 0.0])]
        );
        assert_eq!(b.radiance(l), S::new([11.0, 2.0, 23.0, 34.0]));
    }

    /// Without a split the walk ends at once with its own radiance.
    #[test]
    fn no_split_no_sub_paths() {
        type S = SampledSpectrum;
        let mut b = Branches::<S>::new();
        let mut l = S::new([1.0, 2.0, 3.0, 4.0]);
        let mut st = PathState::<S>::new(Vec3::ZERO);
        let mut r = Ray::new(Vec3::ZERO, Vec3::Y);
        let mut lam = Lambdas::new(SampledWavelengths::sample_visible(0.3));
        assert!(!b.next(&mut l, &mut r, &mut lam, &mut st));
        assert_eq!(b.radiance(l), S::new([1.0, 2.0, 3.0, 4.0]));
    }
}
