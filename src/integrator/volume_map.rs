//! The hybrid's volumetric caustic map: photons stored where they first scatter in a
//! medium after reaching it through a specular chain (L S+ M: the concentrated light of a
//! volumetric caustic, not the diffuse glow it spreads into), gathered along the camera's
//! rays by the beam radiance estimate (Jarosz,
//! Zwicker & Jensen 2008, "The Beam Radiance Estimate for Volumetric Photon Mapping",
//! Eurographics, eq. 12, with a constant 2D kernel):
//!
//!   L_b(ray segment) = Σₚ T(s, tₚ) p(−d, ωₚ) Φₚ / (π r²)
//!
//! over the photons within distance r of the segment, tₚ the photon's projection on the
//! ray, T the medium's transmittance from the segment's start to tₚ, p the phase function
//! between the camera direction and the photon's arrival, Φₚ the flux scattered at the
//! photon (its free-flight weight already holds σ_s: [`crate::shading::media::fly`]). The
//! radius shrinks over passes as a 2D kernel's must (r²ᵢ₊₁ = r²ᵢ (i + α)/(i + 1): Knaus &
//! Zwicker 2011 §4.3; Jarosz, Nowrouzezahrai, Thomas, Sloan & Zwicker 2011, "Progressive
//! Photon Beams", §5, for the point-photon/beam-query pairing), so the average over passes
//! converges like the surface map's.
//!
//! The split with the path tracer and the surface map ([`super::caustic`]). Seen from the
//! camera, a full path ends X S* L, X its last non-delta vertex (a surface point or a
//! scattering event):
//! - X = M (a scattering event) after ≥ 1 delta bounce from the light (L S+ M): the beam
//!   estimate of the camera segment M lies on. Camera paths gather it along every segment
//!   through a medium, whatever the free flight then samples there, and drop emission
//!   found after a scattering event and ≥ 1 delta bounces;
//! - X = D after L S+, the camera path's first non-delta vertex D₁ a surface and no
//!   scattering event on the path: the surface map at D₁, whose photons are stored at every
//!   non-delta surface vertex of a caustic-origin photon until it first scatters in a
//!   medium; the path tracer drops such emission until the camera path scatters in a
//!   medium;
//! - everything else: the path tracer (the glow a caustic spreads into through the medium
//!   included: stored as photons after their scattering, it made sparse blotches).
//!
//! Each full path is counted once.
//!
//! Units: world space; photon power is flux divided by the photons emitted in the pass;
//! radiance as the film's. Determinism: photons come from the surface map's pass
//! ([`super::caustic::CausticMap::trace_pass`]), in chunk order.

use super::photon_pass::{GatherLanes, RadiusSequence};
use crate::math::Ray;
use crate::photon::grid::HashGrid;
use crate::photon::store::Photon;
use crate::shading::media::Segment;
use crate::spectrum::Carrier;
use crate::volume::track;
use glam::Vec3;

/// Most gather steps along one segment (a segment longer than this many diameters is
/// gathered over its first part only; 10⁵ steps of 2r).
const MAX_STEPS: usize = 100_000;

/// One pass's volume photons, their grid and the radius sequence.
#[derive(Debug, Default)]
pub struct VolumeMap {
    /// The pass's photons (power already divided by the photons emitted).
    pub photons: Vec<Photon>,
    grid: HashGrid,
    /// The photons' bounding box grown by the radius: a segment is gathered only where it
    /// crosses it.
    bounds: Option<(Vec3, Vec3)>,
    radius: RadiusSequence,
}

impl VolumeMap {
    /// An empty map with the surface map's α; the first radius is chosen on the first pass.
    pub fn new(alpha: f32) -> VolumeMap {
        VolumeMap {
            radius: RadiusSequence::new(None, alpha),
            ..VolumeMap::default()
        }
    }

    /// The current radius, choosing the first with `initial(photons)` (finite and positive,
    /// else 1 mm), and the grid for the pass's gathers.
    pub fn begin_gather(&mut self, initial: impl FnOnce(&[Photon]) -> f32) -> f32 {
        let photons = &self.photons;
        let r = self.radius.or_first(|| initial(photons));
        // Queries are spheres of radius r√2 around steps of 2r (see `beam`).
        self.grid
            .rebuild(&self.photons, r * std::f32::consts::SQRT_2);
        let grow = |(lo, hi): (Vec3, Vec3)| (lo - Vec3::splat(r), hi + Vec3::splat(r));
        self.bounds = self
            .photons
            .iter()
            .map(Photon::position)
            .fold(None, |b: Option<(Vec3, Vec3)>, p| {
                Some(b.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
            })
            .map(grow);
        r
    }

    /// The current radius (0 before the first is chosen).
    pub fn radius(&self) -> f32 {
        self.radius.radius()
    }

    /// Ends pass `pass` ([`RadiusSequence::end_pass`]).
    pub fn end_pass(&mut self, pass: u32) {
        self.radius.end_pass(pass);
    }

    /// Ends passes 0..`first` ([`RadiusSequence::replay`]).
    pub fn replay(&mut self, first: u64) {
        self.radius.replay(first);
    }

    /// The beam radiance estimate (module docs) along `seg` of the unit-direction `ray`, at
    /// the camera path's wavelengths `lambda` (the photons' lanes paired as the surface
    /// gather pairs them, [`GatherLanes`]). Zero for an empty map or an unbounded segment.
    pub fn beam<C: Carrier>(&self, ray: &Ray, seg: &Segment<'_>, lambda: &C::Lambda) -> C {
        let r2 = self.radius.r2() as f32;
        if self.photons.is_empty() || r2 <= 0.0 || !seg.end.is_finite() {
            return C::ZERO;
        }
        let r = r2.sqrt();
        let (o, d) = (ray.origin, ray.dir);
        // Only where the segment crosses the photons' box.
        let Some((start, end)) = self
            .bounds
            .and_then(|b| clip(b, o, d, (seg.start, seg.end)))
        else {
            return C::ZERO;
        };
        let c = seg.medium.coeffs::<C>(lambda);
        let lanes = GatherLanes::of::<C>(lambda);
        let phase = seg.medium.phase;
        let step = 2.0 * r;
        let steps = (((end - start) / step).ceil() as usize).clamp(1, MAX_STEPS);
        let mut sum = C::ZERO;
        for k in 0..steps {
            let s0 = start + k as f32 * step;
            let s1 = (s0 + step).min(end);
            let last = k + 1 == steps;
            let half = 0.5 * (s1 - s0);
            let query = (half * half + r2).sqrt();
            self.grid
                .for_each_within(o + d * (s0 + half), query, |i, _| {
                    let ph = &self.photons[i as usize];
                    let q = ph.position() - o;
                    let t = q.dot(d);
                    // Each photon counts once: in the step its projection falls in.
                    if t < s0 || t > s1 || (t == s1 && !last) {
                        return;
                    }
                    if q.length_squared() - t * t > r2 {
                        return;
                    }
                    let transmit = track::transmittance(&c, t - seg.start);
                    let p = phase.eval(-d, ph.wi());
                    sum += transmit * lanes.power::<C>(ph) * p;
                });
        }
        sum / (std::f32::consts::PI * r2)
    }
}

/// The part of [t0, t1] along `o + t d` inside the box `(lo, hi)` (slab method), if any.
fn clip((lo, hi): (Vec3, Vec3), o: Vec3, d: Vec3, (t0, t1): (f32, f32)) -> Option<(f32, f32)> {
    let inv = d.recip();
    let (a, b) = ((lo - o) * inv, (hi - o) * inv);
    let (near, far) = (a.min(b), a.max(b));
    let start = near.max_element().max(t0);
    let end = far.min_element().min(t1);
    (start < end).then_some((start, end))
}
