//! What a camera path carries from vertex to vertex ([`PathState`]): throughput, media,
//! bounce counts, the η scale Russian roulette reads, and the previous bounce for MIS.
//! Units: throughput is dimensionless per unit radiance; positions in world space.

use super::CausticSplit;
use crate::bsdf::{Bsdf, BsdfSample};
use crate::medium::MediumStack;
use crate::sampler::Bounce;
use crate::shading::{Surface, MAX_DELTA_BOUNCES};
use crate::spectrum::Carrier;
use glam::Vec3;

/// The previous bounce, for MIS of emission found by BSDF sampling: whether it was delta
/// (no MIS), its BSDF pdf and where it left from.
#[derive(Debug, Clone, Copy)]
pub(super) struct Prev {
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
    /// Non-delta and delta bounces so far (each with its own limit).
    pub depth: u32,
    pub delta_depth: u32,
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
    /// the surface map's ([`PathState::closes_caustic`]).
    pub clear: bool,
}

impl<C: Carrier> PathState<C> {
    /// A path leaving the camera at `origin` (in air).
    pub fn new(origin: Vec3) -> Self {
        PathState {
            beta: C::ONE,
            media: MediumStack::new(),
            depth: 0,
            delta_depth: 0,
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
        }
    }

    /// Whether the light end found now closes a D S+ L chain: the caustic map's (or light
    /// tracing's) share when the path is split. With media: an M S+ L chain is always the
    /// volume map's, a D S+ L chain the surface map's only while the path has not scattered
    /// in a medium ([`crate::integrator::volume_map`] gives the split).
    pub fn closes_caustic(&self, split: &CausticSplit<'_, C>) -> bool {
        !matches!(split, CausticSplit::None)
            && self.since_diffuse.unwrap_or(0) > 0
            && (self.last_in_medium || self.clear)
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
        if let (Bsdf::Dielectric { eta, .. }, true) = (s.bsdf, bs.transmission) {
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
        self.count_bounce(bs.delta, max_depth, u)
    }

    /// Follows a direction sampled with density `pdf` by the phase function at the point
    /// `p` of a medium (the sample's value over its density is 1): the MIS record, then the
    /// bounce limits and Russian roulette as for a non-delta surface bounce. `false` when
    /// the path ends here.
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
        self.count_bounce(false, max_depth, u)
    }

    /// The bounce limits (delta bounces and the others counted apart) and, after three
    /// non-delta bounces, Russian roulette on `u`. `false` when the path ends here.
    fn count_bounce(&mut self, delta: bool, max_depth: u32, u: &mut Bounce<'_>) -> bool {
        if delta {
            self.delta_depth += 1;
            return self.delta_depth <= MAX_DELTA_BOUNCES;
        }
        self.depth += 1;
        if self.depth >= max_depth {
            return false;
        }
        if self.depth >= 3 {
            let p = (self.beta * self.eta_scale).max_element().min(0.95);
            if u.roulette() >= p {
                return false;
            }
            self.beta /= p;
        }
        true
    }
}
