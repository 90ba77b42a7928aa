//! The polarized path tracer (`--polarization on`, chosen by the plan for scenes with a
//! birefringent crystal or a polarizer on the camera): the path tracer's loop carrying an
//! [`Analyzer`] — the row vector a with a·S the pixel's reading of light of Stokes vector S
//! ([`crate::polar::stokes`]). One analyzer serves the sample's 4 wavelengths while the
//! Mueller matrices met do not depend on them; at a crystal (dispersive indices, modes
//! whose paths differ by wavelength), a dispersive interface or a measured metal
//! ([`crate::bsdf::Bsdf::hero_polarizes`]) the path keeps its hero alone.
//!
//! At each vertex: emission and the environment (unpolarized) count with a₀; next-event
//! estimation with a·N(light direction)₀, N the surface's normalized Mueller matrix
//! ([`surface`]); the BSDF sample updates a ← a·N, its scalar weight f·|cos|/pdf staying in
//! the throughput; a smooth crystal surface is handled by [`crystal_step`] (two modes, the
//! walk-off, absorption per mode). Russian roulette, MIS (power heuristic) and the bounce
//! limits are the path tracer's ([`super::state::PathState`]). Unbiased for the model:
//! E[a_camera · Π M_i · S_light / Π p_i] is the polarized measurement (Mitsuba 3 traces
//! Mueller matrices the same way, its `polarized` variants; Wilkie & Weidlich 2012,
//! "Polarised light in computer graphics", SIGGRAPH Asia course).
//!
//! With a caustic map (the polarized hybrid, [`crate::integrator::hybrid`]) the split is
//! the unpolarized one ([`crate::integrator::hybrid::CausticSplit::Map`], through the same
//! tests [`super::History::closes_caustic`] and [`super::History::first_diffuse`]): at the
//! first non-delta vertex D₁ the map's polarized photons are gathered through the analyzer
//! ([`PolarizedGather`]), and light found after D S+ (crystal surfaces and polarizer sheets
//! count as delta bounces) is dropped. Rough crystals scatter as isotropic dielectrics with
//! their mean index.
//!
//! Shared with the path tracer's vertex ([`super::vertex`]): the path state, its bounce
//! limits, delta counter and Russian roulette ([`super::state::PathState`]), emission and
//! the environment with MIS, next-event estimation and its shadow ray
//! ([`super::walk::Pending::transmitted`]), the caustic tests. Not shared, so not had:
//! - scattering media: a phase function here is a scalar (Henyey–Greenstein), with no
//!   Mueller matrix to carry the analyzer through a scattering event; the plan refuses
//!   them with polarization (absorbing volumes are traced: Beer–Lambert, and per crystal
//!   mode);
//! - the wavelength split: a smooth dispersive interface keeps the hero alone, as the path
//!   did before the split existed; splitting would change the images of polarized scenes
//!   with dispersive glass;
//! - lanes: the vertex's order differs (a crystal's numbers are drawn before emission is
//!   counted, the analyzer weighs emission, light samples and the gather), so polarized
//!   paths run on single rays; sharing the vertex means a second generic axis on it, the
//!   state a path carries besides its throughput (nothing, or the analyzer and crystal
//!   mode).

mod crystal_step;
mod surface;

use super::light_sample::{next_event, Scatterer};
use super::state::PathState;
use super::vertex::{emitted, escaped};
use super::walk::pending;
use crate::bsdf::TransportMode;
use crate::material::CrystalDesc;
use crate::math::Ray;
use crate::polar::modes::InMode;
use crate::polar::stokes::{linear_polarizer, transverse};
use crate::polar::Analyzer;
use crate::render::Context;
use crate::scene::Scene;
use crate::shading::polarized::{polarizer_sheet, segment_transmittance, smooth_crystal};
use crate::shading::{self, Arrival, Event, Surface};
use crate::spectrum::Carrier;

/// Why polarized transport refuses scattering media (the plan's and the render's refusal).
pub const WHY_NO_MEDIA: &str = "a scattering event's phase function (Henyey–Greenstein, \
Rayleigh) is a scalar here, with no Mueller matrix to carry a path's analyzer through it";

/// Why polarized camera paths are not traced in lanes (the plan's "lanes" stage).
pub const WHY_SINGLE_RAYS: &str = "the lanes step 8 or 16 paths through the path tracer's \
vertex, which carries a throughput alone; a polarized path also carries its analyzer and \
crystal mode through its own vertex, one ray at a time";

/// Why a polarized path keeps its hero at a dispersive interface (the plan's "polarization"
/// stage).
pub const WHY_NO_SPLIT: &str = "no wavelength split: from a crystal, a smooth dispersive \
interface or a measured metal on a polarized path keeps its hero wavelength alone; the split \
into 4 sub-paths belongs to the path tracer's vertex, which polarized paths do not use";

/// What the camera of a polarized render looks through.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polarization {
    /// A linear polarizer in front of the camera, its transmission axis at this angle
    /// (radians) from the image's horizontal, counter-clockwise as the viewer sees it;
    /// `None`: no filter.
    pub polarizer: Option<f32>,
}

impl Polarization {
    /// The analyzer of a camera ray along `dir` for a camera whose image right and up are
    /// `basis` (world, unit).
    pub fn analyzer(&self, (right, up): (glam::Vec3, glam::Vec3), dir: glam::Vec3) -> Analyzer {
        match self.polarizer {
            Some(angle) => Analyzer::polarizer(dir, right, up, angle),
            None => Analyzer::open(dir, up),
        }
    }
}

/// A caustic map's gather at a polarized camera vertex: the radiance its photons reflect
/// toward the camera as read by the path's analyzer there (the analyzer of the light
/// leaving the vertex), [`crate::integrator::caustic::CausticMap::density_polarized`].
pub type PolarizedGather<'a, C> =
    &'a (dyn Fn(&Surface<C>, &<C as Carrier>::Lambda, &Analyzer) -> C + Sync);

/// The polarized radiance along the camera `ray` seen through `analyzer` at the
/// wavelengths `lambda` (the hero alone from a crystal, a dispersive interface or a
/// measured metal on, [`Carrier::keep_hero`]); with `gather`, the caustic paths are the
/// map's (module docs).
pub fn radiance<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    (max_depth, gather): (u32, Option<PolarizedGather<'_, C>>),
    mut lambda: C::Lambda,
    analyzer: Analyzer,
    ctx: &mut Context,
) -> C {
    let mut st = PathState::<C>::new(ray.origin);
    let mut walk = Polarized {
        ray: *ray,
        pol: analyzer,
        crystal: None,
        l: C::ZERO,
    };
    loop {
        let at = shading::arrive::<C>(scene, &walk.ray, &st.media, &lambda, &mut ctx.rays);
        let rules = (max_depth, gather);
        if !vertex(scene, rules, &mut walk, &mut st, at, &mut lambda, ctx) {
            return walk.l;
        }
    }
}

/// A polarized camera path between vertices.
struct Polarized<C: Carrier> {
    ray: Ray,
    pol: Analyzer,
    crystal: Option<InMode>,
    l: C,
}

/// One vertex; `false` when the path ends.
fn vertex<C: Carrier>(
    scene: &Scene,
    (max_depth, gather): (u32, Option<PolarizedGather<'_, C>>),
    w: &mut Polarized<C>,
    st: &mut PathState<C>,
    arrival: Option<Arrival<'_, C>>,
    lambda: &mut C::Lambda,
    ctx: &mut Context,
) -> bool {
    // Light closing a caustic chain is the map's (the hybrid's split, `CausticPaths`).
    let h = st.history(max_depth);
    let caustic = gather.is_some() && h.closes_caustic();
    let Some(at) = arrival else {
        if let (Some(e), false) = (escaped(scene, &w.ray, &st.prev, st.beta, lambda), caustic) {
            w.l += e * w.pol.unpolarized();
        }
        return false;
    };
    let mut u = ctx.sample.bounce(st.vertex);
    // A smooth crystal surface: its numbers (reflect or refract, which mode, the mode of a
    // path met inside in none) and the hero alone (the modes depend on the wavelength).
    let crystal = smooth_crystal(&at).zip(C::hero(lambda));
    let uc = crystal.map(|_| (u.bsdf_lobe(), u.bsdf_direction()));
    if let (Some((c, nm)), Some((_, ud))) = (crystal, uc) {
        st.beta = st.beta.keep_hero(lambda);
        if w.crystal.is_none() && w.ray.dir.dot(at.hit.ng) > 0.0 {
            // Inside the crystal in no mode: the path started inside, or left a surface
            // inside that is not the crystal's. Its mode is chosen now, for the segment
            // just travelled (its absorption is the mode's).
            let d = w.ray.dir.normalize();
            let Some((mode, pol)) = crystal_step::start(&c.at(nm), d, &w.pol, ud.y) else {
                return false;
            };
            w.crystal = Some(mode);
            w.pol = pol;
        }
    }
    let mode_d = w.crystal.map(|m| m.d);
    st.beta *= segment_transmittance(scene, &st.media, mode_d, &at, lambda);
    if let (Some(e), false) = (emitted(scene, &at, &st.prev, st.beta, lambda), caustic) {
        w.l += e * w.pol.unpolarized();
    }
    if let Some(axis) = polarizer_sheet(&at) {
        // An ideal polarizer sheet: straight through, the analyzer times the sheet's
        // polarizer with its axis made ⊥ the light.
        let k = w.pol.k;
        let x = transverse(axis, k);
        w.pol = w.pol.through(&linear_polarizer(0.0), x, x, k, 1.0);
        w.ray = at.hit.spawn_ray(w.ray.dir);
        return st.delta_bounce(at.hit.p);
    }
    if let (Some((c, nm)), Some((lobe, ud))) = (crystal, uc) {
        return crystal_vertex(scene, (c, nm), w, st, &at, lambda, (lobe, ud.x));
    }
    w.crystal = None;
    let s = match at.event(scene, st.media, &mut st.beta, lambda, &mut u) {
        Event::PassThrough(next) => {
            w.ray = next;
            return true;
        }
        Event::Scatter(s) => s,
    };
    if s.bsdf.hero_polarizes() {
        st.beta = st.beta.keep_hero(lambda);
    }
    let lambda = &*lambda;
    let k_out = s.hit.wo;
    if !s.bsdf.is_delta() {
        let ls = next_event(
            scene,
            &Scatterer::Surface(&s),
            lambda,
            true,
            &mut u,
            &mut ctx.rays,
        );
        if ls.shadow.is_some() {
            let a = surface::through(&w.pol, &s.bsdf, &s.frame, (k_out, ls.wi));
            let v = pending(st.beta, ls, None).transmitted(scene, lambda, &mut ctx.rays);
            w.l += st.beta * v * a.unpolarized();
        }
        if let Some(g) = gather.filter(|_| h.first_diffuse()) {
            w.l += st.beta * g(&s, lambda, &w.pol);
        }
    }
    let uc = u.bsdf_lobe();
    let ud = u.bsdf_direction_if(s.bsdf.samples_direction());
    let Some(bs) = s.sample(uc, ud, TransportMode::Radiance) else {
        return false;
    };
    let wi = s.frame.to_world(bs.wi);
    w.pol = surface::through(&w.pol, &s.bsdf, &s.frame, (k_out, wi));
    if !st.advance(&s, &bs, max_depth, &mut u) {
        return false;
    }
    w.ray = s.spawn(bs.wi);
    st.vertex += 1;
    true
}

/// The vertex at a smooth crystal surface ([`crystal_step::bounce`]).
fn crystal_vertex<C: Carrier>(
    scene: &Scene,
    (crystal, nm): (&CrystalDesc, f32),
    w: &mut Polarized<C>,
    st: &mut PathState<C>,
    at: &Arrival<'_, C>,
    lambda: &C::Lambda,
    u: (f32, f32),
) -> bool {
    let (n_i, n_t, beyond, _) =
        shading::interface::<C>(scene, &at.hit, &at.coincident, st.media, lambda);
    let d = w.ray.dir.normalize();
    let n = at.hit.ng;
    let entering = d.dot(n) < 0.0;
    let n_outside = if entering { n_i } else { n_t };
    let state = if entering { None } else { w.crystal };
    let Some(b) = crystal_step::bounce(&crystal.at(nm), (n, n_outside), d, state, &w.pol, u) else {
        return false;
    };
    st.beta *= b.radiance;
    if b.radiance > 0.0 && b.radiance != 1.0 {
        st.eta_scale /= b.radiance;
    }
    if b.crossed {
        st.media = beyond;
    }
    if !st.delta_bounce(at.hit.p) {
        return false;
    }
    w.pol = b.analyzer;
    w.crystal = b.inside;
    w.ray = at.hit.spawn_ray(b.dir);
    st.vertex += 1;
    true
}
