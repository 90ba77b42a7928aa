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
//! MIS sides use is the hero-marginal one. At its first smooth dispersive interface the
//! path splits into its 4 wavelengths,
//! each traced on as its own sub-path ([`split`], which gives the unbiasedness argument).
//!
//! The photon methods' camera paths are this loop too ([`camera_path`]): what a method asks
//! of them (where they stop, what another estimator gathers along them or owns of their
//! light, which hero orders their lanes) is its [`Strategy`], which the vertex calls.

mod capabilities;
mod in_medium;
pub mod kernel;
mod lanes;
mod light_sample;
mod own_hero;
pub mod polarized;
mod split;
mod state;
mod strategy;
mod vertex;
mod walk;

pub use capabilities::CAPABILITIES;
pub use lanes::{estimate_lanes, estimate_path, LaneWidth};
pub use own_hero::HeroOf;
pub use strategy::{History, RoughLanes, Strategy};

/// What the path tracer's camera paths keep of their 4 wavelengths at dispersive
/// interfaces in spectral transport (nothing changes in RGB). Each off choice falls back to
/// the hero only (pbrt-v4 `TerminateSecondary`), for comparisons.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dispersion {
    /// At a rough one: all 4, with spectral MIS ([`crate::shading::spectral_mis`]).
    pub spectral_mis: bool,
    /// At the first smooth one: split into 4 sub-paths ([`split`]).
    pub split: bool,
}

impl Dispersion {
    /// Both on: the path tracer's default.
    pub const ALL: Dispersion = Dispersion {
        spectral_mis: true,
        split: true,
    };
    /// The hero only everywhere (the photon map's camera paths; SPPM's with
    /// [`crate::integrator::SppmSettings::spectral_mis`] off, the hybrid's with
    /// [`crate::integrator::CausticSettings::split`] off; comparisons).
    pub const HERO: Dispersion = Dispersion {
        spectral_mis: false,
        split: false,
    };
    /// The split without spectral MIS: the hybrid's camera paths (spectral MIS under the
    /// sample's hero would tie the camera's hero to the photons' hero, [`own_hero`]).
    pub const SPLIT: Dispersion = Dispersion {
        spectral_mis: false,
        split: true,
    };
}

use super::Context;
use crate::bsdf::Bsdf;
use crate::interaction::SurfaceHit;
use crate::math::{Frame, Ray};
use crate::scene::Scene;
use crate::shading;
use crate::spectrum::Carrier;
use glam::Vec3;
use walk::{Next, Rules, Walk};

/// A volumetric caustic map's beam radiance estimate along a camera ray's segment through
/// a medium ([`super::volume_map::VolumeMap::beam`]), per unit throughput.
pub type Beam<'a, C> =
    &'a (dyn Fn(&Ray, &crate::shading::media::Segment<'_>, &<C as Carrier>::Lambda) -> C + Sync);

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
    /// Path throughput from the camera to here (lanes in the path's order, `hero`).
    pub beta: C,
    /// The path's wavelengths (hero only if it crossed a smooth dispersive interface), in
    /// the path's lane order.
    pub lambda: C::Lambda,
    /// The hit (for spawning final-gather rays).
    pub hit: SurfaceHit,
    /// At a rough dispersive dielectric reached with the lanes kept: each lane's η (lane
    /// 0's is `bsdf`'s), for f per lane ([`crate::shading::spectral_mis::eval_lanes`]).
    pub etas: Option<[f32; 4]>,
    /// Whose hero orders the lanes: the gather rotates a photon's power (in the sample's
    /// order) into the path's, and divides by 4 only for a path coupled to the sample's
    /// hero (`crate::integrator::photon_pass`'s `GatherLanes`).
    pub hero: HeroOf,
}

/// Radiance along `ray` (the camera is in air) at the sample's wavelengths `lambda`
/// (nothing in RGB transport), keeping them at dispersive interfaces as `dispersion` says:
/// the plain path tracer, [`camera_path`] with its [`Dispersion`] as the strategy.
pub fn radiance<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    (max_depth, dispersion): (u32, Dispersion),
    lambda: C::Lambda,
    ctx: &mut Context,
) -> C {
    camera_path(scene, ray, (max_depth, &dispersion), lambda, ctx).0
}

/// The path tracer's loop under the caller's `strategy` ([`Strategy`]): radiance gathered
/// along the path and the visible point where the strategy stopped it (none if it escaped,
/// was absorbed or hit the depth limit first). One vertex ([`vertex::vertex`]) after the
/// other, each shadow ray traced at once.
pub fn camera_path<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    ray: &Ray,
    (max_depth, strategy): (u32, &S),
    lambda: C::Lambda,
    ctx: &mut Context,
) -> (C, Option<VisiblePoint<C>>) {
    let rules = Rules {
        max_depth,
        strategy,
    };
    let mut walk = Walk::new(*ray, lambda);
    let mut visible = None;
    walk_on(scene, &rules, &mut walk, ctx, &mut visible);
    (walk.radiance(), visible)
}

/// Follows `walk` under `rules` until it ends ([`camera_path`]'s loop, also where the
/// structure-of-arrays kernel hands a lane over, [`kernel`]): one vertex ([`step`]) after
/// the other; the visible point where the strategy stops the path into `visible`.
fn walk_on<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    rules: &Rules<'_, S>,
    walk: &mut Walk<C>,
    ctx: &mut Context,
    visible: &mut Option<VisiblePoint<C>>,
) {
    loop {
        if step(scene, rules, walk, ctx, visible) == Next::End && !walk.next_branch() {
            return;
        }
    }
}

/// One vertex of `walk` under `rules` ([`vertex::vertex`], its hit traced unless the walk
/// met it already), its shadow ray traced at once; what follows it.
fn step<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    rules: &Rules<'_, S>,
    walk: &mut Walk<C>,
    ctx: &mut Context,
    visible: &mut Option<VisiblePoint<C>>,
) -> Next {
    let (media, lambda) = (&walk.st.media, &walk.lambda);
    let arrival = match walk.st.meet {
        Some(h) => shading::arrival::<C>(scene, &walk.ray, Some(h), media, lambda),
        None => shading::arrive::<C>(scene, &walk.ray, media, lambda, &mut ctx.rays),
    };
    let (nee, next) = vertex::vertex(scene, rules, walk, arrival, ctx, visible);
    if let Some(nee) = nee {
        nee.resolve_traced(scene, &walk.lambda, &mut ctx.rays, &mut walk.l);
    }
    next
}
