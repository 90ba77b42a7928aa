//! The densities with which a light path starts, for estimators that weigh one way of
//! sampling a light path against the others (vertex connection and merging,
//! [`crate::integrator::vcm`]): the emitter's own density (light choice by power, the
//! point, the direction, with the aiming mixture of [`super::aimed`]) and the density with
//! which next-event estimation (the scene's light sampler, [`crate::shading::lights`])
//! reaches the same light point.
//!
//! Units: positions per m², directions per steradian. A delta position (punctual light)
//! counts as density 1 in place of the position; a delta direction (directional light)
//! counts as 1 in place of the direction (Georgiev et al. 2012's tech report
//! "Implementing Vertex Connection and Merging", §5.1, as SmallVCM's lights do). For distant
//! light (directional, environment) the "position" is the photon's start on the disc ⟂ its
//! travel direction, found by projecting a point of the ray onto that disc.

use super::{PhotonEmitter, Source};
use crate::light::{Light, LightId};
use crate::math::Frame;
use crate::photon::aim::Aim;
use crate::photon::flux::spot_pdf;
use crate::scene::Scene;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The densities of one light point and direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Densities {
    /// The emitter's density of emitting it: light choice × position × direction.
    pub emit: f32,
    /// Next-event estimation's density of choosing it: the light sampler's choice ×
    /// position per m² (1 for a punctual light); for distant light the direction's density
    /// per steradian (1 for a directional light).
    pub direct: f32,
    /// |cos| between the direction and the emitter's normal (1 for punctual and distant
    /// light).
    pub cos: f32,
    /// The light is a delta in position or direction: no camera path can hit it.
    pub delta: bool,
    /// The light has a position (not distant).
    pub finite: bool,
}

impl PhotonEmitter {
    /// The densities of `source` emitting along the unit direction `dir` (travel
    /// direction) from `point`: the point on an emissive triangle, or for distant light
    /// any point of the ray (it fixes the disc position); a punctual light's own position
    /// is used. `aim` as the photons were emitted with.
    pub fn densities(
        &self,
        scene: &Scene,
        source: Source,
        point: Vec3,
        dir: Vec3,
        aim: Aim,
    ) -> Densities {
        let a = if self.targets.is_empty() {
            0.0
        } else {
            aim.fraction()
        };
        let (id, nee_id) = match source {
            Source::Punctual(k) => (LightId::Punctual(k), LightId::Punctual(k)),
            Source::Area(_) => (LightId::Area, LightId::Area),
            Source::Environment => (LightId::Environment, LightId::Environment),
        };
        let (pick, pick_nee) = (self.sampler.pmf(id), scene.light_sampler().pmf(nee_id));
        let none = Densities {
            emit: 0.0,
            direct: 0.0,
            cos: 0.0,
            delta: false,
            finite: true,
        };
        match source {
            Source::Area(prim) => {
                let Some((pdf_a, n)) = scene.area_lights().point_pdf(prim) else {
                    return none;
                };
                let mat = scene.material(scene.triangle(prim).material());
                let c = dir.dot(n);
                let base = if mat.desc.double_sided {
                    c.abs() / (2.0 * PI)
                } else {
                    c.max(0.0) / PI
                };
                Densities {
                    emit: pick * pdf_a * self.aimed_direction(point, dir, a, base),
                    direct: pick_nee * pdf_a,
                    cos: c.abs(),
                    delta: false,
                    finite: true,
                }
            }
            Source::Punctual(k) => {
                let Some(l) = scene.lights().get(k as usize) else {
                    return none;
                };
                let (emit, finite) = match l.light {
                    Light::Point { position, .. } => (
                        self.aimed_direction(position, dir, a, 1.0 / (4.0 * PI)),
                        true,
                    ),
                    Light::Spot {
                        position,
                        direction,
                        cos_inner,
                        cos_outer,
                        ..
                    } => {
                        let base = spot_pdf(cos_inner, cos_outer, dir.dot(direction));
                        (self.aimed_direction(position, dir, a, base), true)
                    }
                    Light::Directional { .. } => (self.disc_density(dir, point, a), false),
                };
                Densities {
                    emit: pick * emit,
                    direct: pick_nee,
                    cos: 1.0,
                    delta: true,
                    finite,
                }
            }
            Source::Environment => {
                let pdf_w = scene.environment().map_or(0.0, |e| e.pdf(-dir));
                Densities {
                    emit: pick * pdf_w * self.disc_density(dir, point, a),
                    direct: pick_nee * pdf_w,
                    cos: 1.0,
                    delta: false,
                    finite: false,
                }
            }
        }
    }

    /// The mixture density of direction `dir` from `p` ([`super::aimed`]'s
    /// `mix_direction`): the usual density `base` alone when nothing is aimed at.
    fn aimed_direction(&self, p: Vec3, dir: Vec3, a: f32, base: f32) -> f32 {
        if a <= 0.0 {
            return base;
        }
        let cones = self.targets.cones_from(p);
        if cones.total() <= 0.0 {
            return base;
        }
        (1.0 - a) * base + a * self.targets.direction_pdf(&cones, dir, None)
    }

    /// The mixture density per m² of a distant-light photon travelling along `dir` through
    /// `x` starting where it starts on the disc ([`super::aimed`]'s `distant_origin`).
    fn disc_density(&self, dir: Vec3, x: Vec3, a: f32) -> f32 {
        let disc_area = PI * self.radius * self.radius;
        let f = Frame::from_normal(dir);
        let d = x - self.centre;
        let xs = Vec2::new(d.dot(f.s), d.dot(f.t));
        let base = if disc_area > 0.0 && xs.length_squared() <= self.radius * self.radius {
            1.0 / disc_area
        } else {
            0.0
        };
        if a <= 0.0 {
            return base;
        }
        (1.0 - a) * base + a * self.targets.across_pdf(&f, self.centre, xs, None)
    }
}
