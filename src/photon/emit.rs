//! (temporary lead stub, replaced by the helper's emit.rs on merge)
use crate::light::Light;
use crate::math::Ray;
use crate::scene::Scene;
use crate::spectrum::EmitterShape;
use glam::{Vec2, Vec3};

/// One photon leaving a light.
#[derive(Debug, Clone, Copy)]
pub struct EmittedPhoton<'a> {
    /// Origin and unit direction.
    pub ray: Ray,
    /// Flux carried.
    pub power: Vec3,
    /// Exact spectral shape.
    pub shape: Option<&'a EmitterShape>,
    /// Range.
    pub range: Option<f32>,
}

/// Photon emission.
pub struct PhotonEmitter {
    total: Vec3,
    r: f32,
    c: Vec3,
}

impl PhotonEmitter {
    /// New.
    pub fn new(scene: &Scene) -> PhotonEmitter {
        let c = 0.5 * (scene.bounds.0 + scene.bounds.1);
        let r = 0.5 * (scene.bounds.1 - scene.bounds.0).length() * 1.01;
        let mut total = Vec3::ZERO;
        for l in &scene.lights {
            total += match *l {
                Light::Point { intensity, .. } => intensity * 4.0 * std::f32::consts::PI,
                Light::Directional { illuminance, .. } => {
                    illuminance * std::f32::consts::PI * r * r
                }
                _ => Vec3::ZERO,
            };
        }
        PhotonEmitter { total, r, c }
    }
    /// Empty.
    pub fn is_empty(&self) -> bool {
        self.total == Vec3::ZERO
    }
    /// Total.
    pub fn total_power(&self) -> Vec3 {
        self.total
    }
    /// Emit.
    pub fn emit<'a>(
        &self,
        scene: &'a Scene,
        u_light: f32,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<EmittedPhoton<'a>> {
        let n = scene.lights.len();
        let k = ((u_light * n as f32) as usize).min(n.checked_sub(1)?);
        let sph = |u: Vec2| {
            let z = 1.0 - 2.0 * u.x;
            let s = (1.0 - z * z).max(0.0).sqrt();
            let phi = 2.0 * std::f32::consts::PI * u.y;
            Vec3::new(s * phi.cos(), s * phi.sin(), z)
        };
        match scene.lights[k] {
            Light::Point {
                position,
                intensity,
                range,
            } => Some(EmittedPhoton {
                ray: Ray::new(position, sph(u_dir)),
                power: intensity * 4.0 * std::f32::consts::PI * n as f32,
                shape: scene.light_shapes.get(k).and_then(Option::as_ref),
                range,
            }),
            Light::Directional {
                direction,
                illuminance,
            } => {
                let f = crate::math::Frame::from_normal(direction);
                let rr = self.r * u_pos.x.sqrt();
                let phi = 2.0 * std::f32::consts::PI * u_pos.y;
                let o = self.c - direction * self.r
                    + f.to_world(Vec3::new(rr * phi.cos(), rr * phi.sin(), 0.0));
                Some(EmittedPhoton {
                    ray: Ray::new(o, direction),
                    power: illuminance * std::f32::consts::PI * self.r * self.r * n as f32,
                    shape: scene.light_shapes.get(k).and_then(Option::as_ref),
                    range: None,
                })
            }
            _ => None,
        }
    }
}
