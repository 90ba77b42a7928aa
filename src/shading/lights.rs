//! Light samples toward a hit, shared by the integrators' direct lighting (the path
//! tracer's next-event estimation, the Whitted tracer's [`super::direct`]): one punctual
//! light, one point on the emissive triangles, or one direction of the environment, each
//! with its shadow ray, its incident light and, for an emitter that names one, its exact
//! spectral shape. Random numbers are drawn by the callers, so each integrator keeps its own
//! sequence.
//!
//! Units: `incident` is irradiance at normal incidence (lux-based) for punctual lights, and
//! radiance / solid-angle pdf for area and environment samples, linear RGB (spectral
//! transport converts it with [`crate::spectrum::Carrier::emitted`]).
//!
//! The lights themselves (punctual, area, environment) are defined in [`crate::light`];
//! sampling them toward a hit lives here because it needs the built scene and the
//! intersection layer, which sit above those definitions (`crate::light` must not import
//! `crate::scene`).

use crate::interaction::SurfaceHit;
use crate::light::area::AreaSample;
use crate::light::LightId;
use crate::math::Ray;
use crate::scene::Scene;
use crate::spectrum::EmitterShape;
use glam::{Vec2, Vec3};

/// One light sample seen from a hit.
#[derive(Debug, Clone, Copy)]
pub struct LightSample<'a> {
    /// Unit direction from the hit toward the light.
    pub wi: Vec3,
    /// The shadow ray that must be unblocked.
    pub shadow: Ray,
    /// Irradiance (punctual) or radiance / pdf (area, environment), linear RGB.
    pub incident: Vec3,
    /// The emitter's exact spectral shape, if it names one.
    pub shape: Option<&'a EmitterShape>,
    /// Solid-angle pdf for MIS, `None` for delta (punctual) lights.
    pub pdf: Option<f32>,
    /// The light's point (an emissive triangle's sampled point, a point or spot light's
    /// position); `None` for distant light.
    pub position: Option<Vec3>,
    /// The emissive triangle sampled (area light only).
    pub prim: Option<u32>,
}

/// Which numbers [`sample`] reads for light `id`: (`u`, the position or direction; `uc`,
/// the member of the emissive group). Callers skip drawing the others.
pub fn numbers_read(id: LightId) -> (bool, bool) {
    match id {
        LightId::Punctual(_) => (false, false),
        LightId::Environment => (true, false),
        LightId::Area => (true, true),
    }
}

/// A sample of light `id` toward `hit`: `uc` picks the emissive triangle, `u` the point on
/// it or the environment's direction (punctual lights need no numbers, [`numbers_read`]).
pub fn sample<'a>(
    scene: &'a Scene,
    hit: &SurfaceHit,
    id: LightId,
    uc: f32,
    u: Vec2,
) -> Option<LightSample<'a>> {
    match id {
        LightId::Punctual(k) => punctual(scene, hit, k as usize),
        LightId::Area => area(scene, hit, uc, u),
        LightId::Environment => environment(scene, hit, u),
    }
}

/// The solid-angle density with which next-event estimation ([`sample`] of the light the
/// scene's light sampler picks) reaches the point `q` of emissive triangle `prim` from `p`:
/// the sampler's probability of the emissive group times the group's density. The MIS
/// weight of a BSDF-sampled hit on an emitter uses it; 0 if `prim` does not emit.
pub fn area_pdf(scene: &Scene, prim: u32, p: Vec3, q: Vec3) -> f32 {
    scene.light_sampler().pmf(LightId::Area) * scene.area_lights().pdf(prim, p, q)
}

/// As [`area_pdf`], for the environment seen along the unit direction `dir`; 0 without an
/// environment.
pub fn environment_pdf(scene: &Scene, dir: Vec3) -> f32 {
    match scene.environment() {
        Some(env) => scene.light_sampler().pmf(LightId::Environment) * env.pdf(dir),
        None => 0.0,
    }
}

/// Punctual light `k`.
pub fn punctual<'a>(scene: &'a Scene, hit: &SurfaceHit, k: usize) -> Option<LightSample<'a>> {
    let light = &scene.lights()[k];
    let ls = light.light.sample_li(hit.p)?;
    let shadow = match ls.position {
        Some(p) => hit.spawn_ray_to(p),
        None => hit.spawn_ray(ls.wi),
    };
    Some(LightSample {
        wi: ls.wi,
        shadow,
        incident: ls.irradiance,
        shape: light.shape.as_ref(),
        pdf: None,
        position: ls.position,
        prim: None,
    })
}

/// A point on the emissive triangles (chosen by power with `uc`, placed with `u`), its
/// emission textured there; `None` when the emitter faces away (single-sided) or the
/// density is degenerate.
pub fn area<'a>(scene: &'a Scene, hit: &SurfaceHit, uc: f32, u: Vec2) -> Option<LightSample<'a>> {
    let (s, incident, shape) = area_at(scene, hit.p, uc, u)?;
    Some(LightSample {
        wi: s.wi,
        shadow: hit.spawn_ray_to(s.point),
        incident,
        shape,
        pdf: Some(s.pdf),
        position: Some(s.point),
        prim: Some(s.prim),
    })
}

/// [`area`] for a receiver at the point `p`: the sample, its textured emission over its
/// solid-angle pdf (RGB) and the emitter's exact spectral shape, if it names one.
pub fn area_at(
    scene: &Scene,
    p: Vec3,
    uc: f32,
    u: Vec2,
) -> Option<(AreaSample, Vec3, Option<&EmitterShape>)> {
    let s = scene.area_lights().sample(p, uc, u)?;
    if s.pdf.is_nan() || s.pdf <= 0.0 {
        return None;
    }
    let mat = scene.material(scene.triangle(s.prim).material());
    // Single-sided emitters only shine along their outward normal.
    if !mat.desc.double_sided && s.normal.dot(s.wi) >= 0.0 {
        return None;
    }
    let incident = scene.emission_at(s.prim, s.bary) / s.pdf;
    Some((s, incident, mat.emitter_shape()))
}

/// An importance-sampled direction of the environment.
pub fn environment<'a>(scene: &'a Scene, hit: &SurfaceHit, u: Vec2) -> Option<LightSample<'a>> {
    let s = scene.environment()?.sample(u)?;
    Some(LightSample {
        wi: s.wi,
        shadow: hit.spawn_ray(s.wi),
        incident: s.radiance / s.pdf,
        shape: None,
        pdf: Some(s.pdf),
        position: None,
        prim: None,
    })
}
