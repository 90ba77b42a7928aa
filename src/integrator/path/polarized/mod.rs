//! The polarized path tracer (`--polarization on`, chosen by the plan for scenes with a
//! birefringent crystal or a polarizer on the camera): the path tracer's loop at one
//! wavelength per path (the hero; the crystals' indices are dispersive and the modes' paths
//! differ by wavelength), carrying an [`Analyzer`] — the row vector a with a·S the pixel's
//! reading of light of Stokes vector S ([`crate::polar::stokes`]).
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
//! Not handled here: scattering media (the plan refuses them with polarization), the
//! caustic map. Rough crystals scatter as isotropic dielectrics with their mean index.

mod crystal_step;
mod surface;

use super::light_sample::{next_event, Scatterer};
use super::state::PathState;
use super::vertex::{emitted, escaped};
use crate::bsdf::{TransportMode, SMOOTH_ALPHA};
use crate::material::CrystalDesc;
use crate::math::Ray;
use crate::polar::stokes::{linear_polarizer, transverse};
use crate::polar::Analyzer;
use crate::render::Context;
use crate::scene::Scene;
use crate::shading::{self, media, Arrival, Event};
use crate::spectrum::Carrier;
use crystal_step::InCrystal;

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

/// The polarized radiance along the camera `ray` seen through `analyzer`, at the hero of
/// `lambda` (the others are dropped at once, [`Carrier::keep_hero`]).
pub fn radiance<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    max_depth: u32,
    mut lambda: C::Lambda,
    analyzer: Analyzer,
    ctx: &mut Context,
) -> C {
    let mut st = PathState::<C>::new(ray.origin);
    st.beta = st.beta.keep_hero(&mut lambda);
    let mut walk = Polarized {
        ray: *ray,
        pol: analyzer,
        crystal: None,
        l: C::ZERO,
    };
    loop {
        let at = shading::arrive::<C>(scene, &walk.ray, &st.media, &lambda, &mut ctx.rays);
        if !vertex(scene, max_depth, &mut walk, &mut st, at, &lambda, ctx) {
            return walk.l;
        }
    }
}

/// A polarized camera path between vertices.
struct Polarized<C: Carrier> {
    ray: Ray,
    pol: Analyzer,
    crystal: Option<InCrystal>,
    l: C,
}

/// One vertex; `false` when the path ends.
fn vertex<C: Carrier>(
    scene: &Scene,
    max_depth: u32,
    w: &mut Polarized<C>,
    st: &mut PathState<C>,
    arrival: Option<Arrival<'_, C>>,
    lambda: &C::Lambda,
    ctx: &mut Context,
) -> bool {
    let Some(at) = arrival else {
        if let Some(e) = escaped(scene, &w.ray, &st.prev, st.beta, lambda) {
            w.l += e * w.pol.unpolarized();
        }
        return false;
    };
    st.beta *= segment_transmittance(scene, st, w, &at, lambda);
    if let Some(e) = emitted(scene, &at, &st.prev, st.beta, lambda) {
        w.l += e * w.pol.unpolarized();
    }
    if let Some(axis) = at.mat.desc.polarizer.filter(|_| at.sp.transmission > 0.0) {
        // An ideal polarizer sheet: straight through, the analyzer times the sheet's
        // polarizer with its axis made ⊥ the light.
        let k = w.pol.k;
        let x = transverse(axis, k);
        w.pol = w.pol.through(&linear_polarizer(0.0), x, x, k, 1.0);
        w.ray = at.hit.spawn_ray(w.ray.dir);
        return true;
    }
    let mut u = ctx.sample.bounce(st.vertex);
    if let (Some(crystal), Some(nm)) = (smooth_crystal(&at), C::hero(lambda)) {
        let uc = (u.bsdf_lobe(), u.bsdf_direction().x);
        return crystal_vertex(scene, (crystal, nm), w, st, &at, lambda, uc);
    }
    w.crystal = None;
    let s = match at.event(scene, st.media, &mut st.beta, &mut lambda.clone(), &mut u) {
        Event::PassThrough(next) => {
            w.ray = next;
            return true;
        }
        Event::Scatter(s) => s,
    };
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
        if let Some(shadow) = ls.shadow {
            let a = surface::through(&w.pol, &s.bsdf, &s.frame, (k_out, ls.wi));
            let v = match ls.through {
                Some(m) => ls.value * media::shadow::<C>(scene, &shadow, m, lambda, &mut ctx.rays),
                None if !scene.occluded(&shadow) => ls.value,
                None => C::ZERO,
            };
            w.l += st.beta * v * a.unpolarized();
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

/// The crystal at an arrival if its material is one and smooth there.
fn smooth_crystal<'a, C: Carrier>(at: &Arrival<'a, C>) -> Option<&'a CrystalDesc> {
    let c = at.mat.desc.crystal.as_ref()?;
    let smooth = at.sp.roughness * at.sp.roughness < SMOOTH_ALPHA;
    (smooth && at.mat.is_volume() && at.sp.transmission > 0.0).then_some(c)
}

/// The transmittance of the segment just travelled: inside a crystal with an absorption
/// table, e^(−σ_m t) for the mode's σ_m; elsewhere the arrival's (Beer–Lambert).
fn segment_transmittance<C: Carrier>(
    scene: &Scene,
    st: &PathState<C>,
    w: &Polarized<C>,
    at: &Arrival<'_, C>,
    lambda: &C::Lambda,
) -> C {
    let crystal = st
        .media
        .current()
        .and_then(|m| scene.materials()[m as usize].desc.crystal.as_ref());
    match (crystal, w.crystal, C::hero(lambda)) {
        (Some(c), Some(mode), Some(nm)) => {
            let sigma = c.absorption(nm);
            if sigma == [0.0; 3] {
                return at.transmittance;
            }
            let s = c.at(nm).absorption(mode.d, sigma);
            C::splat((-s * at.hit.t).exp())
        }
        _ => at.transmittance,
    }
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
    st.prev = super::state::Prev {
        delta: true,
        pdf: 0.0,
        p: at.hit.p,
    };
    st.delta_depth += 1;
    if st.delta_depth > shading::MAX_DELTA_BOUNCES {
        return false;
    }
    w.pol = b.analyzer;
    w.crystal = b.inside;
    w.ray = at.hit.spawn_ray(b.dir);
    st.vertex += 1;
    true
}
