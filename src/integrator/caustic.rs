//! The hybrid's progressive caustic photon map (`--method hybrid`, [`super::hybrid`]):
//! Jensen's caustic map ("Realistic Image Synthesis Using Photon Mapping", 2001, §7.5) made
//! progressive with a global radius sequence (Knaus & Zwicker 2011, "Progressive Photon
//! Mapping: A Probabilistic Approach", ACM TOG 30(3), §4.3):
//! r²ᵢ₊₁ = r²ᵢ · (i + α)/(i + 1), so r²ᵢ = r²₁ · Πₖ₌₁^{i−1} (k + α)/(k + 1) and the average of
//! the passes' estimates converges without per-pixel statistics.
//!
//! ## The split (Heckbert's notation; S = a delta bounce, `bs.delta`; D = a non-delta one)
//! - **Caustic lights** (the one rule, kept here in [`emitter`]): every light — punctual
//!   lights, emissive triangles and the environment. Punctual lights must be: no camera
//!   path can hit them, so NEE through glass is impossible. Emissive triangles and the
//!   environment are the consistent simple choice, and the one that pays on gems: a small
//!   stone under a studio focuses its softboxes onto the floor, which a camera path finds
//!   only when its BSDF sample happens to pass the stone and hit a softbox (bright
//!   fireflies), while photons aimed at the stone carry that light exactly. Caustic photons
//!   are mostly aimed at the caustic makers ([`CAUSTIC_AIM`]), so most of the
//!   environment's start on the discs the stones' bounding spheres project, not across the
//!   whole scene. (A first
//!   version left the environment to the path tracer; on a diamond under the studio it
//!   lost to SPPM 10× by relative MSE, from exactly those fireflies.)
//! - **Photons** (this module): a caustic light's photon whose light subpath starts L S+ D
//!   (≥ 1 delta bounce before its first non-delta vertex) — a *caustic-origin* photon — is
//!   stored at that vertex (flagged [`Photon::CAUSTIC`]) and at every later non-delta vertex as it goes on bouncing
//!   (throughput roulette, the integrator's depth); other photons are not stored.
//! - **Camera paths** ([`super::path::camera_path`] with [`super::hybrid::CausticSplit::Map`]):
//!   at the camera path's FIRST non-delta vertex D₁ only (if its bounce would be followed),
//!   the map's reflected radiance L = Σ f(wo, wiₚ) Φₚ / (N π r²) (constant kernel) times the
//!   throughput; at every vertex, emission found by BSDF sampling after a non-delta bounce
//!   followed by ≥ 1 delta bounces (… D S+ L: a caustic-origin light end, the environment
//!   seen by an escaping ray included) is dropped. NEE is
//!   unchanged (shadow rays through glass are occluded). Every full path is counted exactly
//!   once, by its light end: a caustic-origin light end by the map at D₁ (the light side
//!   may bounce diffusely before reaching D₁), any other by the path tracer.
//! - **Light tracing** (`--caustics light|mixed`, [`super::light_trace`]): where the camera
//!   sees D₁ directly, the photons' vertices (all, or the first only) are splatted onto the
//!   image instead, and D₁ gathers none of them (or the later ones only); the proof that
//!   the three estimators still count each path once is there.
//! - A first version gathered a map of first-vertex photons at every camera vertex; the
//!   map is concentrated (a gem's caustic), and gathering it at the second and later camera
//!   vertices made bright splotches in indirect light: it lost to SPPM at equal time on
//!   every caustic scene measured. Gathering only at D₁, with the light side carrying the
//!   caustic's indirect light as SPPM's photons do, is the fix.
//!
//! Units: world space, metres; photon power is flux (the lights' units) divided by the
//! photons emitted in the pass; radii in metres. Determinism: photon `i` of pass `p` starts
//! from number `p·n + i` of the seed's digit-permuted Halton sequence, aimed by
//! [`CAUSTIC_AIM`] ([`emit_one`]), and continues on the stream `Rng::new(&[seed, p, i, KEY])`,
//! traced in fixed chunks and concatenated in chunk order, so the map is the same whatever
//! the thread count.

use super::light_trace::{Splat, Splatter};
use super::photon_pass::{photon_term, GatherLanes, RadiusSequence};
use super::volume_map::VolumeMap;
use super::{StoreBudget, MAX_PHOTONS};
use crate::error::Result;
use crate::math::Rng;
use crate::photon::aim::DEFAULT_AIM;
use crate::photon::emit::{Aim, EmittedPhoton, PhotonEmitter, PhotonNumbers};
use crate::photon::grid::HashGrid;
use crate::photon::store::Photon;
use crate::photon::trace::{self, Roulette, TraceSettings};
use crate::polar::stokes::{angle_between, rotate, Analyzer};
use crate::scene::Scene;
use crate::shading::polarized::s_basis;
use crate::shading::Surface;
use crate::spectrum::Carrier;
use rayon::prelude::*;

mod chunk;
#[cfg(test)]
mod tests;

use chunk::Chunk;
pub use chunk::Walk;

/// Photons traced per parallel work item (a fixed split: deterministic).
const CHUNK: u64 = 4096;
/// Stream key of caustic photons (distinct from SPPM's).
const KEY: u64 = 0xCA05_71C0;

/// The caustic lights' emitter (see the module docs: every light, the environment
/// included).
pub fn emitter(scene: &Scene) -> PhotonEmitter {
    PhotonEmitter::new(scene)
}

/// How caustic photons are aimed: a defensive mixture, 3/4 of them aimed at the caustic
/// makers' bounding spheres and 1/4 drawn as the light emits ([`Aim::Mixture`]), so a
/// photon's power is at most 1/(1 − 3/4) = 4× the unaimed one's. Aiming only
/// ([`Aim::Only`]) spends nothing on directions that cannot start a caustic but has no such
/// bound: in a narrow spot beam the rare aimed photon carries p_spot/p_aim times the
/// power, without limit as the beam narrows, and the hybrid's image keeps single-pixel
/// fireflies (BENCHMARKS.md, "Photons aimed at the caustic makers").
pub const CAUSTIC_AIM: Aim = Aim::Mixture(0.75);

/// The one place a caustic photon is emitted: number `index` of the seed's digit-permuted
/// Halton sequence ([`PhotonNumbers`]), aimed by [`CAUSTIC_AIM`].
fn emit_one<'a>(
    emitter: &PhotonEmitter,
    scene: &'a Scene,
    numbers: &PhotonNumbers,
    index: u64,
) -> Option<EmittedPhoton<'a>> {
    emitter.emit_index(scene, numbers, index, CAUSTIC_AIM)
}

/// Photons emitted per pass: `photons`, or one per pixel (at most [`MAX_PHOTONS`]).
pub fn photons_per_pass(photons: u64, pixels: u64) -> u64 {
    if photons > 0 {
        photons
    } else {
        pixels.clamp(1, MAX_PHOTONS)
    }
}

/// The basis x of a polarized photon's Stokes vector: any unit vector ⊥ its stored
/// direction of travel −wi, a function of that direction alone (the gather rebuilds it).
fn photon_basis(p: &Photon) -> glam::Vec3 {
    crate::polar::stokes::perpendicular(-p.wi())
}

/// One pass's caustic photons, their grid and the radius sequence.
#[derive(Debug, Default)]
pub struct CausticMap {
    /// The pass's stored photons (power already divided by the photons emitted).
    pub photons: Vec<Photon>,
    grid: HashGrid,
    /// The radius of the current pass (none until the first is chosen).
    radius: RadiusSequence,
    /// In a scene with media: the volume photons of the same pass ([`VolumeMap`]).
    pub volume: Option<VolumeMap>,
    /// Photons traced with polarization (the polarized hybrid, [`Self::polarized`]).
    polarized: bool,
    /// With polarization: each photon's Stokes vector over s₀ (s₁, s₂, s₃) in the basis
    /// [`photon_basis`], by photon index.
    stokes: Vec<[f32; 3]>,
    /// How far its photons are followed ([`Walk`]; polarized photons walk in full).
    walk: Walk,
}

impl CausticMap {
    /// An empty map with an initial radius (`None`: chosen on the first pass) and α.
    pub fn new(radius: Option<f32>, alpha: f32) -> CausticMap {
        CausticMap {
            radius: RadiusSequence::new(radius, alpha),
            ..CausticMap::default()
        }
    }

    /// The same map traced with polarized photons ([`crate::photon::polarized`]), gathered
    /// with [`Self::density_polarized`].
    pub fn polarized(self) -> CausticMap {
        CausticMap {
            polarized: true,
            ..self
        }
    }

    /// The same map with its photons walked in full ([`Walk::Full`]: the pilot's maps).
    pub fn full_walks(self) -> CausticMap {
        CausticMap {
            walk: Walk::Full,
            ..self
        }
    }

    /// Traces `n` photons of pass `pass` from the caustic lights and keeps the L S+ D
    /// vertices; with a `splatter`, also connects each kept vertex to the camera
    /// ([`super::light_trace`]). Returns the rays traced and the splats, one list per fixed
    /// photon chunk in chunk order (empty without a splatter); an error when the store
    /// budget is crossed.
    #[allow(clippy::too_many_arguments)]
    pub fn trace_pass<C: Carrier>(
        &mut self,
        scene: &Scene,
        emitter: &PhotonEmitter,
        seed: u64,
        pass: u32,
        n: u64,
        lambda: C::Lambda,
        max_depth: u32,
        splatter: Option<&Splatter>,
    ) -> Result<(u64, Vec<Vec<Splat>>)> {
        // Throughput roulette only: the lobe rule's "specular" is not the delta split.
        let settings = TraceSettings {
            max_depth,
            roulette: Roulette::Throughput,
        };
        let budget = StoreBudget::default();
        let inv_n = 1.0 / n.max(1) as f32;
        let numbers = PhotonNumbers::new(seed ^ KEY);
        let (polarized, walk) = (self.polarized, self.walk);
        let per_chunk: Vec<Chunk> = (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let mut chunk = Chunk::default();
                for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                    let mut rng = Rng::new(&[seed, u64::from(pass), i, KEY]);
                    let Some(ph) = emit_one(emitter, scene, &numbers, u64::from(pass) * n + i)
                    else {
                        continue;
                    };
                    let before = chunk.surface.len();
                    if polarized {
                        let run = (scene, max_depth);
                        chunk.trace_polarized::<C>(run, &ph, lambda, inv_n, &mut rng);
                    } else {
                        let run = (scene, &settings, splatter, walk);
                        chunk.trace_one::<C>(run, &ph, lambda, inv_n, &mut rng);
                    }
                    if !budget.add(chunk.surface.len() - before) {
                        break;
                    }
                }
                chunk
            })
            .collect();
        budget.check(n, 1)?;
        self.photons.clear();
        self.stokes.clear();
        self.photons
            .reserve_exact(per_chunk.iter().map(|c| c.surface.len()).sum());
        let (mut rays, mut splats) = (0, Vec::with_capacity(per_chunk.len()));
        if let Some(v) = &mut self.volume {
            v.photons.clear();
        }
        for c in per_chunk {
            self.photons.extend_from_slice(&c.surface);
            self.stokes.extend_from_slice(&c.stokes);
            splats.push(c.splats);
            rays += c.rays;
            if let Some(v) = &mut self.volume {
                v.photons.extend_from_slice(&c.volume);
            }
        }
        Ok((rays, splats))
    }

    /// The current pass's radius, choosing the first with `initial(photons)` when none was
    /// given (it must be finite and positive, else 1 mm), and builds the grid for it.
    pub fn begin_gather(&mut self, initial: impl Fn(&[Photon]) -> f32) -> f32 {
        let photons = &self.photons;
        let r = self.radius.or_first(|| initial(photons));
        self.grid.rebuild(&self.photons, r);
        // The volume map likewise, its first radius from its own photons.
        if let Some(v) = &mut self.volume {
            v.begin_gather(&initial);
        }
        r
    }

    /// The current radius (0 before the first is chosen).
    pub fn radius(&self) -> f32 {
        self.radius.radius()
    }

    /// Ends pass `pass` (0-based): r² ← r² · (i + α)/(i + 1) with i = pass + 1
    /// ([`RadiusSequence::end_pass`]), for the volume map's radius too.
    pub fn end_pass(&mut self, pass: u32) {
        self.radius.end_pass(pass);
        if let Some(v) = &mut self.volume {
            v.end_pass(pass);
        }
    }

    /// Ends passes 0..`first` in order (a shard starting at pass `first`,
    /// [`RadiusSequence::replay`]), for the volume map's radius too.
    pub fn replay(&mut self, first: u64) {
        self.radius.replay(first);
        if let Some(v) = &mut self.volume {
            v.replay(first);
        }
    }

    /// Radiance the map reflects at the camera vertex `s` toward its `wo`:
    /// Σ f(wo, wiₚ) Φₚ / (π r²) over the photons within r (Jensen 2001 eq. 7.6 with a
    /// constant kernel); with `later_only`, over the photons stored after a diffuse bounce
    /// only (not at a photon's first vertex, flagged [`Photon::CAUSTIC`]: light tracing's in
    /// mixed mode, [`super::light_trace`]). Hero-wavelength bookkeeping and split camera
    /// samples as in SPPM ([`photon_term`]).
    pub fn density<C: Carrier>(&self, s: &Surface<C>, lambda: &C::Lambda, later_only: bool) -> C {
        let lanes = GatherLanes::of::<C>(lambda);
        self.sum_within(s, |_, ph| {
            if later_only && ph.flags() & Photon::CAUSTIC != 0 {
                return C::ZERO;
            }
            photon_term(&s.bsdf, &s.frame, s.wo, lanes, ph)
        })
    }

    /// [`Self::density`] of a polarized map read through the camera path's `analyzer` at
    /// `s` (the analyzer of the light leaving toward the camera): Σ f(wo, wiₚ) Φₚ
    /// (a·N·Sₚ) / (π r²), N the surface's normalized Mueller matrix for the photon's
    /// direction ([`crate::shading::polarized::mueller`]; a depolarizing surface reads a₀)
    /// and Sₚ the photon's Stokes vector over s₀.
    pub fn density_polarized<C: Carrier>(
        &self,
        s: &Surface<C>,
        lambda: &C::Lambda,
        analyzer: &Analyzer,
    ) -> C {
        if self.stokes.len() != self.photons.len() {
            return C::ZERO;
        }
        // A depolarizing surface reads every photon as unpolarized light.
        if s.bsdf.depolarizes() {
            return self.density(s, lambda, false) * analyzer.unpolarized();
        }
        let lanes = GatherLanes::of::<C>(lambda);
        self.sum_within(s, |i, ph| {
            let f = photon_term(&s.bsdf, &s.frame, s.wo, lanes, ph);
            let wi = ph.wi();
            let read = match s.bsdf.mueller(s.wo, s.frame.to_local(wi)) {
                None => analyzer.unpolarized(),
                Some((n, m)) => {
                    let k_in = -wi;
                    let x = s_basis(k_in, s.frame.to_world(m), analyzer.x);
                    let a = analyzer.through(&n, x, x, k_in, 1.0).a;
                    let [s1, s2, s3] = self.stokes[i];
                    let phi = angle_between(photon_basis(ph), x, k_in);
                    let sp = rotate(&[1.0, s1, s2, s3], phi);
                    a[0] * sp[0] + a[1] * sp[1] + a[2] * sp[2] + a[3] * sp[3]
                }
            };
            f * read
        })
    }

    /// Σ `term(index, photon)` over the photons within the current radius of the camera
    /// vertex `s` and in its disc ([`crate::photon::grid::in_disc`]), over π r² (zero
    /// before the first radius or without photons).
    fn sum_within<C: Carrier>(
        &self,
        s: &Surface<C>,
        mut term: impl FnMut(usize, &Photon) -> C,
    ) -> C {
        let r2 = self.radius.r2();
        if self.photons.is_empty() || r2 <= 0.0 {
            return C::ZERO;
        }
        let r = r2.sqrt() as f32;
        let mut sum = C::ZERO;
        self.grid.for_each_within(s.hit.p, r, |i, _| {
            let ph = &self.photons[i as usize];
            if crate::photon::grid::in_disc(s.hit.p, s.hit.ng, ph.position(), r) {
                sum += term(i as usize, ph);
            }
        });
        sum / (std::f64::consts::PI * r2) as f32
    }
}

/// The caustic lights' probe behind `--method auto` ([`crate::plan::resolve_method`]): of
/// `n` photons from the caustic lights (fixed seed, RGB, the map's split), the share of the
/// power arriving at first non-delta hits that arrives after ≥ 1 delta bounce (L S+ D),
/// in [0, 1]; 0 when no photon reaches a non-delta surface. The photons are emitted as
/// SPPM's are ([`DEFAULT_AIM`]: half aimed at the caustic makers, each weighted by
/// p_usual/p_mixture), so the share is of all the light the lights send, estimated with
/// enough photons through a small stone under a large sky to see it.
pub fn probe_share(scene: &Scene, n: u32) -> f64 {
    let emitter = emitter(scene);
    if emitter.is_empty() {
        return 0.0;
    }
    let settings = TraceSettings {
        max_depth: 1,
        roulette: Roulette::Throughput,
    };
    let (mut all, mut caustic) = (0.0f64, 0.0f64);
    let numbers = PhotonNumbers::new(KEY ^ 0x9206E);
    for i in 0..n {
        let mut rng = Rng::new(&[KEY, u64::from(i), 0x9206E]);
        let Some(ph) = emitter.emit_index(scene, &numbers, u64::from(i), DEFAULT_AIM) else {
            continue;
        };
        let mut first = true;
        trace::trace::<glam::Vec3>(scene, &ph, (), &settings, &mut rng, |v, _| {
            if std::mem::take(&mut first) {
                let y = f64::from(crate::light::env::luminance(v.power));
                if y.is_finite() {
                    all += y;
                    if v.bounces > 0 {
                        caustic += y;
                    }
                }
            }
        });
    }
    if all > 0.0 {
        caustic / all
    } else {
        0.0
    }
}
