//! Unidirectional path tracing (`--method path`, Kajiya 1986; pbrt-v4 `PathIntegrator`):
//! at each non-delta hit, next-event estimation toward one light chosen by the scene's light
//! sampler ([`crate::light::sampler`]), combined with BSDF sampling
//! by multiple importance sampling (power heuristic, Veach 1997). Delta bounces (smooth
//! glass, mirrors) do not use up the `max_depth` budget: they are counted separately up to
//! [`MAX_DELTA_BOUNCES`], so a gem's internal reflections are not cut short. Russian
//! roulette on the throughput after three non-delta bounces.
//!
//! Each hit is the per-hit step shared with the other loops ([`crate::shading::step`]):
//! materials become BSDFs ([`crate::bsdf`]) in the local frame of the outward shading
//! normal, volumes use the path's medium stack for η and Beer–Lambert, and alpha-BLEND
//! surfaces are passed through with probability 1 − α. Emission, MIS and next-event
//! estimation are this loop's own. In spectral transport a rough dispersive interface keeps
//! the 4 wavelengths with spectral MIS ([`crate::shading::spectral_mis`]): the BSDF's f and
//! pdf there come from [`Surface::sample_mis`] / [`Surface::eval_mis`], and the pdf both
//! MIS sides use is the hero-marginal one.

use super::Context;
use crate::bsdf::{Bsdf, BsdfSample, TransportMode};
use crate::interaction::SurfaceHit;
use crate::math::{Frame, Ray};
use crate::medium::MediumStack;
use crate::sampler::Bounce;
use crate::scene::Scene;
use crate::shading::{self, is_diffuse_like, lights, Arrival, Event, Surface, MAX_DELTA_BOUNCES};
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

/// Power heuristic with β = 2.
fn mis(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 {
        a2 / (a2 + b2)
    } else {
        0.0
    }
}

/// Next-event estimation at `s`: one light, chosen by the scene's light sampler
/// ([`Scene::light_sampler`](crate::scene::Scene)). With `use_mis` false the light sample
/// gets the full weight (the path stops here, so BSDF sampling will not find the light).
fn next_event<C: Carrier>(
    scene: &Scene,
    s: &Surface<C>,
    lambda: &C::Lambda,
    use_mis: bool,
    u: &mut Bounce<'_>,
    rays: &mut u64,
) -> C {
    let hit = &s.hit;
    let sampler = &scene.light_sampler();
    if sampler.is_empty() {
        return C::ZERO;
    }
    // Numbers a light does not use are skipped ([`Bounce::skip_light_choice`]).
    let u_choice = if sampler.lights().len() > 1 {
        u.light_choice()
    } else {
        u.skip_light_choice();
        0.0
    };
    let Some(choice) = sampler.sample(u_choice) else {
        return C::ZERO;
    };
    let p_sel = choice.pmf;
    let (reads_position, reads_member) = lights::numbers_read(choice.light);
    let up = if reads_position {
        u.light_position()
    } else {
        u.skip_light_position();
        Vec2::ZERO
    };
    let uc = if reads_member {
        u.light_member()
    } else {
        u.skip_light_member();
        0.0
    };
    let Some(ls) = lights::sample(scene, hit, choice.light, uc, up) else {
        return C::ZERO;
    };
    // The light's pdf includes choosing it ([`lights::area_pdf`] and
    // [`lights::environment_pdf`] give the same for a BSDF-sampled direction).
    let light_pdf = ls.pdf.map(|p| p * p_sel);
    let wi_local = s.frame.to_local(ls.wi);
    // Per lane with the hero-marginal pdf at a rough dispersive interface (spectral MIS).
    let (f, bsdf_pdf) = s.eval_mis(wi_local, TransportMode::Radiance, lambda);
    if f == C::ZERO {
        return C::ZERO;
    }
    *rays += 1;
    if scene.occluded(&ls.shadow) {
        return C::ZERO;
    }
    let w = match light_pdf {
        Some(lp) if use_mis => mis(lp, bsdf_pdf),
        _ => 1.0,
    };
    let incident = C::emitted(ls.incident / p_sel, ls.shape, lambda);
    f * incident * (wi_local.z.abs() * w)
}

/// Where a camera path ends (`--method photon` and `sppm` hand the rest to photons).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopAt {
    /// The plain path tracer: continue until Russian roulette or the depth limit.
    Never,
    /// Stop at the first diffuse-like hit ([`is_diffuse_like`]) and return it as a
    /// [`VisiblePoint`]; its direct light is still estimated here (with full weight, as
    /// BSDF sampling does not continue).
    Diffuse,
}

/// A caustic map's gather at a camera vertex: reflected radiance toward its `wo`
/// ([`super::caustic::CausticMap::density`]).
pub type Gather<'a, C> = &'a (dyn Fn(&Surface<C>, &<C as Carrier>::Lambda) -> C + Sync);

/// How the path tracer shares light transport with a caustic photon map (`--method hybrid`,
/// [`super::caustic`]); the split is Jensen's caustic map in Heckbert's notation.
#[derive(Clone, Copy)]
pub enum CausticSplit<'a, C: Carrier> {
    /// The plain path tracer: every path is counted here.
    None,
    /// Paths whose light end starts L S+ D (a caustic light, at least one delta bounce, a
    /// non-delta vertex) belong to the caustic map ([`super::caustic`]): at the path's
    /// first non-delta vertex, if its BSDF-sampled bounce would be followed,
    /// `gather(surface, lambda)` adds the map's reflected radiance (times the path
    /// throughput), and emission found by BSDF sampling after any non-delta bounce followed
    /// by ≥ 1 delta bounces is dropped (exactly the paths the map counts), the environment's
    /// radiance seen by a ray escaping after D S+ included (the environment is a caustic
    /// light).
    Map(Gather<'a, C>),
    /// As `Map`, but D₁ gathers with `through` if the camera reached it through ≥ 1 delta
    /// bounce or BLEND pass-through, with `direct` if it is seen directly (`None`: nothing);
    /// light tracing counts the rest ([`super::light_trace`], which proves the split).
    Mixed {
        /// The gather at a D₁ seen through delta bounces (the whole map).
        through: Gather<'a, C>,
        /// The gather at a D₁ seen directly (the photons light tracing does not splat).
        direct: Option<Gather<'a, C>>,
    },
}

/// The first diffuse-like hit of a camera path: where photons are gathered.
#[derive(Debug, Clone, Copy)]
pub struct VisiblePoint<C: Carrier> {
    /// Position.
    pub p: Vec3,
    /// Geometric normal (outward).
    pub ng: Vec3,
    /// Frame of the shading normal (the BSDF's frame).
    pub frame: Frame,
    /// Direction toward the camera, in `frame`.
    pub wo: Vec3,
    /// The BSDF there.
    pub bsdf: Bsdf<C>,
    /// Path throughput from the camera to here.
    pub beta: C,
    /// The path's wavelengths (hero only if it crossed a dispersive interface).
    pub lambda: C::Lambda,
    /// The hit (for spawning final-gather rays).
    pub hit: SurfaceHit,
}

/// Radiance along `ray` (the camera is in air) at the sample's wavelengths `lambda`
/// (nothing in RGB transport); `spectral_mis`: keep the 4 wavelengths at rough dispersive
/// interfaces ([`crate::shading::spectral_mis`]) rather than the hero only.
pub fn radiance<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    max_depth: u32,
    lambda: C::Lambda,
    spectral_mis: bool,
    ctx: &mut Context,
) -> C {
    trace(
        scene,
        ray,
        max_depth,
        lambda,
        StopAt::Never,
        CausticSplit::None,
        spectral_mis,
        ctx,
    )
    .0
}

/// The previous bounce, for MIS of emission found by BSDF sampling: whether it was delta
/// (no MIS), its BSDF pdf and where it left from.
#[derive(Debug, Clone, Copy)]
struct Prev {
    delta: bool,
    pdf: f32,
    p: Vec3,
}

/// The environment seen along an escaped ray, times `beta`, MIS-weighted against the light
/// sampling of the previous bounce (the light sampler's probability of the environment);
/// `None` without an environment.
fn escaped<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    prev: &Prev,
    beta: C,
    lambda: &C::Lambda,
) -> Option<C> {
    let env = scene.environment()?;
    let d = ray.dir.normalize();
    let w = if prev.delta {
        1.0
    } else {
        mis(prev.pdf, lights::environment_pdf(scene, d))
    };
    Some(beta * C::illuminant(env.eval(d), lambda) * w)
}

/// Emission of the surface arrived at (its emitting side only), times `beta`, MIS-weighted
/// like [`escaped`] with the probability of the emissive group; `None` if it does not emit
/// toward the path.
fn emitted<C: Carrier>(
    scene: &Scene,
    at: &Arrival<'_, C>,
    prev: &Prev,
    beta: C,
    lambda: &C::Lambda,
) -> Option<C> {
    let (hit, mat) = (&at.hit, at.mat);
    if at.sp.emissive == Vec3::ZERO || !(hit.front_face || mat.desc.double_sided) {
        return None;
    }
    let w = if prev.delta {
        1.0
    } else {
        mis(prev.pdf, lights::area_pdf(scene, hit.prim, prev.p, hit.p))
    };
    Some(beta * C::emitted(at.sp.emissive, mat.emitter_shape(), lambda) * w)
}

/// The path tracer's loop: radiance gathered along the path and, with [`StopAt::Diffuse`],
/// the visible point where it stopped (none if it escaped, was absorbed or hit the depth
/// limit first). Each hit is the shared step ([`shading::arrive`], [`Arrival::event`]);
/// emission is counted on arrival, before BLEND coverage is decided. `split` hands the
/// caustic paths to a caustic map ([`CausticSplit`]).
#[allow(clippy::too_many_arguments)]
pub fn camera_path<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    max_depth: u32,
    lambda: C::Lambda,
    stop: StopAt,
    split: CausticSplit<'_, C>,
    ctx: &mut Context,
) -> (C, Option<VisiblePoint<C>>) {
    trace(scene, ray, max_depth, lambda, stop, split, false, ctx)
}

/// The state a camera path carries from vertex to vertex.
struct PathState<C: Carrier> {
    /// Throughput.
    beta: C,
    /// The media the path is in.
    media: MediumStack,
    /// Non-delta and delta bounces so far (each with its own limit).
    depth: u32,
    delta_depth: u32,
    /// Scattering vertices so far: the sampler's bounce index (every vertex, delta
    /// included).
    vertex: u32,
    /// Product of η'² over the refractions so far: Russian roulette looks at
    /// beta·eta_scale, which leaves out the radiance-mode 1/η'² factors that cancel on
    /// leaving the object (pbrt-v4 `etaScale`); otherwise paths inside glass would be
    /// killed ~η² times as often.
    eta_scale: f32,
    /// The previous bounce, for MIS of emission found next.
    prev: Prev,
    /// Delta bounces since the last non-delta bounce (None before the first): ≥ 1 when
    /// emission found now closes a D S+ L chain, the caustic map's share.
    since_diffuse: Option<u32>,
    /// No bounce and no BLEND pass-through yet: the next vertex is seen directly.
    direct: bool,
}

impl<C: Carrier> PathState<C> {
    /// A path leaving the camera at `origin` (in air).
    fn new(origin: Vec3) -> Self {
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
        }
    }

    /// Whether the light end found now closes a D S+ L chain: the caustic map's (or light
    /// tracing's) share when the path is split.
    fn closes_caustic(&self, split: &CausticSplit<'_, C>) -> bool {
        !matches!(split, CausticSplit::None) && self.since_diffuse.unwrap_or(0) > 0
    }

    /// Follows the BSDF sample `bs` taken at `s`: throughput, η scale, media and the MIS
    /// record; then the bounce limits and, after three non-delta bounces, Russian roulette
    /// on `u`. `false` when the path ends here.
    fn advance(
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
            Some(0)
        };
        if bs.delta {
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

/// The caustic map's gather at a path's first non-delta vertex under `split`: the whole
/// map, or with [`CausticSplit::Mixed`] the part for a vertex seen `direct`ly or through
/// delta bounces.
fn split_gather<'a, C: Carrier>(split: CausticSplit<'a, C>, direct: bool) -> Option<Gather<'a, C>> {
    match split {
        CausticSplit::None => None,
        CausticSplit::Map(g) => Some(g),
        CausticSplit::Mixed { through, direct: d } => {
            if direct {
                d
            } else {
                Some(through)
            }
        }
    }
}

/// [`camera_path`], with spectral MIS at rough dispersive interfaces when `spectral_mis`
/// (only with [`StopAt::Never`]: the photon methods' visible points keep the hero only, as
/// their gather evaluates the BSDF with one η).
#[allow(clippy::too_many_arguments)]
fn trace<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    max_depth: u32,
    mut lambda: C::Lambda,
    stop: StopAt,
    split: CausticSplit<'_, C>,
    spectral_mis: bool,
    ctx: &mut Context,
) -> (C, Option<VisiblePoint<C>>) {
    let spectral_mis = spectral_mis && stop == StopAt::Never;
    let mut l = C::ZERO;
    let mut ray = *ray;
    let mut st = PathState::<C>::new(ray.origin);
    loop {
        let caustic = st.closes_caustic(&split);
        let arrival = shading::arrive::<C>(scene, &ray, &st.media, &lambda, &mut ctx.rays);
        let Some(at) = &arrival else {
            if let (Some(e), false) = (escaped(scene, &ray, &st.prev, st.beta, &lambda), caustic) {
                l += e;
            }
            break;
        };
        st.beta *= at.transmittance;
        if let (Some(e), false) = (emitted(scene, at, &st.prev, st.beta, &lambda), caustic) {
            l += e;
        }
        let mut u = ctx.sample.bounce(st.vertex);
        let ev = if spectral_mis {
            at.event_lanes(scene, st.media, &mut st.beta, &mut lambda, &mut u)
        } else {
            at.event(scene, st.media, &mut st.beta, &mut lambda, &mut u)
        };
        // By reference: the surface stays where `event` built it.
        let s = match &ev {
            Event::PassThrough(next) => {
                ray = *next;
                st.direct = false;
                continue;
            }
            Event::Scatter(s) => s,
        };
        if stop == StopAt::Diffuse && is_diffuse_like(&s.bsdf) {
            l += st.beta * next_event(scene, s, &lambda, false, &mut u, &mut ctx.rays);
            let vp = VisiblePoint {
                p: s.hit.p,
                ng: s.hit.ng,
                frame: s.frame,
                wo: s.wo,
                bsdf: s.bsdf,
                beta: st.beta,
                lambda,
                hit: s.hit,
            };
            return (l, Some(vp));
        }
        if !s.bsdf.is_delta() {
            l += st.beta * next_event(scene, s, &lambda, true, &mut u, &mut ctx.rays);
            let first = st.since_diffuse.is_none();
            let gather = split_gather(split, st.direct);
            if let (Some(gather), true) = (gather, first && st.depth + 1 < max_depth) {
                l += st.beta * gather(s, &lambda);
            }
        }
        let uc = u.bsdf_lobe();
        let ud = if s.bsdf.samples_direction() {
            u.bsdf_direction()
        } else {
            u.skip_bsdf_direction();
            Vec2::ZERO
        };
        let Some(bs) = s.sample_mis(uc, ud, TransportMode::Radiance, &mut lambda) else {
            break;
        };
        if !st.advance(s, &bs, max_depth, &mut u) {
            break;
        }
        ray = s.spawn(bs.wi);
        st.vertex += 1;
        st.direct = false;
    }
    (l, None)
}
