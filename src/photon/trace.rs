//! Photon paths: a photon from [`super::emit`] followed through the scene with the
//! per-hit step camera paths take too ([`crate::shading::step`]: coincident faces, BLEND
//! coverage, the BSDF, the medium stack and η), sampling the BSDFs in importance mode
//! ([`TransportMode::Importance`]: no 1/η'² factor on refraction, pbrt-v4 §9.5.2) and
//! Beer–Lambert attenuation in media. Every non-delta hit is reported to the caller, which
//! keeps what its estimator needs (a caustic map keeps L S+ D, SPPM keeps everything after
//! the first bounce).
//!
//! Spectral transport: the photon carries the 4 wavelengths it was given (one random set
//! per photon for `--method photon`, the pass's shared set for SPPM); a dispersive interface
//! keeps only the hero, as for camera paths ([`Carrier::keep_hero`]).
//!
//! Russian roulette ([`Roulette`]): by default on the throughput (survival = the ratio of
//! the new to the old throughput's largest channel, capped at 1, so a surviving photon keeps
//! its power: Jensen 2001 §5.1); or by lobe (`--photon-rr lobe`), the rule of Cropp &
//! Zhang, "Light Refraction with Dispersion", the paper Iris grew from, which picks diffuse
//! reflection, specular reflection or refraction by the magnitudes of the material's
//! colours and absorbs otherwise (Jensen 2001 §2.4 / Cropp & Zhang §4.5), ignoring
//! Fresnel's angle dependence and roughness — kept to reproduce the paper's figures.
//!
//! Lights are assumed to be outside every volume (the photon starts with an empty medium
//! stack, like camera rays).

use super::emit::EmittedPhoton;
use crate::bsdf::{cosine_direction, Bsdf, RouletteLobes, TransportMode};
use crate::interaction::{Leave, SurfaceHit};
use crate::math::Rng;
use crate::medium_stack::MediumStack;
use crate::scene::Scene;
use crate::shading::media::Ends;
use crate::shading::termination::{roulette, throughput_roulette, Bounces, Draw};
use crate::shading::{self, media, Arrival, Event, Surface};
use crate::spectrum::Carrier;
use crate::volume::coarse::Scale;
use glam::{Vec2, Vec3};
use std::ops::ControlFlow;

/// How photon paths are terminated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Roulette {
    /// Survival probability from the throughput change; survivors keep their power.
    #[default]
    Throughput,
    /// One lobe (diffuse / reflect / refract) or absorption, chosen by the magnitudes of the
    /// material's diffuse, specular and transmission colours (Cropp & Zhang's rule).
    Lobe,
}

impl Roulette {
    /// Parses `--photon-rr throughput|lobe` ([`crate::error::parse_name`]); `seed`, the
    /// value's former name, is still accepted for `lobe`.
    pub fn parse(s: &str) -> crate::error::Result<Roulette> {
        if s.trim().eq_ignore_ascii_case("seed") {
            return Ok(Roulette::Lobe);
        }
        let names = [
            ("throughput", Roulette::Throughput),
            ("lobe", Roulette::Lobe),
        ];
        crate::error::parse_name("--photon-rr", s, &names)
    }
}

/// Photon tracing limits.
#[derive(Debug, Clone, Copy)]
pub struct TraceSettings {
    /// Most non-delta bounces (delta bounces are limited by
    /// [`MAX_DELTA_BOUNCES`](crate::shading::MAX_DELTA_BOUNCES)).
    pub max_depth: u32,
    /// Termination rule.
    pub roulette: Roulette,
}

/// A photon arriving at a non-delta surface.
#[derive(Debug, Clone, Copy)]
pub struct PhotonVertex<'s, C: Carrier> {
    /// Position.
    pub p: Vec3,
    /// Unit direction back toward where the photon came from (world).
    pub wi: Vec3,
    /// Flux carried (the emitted photon's power times the path's throughput).
    pub power: C,
    /// Bounces before this hit (0: straight from the light).
    pub bounces: u32,
    /// The path so far is L S+ (at least one bounce, all specular or near-specular): a
    /// caustic photon.
    pub caustic: bool,
    /// The surface there (hit, BSDF, shading frame; its `wo` is `wi` in the frame): what
    /// connecting the vertex to the camera needs ([`crate::integrator::light_trace`]).
    pub surface: &'s Surface<C>,
}

/// A photon scattering in a medium ([`crate::volume`], [`trace_in_media`]).
#[derive(Debug, Clone, Copy)]
pub struct MediumVertex {
    /// Position.
    pub p: Vec3,
    /// Unit direction back toward where the photon came from (world).
    pub wi: Vec3,
    /// Bounces before this event (0: straight from the light).
    pub bounces: u32,
    /// The path so far is L S+ (at least one bounce, all delta or near-specular): a
    /// volumetric caustic photon.
    pub caustic: bool,
}

/// What a photon's flight through a medium did ([`scatter_in_medium`]).
enum Flight {
    /// It reached the surface (or escaped).
    Pass,
    /// It scattered; its ray is the new direction.
    Scattered,
    /// Roulette ended it.
    Absorbed,
}

/// Free flight of a photon (`beta`, `lambda` along `ray` between its `ends`): a chromatic
/// medium keeps the hero only, then [`media::fly`] (at the fine scale: photon walks count
/// every event against `max_depth`). At a scattering event `store(vertex, power, lambda)` is
/// called (the vertex's `bounces` and `caustic` are the caller's to fill; `Break` ends the
/// photon there, [`Flight::Absorbed`]), the photon is rouletted on the flight's weight (survivors keep their power), the light's range window
/// `range` applied on its first flight, and the photon leaves along a phase-sampled
/// direction as the event lets it ([`media::Scattered::leave`]): `ray` and `next` set.
/// `next` says where `ray` left from (a free point of a medium: `media` are checked first,
/// [`media::starting`]), `at` what it meets.
fn scatter_in_medium<C: Carrier>(
    (scene, media, at): (&Scene, &mut MediumStack, Option<&Arrival<'_, C>>),
    (beta, lambda, ray): (&mut C, &mut C::Lambda, &mut crate::math::Ray),
    (range, next): (Option<f32>, &mut Leaving),
    rng: &mut Rng,
    store: impl FnOnce(MediumVertex, C, &C::Lambda) -> ControlFlow<()>,
) -> Flight {
    if let Leaving::Point = next {
        *media = media::starting(scene, *media, at.map(|a| (&a.hit, &a.coincident)));
    }
    let from = match *next {
        Leaving::Surface(h) => Some(h),
        _ => None,
    };
    let ends = Ends {
        from: from.as_ref(),
        meets: at.map(|a| &a.hit),
    };
    let before = beta.max_element();
    let t_hit = ends.meets.map_or(f32::INFINITY, |h| h.t);
    media::keep_hero_in(scene, ray, t_hit, media, (&mut *beta, &mut *lambda));
    let values = (&mut *beta, &mut *lambda);
    let Some(sc) = media::fly(scene, (ray, ends), media, Scale::FINE, values, rng) else {
        return Flight::Pass;
    };
    let wo = -ray.dir.normalize();
    let survive = if before > 0.0 {
        (beta.max_element() / before).min(1.0)
    } else {
        0.0
    };
    if range.is_some() {
        *beta *= crate::light::range_window((sc.p - ray.origin).length(), range);
    }
    let v = MediumVertex {
        p: sc.p,
        wi: wo,
        bounces: 0,
        caustic: false,
    };
    if store(v, *beta, lambda).is_break() {
        return Flight::Absorbed;
    }
    let Some(survive) = roulette(survive, Draw::UnlessDead, || rng.next_f32()) else {
        return Flight::Absorbed;
    };
    if !beta.is_finite() {
        return Flight::Absorbed;
    }
    *beta /= survive;
    let (wi, _) = sc
        .phase
        .sample(wo, Vec2::new(rng.next_f32(), rng.next_f32()));
    *next = match sc.leave(wi) {
        Leave::Ray(r) => {
            *ray = r;
            match sc.band {
                Some(b) => Leaving::Surface(*b.surface()),
                None => Leaving::Point,
            }
        }
        Leave::Meets { hit, distance } => {
            *ray = crate::math::Ray {
                t_max: distance,
                ..crate::math::Ray::new(sc.p, wi)
            };
            Leaving::Meets(hit)
        }
    };
    Flight::Scattered
}

/// Where a photon's ray leaves from and what it meets untraced (the path tracer keeps the
/// same in its `PathState::from` and `meet`).
#[derive(Debug, Clone, Copy)]
enum Leaving {
    /// The light (or an unknown surface).
    Light,
    /// A surface, its origin offset from it ([`crate::math::Ray::skipped`]).
    Surface(SurfaceHit),
    /// A free point of a medium ([`media::starting`] checks its media).
    Point,
    /// A band point toward its surface: it meets that surface untraced.
    Meets(SurfaceHit),
}

/// One step of [`Roulette::Lobe`] at local `wo`: the new local direction and the
/// colour factor, `None` when absorbed.
fn lobe_step<C: Carrier>(bsdf: &Bsdf<C>, wo: Vec3, rng: &mut Rng) -> Option<(Vec3, C, bool)> {
    let RouletteLobes {
        diffuse: d,
        specular: s,
        transmission: t,
    } = bsdf.roulette_lobes();
    let (pd, ps, pt) = (d.average(), s.average(), t.average());
    let xi = rng.next_f32();
    if xi < pd {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let wi = cosine_direction(wo, u)?;
        Some((wi, d / pd, false))
    } else if xi < pd + ps {
        Some((Vec3::new(-wo.x, -wo.y, wo.z), s / ps, false))
    } else if xi < pd + ps + pt {
        let wi = bsdf.roulette_transmission(wo);
        Some((wi, t / pt, wi.z * wo.z < 0.0))
    } else {
        None
    }
}

/// The photon's next direction at surface `s` under `roulette` (throughput roulette:
/// survival = the throughput's change, survivors keep their power; or by lobe), updating
/// `beta`: (direction, whether it is a transmission, whether the bounce counts as delta);
/// `None` when the photon ends.
fn next_direction<C: Carrier>(
    s: &Surface<C>,
    roulette: Roulette,
    beta: &mut C,
    rng: &mut Rng,
) -> Option<(Vec3, bool, bool)> {
    Some(match roulette {
        Roulette::Throughput => {
            let uc = rng.next_f32();
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            let bs = s.sample(uc, u, TransportMode::Importance)?;
            let new = *beta * bs.f * (bs.wi.z.abs() / bs.pdf);
            *beta = throughput_roulette(*beta, new, || rng.next_f32())?;
            (bs.wi, bs.transmission, bs.delta)
        }
        Roulette::Lobe => {
            let (wi, colour, transmission) = lobe_step(&s.bsdf, s.wo, rng)?;
            *beta *= colour;
            (
                wi,
                transmission,
                !s.bsdf.is_diffuse_like() || s.bsdf.is_delta(),
            )
        }
    })
}

/// Traces one photon; `store(vertex, lambda)` is called at every non-delta hit with the
/// photon's wavelengths at that point (hero-only after a dispersive interface). Returns the
/// number of rays traced.
pub fn trace<C: Carrier>(
    scene: &Scene,
    photon: &EmittedPhoton,
    lambda: C::Lambda,
    settings: &TraceSettings,
    rng: &mut Rng,
    mut store: impl FnMut(&PhotonVertex<C>, &C::Lambda),
) -> u64 {
    let store = |v: &PhotonVertex<C>, l: &C::Lambda| {
        store(v, l);
        ControlFlow::Continue(())
    };
    trace_in_media(scene, photon, lambda, settings, rng, store, |_, _, _| {
        ControlFlow::Continue(())
    })
}

/// [`trace`], also reporting the photon's scattering events in media:
/// `store_medium(vertex, power, lambda)` with the flux scattered there (the free-flight
/// weight σ_s e^(−σ_t t) / p included, [`crate::shading::media::fly`]). In a scene with
/// media the photon flies through them as camera paths do, crosses index-matched
/// boundaries without a bounce ([`crate::shading::media::cross_matched`]), keeps only its
/// hero wavelength in a chromatic medium (so that its weights do not depend on which lane
/// is the hero, [`crate::shading::media::keep_hero_in`]), scatters by sampling the phase
/// function exactly (value / density = 1; phase functions are symmetric, so importance and
/// radiance transport agree) and is rouletted on the flight's weight. A medium event
/// counts as a non-delta bounce.
///
/// Either callback returning `Break` ends the photon at that event (no BSDF or phase
/// sample, no further ray): a caller that can store nothing more from this photon (the
/// caustic map, once the photon's first non-delta event says it is not caustic-origin)
/// saves the rest of its walk. The vertices reported before are those of the full walk.
pub fn trace_in_media<C: Carrier>(
    scene: &Scene,
    photon: &EmittedPhoton,
    mut lambda: C::Lambda,
    settings: &TraceSettings,
    rng: &mut Rng,
    mut store: impl FnMut(&PhotonVertex<C>, &C::Lambda) -> ControlFlow<()>,
    mut store_medium: impl FnMut(&MediumVertex, C, &C::Lambda) -> ControlFlow<()>,
) -> u64 {
    let mut beta = C::emitted(photon.power, photon.shape, &lambda);
    let mut ray = photon.ray;
    let mut media = MediumStack::new();
    let (mut bounces, mut counts) = (0u32, Bounces::default());
    let mut all_specular = true;
    let mut rays = 0u64;
    let mut leaving = Leaving::Light;
    loop {
        let arrival = match leaving {
            Leaving::Meets(h) => shading::arrival::<C>(scene, &ray, Some(h), &media, &lambda),
            _ => shading::arrive::<C>(scene, &ray, &media, &lambda, &mut rays),
        };
        if scene.has_media() {
            let photon_state = (&mut beta, &mut lambda, &mut ray);
            let first = (bounces == 0).then_some(photon.range).flatten();
            let caustic = bounces > 0 && all_specular;
            let keep = |v: MediumVertex, power: C, l: &C::Lambda| {
                store_medium(
                    &MediumVertex {
                        bounces,
                        caustic,
                        ..v
                    },
                    power,
                    l,
                )
            };
            let at = (scene, &mut media, arrival.as_ref());
            match scatter_in_medium(at, photon_state, (first, &mut leaving), rng, keep) {
                Flight::Pass => {}
                Flight::Scattered => {
                    all_specular = false;
                    bounces += 1;
                    if !counts.bounce(false, settings.max_depth) {
                        break;
                    }
                    continue;
                }
                Flight::Absorbed => break,
            }
        }
        let Some(at) = &arrival else {
            break;
        };
        if bounces == 0 && photon.range.is_some() {
            beta *= crate::light::range_window(at.hit.t, photon.range);
        }
        if scene.has_media() {
            if let Some(after) =
                media::cross_matched::<C>(scene, &at.hit, &at.coincident, media, &lambda)
            {
                media = after;
                ray = at.hit.spawn_ray(-at.hit.wo);
                leaving = Leaving::Surface(at.hit);
                continue;
            }
        }
        beta *= at.transmittance;
        if beta == C::ZERO {
            break;
        }
        let ev = at.event(scene, media, &mut beta, &mut lambda, rng);
        let s = match &ev {
            Event::PassThrough(next) => {
                ray = *next;
                leaving = Leaving::Surface(at.hit);
                continue;
            }
            Event::Scatter(s) => s,
        };
        if !s.bsdf.is_delta() {
            let v = PhotonVertex {
                p: s.hit.p,
                wi: s.hit.wo,
                power: beta,
                bounces,
                caustic: bounces > 0 && all_specular,
                surface: s,
            };
            if store(&v, &lambda).is_break() {
                break;
            }
        }
        let Some((wi, transmission, delta)) = next_direction(s, settings.roulette, &mut beta, rng)
        else {
            break;
        };
        if !beta.is_finite() {
            break;
        }
        all_specular &= !s.bsdf.is_diffuse_like();
        media = s.media_after(transmission);
        bounces += 1;
        if !counts.bounce(delta, settings.max_depth) {
            break;
        }
        ray = s.spawn(wi);
        leaving = Leaving::Surface(s.hit);
    }
    rays
}

#[cfg(test)]
mod tests {
    use super::Roulette;

    #[test]
    fn photon_rr_names_and_the_former_seed_spelling() {
        assert_eq!(Roulette::parse("throughput").unwrap(), Roulette::Throughput);
        assert_eq!(Roulette::parse("lobe").unwrap(), Roulette::Lobe);
        assert_eq!(Roulette::parse("seed").unwrap(), Roulette::Lobe);
        let err = Roulette::parse("fast").unwrap_err().to_string();
        assert!(err.contains("throughput, lobe"), "{err}");
    }
}
