//! The hybrid's volumetric caustic map: photons stored where they scatter in a medium
//! after reaching it through a specular chain (L S+ M, and every later medium event of such
//! a photon), gathered along the camera's rays by the beam radiance estimate (Jarosz,
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
//! The split with the path tracer (proved with the surface map's in
//! [`super::caustic`]): a camera path gathers the beam estimate along every ray segment
//! through a medium **before** its first non-delta vertex, and drops emission found after a
//! non-delta vertex (surface or medium) and ≥ 1 delta bounces. A full path whose light end
//! starts L S+ and whose first non-delta camera vertex lies in a medium is counted by the
//! beam estimate of the segment that vertex lies on; if it lies on a surface, by the
//! surface map; every other path by the path tracer.
//!
//! Units: world space; photon power is flux divided by the photons emitted in the pass;
//! radiance as the film's. Determinism: photons come from the surface map's pass
//! ([`super::caustic::CausticMap::trace_pass`]), in chunk order.

use super::sppm::GatherLanes;
use crate::math::Ray;
use crate::photon::grid::HashGrid;
use crate::photon::store::Photon;
use crate::shading::media::Segment;
use crate::spectrum::Carrier;
use crate::volume::track;

/// Most gather steps along one segment (a segment longer than this many diameters is
/// gathered over its first part only; 10⁵ steps of 2r).
const MAX_STEPS: usize = 100_000;

/// One pass's volume photons, their grid and the radius sequence.
#[derive(Debug, Default)]
pub struct VolumeMap {
    /// The pass's photons (power already divided by the photons emitted).
    pub photons: Vec<Photon>,
    grid: HashGrid,
    r2: Option<f64>,
    alpha: f32,
}

impl VolumeMap {
    /// An empty map with the surface map's α; the first radius is chosen on the first pass.
    pub fn new(alpha: f32) -> VolumeMap {
        VolumeMap {
            alpha,
            ..VolumeMap::default()
        }
    }

    /// The current radius, choosing the first with `initial(photons)` (finite and positive,
    /// else 1 mm), and the grid for the pass's gathers.
    pub fn begin_gather(&mut self, initial: impl FnOnce(&[Photon]) -> f32) -> f32 {
        if self.r2.is_none() {
            let r = initial(&self.photons);
            let r = if r.is_finite() && r > 0.0 { r } else { 1e-3 };
            self.r2 = Some(f64::from(r) * f64::from(r));
        }
        let r = self.radius();
        // Queries are spheres of radius r√2 around steps of 2r (see `beam`).
        self.grid
            .rebuild(&self.photons, r * std::f32::consts::SQRT_2);
        r
    }

    /// The current radius (0 before the first is chosen).
    pub fn radius(&self) -> f32 {
        self.r2.map_or(0.0, f64::sqrt) as f32
    }

    /// Ends pass `pass` (0-based): r² ← r² · (i + α)/(i + 1) with i = pass + 1.
    pub fn end_pass(&mut self, pass: u32) {
        let factor = super::sppm::radius2_factor(pass + 1, self.alpha);
        self.r2 = self.r2.map(|r2| r2 * factor);
    }

    /// The beam radiance estimate (module docs) along `seg` of the unit-direction `ray`, at
    /// the camera path's wavelengths `lambda` (the photons' lanes paired as the surface
    /// gather pairs them, [`GatherLanes`]). Zero for an empty map or an unbounded segment.
    pub fn beam<C: Carrier>(&self, ray: &Ray, seg: &Segment<'_>, lambda: &C::Lambda) -> C {
        let r2 = self.r2.unwrap_or(0.0) as f32;
        if self.photons.is_empty() || r2 <= 0.0 || !seg.end.is_finite() {
            return C::ZERO;
        }
        let r = r2.sqrt();
        let (o, d) = (ray.origin, ray.dir);
        let c = seg.medium.coeffs::<C>(lambda);
        let lanes = GatherLanes::of::<C>(lambda);
        let phase = seg.medium.phase;
        let step = 2.0 * r;
        let steps = (((seg.end - seg.start) / step).ceil() as usize).clamp(1, MAX_STEPS);
        let mut sum = C::ZERO;
        for k in 0..steps {
            let s0 = seg.start + k as f32 * step;
            let s1 = (s0 + step).min(seg.end);
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
