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
//! Owen-scrambled Halton dimensions 0–4 over the photon index ([`photon_numbers`]; pbrt-v4
//! SPPM draws its photon paths from Halton over the photon index,
//! src/pbrt/cpu/integrators.cpp). The aim choice and the sphere choice reuse the direction's
//! first number (the disc point's, for distant light), rescaled within the chosen interval.

pub use super::aim::{Aim, DEFAULT_AIM};
use super::aim::{split_choice, Targets};
use super::flux::{
    area_flux, area_point, environment_integral, punctual_flux, sample_spot_cos, spot_integral,
    uniform_sphere, unit_disc,
};
use crate::interaction::OFFSET_SCALE;
use crate::light::env::luminance;
use crate::light::Light;
use crate::math::{Frame, Ray, Rng};
use crate::sampler::halton::halton_sample;
use crate::scene::Scene;
use crate::spectrum::EmitterShape;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

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
}

/// A group of lights chosen as one by the light selection.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Source {
    /// `scene.lights[k]`.
    Punctual(usize),
    /// All emissive triangles (`scene.area_lights` picks one by power).
    Area,
    /// `scene.environment`.
    Environment,
}

/// Chooses lights by power and emits photons from them (see the module docs).
#[derive(Debug, Clone)]
pub struct PhotonEmitter {
    /// Lights with positive power, their RGB flux and their selection probability.
    sources: Vec<(Source, Vec3, f32)>,
    /// Cumulative selection probability (last entry 1).
    cdf: Vec<f32>,
    /// Σ flux.
    total: Vec3,
    /// Bounding-sphere centre of the scene.
    centre: Vec3,
    /// Disc radius for distant light (0 without geometry).
    radius: f32,
    /// The caustic makers' bounding spheres.
    targets: Targets,
}

/// The five emission numbers of photon `index` under `seed`: Owen-scrambled Halton
/// dimensions 0–4 (light, point, direction), a pure function of `(index, seed)`.
pub fn photon_numbers(index: u64, seed: u64) -> [f32; 5] {
    std::array::from_fn(|d| halton_sample(index, d, seed))
}

impl PhotonEmitter {
    /// Collects the scene's lights and their flux.
    pub fn new(scene: &Scene) -> PhotonEmitter {
        let (lo, hi) = scene.bounds;
        let (centre, radius) = if lo.is_finite() && hi.is_finite() && lo.cmple(hi).all() {
            let half = 0.5 * (hi - lo).length();
            // A point-like scene still gets a disc of positive area.
            let r = DISC_MARGIN * half.max(OFFSET_SCALE * (1.0 + lo.abs().max_element()));
            (0.5 * (lo + hi), r)
        } else {
            (Vec3::ZERO, 0.0)
        };
        let mut candidates: Vec<(Source, Vec3)> = scene
            .lights
            .iter()
            .enumerate()
            .map(|(k, l)| (Source::Punctual(k), punctual_flux(l, radius)))
            .collect();
        if !scene.area_lights.is_empty() {
            candidates.push((Source::Area, area_flux(scene)));
        }
        if let Some(env) = &scene.environment {
            let flux = environment_integral(env) * (PI * radius * radius);
            candidates.push((Source::Environment, flux));
        }
        candidates.retain(|(_, f)| {
            let y = luminance(*f);
            f.is_finite() && y.is_finite() && y > 0.0
        });
        let lum_total: f64 = candidates.iter().map(|(_, f)| luminance(*f) as f64).sum();
        let mut cdf = Vec::with_capacity(candidates.len());
        let mut sources = Vec::with_capacity(candidates.len());
        let mut acc = 0.0f64;
        let mut total = Vec3::ZERO;
        for (s, f) in candidates {
            let y = luminance(f) as f64;
            acc += y;
            cdf.push((acc / lum_total) as f32);
            sources.push((s, f, (y / lum_total) as f32));
            total += f;
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        PhotonEmitter {
            sources,
            cdf,
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
        self.sources.is_empty()
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

    /// Photon `index` of the Halton sequence under `seed` ([`photon_numbers`]), aimed by
    /// `aim`: what every photon loop of the renderers (and the plan's caustic probe) emits.
    pub fn emit_index<'a>(
        &self,
        scene: &'a Scene,
        index: u64,
        seed: u64,
        aim: Aim,
    ) -> Option<EmittedPhoton<'a>> {
        self.emit_aimed(scene, photon_numbers(index, seed), aim)
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
        if self.sources.is_empty() {
            return None;
        }
        let (u_light, u_pos, u_dir) = (u[0], Vec2::new(u[1], u[2]), Vec2::new(u[3], u[4]));
        let only = aim == Aim::Only;
        let a = if self.targets.is_empty() {
            if only {
                return None;
            }
            0.0
        } else {
            aim.fraction()
        };
        let k = self
            .cdf
            .partition_point(|&c| c <= u_light)
            .min(self.sources.len() - 1);
        let (source, flux, prob) = self.sources[k];
        // Reuse u_light within the chosen interval (for the triangle choice).
        let lo = if k == 0 { 0.0 } else { self.cdf[k - 1] };
        let u_sub = ((u_light - lo) / prob).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
        let mix = Mix { a, only };
        let photon = match source {
            Source::Punctual(i) => {
                let shape = scene.light_shapes.get(i).and_then(Option::as_ref);
                self.punctual(&scene.lights[i], flux, u_pos, u_dir, shape, mix)
            }
            Source::Area => {
                let pt = area_point(scene, u_sub, u_pos)?;
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
                })
            }
            Source::Environment => {
                let s = scene.environment.as_ref()?.sample(u_dir)?;
                let (origin, area) = self.distant_origin(-s.wi, u_pos, mix)?;
                Some(EmittedPhoton {
                    ray: Ray::new(origin, -s.wi),
                    power: s.radiance / s.pdf * area,
                    shape: None,
                    range: None,
                })
            }
        }?;
        let power = photon.power / prob;
        (power.is_finite() && power.max_element() > 0.0)
            .then_some(EmittedPhoton { power, ..photon })
    }

    /// A direction from `p`: with probability `mix.a` aimed at a target, else
    /// `base_sample` (whose density is `base_pdf`) with `u.x` rescaled. Returns the direction
    /// and p_usual/p_mixture, the factor on the usual photon's power (exactly 1 unaimed).
    fn mix_direction(
        &self,
        p: Vec3,
        mix: Mix,
        u: Vec2,
        base_sample: impl FnOnce(Vec2) -> Option<Vec3>,
        base_pdf: impl Fn(Vec3) -> f32,
    ) -> Option<(Vec3, f32)> {
        if mix.a <= 0.0 {
            return Some((base_sample(u)?, 1.0));
        }
        let cones = self.targets.cones_from(p);
        if cones.total() <= 0.0 {
            return if mix.only {
                None
            } else {
                Some((base_sample(u)?, 1.0))
            };
        }
        let (aimed, ux) = split_choice(u.x, mix.a);
        let (dir, sampled) = if aimed {
            let (d, j) = self
                .targets
                .sample_direction(&cones, Vec2::new(ux, u.y))?;
            (d, Some(j))
        } else {
            (base_sample(Vec2::new(ux, u.y))?, None)
        };
        let p_aim = self.targets.direction_pdf(&cones, dir, sampled);
        let p_base = base_pdf(dir);
        let p_mix = if mix.only {
            p_aim
        } else {
            (1.0 - mix.a) * p_base + mix.a * p_aim
        };
        (p_mix > 0.0).then(|| (dir, p_base / p_mix))
    }

    /// Where a distant-light photon travelling along `dir` starts: a point of the plane ⟂
    /// `dir` r upstream of the scene centre, uniform on the disc of radius r or (with
    /// probability `mix.a`) in a target's projection. Returns the origin and 1/(its area
    /// density) (π r² unaimed).
    fn distant_origin(&self, dir: Vec3, u: Vec2, mix: Mix) -> Option<(Vec3, f32)> {
        let disc_area = PI * self.radius * self.radius;
        if mix.a <= 0.0 {
            return Some((self.disc_origin(dir, u), disc_area));
        }
        let f = Frame::from_normal(dir);
        let (aimed, ux) = split_choice(u.x, mix.a);
        let (x, sampled) = if aimed {
            let (x, j) = self
                .targets
                .sample_across(&f, self.centre, Vec2::new(ux, u.y))?;
            (x, Some(j))
        } else {
            (unit_disc(Vec2::new(ux, u.y)) * self.radius, None)
        };
        let p_aim = self.targets.across_pdf(&f, self.centre, x, sampled);
        let inside = sampled.is_none() || x.length_squared() <= self.radius * self.radius;
        let p_base = if inside && disc_area > 0.0 {
            1.0 / disc_area
        } else {
            0.0
        };
        let p_mix = if mix.only {
            p_aim
        } else {
            (1.0 - mix.a) * p_base + mix.a * p_aim
        };
        let origin = self.centre - dir * self.radius + f.s * x.x + f.t * x.y;
        (p_mix > 0.0).then(|| (origin, 1.0 / p_mix))
    }

    /// A point of the disc ⟂ `dir`, centred r upstream of the scene centre.
    fn disc_origin(&self, dir: Vec3, u: Vec2) -> Vec3 {
        let f = Frame::from_normal(dir);
        let d = unit_disc(u) * self.radius;
        self.centre - dir * self.radius + f.s * d.x + f.t * d.y
    }

    /// A photon of one punctual light carrying its contribution before light selection
    /// (its whole flux when not aimed).
    fn punctual<'a>(
        &self,
        light: &Light,
        flux: Vec3,
        u_pos: Vec2,
        u_dir: Vec2,
        shape: Option<&'a EmitterShape>,
        mix: Mix,
    ) -> Option<EmittedPhoton<'a>> {
        let (ray, range, ratio) = match *light {
            Light::Point {
                position, range, ..
            } => {
                let (dir, ratio) = self.mix_direction(
                    position,
                    mix,
                    u_dir,
                    |u| Some(uniform_sphere(u)),
                    |_| 1.0 / (4.0 * PI),
                )?;
                (Ray::new(position, dir), range, ratio)
            }
            Light::Spot {
                position,
                direction,
                cos_inner,
                cos_outer,
                range,
                ..
            } => {
                let frame = Frame::from_normal(direction);
                let sample = |u: Vec2| {
                    let c = sample_spot_cos(cos_inner, cos_outer, u.x);
                    let s = (1.0 - c * c).max(0.0).sqrt();
                    let (sp, cp) = (2.0 * PI * u.y).sin_cos();
                    Some(frame.to_world(Vec3::new(s * cp, s * sp, c)).normalize())
                };
                // Density t(c)²/(2πK) on the cone, 0 outside (KHR falloff, crate::light).
                let k = spot_integral(cos_inner, cos_outer);
                let pdf = |d: Vec3| {
                    let c = d.dot(direction);
                    let ci = cos_inner.max(cos_outer);
                    let t = if ci > cos_outer {
                        ((c - cos_outer) / (ci - cos_outer)).clamp(0.0, 1.0)
                    } else if c >= cos_outer {
                        1.0
                    } else {
                        0.0
                    };
                    if k > 0.0 {
                        t * t / (2.0 * PI * k)
                    } else {
                        0.0
                    }
                };
                let (dir, ratio) = self.mix_direction(position, mix, u_dir, sample, pdf)?;
                (Ray::new(position, dir), range, ratio)
            }
            Light::Directional { direction, .. } => {
                let (origin, area) = self.distant_origin(direction, u_pos, mix)?;
                // flux = E·π r²; the photon carries E / p_area.
                let ratio = area / (PI * self.radius * self.radius);
                (Ray::new(origin, direction), None, ratio)
            }
        };
        Some(EmittedPhoton {
            ray,
            power: flux * ratio,
            shape,
            range,
        })
    }
}

/// The aim of one emission: the aimed fraction (0 when there is nothing to aim at) and
/// whether the usual term is dropped.
#[derive(Debug, Clone, Copy)]
struct Mix {
    a: f32,
    only: bool,
}
