//! Per-hit shading shared by the integrators: the glTF metallic-roughness BRDF (glTF 2.0
//! spec, Appendix B: Lambert diffuse + Trowbridge-Reitz/GGX specular with the Smith
//! height-correlated visibility, Fresnel-Schlick, `mix(dielectric, metal, metallic)`), and
//! direct lighting from punctual lights with shadow rays.
//!
//! Directions are unit vectors pointing away from the surface; radiance in the units of the
//! lights (cd and lux give nits).

use super::Context;
use crate::interaction::SurfaceHit;
use crate::material::{Material, ShadingPoint};
use crate::optics::fresnel_schlick;
use crate::scene::Scene;
use glam::Vec3;
use std::f32::consts::PI;

/// Smallest GGX α used for evaluating point-light highlights (a delta lobe has none).
const MIN_ALPHA: f32 = 1e-2;

/// glTF BRDF f(wo, wi) for shading normal `n` (both directions on `n`'s side).
pub fn brdf(mat: &Material, sp: &ShadingPoint, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
    let nl = n.dot(wi);
    let nv = n.dot(wo);
    if nl <= 0.0 || nv <= 0.0 {
        return Vec3::ZERO;
    }
    let h = (wo + wi).normalize_or_zero();
    let nh = n.dot(h).max(0.0);
    let vh = wo.dot(h).max(0.0);
    let alpha = (sp.roughness * sp.roughness).max(MIN_ALPHA);
    let a2 = alpha * alpha;
    // GGX normal distribution (Walter et al. 2007, eq. 33).
    let dd = nh * nh * (a2 - 1.0) + 1.0;
    let d = a2 / (PI * dd * dd);
    // Height-correlated Smith visibility V = G/(4 NL NV) (Heitz 2014, eq. 99).
    let gv = nl * (nv * nv * (1.0 - a2) + a2).sqrt();
    let gl = nv * (nl * nl * (1.0 - a2) + a2).sqrt();
    let vis = 0.5 / (gv + gl).max(1e-12);
    let spec = d * vis;
    // Dielectric F0 from the IOR and KHR_materials_specular.
    let ior = mat.ior();
    let f0_ior = if ior.is_finite() {
        ((ior - 1.0) / (ior + 1.0)).powi(2)
    } else {
        1.0
    };
    let ds = &mat.desc;
    let f0_d = (Vec3::splat(f0_ior) * ds.specular_color).min(Vec3::ONE) * ds.specular;
    let f_d = f0_d + (Vec3::splat(ds.specular) - f0_d) * (1.0 - vh).powi(5);
    let diffuse = sp.base_color / PI;
    // KHR_materials_specular: the diffuse base is scaled by 1 − max(F).
    let dielectric = diffuse * (1.0 - f_d.max_element()) + f_d * spec;
    let metal = fresnel_schlick(sp.base_color, vh) * spec;
    dielectric.lerp(metal, sp.metallic)
}

/// An opaque hit seen from the viewer's side, ready to receive light.
struct Receiver<'a> {
    scene: &'a Scene,
    hit: &'a SurfaceHit,
    mat: &'a Material,
    sp: &'a ShadingPoint,
    /// Shading normal on the viewer's side.
    n: Vec3,
    /// Geometric normal on the viewer's side.
    ng: Vec3,
}

impl Receiver<'_> {
    /// Light arriving from unit direction `wi` along the unblocked `shadow` ray, carrying
    /// `incident` (irradiance at normal incidence, or radiance / pdf): f · incident · cos.
    fn connect(
        &self,
        wi: Vec3,
        shadow: crate::math::Ray,
        incident: Vec3,
        ctx: &mut Context,
    ) -> Vec3 {
        let cos = self.n.dot(wi);
        if cos <= 0.0 || self.ng.dot(wi) <= 0.0 {
            return Vec3::ZERO;
        }
        let f = brdf(self.mat, self.sp, self.n, self.hit.wo, wi);
        if f == Vec3::ZERO {
            return Vec3::ZERO;
        }
        ctx.rays += 1;
        if self.scene.occluded(&shadow) {
            return Vec3::ZERO;
        }
        f * incident * cos
    }
}

/// Direct light at an opaque hit, with shadow rays: every punctual light, one sample of the
/// emissive triangles and one of the environment.
pub fn direct_light(
    scene: &Scene,
    hit: &SurfaceHit,
    mat: &Material,
    sp: &ShadingPoint,
    ctx: &mut Context,
) -> Vec3 {
    // Shade the side the viewer is on.
    let (n, ng) = if hit.front_face || mat.desc.double_sided || !mat.is_volume() {
        let s = if hit.ng.dot(hit.wo) >= 0.0 { 1.0 } else { -1.0 };
        (hit.ns * s, hit.ng * s)
    } else {
        (-hit.ns, -hit.ng)
    };
    let r = Receiver {
        scene,
        hit,
        mat,
        sp,
        n,
        ng,
    };
    let mut sum = Vec3::ZERO;
    for light in &scene.lights {
        if let Some(ls) = light.sample_li(hit.p) {
            let shadow = match ls.position {
                Some(p) => hit.spawn_ray_to(p),
                None => hit.spawn_ray(ls.wi),
            };
            sum += r.connect(ls.wi, shadow, ls.irradiance, ctx);
        }
    }
    sum + area_light(&r, ctx) + environment(&r, ctx)
}

/// One importance sample of the environment light.
fn environment(r: &Receiver, ctx: &mut Context) -> Vec3 {
    let Some(env) = &r.scene.environment else {
        return Vec3::ZERO;
    };
    let u = glam::Vec2::new(ctx.rng.next_f32(), ctx.rng.next_f32());
    match env.sample(u) {
        Some(s) => r.connect(s.wi, r.hit.spawn_ray(s.wi), s.radiance / s.pdf, ctx),
        None => Vec3::ZERO,
    }
}

/// One sample of the emissive triangles.
fn area_light(r: &Receiver, ctx: &mut Context) -> Vec3 {
    let scene = r.scene;
    let u = ctx.rng.next_f32();
    let uv = glam::Vec2::new(ctx.rng.next_f32(), ctx.rng.next_f32());
    let Some(s) = scene
        .area_lights
        .sample(&scene.triangle_data, r.hit.p, u, uv)
    else {
        return Vec3::ZERO;
    };
    if s.pdf.is_nan() || s.pdf <= 0.0 {
        return Vec3::ZERO;
    }
    let light = &scene.materials[scene.triangle_data[s.prim as usize].material() as usize].desc;
    // Single-sided emitters only shine along their outward normal.
    if !light.double_sided && s.normal.dot(s.wi) >= 0.0 {
        return Vec3::ZERO;
    }
    r.connect(
        s.wi,
        r.hit.spawn_ray_to(s.point),
        light.emissive / s.pdf,
        ctx,
    )
}
