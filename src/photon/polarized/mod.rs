//! Polarized photon paths (the polarized hybrid's caustic photons,
//! [`crate::integrator::hybrid`]): a photon carrying its light as one Stokes vector
//! ([`Light`]: s₀ = 1, the scalar power per wavelength in the carrier) through the same
//! per-hit step as [`super::trace`]. Its 4 wavelengths share the Stokes vector until a
//! crystal (whose indices and modes depend on the wavelength), a dispersive interface or a
//! measured metal ([`crate::bsdf::Bsdf::hero_polarizes`]); from there on it carries the hero alone.
//!
//! At each hit, with the light arriving along its direction k:
//! - an ideal polarizer sheet (`extras.iris_polarizer`) passes P·S straight through;
//! - a smooth birefringent crystal splits it into its modes ([`crystal`]), the photon
//!   moving along the mode's ray direction and absorbed per mode inside
//!   ([`segment_transmittance`]);
//! - any other surface samples its BSDF in importance mode, the power times the scalar
//!   weight f·|cos|/pdf and the polarization factor (N·S)₀, the light becoming N·S / (N·S)₀
//!   (N the surface's normalized Mueller matrix, [`crate::shading::polarized::mueller`];
//!   a depolarizing BSDF leaves it unpolarized). Since the scalar weight is the BSDF's
//!   response to unpolarized light, the photon's expected power is the polarized one.
//!
//! Every non-delta hit is reported with the light arriving there. Sheets and crystal
//! surfaces count as delta bounces, as on the camera side. Russian roulette on the
//! throughput's change (survivors keep their power: Jensen 2001 §5.1). Scattering media are
//! not traced (the plan refuses them with polarization). A photon of a light inside a
//! crystal (or leaving a surface inside one) is in no mode until it meets the crystal's
//! surface from inside; it takes the mode its segment ran in there
//! ([`crystal::start`]), as camera paths starting inside do.

mod crystal;

use super::emit::EmittedPhoton;
use super::trace::PhotonVertex;
use crate::bsdf::TransportMode;
use crate::math::{Ray, Rng};
use crate::medium_stack::MediumStack;
use crate::polar::modes::InMode;
use crate::polar::stokes::{linear_polarizer, transverse, Light};
use crate::scene::Scene;
use crate::shading::polarized::{polarizer_sheet, s_basis, segment_transmittance, smooth_crystal};
use crate::shading::{self, Arrival, Event, MAX_DELTA_BOUNCES};
use crate::spectrum::Carrier;
use glam::Vec2;

/// A photon between hits.
struct Flight<C: Carrier> {
    beta: C,
    lambda: C::Lambda,
    ray: Ray,
    light: Light,
    media: MediumStack,
    /// The crystal mode it is in (`None` outside a crystal).
    mode: Option<InMode>,
}

/// What a hit did to the photon.
struct Bounce<C> {
    /// The power factor, before roulette.
    weight: C,
    /// A delta bounce (not counted against the depth limit).
    delta: bool,
    /// The surface scatters diffusely (the path is no longer all specular).
    diffuse: bool,
}

/// Traces one photon at the wavelengths `lambda` with at most `max_depth` non-delta bounces;
/// `store(vertex, light, lambda)` is called at every non-delta hit. Returns the rays traced.
pub fn trace<C: Carrier>(
    scene: &Scene,
    photon: &EmittedPhoton,
    lambda: C::Lambda,
    max_depth: u32,
    rng: &mut Rng,
    mut store: impl FnMut(&PhotonVertex<C>, &Light, &C::Lambda),
) -> u64 {
    let mut f = Flight {
        beta: C::emitted(photon.power, photon.shape, &lambda),
        lambda,
        ray: photon.ray,
        light: Light::unpolarized(photon.ray.dir),
        media: MediumStack::new(),
        mode: None,
    };
    let (mut bounces, mut depth, mut delta_depth) = (0u32, 0u32, 0u32);
    let mut all_specular = true;
    let mut rays = 0u64;
    while let Some(at) = shading::arrive::<C>(scene, &f.ray, &f.media, &f.lambda, &mut rays) {
        if bounces == 0 && photon.range.is_some() {
            f.beta *= crate::light::range_window(at.hit.t, photon.range);
        }
        if !start_in_crystal(&mut f, &at, rng) {
            break;
        }
        f.beta *= segment_transmittance(scene, &f.media, f.mode.map(|m| m.d), &at, &f.lambda);
        if f.beta == C::ZERO {
            break;
        }
        let caustic = bounces > 0 && all_specular;
        let visit = |v: &PhotonVertex<C>, light: &Light, l: &C::Lambda| store(v, light, l);
        let Some(b) = hit(scene, &mut f, &at, rng, (bounces, caustic), visit) else {
            break;
        };
        let Some(b) = b else {
            continue;
        };
        let new_beta = f.beta * b.weight;
        if !new_beta.is_finite() {
            break;
        }
        let Some(beta) = super::trace::survive(f.beta, new_beta, rng) else {
            break;
        };
        f.beta = beta;
        all_specular &= !b.diffuse;
        bounces += 1;
        if b.delta {
            delta_depth += 1;
            if delta_depth > MAX_DELTA_BOUNCES {
                break;
            }
        } else {
            depth += 1;
            if depth >= max_depth {
                break;
            }
        }
    }
    rays
}

/// A photon meeting a smooth crystal's surface from inside in no mode (its light is
/// inside the crystal, or it left a surface inside that is not the crystal's) takes the
/// mode it travelled the segment in now ([`crystal::start`]), before the segment's
/// absorption, which is the mode's; its hero alone from there. `false` when nothing of
/// its light is in either mode.
fn start_in_crystal<C: Carrier>(f: &mut Flight<C>, at: &Arrival<'_, C>, rng: &mut Rng) -> bool {
    let (Some(c), Some(nm), None) = (smooth_crystal(at), C::hero(&f.lambda), f.mode) else {
        return true;
    };
    let d = f.ray.dir.normalize();
    if d.dot(at.hit.ng) <= 0.0 {
        return true;
    }
    f.beta = f.beta.keep_hero(&mut f.lambda);
    match crystal::start(&c.at(nm), d, &f.light, rng.next_f32()) {
        Some((mode, light, power)) => {
            f.mode = Some(mode);
            f.light = light;
            f.beta *= C::splat(power);
            true
        }
        None => false,
    }
}

/// The photon `f` at the hit `at` (`bounces` so far, a `caustic` path so far): stores a
/// non-delta vertex with `store` and sets the photon's next ray, light, media and mode.
/// `None` when the photon ends; `Some(None)` when it passed through without a bounce
/// (BLEND coverage).
fn hit<C: Carrier>(
    scene: &Scene,
    f: &mut Flight<C>,
    at: &Arrival<'_, C>,
    rng: &mut Rng,
    (bounces, caustic): (u32, bool),
    mut store: impl FnMut(&PhotonVertex<C>, &Light, &C::Lambda),
) -> Option<Option<Bounce<C>>> {
    if let Some(axis) = polarizer_sheet(at) {
        let k = f.light.k;
        let x = transverse(axis, k);
        let (light, weight) = f.light.after(&linear_polarizer(0.0), x, x, k)?;
        f.light = light;
        f.ray = at.hit.spawn_ray(f.ray.dir);
        return Some(Some(Bounce {
            weight: C::splat(weight),
            delta: true,
            diffuse: false,
        }));
    }
    if let (Some(c), Some(nm)) = (smooth_crystal(at), C::hero(&f.lambda)) {
        f.beta = f.beta.keep_hero(&mut f.lambda);
        let (n_i, n_t, beyond, _) =
            shading::interface::<C>(scene, &at.hit, &at.coincident, f.media, &f.lambda);
        let d = f.ray.dir.normalize();
        let n = at.hit.ng;
        let entering = d.dot(n) < 0.0;
        let n_outside = if entering { n_i } else { n_t };
        let state = if entering { None } else { f.mode };
        let u = (rng.next_f32(), rng.next_f32());
        let step = crystal::bounce(&c.at(nm), (n, n_outside), d, state, &f.light, u)?;
        if step.crossed {
            f.media = beyond;
        }
        f.mode = step.inside;
        f.light = step.light;
        f.ray = at.hit.spawn_ray(step.dir);
        return Some(Some(Bounce {
            weight: C::splat(step.weight),
            delta: true,
            diffuse: false,
        }));
    }
    f.mode = None;
    let ev = at.event(scene, f.media, &mut f.beta, &mut f.lambda, rng);
    let s = match &ev {
        Event::PassThrough(next) => {
            f.ray = *next;
            return Some(None);
        }
        Event::Scatter(s) => s,
    };
    if s.bsdf.hero_polarizes() {
        f.beta = f.beta.keep_hero(&mut f.lambda);
    }
    if !s.bsdf.is_delta() {
        let v = PhotonVertex {
            p: s.hit.p,
            wi: s.hit.wo,
            power: f.beta,
            bounces,
            caustic,
            surface: s,
        };
        store(&v, &f.light, &f.lambda);
    }
    let uc = rng.next_f32();
    let u = Vec2::new(rng.next_f32(), rng.next_f32());
    let bs = s.sample(uc, u, TransportMode::Importance)?;
    let wi = s.frame.to_world(bs.wi);
    let (light, factor) = match s.bsdf.mueller(bs.wi, s.wo) {
        Some((n, m)) => {
            let x = s_basis(f.light.k, s.frame.to_world(m), f.light.x);
            f.light.after(&n, x, x, wi)?
        }
        None => (Light::unpolarized(wi), 1.0),
    };
    f.light = light;
    f.media = s.media_after(bs.transmission);
    f.ray = s.spawn(bs.wi);
    Some(Some(Bounce {
        weight: bs.f * (bs.wi.z.abs() / bs.pdf * factor),
        delta: bs.delta,
        diffuse: s.bsdf.is_diffuse_like(),
    }))
}
