//! The aimed half of [`super::PhotonEmitter`]: directions from a point (point, spot and
//! emissive-triangle light) and origins across the distant-light disc drawn from the
//! defensive mixture of the usual density and the aimed one ([`crate::photon::aim`]), each
//! returned with the factor p_usual/p_mixture that turns the usual photon's power into the
//! mixture's. Units and frames as in [`super`] (world space, metres, steradians).

use super::{EmittedPhoton, PhotonEmitter};
use crate::light::{Light, PunctualLight};
use crate::math::{Frame, Ray};
use crate::photon::aim::split_choice;
use crate::photon::flux::{sample_spot_cos, spot_pdf, uniform_sphere, unit_disc};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The aim of one emission: the aimed fraction (0 when there is nothing to aim at) and
/// whether the usual term is dropped.
#[derive(Debug, Clone, Copy)]
pub(super) struct Mix {
    /// Probability of an aimed sample, in [0, 1].
    pub a: f32,
    /// [`crate::photon::aim::Aim::Only`]: the density is the aimed one alone.
    pub only: bool,
}

impl PhotonEmitter {
    /// A direction from `p`: with probability `mix.a` aimed at a target, else
    /// `base_sample` (whose density is `base_pdf`) with `u.x` rescaled. Returns the direction
    /// and p_usual/p_mixture, the factor on the usual photon's power (exactly 1 unaimed).
    pub(super) fn mix_direction(
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
            let (d, j) = self.targets.sample_direction(&cones, Vec2::new(ux, u.y))?;
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
    pub(super) fn distant_origin(&self, dir: Vec3, u: Vec2, mix: Mix) -> Option<(Vec3, f32)> {
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
    pub(super) fn disc_origin(&self, dir: Vec3, u: Vec2) -> Vec3 {
        let f = Frame::from_normal(dir);
        let d = unit_disc(u) * self.radius;
        self.centre - dir * self.radius + f.s * d.x + f.t * d.y
    }

    /// A photon of one punctual light carrying its contribution before light selection
    /// (its whole flux when not aimed).
    pub(super) fn punctual<'a>(
        &self,
        (light, index): (&'a PunctualLight, u32),
        flux: Vec3,
        u_pos: Vec2,
        u_dir: Vec2,
        mix: Mix,
    ) -> Option<EmittedPhoton<'a>> {
        let (ray, range, ratio) = match light.light {
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
                let pdf = |d: Vec3| spot_pdf(cos_inner, cos_outer, d.dot(direction));
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
            shape: light.shape.as_ref(),
            range,
            source: super::Source::Punctual(index),
        })
    }
}
