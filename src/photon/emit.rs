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

use crate::interaction::OFFSET_SCALE;
use crate::light::env::{luminance, Environment};
use crate::light::Light;
use crate::math::{Frame, Ray, Rng};
use crate::scene::{Scene, TriangleData};
use crate::spectrum::EmitterShape;
use crate::texture::{self, Encoding};
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
}

/// ∫_{cos_o}^1 t(c)² dc for the KHR spot falloff; `cos_i ≤ cos_o` is the hard cone of
/// [`Light::sample_li`].
fn spot_integral(cos_i: f32, cos_o: f32) -> f32 {
    let ci = cos_i.max(cos_o);
    ((1.0 - ci) + (ci - cos_o) / 3.0).max(0.0)
}

/// Samples cos θ ∝ t(c)² on [cos_o, 1]: the CDF is (c − cos_o)³/(3Δ²) on the falloff and
/// linear above cos_i.
fn sample_spot_cos(cos_i: f32, cos_o: f32, u: f32) -> f32 {
    let ci = cos_i.max(cos_o);
    let delta = ci - cos_o;
    let x = u * spot_integral(cos_i, cos_o);
    let c = if x < delta / 3.0 {
        cos_o + (3.0 * delta * delta * x).cbrt()
    } else {
        ci + (x - delta / 3.0)
    };
    c.clamp(cos_o, 1.0)
}

/// Uniform direction on the unit sphere (Archimedes: z uniform in [−1, 1]).
fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(r * c, r * s, z)
}

/// Uniform point on the unit disc (polar mapping, radius √u).
fn unit_disc(u: Vec2) -> Vec2 {
    let r = u.x.sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec2::new(r * c, r * s)
}

/// Flux of one punctual light.
fn punctual_flux(light: &Light, radius: f32) -> Vec3 {
    match *light {
        Light::Point { intensity, .. } => intensity * (4.0 * PI),
        Light::Spot {
            intensity,
            cos_inner,
            cos_outer,
            ..
        } => intensity * (2.0 * PI * spot_integral(cos_inner, cos_outer)),
        Light::Directional { illuminance, .. } => illuminance * (PI * radius * radius),
    }
}

/// ∫ L dω over the sphere, RGB: the exact texel sum for a map (texel solid angle
/// (2π/W)(cos θ₀ − cos θ₁)).
fn environment_integral(env: &Environment) -> Vec3 {
    match env {
        Environment::Uniform { radiance } => *radiance * (4.0 * PI),
        Environment::Map(m) => {
            let (w, h) = (m.width(), m.height());
            let dtheta = std::f64::consts::PI / h as f64;
            let mut sum = [0.0f64; 3];
            for y in 0..h {
                let d_omega = 2.0 * std::f64::consts::PI / w as f64
                    * ((y as f64 * dtheta).cos() - ((y + 1) as f64 * dtheta).cos());
                for x in 0..w {
                    let t = m.texel(x, y);
                    for (s, c) in sum.iter_mut().zip([t.x, t.y, t.z]) {
                        *s += c as f64 * d_omega;
                    }
                }
            }
            Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32)
        }
    }
}

/// RGB flux of all emissive triangles: Σ L·π·A·sides (emissive factor, no texture), over
/// the triangles [`crate::light::area::AreaLights`] selects from.
fn area_flux(scene: &Scene) -> Vec3 {
    let mut sum = [0.0f64; 3];
    for t in &scene.triangle_data {
        let Some(mat) = scene.materials.get(t.material() as usize) else {
            continue;
        };
        let le = mat.emission();
        let area = 0.5 * (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]).length();
        let sides = if mat.desc.double_sided { 2.0 } else { 1.0 };
        let w = luminance(le) * area * PI * sides;
        if w > 0.0 && w.is_finite() {
            let f = le * (area * PI * sides);
            for (s, c) in sum.iter_mut().zip([f.x, f.y, f.z]) {
                *s += c as f64;
            }
        }
    }
    Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32)
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
        }
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

    /// A photon from the next five numbers of `rng` (light, point, direction: the order
    /// every photon loop uses, so photon `i` of a seed is the same everywhere).
    pub fn emit_from<'a>(&self, scene: &'a Scene, rng: &mut Rng) -> Option<EmittedPhoton<'a>> {
        let u_light = rng.next_f32();
        let u_pos = Vec2::new(rng.next_f32(), rng.next_f32());
        let u_dir = Vec2::new(rng.next_f32(), rng.next_f32());
        self.emit(scene, u_light, u_pos, u_dir)
    }

    /// A photon from uniform numbers: `u_light` picks the light (by power), `u_pos` the
    /// point, `u_dir` the direction. `None` if the sample is degenerate.
    pub fn emit<'a>(
        &self,
        scene: &'a Scene,
        u_light: f32,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<EmittedPhoton<'a>> {
        if self.sources.is_empty() {
            return None;
        }
        let k = self
            .cdf
            .partition_point(|&c| c <= u_light)
            .min(self.sources.len() - 1);
        let (source, flux, prob) = self.sources[k];
        // Reuse u_light within the chosen interval (for the triangle choice).
        let lo = if k == 0 { 0.0 } else { self.cdf[k - 1] };
        let u_sub = ((u_light - lo) / prob).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
        let photon = match source {
            Source::Punctual(i) => {
                let shape = scene.light_shapes.get(i).and_then(Option::as_ref);
                self.punctual(&scene.lights[i], flux, u_pos, u_dir, shape)
            }
            Source::Area => area(scene, u_sub, u_pos, u_dir),
            Source::Environment => {
                let s = scene.environment.as_ref()?.sample(u_dir)?;
                let power = s.radiance / s.pdf * (PI * self.radius * self.radius);
                Some(EmittedPhoton {
                    ray: Ray::new(self.disc_origin(-s.wi, u_pos), -s.wi),
                    power,
                    shape: None,
                    range: None,
                })
            }
        }?;
        let power = photon.power / prob;
        (power.is_finite() && power.max_element() > 0.0)
            .then_some(EmittedPhoton { power, ..photon })
    }

    /// A point of the disc ⟂ `dir`, centred r upstream of the scene centre.
    fn disc_origin(&self, dir: Vec3, u: Vec2) -> Vec3 {
        let f = Frame::from_normal(dir);
        let d = unit_disc(u) * self.radius;
        self.centre - dir * self.radius + f.s * d.x + f.t * d.y
    }

    /// A photon of one punctual light carrying its whole flux (before selection).
    fn punctual<'a>(
        &self,
        light: &Light,
        flux: Vec3,
        u_pos: Vec2,
        u_dir: Vec2,
        shape: Option<&'a EmitterShape>,
    ) -> Option<EmittedPhoton<'a>> {
        let (ray, range) = match *light {
            Light::Point {
                position, range, ..
            } => (Ray::new(position, uniform_sphere(u_dir)), range),
            Light::Spot {
                position,
                direction,
                cos_inner,
                cos_outer,
                range,
                ..
            } => {
                let c = sample_spot_cos(cos_inner, cos_outer, u_dir.x);
                let s = (1.0 - c * c).max(0.0).sqrt();
                let (sp, cp) = (2.0 * PI * u_dir.y).sin_cos();
                let local = Vec3::new(s * cp, s * sp, c);
                let dir = Frame::from_normal(direction).to_world(local).normalize();
                (Ray::new(position, dir), range)
            }
            Light::Directional { direction, .. } => (
                Ray::new(self.disc_origin(direction, u_pos), direction),
                None,
            ),
        };
        Some(EmittedPhoton {
            ray,
            power: flux,
            shape,
            range,
        })
    }
}

/// A photon from the emissive triangles carrying L·cos/(p_A·p_ω) before light selection.
fn area<'a>(scene: &'a Scene, u: f32, u_pos: Vec2, u_dir: Vec2) -> Option<EmittedPhoton<'a>> {
    let e = scene
        .area_lights
        .sample_point(&scene.triangle_data, u, u_pos)?;
    let t = scene.triangle_data.get(e.prim as usize)?;
    let mat = scene.materials.get(t.material() as usize)?;
    let mut le = mat.emission();
    if let (Some(tex), true) = (
        mat.desc.emissive_texture,
        t.info & TriangleData::HAS_UVS != 0,
    ) {
        let vi = scene.triangles.get(e.prim as usize)?;
        let uv = vi
            .iter()
            .zip(e.bary)
            .map(|(&i, b)| scene.uvs.get(i as usize).copied().unwrap_or(Vec2::ZERO) * b)
            .sum();
        if let Some(img) = scene.images.get(tex.image) {
            le *= texture::sample(img, uv, Encoding::Srgb).truncate();
        }
    }
    // Double-sided: u_dir.x < ½ picks the front, else the back, each with probability ½.
    let (normal, ux, sides) = if mat.desc.double_sided {
        if u_dir.x < 0.5 {
            (e.normal, 2.0 * u_dir.x, 2.0)
        } else {
            (-e.normal, 2.0 * u_dir.x - 1.0, 2.0)
        }
    } else {
        (e.normal, u_dir.x, 1.0)
    };
    // Cosine-weighted hemisphere (Malley's method): pdf cos/π, so L·cos/(pdf·p_A) = L·π/p_A.
    let d = unit_disc(Vec2::new(ux, u_dir.y));
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    if z <= 0.0 {
        return None;
    }
    let dir = Frame::from_normal(normal)
        .to_world(Vec3::new(d.x, d.y, z))
        .normalize();
    Some(EmittedPhoton {
        ray: scene.spawn_from_triangle(e.prim, e.point, dir),
        power: le * (PI * sides * e.area / e.prob),
        shape: mat.emitter_shape(),
        range: None,
    })
}

impl PhotonEmitter {
    /// The same emitter without the environment: the punctual lights and emissive
    /// triangles only, reselected by the luminance of their flux (the hybrid's caustic
    /// lights, [`crate::integrator::caustic`]). Each photon's power is still divided by its
    /// (new) selection probability, so the mean power is the remaining lights' flux.
    pub fn without_environment(&self) -> PhotonEmitter {
        let kept: Vec<(Source, Vec3)> = self
            .sources
            .iter()
            .filter(|(s, _, _)| *s != Source::Environment)
            .map(|&(s, f, _)| (s, f))
            .collect();
        let lum_total: f64 = kept.iter().map(|(_, f)| luminance(*f) as f64).sum();
        let (mut sources, mut cdf, mut total, mut acc) = (Vec::new(), Vec::new(), Vec3::ZERO, 0.0);
        for (s, f) in kept {
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
            ..self.clone()
        }
    }
}
