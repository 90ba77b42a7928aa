//! Light flux and the usual (unaimed) sampling shapes of photon emission, for
//! [`super::emit`]: spot-falloff integrals and inverse CDF, uniform sphere and disc
//! mappings, each light type's flux, and the emissive-triangle photon.
//!
//! Units as in [`super::emit`]: flux is linear RGB in the lights' own units (cd·sr for
//! point and spot lights, lux·m² for directional light, radiance·m²·sr for emitters and the
//! environment); world space, metres; directions are unit vectors.

use crate::light::env::{luminance, Environment};
use crate::light::punctual::cone_falloff;
use crate::light::Light;
use crate::math::Frame;
use crate::scene::Scene;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// ∫_{cos_o}^1 t(c)² dc for the KHR spot falloff; `cos_i ≤ cos_o` is the hard cone of
/// [`Light::sample_li`].
pub(super) fn spot_integral(cos_i: f32, cos_o: f32) -> f32 {
    let ci = cos_i.max(cos_o);
    ((1.0 - ci) + (ci - cos_o) / 3.0).max(0.0)
}

/// Samples cos θ ∝ t(c)² on [cos_o, 1]: the CDF is (c − cos_o)³/(3Δ²) on the falloff and
/// linear above cos_i.
pub(super) fn sample_spot_cos(cos_i: f32, cos_o: f32, u: f32) -> f32 {
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

/// The density (per steradian) of the spot sampling at cos θ = `c`: t(c)²/(2πK) inside the
/// outer cone, 0 outside (t as in [`crate::light`]; a hard cone when `cos_i ≤ cos_o`).
pub(super) fn spot_pdf(cos_i: f32, cos_o: f32, c: f32) -> f32 {
    let falloff = cone_falloff(c, cos_i.max(cos_o), cos_o);
    let k = spot_integral(cos_i, cos_o);
    if k > 0.0 {
        falloff / (2.0 * PI * k)
    } else {
        0.0
    }
}

/// Uniform direction on the unit sphere (Archimedes: z uniform in [−1, 1]).
pub(super) fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(r * c, r * s, z)
}

/// Uniform point on the unit disc (polar mapping, radius √u).
pub(super) fn unit_disc(u: Vec2) -> Vec2 {
    let r = u.x.sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec2::new(r * c, r * s)
}

/// Flux of one punctual light.
pub(super) fn punctual_flux(light: &Light, radius: f32) -> Vec3 {
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
pub(super) fn environment_integral(env: &Environment) -> Vec3 {
    match env {
        Environment::Uniform { radiance } => *radiance * (4.0 * PI),
        Environment::Map(m) => map_integral(m),
        Environment::Sky(sky) => map_integral(&sky.map),
    }
}

/// ∫ L dω of an equirectangular map (the exact texel sum).
fn map_integral(m: &crate::light::env::EnvMap) -> Vec3 {
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

/// RGB flux of all emissive triangles: Σ L·π·A·sides (emissive factor, no texture), over
/// the triangles [`crate::light::area::AreaLights`] selects from.
pub(super) fn area_flux(scene: &Scene) -> Vec3 {
    let mut sum = [0.0f64; 3];
    for e in scene.area_lights().emitters() {
        let t = scene.triangle(e.prim);
        let mat = scene.material(t.material());
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

/// A point on the emissive triangles and what it emits.
pub(super) struct AreaPoint<'a> {
    /// The triangle.
    pub prim: u32,
    /// The point (world).
    pub point: Vec3,
    /// The triangle's geometric normal (unit, outward front side).
    pub normal: Vec3,
    /// Emitted radiance at the point (the emissive texture applied).
    pub le: Vec3,
    /// Both sides emit.
    pub double_sided: bool,
    /// 1 / (area density of the point) = triangle area / triangle selection probability.
    pub inv_pdf_area: f32,
    /// The emitter's spectral shape, if it names one.
    pub shape: Option<&'a crate::spectrum::EmitterShape>,
}

/// A point on the emissive triangles: `u` picks the triangle by power, `u_pos` the point
/// uniformly by area.
pub(super) fn area_point(scene: &Scene, u: f32, u_pos: Vec2) -> Option<AreaPoint<'_>> {
    let e = scene.area_lights().sample_point(u, u_pos)?;
    let mat = scene.material(scene.triangle(e.prim).material());
    let le = scene.emission_at(e.prim, e.bary);
    Some(AreaPoint {
        prim: e.prim,
        point: e.point,
        normal: e.normal,
        le,
        double_sided: mat.desc.double_sided,
        inv_pdf_area: e.area / e.prob,
        shape: mat.emitter_shape(),
    })
}

impl AreaPoint<'_> {
    /// Emitting sides (1 or 2).
    pub fn sides(&self) -> f32 {
        if self.double_sided {
            2.0
        } else {
            1.0
        }
    }

    /// The flux-per-photon of a cosine-weighted direction, before light selection:
    /// L·cos/(p_A·p_ω) = L·π·sides/p_A.
    pub fn base_power(&self) -> Vec3 {
        self.le * (PI * self.sides() * self.inv_pdf_area)
    }

    /// A cosine-weighted direction about the normal (Malley's method); for double-sided
    /// emitters `u.x < ½` picks the front, else the back, each with probability ½.
    pub fn base_direction(&self, u: Vec2) -> Option<Vec3> {
        let (normal, ux) = if self.double_sided {
            if u.x < 0.5 {
                (self.normal, 2.0 * u.x)
            } else {
                (-self.normal, 2.0 * u.x - 1.0)
            }
        } else {
            (self.normal, u.x)
        };
        let d = unit_disc(Vec2::new(ux, u.y));
        let z = (1.0 - d.length_squared()).max(0.0).sqrt();
        if z <= 0.0 {
            return None;
        }
        Some(
            Frame::from_normal(normal)
                .to_world(Vec3::new(d.x, d.y, z))
                .normalize(),
        )
    }

    /// The density of [`AreaPoint::base_direction`] at unit `dir`: |cos|/(π·sides) on an
    /// emitting side, 0 elsewhere.
    pub fn base_pdf(&self, dir: Vec3) -> f32 {
        let c = dir.dot(self.normal);
        if self.double_sided {
            c.abs() / (2.0 * PI)
        } else {
            c.max(0.0) / PI
        }
    }
}
