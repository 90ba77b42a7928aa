//! What a camera path carries from vertex to vertex ([`PathState`]): throughput, media,
//! bounce counts, the η scale Russian roulette reads, and the previous bounce for MIS.
//! Units: throughput is dimensionless per unit radiance; positions in world space.
//!
//! Bounce limits: a non-delta surface bounce counts against `max_depth`, a delta bounce
//! against [`MAX_DELTA_BOUNCES`]. A scattering event in a medium counts against `max_depth`
//! when it is the first since the path last met a surface (so `max_depth` 1 is single
//! scattering); the events after it in that run count against [`MAX_RUN`], the walk being
//! coarse-grained after the first [`crate::volume::coarse::FINE_EVENTS`]: a random walk
//! through a dense medium is one bounce, as a chain of delta bounces is none.
//!
//! Russian roulette (pbrt-v4 `PathIntegrator`): after three non-delta vertices, a path
//! whose throughput's largest lane (times the η scale) is q < 1 survives with probability
//! q and is divided by it; a path with q ≥ 1 always continues, so a white medium's walk or
//! rough glass's compensated weights never turn into a few heavy survivors.

use super::strategy::History;
use crate::bsdf::BsdfSample;
use crate::interaction::SurfaceHit;
use crate::medium_stack::MediumStack;
use crate::sampler::Bounce;
use crate::shading::termination::{delta_bounce, roulette, Draw};
use crate::shading::Surface;
use crate::spectrum::Carrier;
use crate::volume::coarse::{Scale, MAX_RUN};
use glam::Vec3;

/// The previous bounce, for MIS of emission found by BSDF sampling: whether it was delta
/// (no MIS), its BSDF pdf and where it left from.
#[derive(Debug, Clone, Copy)]
pub struct Prev {
    pub delta: bool,
    pub pdf: f32,
    pub p: Vec3,
}

/// The state a camera path carries from vertex to vertex.
#[derive(Clone, Copy)]
pub(super) struct PathState<C: Carrier> {
    /// Throughput.
    pub beta: C,
    /// The media the path is in.
    pub media: MediumStack,
    /// Non-delta bounces so far, counting a run of scattering events in media once, and
    /// delta bounces (each with its own limit, module docs).
    pub depth: u32,
    pub delta_depth: u32,
    /// Scattering events in media since the path last met a surface (the walk's run).
    pub run: u32,
    /// Scattering vertices so far: the sampler's bounce index (every vertex, delta
    /// included).
    pub vertex: u32,
    /// Product of η'² over the refractions so far: Russian roulette looks at
    /// beta·eta_scale, which leaves out the radiance-mode 1/η'² factors that cancel on
    /// leaving the object (pbrt-v4 `etaScale`); otherwise paths inside glass would be
    /// killed ~η² times as often.
    pub eta_scale: f32,
    /// The previous bounce, for MIS of emission found next.
    pub prev: Prev,
    /// Delta bounces since the last non-delta bounce (None before the first): ≥ 1 when
    /// emission found now closes a D S+ L chain, the caustic map's share.
    pub since_diffuse: Option<u32>,
    /// No bounce and no BLEND pass-through yet: the next vertex is seen directly.
    pub direct: bool,
    /// The last non-delta vertex was a scattering event in a medium.
    pub last_in_medium: bool,
    /// No scattering event in a medium yet: a light end closing at a surface may still be
    /// the surface map's ([`History::clear`]).
    pub clear: bool,
    /// The surface the path's ray was spawned from (its origin offset from it by
    /// [`crate::math::Ray::skipped`]), for the band behind the origin; `None` for the
    /// camera, a point in a medium or a split's sub-path.
    pub from: Option<SurfaceHit>,
    /// The surface the path's ray meets without being traced: leaving a band point toward
    /// its surface ([`crate::interaction::Leave::Meets`]), or a split's sub-path resuming
    /// at such a vertex.
    pub meet: Option<SurfaceHit>,
}

impl<C: Carrier> PathState<C> {
    /// A path leaving the camera at `origin` (in air).
    pub fn new(origin: Vec3) -> Self {
        PathState {
            beta: C::ONE,
            media: MediumStack::new(),
            depth: 0,
            delta_depth: 0,
            run: 0,
            vertex: 0,
            eta_scale: 1.0,
            prev: Prev {
                delta: true,
                pdf: 0.0,
                p: origin,
            },
            since_diffuse: None,
            direct: true,
            last_in_medium: false,
            clear: true,
            from: None,
            meet: None,
        }
    }

    /// The bounces so far as a strategy reads them ([`History`]), under `max_depth`.
    pub fn history(&self, max_depth: u32) -> History {
        History {
            since_diffuse: self.since_diffuse,
            last_in_medium: self.last_in_medium,
            clear: self.clear,
            direct: self.direct,
            continues: self.depth + 1 < max_depth,
        }
    }

    /// Follows the BSDF sample `bs` taken at `s`: throughput, η scale, media and the MIS
    /// record; then the bounce limits and, after three non-delta bounces, Russian roulette
    /// on `u`. `false` when the path ends here.
    pub fn advance(
        &mut self,
        s: &Surface<C>,
        bs: &BsdfSample<C>,
        max_depth: u32,
        u: &mut Bounce<'_>,
    ) -> bool {
        self.beta *= bs.f * (bs.wi.z.abs() / bs.pdf);
        if let (Some(eta), true) = (s.bsdf.interface_eta(), bs.transmission) {
            let etap = if s.wo.z > 0.0 { eta } else { 1.0 / eta };
            if etap.is_finite() && etap > 0.0 {
                self.eta_scale *= etap * etap;
            }
        }
        self.media = s.media_after(bs.transmission);
        self.prev = Prev {
            delta: bs.delta,
            pdf: bs.pdf,
            p: s.hit.p,
        };
        self.since_diffuse = if bs.delta {
            self.since_diffuse.map(|n| n + 1)
        } else {
            self.last_in_medium = false;
            Some(0)
        };
        let kind = if bs.delta { Kind::Delta } else { Kind::Surface };
        self.count(kind, max_depth, u)
    }

    /// Counts a delta bounce at `p` that no light sample can see through and that samples
    /// no BSDF (a crystal surface, a polarizer sheet): no MIS for what the path finds next,
    /// one more delta bounce since the last non-delta one. `false` past the delta bounce
    /// limit.
    pub fn delta_bounce(&mut self, p: Vec3) -> bool {
        self.prev = Prev {
            delta: true,
            pdf: 0.0,
            p,
        };
        self.since_diffuse = self.since_diffuse.map(|n| n + 1);
        self.count_delta()
    }

    /// The path met a surface: a new run of scattering events starts at the fine scale.
    pub fn met_surface(&mut self) {
        self.run = 0;
    }

    /// The coarse-graining scale of the walk's next flight ([`crate::volume::coarse`]).
    pub fn scale(&self) -> Scale {
        Scale::after(self.run)
    }

    /// The scale of the flight leaving the scattering event being taken (it adds one to the
    /// run): its shadow ray's, so next-event estimation and phase sampling see the same
    /// media.
    pub fn event_scale(&self) -> Scale {
        Scale::after(self.run + 1)
    }

    /// Follows a direction sampled with density `pdf` by the phase function at the point
    /// `p` of a medium (the sample's value over its density is 1): the MIS record, then the
    /// bounce limits (module docs) and Russian roulette. `false` when the path ends here.
    pub fn advance_in_medium(
        &mut self,
        p: Vec3,
        pdf: f32,
        max_depth: u32,
        u: &mut Bounce<'_>,
    ) -> bool {
        self.prev = Prev {
            delta: false,
            pdf,
            p,
        };
        self.since_diffuse = Some(0);
        self.last_in_medium = true;
        self.clear = false;
        self.count(Kind::Medium, max_depth, u)
    }

    /// One more delta bounce; `false` past [`MAX_DELTA_BOUNCES`].
    fn count_delta(&mut self) -> bool {
        delta_bounce(&mut self.delta_depth)
    }

    /// The bounce limits for a vertex of `kind` (module docs) and, after three non-delta
    /// vertices, Russian roulette on `u`. `false` when the path ends here.
    fn count(&mut self, kind: Kind, max_depth: u32, u: &mut Bounce<'_>) -> bool {
        match kind {
            Kind::Delta => return self.count_delta(),
            Kind::Surface => self.depth += 1,
            Kind::Medium => {
                if self.run == 0 {
                    self.depth += 1;
                }
                self.run += 1;
                if self.run >= MAX_RUN {
                    return false;
                }
            }
        }
        if self.depth >= max_depth {
            return false;
        }
        // Non-delta vertices so far (a run's first event is in both counts).
        if self.depth + self.run.saturating_sub(1) >= 3 {
            // q NaN or ≤ 0 ends the path; q ≥ 1 always continues (divided by 1).
            let q = (self.beta * self.eta_scale).max_element();
            let Some(q) = roulette(q, Draw::UnlessSure, || u.roulette()) else {
                return false;
            };
            self.beta /= q;
        }
        true
    }
}

/// What kind of vertex a path follows ([`PathState::count`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// A delta bounce at a surface.
    Delta,
    /// A non-delta bounce at a surface.
    Surface,
    /// A scattering event in a medium.
    Medium,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::{PixelSampler, SamplerKind};
    use crate::shading::MAX_DELTA_BOUNCES;
    use crate::volume::coarse::FINE_EVENTS;

    /// `n` scattering events in a medium from a path of throughput `beta` at max depth
    /// `max_depth`: how many it survived and its throughput then.
    fn walk(beta: f32, n: u32, max_depth: u32, seed: u64) -> (u32, f32) {
        let sampler = PixelSampler::new(SamplerKind::Independent, 1, (1, 1), seed);
        let mut stream = sampler.start(0, 0, 0);
        let mut st = PathState::<Vec3>::new(Vec3::ZERO);
        st.beta = Vec3::splat(beta);
        for k in 0..n {
            let mut u = stream.bounce(k);
            if !st.advance_in_medium(Vec3::ZERO, 0.25, max_depth, &mut u) {
                return (k, st.beta.x);
            }
        }
        (n, st.beta.x)
    }

    /// Russian roulette never ends a path whose throughput is 1 or more (a white medium's
    /// walk keeps β = 1): it survives 4 000 events at max depth 2 (the run counts once),
    /// with its throughput unchanged. With p = min(β, 0.95) a path survived 4 000 events
    /// with probability 0.95^3997 and came back with β ≈ 1.05^n.
    #[test]
    fn roulette_spares_a_throughput_of_one() {
        for seed in 0..8 {
            assert_eq!(walk(1.0, 4000, 2, seed), (4000, 1.0));
            assert_eq!(walk(2.5, 4000, 2, seed), (4000, 2.5));
        }
    }

    /// Below 1 the path survives with probability β and is divided by it: from β = 0.5 a
    /// path survives its third vertex half the time (16 000 paths: 0.5 ± 0.016 at 4σ) and
    /// then carries 1.
    #[test]
    fn roulette_below_one_is_unbiased() {
        let n = 16_000;
        let mut survived = 0;
        for seed in 0..n {
            let (k, beta) = walk(0.5, 3, 64, seed);
            if k == 3 {
                survived += 1;
                assert_eq!(beta, 1.0);
            } else {
                assert_eq!(k, 2, "ended before the roulette");
            }
        }
        let p = survived as f64 / n as f64;
        assert!((p - 0.5).abs() < 0.016, "survival {p}");
    }

    /// A delta bounce that samples no BSDF (a crystal surface, a polarizer sheet): no MIS
    /// for what the path finds next, one more delta bounce since the last non-delta vertex
    /// (none before the first), and the path ends past the delta bounce limit.
    #[test]
    fn delta_bounces_count_to_their_limit() {
        let mut st = PathState::<Vec3>::new(Vec3::ZERO);
        assert!(st.delta_bounce(Vec3::X));
        assert_eq!(st.since_diffuse, None);
        st.since_diffuse = Some(0);
        assert!(st.delta_bounce(Vec3::Y));
        let prev = (st.prev.delta, st.prev.pdf, st.prev.p);
        assert_eq!((st.since_diffuse, prev), (Some(1), (true, 0.0, Vec3::Y)));
        for _ in 2..MAX_DELTA_BOUNCES {
            assert!(st.delta_bounce(Vec3::Y));
        }
        assert!(!st.delta_bounce(Vec3::Y));
        assert_eq!(st.depth, 0);
    }

    /// The first event of a run counts against `max_depth` (so max depth 1 is single
    /// scattering), the rest against the run's own bound; meeting a surface starts a new
    /// run, which counts again; the walk coarsens after the fine events.
    #[test]
    fn a_run_of_scattering_events_is_one_bounce() {
        assert_eq!(walk(1.0, 5, 1, 3).0, 0);
        let sampler = PixelSampler::new(SamplerKind::Independent, 1, (1, 1), 1);
        let mut stream = sampler.start(0, 0, 0);
        let mut st = PathState::<Vec3>::new(Vec3::ZERO);
        for k in 0..FINE_EVENTS + 300 {
            assert!(st.advance_in_medium(Vec3::ZERO, 0.25, 3, &mut stream.bounce(k)));
        }
        assert_eq!((st.depth, st.run), (1, FINE_EVENTS + 300));
        assert!(st.scale().k() > 2.0);
        st.met_surface();
        assert_eq!(st.scale(), Scale::FINE);
        assert!(st.advance_in_medium(Vec3::ZERO, 0.25, 3, &mut stream.bounce(0)));
        assert_eq!(st.depth, 2);
        st.met_surface();
        assert!(!st.advance_in_medium(Vec3::ZERO, 0.25, 3, &mut stream.bounce(1)));
    }
}
