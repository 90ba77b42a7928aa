//! Photon emission: where photons start and how much flux each carries, for every light
//! type, the light chosen in proportion to the luminance of its flux.
//!
//! ## Units and frames
//! - World space, metres; directions are unit vectors along which the photon travels.
//! - Flux (`power`) is linear RGB in the lights' own units with no 683 lm/W factor:
//!   cd·sr for point and spot lights, lux·m² for directional light, radiance·m²·sr for
//!   emissive triangles and the environment.
//! - Each photon carries (its light's flux contribution) / (pdf of choosing the light, the
//!   point and the direction), so the mean of `power` over many `emit` calls is
//!   [`PhotonEmitter::total_power`] (the tracer divides the sum by the number emitted).
//!
//! ## Per light (flux Φ, sampling)
//! - Point: Φ = 4π·I, uniform sphere directions.
//! - Spot (KHR smooth falloff t(c)², t = clamp((c − cos_o)/(cos_i − cos_o)), as in
//!   [`crate::light`]): Φ = 2π·I·K with K = ∫_{cos_o}^1 t(c)² dc = (1 − cos_i) +
//!   (cos_i − cos_o)/3. cos θ is sampled exactly ∝ t² (inverse CDF), so every spot photon
//!   carries the same power and none leaves the outer cone.
//! - Directional and environment: photons start on a disc of radius r =
//!   [`DISC_MARGIN`] × the bounding-sphere radius of `scene.bounds`, perpendicular to the
//!   travel direction, centred r upstream of the bounding-sphere centre (so the disc lies
//!   outside the sphere and its shadow covers it; pbrt-v4 §12.4 `DistantLight::SampleLe`).
//!   Directional: Φ = E·π r². Environment: wi from [`crate::light::env::Environment::sample`],
//!   power = L(wi)/pdf(wi)·π r², Φ = π r²·∫L dω (a map's integral is the exact texel sum).
//! - Emissive triangles: triangle by power, point uniform by area, cosine-weighted
//!   direction about the outward normal (either side with probability ½ for double-sided
//!   materials); Φ = L·π·A per side. The emissive **texture** is applied at the sampled uv
//!   (the emitted flux is then the textured one), while [`PhotonEmitter::total_power`] and
//!   the selection use the emissive factor (exact for untextured emitters, an upper bound
//!   otherwise, since texels are ≤ 1).
//!
//! Scenes without geometry (infinite bounds) get no disc: their directional lights and
//! environment emit nothing.
//!
//! ## Aiming ([`Aim`], [`super::aim`])
//! With [`Aim::Mixture`]`(a)` the light is chosen as above, then with probability `a` the
//! direction (point, spot, emissive triangles: uniform in the cone toward one of the caustic
//! makers' bounding spheres, seen from the emission point) or the disc point (directional,
//! environment: uniform in one sphere's projection) is aimed, else drawn as above. The
//! photon's power is the light's contribution over the mixture density
//! (1 − a)·p_usual + a·p_aimed (a defensive mixture, Hesterberg 1995; Veach 1997 §9.2.1),
//! so the mean power is still [`PhotonEmitter::total_power`] for every `a`. Spot light
//! aimed outside its cone, or an emitter aimed behind its emitting side, gives no photon
//! (`None`: a zero-power sample, still counted). [`Aim::Only`] drops the usual term (see its
//! docs for what it keeps). Without caustic makers every aim is [`Aim::Off`] (and `Only`
//! emits nothing).
//!
//! ## Numbers
//! Every photon is a pure function of its five uniform numbers `u = [light, point (2),
//! direction (2)]` ([`PhotonEmitter::emit_aimed`]); the renderers draw them from
//! Halton dimensions 0–4 over the photon index, digit-permuted per seed
//! ([`PhotonNumbers`], [`PhotonEmitter::emit_index`]; pbrt-v4 SPPM draws its photon paths
//! from Halton over the photon index, src/pbrt/cpu/integrators.cpp). The aim choice and the sphere choice reuse the direction's
//! first number (the disc point's, for distant light), rescaled within the chosen interval.

use super::aim::Targets;
pub use super::aim::{Aim, DEFAULT_AIM};
use super::flux::{area_flux, area_point, environment_integral, punctual_flux};
pub use super::numbers::PhotonNumbers;
use crate::light::env::luminance;
use crate::light::sampler::{LightId, LightSampler};
use crate::math::{Ray, Rng};
use crate::scene::triangle::OFFSET_SCALE;
use crate::scene::Scene;
use crate::spectrum::EmitterShape;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

mod aimed;
mod densities;
use aimed::Mix;
pub use densities::Densities;

/// The directional/environment disc radius over the bounding-sphere radius (> 1, so disc
/// origins lie strictly outside the bounding sphere).
pub const DISC_MARGIN: f32 = 1.01;

/// One photon leaving a light.
#[derive(Debug, Clone, Copy)]
pub struct EmittedPhoton<'a> {
    /// Origin (on the light, or on the disc in front of the scene for distant light) and
    /// unit direction.
    pub ray: Ray,
    /// Linear RGB flux this photon carries = light flux contribution / (pdf of choosing the
    /// light, the point and the direction): the mean of `power` over many `emit` calls
    /// equals `total_power()`.
    pub power: Vec3,
    /// The emitter's exact spectral shape if it names one (`Carrier::emitted(power, shape,
    /// lambda)` converts it).
    pub shape: Option<&'a EmitterShape>,
    /// KHR_lights_punctual `range` of a point/spot light; the tracer multiplies by the range
    /// window at its first hit distance.
    pub range: Option<f32>,
    /// The light it left ([`Source`]): what the densities of [`PhotonEmitter::densities`]
    /// need.
    pub source: Source,
}

/// The light a photon left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    /// Punctual light `k` of [`Scene::lights`].
    Punctual(u32),
    /// Emissive triangle `prim`.
    Area(u32),
    /// The environment.
    Environment,
}

/// Chooses lights by power and emits photons from them (see the module docs).
#[derive(Debug, Clone)]
pub struct PhotonEmitter {
    /// The lights with positive power, chosen by the luminance of their flux.
    sampler: LightSampler,
    /// The RGB flux of each light of `sampler`, in its order.
    flux: Vec<Vec3>,
    /// Σ flux.
    total: Vec3,
    /// Bounding-sphere centre of the scene.
    centre: Vec3,
    /// Disc radius for distant light (0 without geometry).
    radius: f32,
    /// The caustic makers' bounding spheres.
    targets: Targets,
}

impl PhotonEmitter {
    /// Collects the scene's lights and their flux.
    pub fn new(scene: &Scene) -> PhotonEmitter {
        let (lo, hi) = scene.bounds();
        let (centre, radius) = if lo.is_finite() && hi.is_finite() && lo.cmple(hi).all() {
            let half = 0.5 * (hi - lo).length();
            // A point-like scene still gets a disc of positive area.
            let r = DISC_MARGIN * half.max(OFFSET_SCALE * (1.0 + lo.abs().max_element()));
            (0.5 * (lo + hi), r)
        } else {
            (Vec3::ZERO, 0.0)
        };
        let mut candidates: Vec<(LightId, Vec3)> = scene
            .lights()
            .iter()
            .enumerate()
            .map(|(k, l)| (LightId::Punctual(k as u32), punctual_flux(&l.light, radius)))
            .collect();
        if !scene.area_lights().is_empty() {
            candidates.push((LightId::Area, area_flux(scene)));
        }
        if let Some(env) = &scene.environment() {
            let flux = environment_integral(env) * (PI * radius * radius);
            candidates.push((LightId::Environment, flux));
        }
        candidates.retain(|(_, f)| {
            let y = luminance(*f);
            f.is_finite() && y.is_finite() && y > 0.0
        });
        let total = candidates.iter().map(|(_, f)| *f).sum();
        let flux = candidates.iter().map(|(_, f)| *f).collect();
        let sampler = LightSampler::by_power(
            candidates
                .iter()
                .map(|&(id, f)| (id, luminance(f)))
                .collect(),
        );
        PhotonEmitter {
            sampler,
            flux,
            total,
            centre,
            radius,
            targets: Targets::new(scene),
        }
    }

    /// The caustic makers' bounding spheres photons are aimed at.
    pub fn targets(&self) -> &Targets {
        &self.targets
    }

    /// No light emits (zero power).
    pub fn is_empty(&self) -> bool {
        self.sampler.is_empty()
    }

    /// The light choice photons are emitted with (by the luminance of each light's flux).
    pub fn sampler(&self) -> &LightSampler {
        &self.sampler
    }

    /// Σ of the lights' emitted flux, linear RGB, computed analytically (not by sampling).
    pub fn total_power(&self) -> Vec3 {
        self.total
    }

    /// The distant-light disc: bounding-sphere centre and radius r (0 without geometry).
    pub fn disc(&self) -> (Vec3, f32) {
        (self.centre, self.radius)
    }

    /// A photon from the next five numbers of `rng` (light, point, direction), not aimed.
    pub fn emit_from<'a>(&self, scene: &'a Scene, rng: &mut Rng) -> Option<EmittedPhoton<'a>> {
        let u_light = rng.next_f32();
        let u_pos = Vec2::new(rng.next_f32(), rng.next_f32());
        let u_dir = Vec2::new(rng.next_f32(), rng.next_f32());
        self.emit(scene, u_light, u_pos, u_dir)
    }

    /// Photon `index` of the scrambled Halton sequence `numbers` ([`PhotonNumbers`], built
    /// once per seed), aimed by `aim`: what every photon loop of the renderers (and the
    /// plan's caustic probe) emits.
    pub fn emit_index<'a>(
        &self,
        scene: &'a Scene,
        numbers: &PhotonNumbers,
        index: u64,
        aim: Aim,
    ) -> Option<EmittedPhoton<'a>> {
        self.emit_aimed(scene, numbers.get(index), aim)
    }

    /// A photon from uniform numbers, not aimed: `u_light` picks the light (by power),
    /// `u_pos` the point, `u_dir` the direction. `None` if the sample is degenerate.
    pub fn emit<'a>(
        &self,
        scene: &'a Scene,
        u_light: f32,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<EmittedPhoton<'a>> {
        let u = [u_light, u_pos.x, u_pos.y, u_dir.x, u_dir.y];
        self.emit_aimed(scene, u, Aim::Off)
    }

    /// A photon from five uniform numbers `[light, point.x, point.y, direction.x,
    /// direction.y]`, aimed by `aim` (module docs). `None` if the sample is degenerate or
    /// carries no power.
    pub fn emit_aimed<'a>(
        &self,
        scene: &'a Scene,
        u: [f32; 5],
        aim: Aim,
    ) -> Option<EmittedPhoton<'a>> {
        let choice = self.sampler.sample(u[0])?;
        let (u_pos, u_dir) = (Vec2::new(u[1], u[2]), Vec2::new(u[3], u[4]));
        let only = aim == Aim::Only;
        let a = if self.targets.is_empty() {
            if only {
                return None;
            }
            0.0
        } else {
            aim.fraction()
        };
        let (flux, prob) = (self.flux[choice.index], choice.pmf);
        let mix = Mix { a, only };
        let photon = match choice.light {
            LightId::Punctual(i) => {
                let l = &scene.lights()[i as usize];
                self.punctual((l, i), flux, u_pos, u_dir, mix)
            }
            LightId::Area => {
                // The rest of the light's number picks the triangle.
                let pt = area_point(scene, choice.u_rest, u_pos)?;
                let (dir, ratio) = self.mix_direction(
                    pt.point,
                    mix,
                    u_dir,
                    |u| pt.base_direction(u),
                    |d| pt.base_pdf(d),
                )?;
                Some(EmittedPhoton {
                    ray: scene.spawn_from_triangle(pt.prim, pt.point, dir),
                    power: pt.base_power() * ratio,
                    shape: pt.shape,
                    range: None,
                    source: Source::Area(pt.prim),
                })
            }
            LightId::Environment => {
                let s = scene.environment()?.sample(u_dir)?;
                let (origin, area) = self.distant_origin(-s.wi, u_pos, mix)?;
                Some(EmittedPhoton {
                    ray: Ray::new(origin, -s.wi),
                    power: s.radiance / s.pdf * area,
                    shape: None,
                    range: None,
                    source: Source::Environment,
                })
            }
        }?;
        let power = photon.power / prob;
        (power.is_finite() && power.max_element() > 0.0)
            .then_some(EmittedPhoton { power, ..photon })
    }
}
