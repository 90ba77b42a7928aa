//! Whitted-style recursive ray tracing, as in the seed paper §4: at a dielectric the ray
//! splits into a reflected and a refracted branch weighted by the exact Fresnel equations
//! (total internal reflection sends everything to the reflected branch); opaque surfaces
//! get direct light from punctual lights; smooth metals recurse as mirrors. Entering vs
//! exiting comes from `front_face`, which picks η = n_in/n_out or its inverse (the outside
//! medium is air here; nested media come with the path tracer).
//!
//! Branches whose weight falls below [`RR_WEIGHT`] continue by Russian roulette (unbiased),
//! so a gem's branching stays bounded; `max_depth` bounds the recursion.

use super::{shading, Context};
use crate::interaction::SurfaceHit;
use crate::math::Ray;
use crate::optics::{fresnel_dielectric, orient_interface, reflect, refract};
use crate::scene::Scene;
use glam::Vec3;

/// Branch weight (max RGB component) below which Russian roulette decides survival.
pub const RR_WEIGHT: f32 = 0.01;

/// Radiance along `ray`.
pub fn radiance(scene: &Scene, ray: &Ray, max_depth: u32, ctx: &mut Context) -> Vec3 {
    trace(scene, ray, 0, max_depth, Vec3::ONE, ctx)
}

/// Continues a branch with weight `w` (relative to the pixel): returns the weight to
/// multiply its radiance by, or `None` if Russian roulette ends it.
fn survive(w: Vec3, ctx: &mut Context) -> Option<f32> {
    let m = w.max_element();
    if m <= 0.0 {
        return None;
    }
    if m >= RR_WEIGHT {
        return Some(1.0);
    }
    let p = m / RR_WEIGHT;
    (ctx.rng.next_f32() < p).then_some(1.0 / p)
}

fn trace(scene: &Scene, ray: &Ray, depth: u32, max_depth: u32, w: Vec3, ctx: &mut Context) -> Vec3 {
    if depth >= max_depth {
        return Vec3::ZERO;
    }
    ctx.rays += 1;
    let Some(hit) = scene.intersect(ray) else {
        return scene
            .environment
            .as_ref()
            .map_or(Vec3::ZERO, |e| e.eval(ray.dir.normalize()));
    };
    let mat = &scene.materials[hit.material as usize];
    let l = shade(scene, &hit, depth, max_depth, w, ctx);
    // Beer–Lambert: the segment just travelled was inside this volume if we exit it.
    if !hit.front_face && mat.is_volume() && mat.is_transmissive() {
        l * mat.transmittance(hit.t)
    } else {
        l
    }
}

/// Follows a child branch of weight `w·k`.
fn branch(
    scene: &Scene,
    ray: Ray,
    depth: u32,
    max_depth: u32,
    w: Vec3,
    k: Vec3,
    ctx: &mut Context,
) -> Vec3 {
    let wk = w * k;
    match survive(wk, ctx) {
        Some(s) => k * s * trace(scene, &ray, depth + 1, max_depth, wk * s, ctx),
        None => Vec3::ZERO,
    }
}

fn shade(
    scene: &Scene,
    hit: &SurfaceHit,
    depth: u32,
    max_depth: u32,
    w: Vec3,
    ctx: &mut Context,
) -> Vec3 {
    let mat = &scene.materials[hit.material as usize];
    let sp = mat.shade(hit.uv, &scene.images);
    let mut l = sp.emissive;
    let t = sp.transmission;
    if t > 0.0 {
        l += t * dielectric(scene, hit, &sp, depth, max_depth, w * t, ctx);
    }
    let opaque = 1.0 - t;
    if opaque > 0.0 {
        let mut o = shading::direct_light(scene, hit, mat, &sp, ctx);
        // Smooth metals reflect the scene as mirrors.
        if sp.metallic > 0.0 && sp.roughness < 0.1 {
            let n = if hit.wo.dot(hit.ns) >= 0.0 {
                hit.ns
            } else {
                -hit.ns
            };
            let r = reflect(hit.wo, n);
            if r.dot(hit.ng) * hit.wo.dot(hit.ng) > 0.0 {
                let f = crate::optics::fresnel_schlick(sp.base_color, hit.wo.dot(n)) * sp.metallic;
                o += branch(
                    scene,
                    hit.spawn_ray(r),
                    depth,
                    max_depth,
                    w * opaque,
                    f,
                    ctx,
                );
            }
        }
        l += opaque * o;
    }
    // glTF BLEND: partial coverage lets the rest of the light through unchanged.
    if matches!(mat.desc.alpha_mode, crate::scene::desc::AlphaMode::Blend) && sp.alpha < 1.0 {
        let behind = branch(
            scene,
            hit.spawn_ray(-hit.wo),
            depth,
            max_depth,
            w,
            Vec3::splat(1.0 - sp.alpha),
            ctx,
        );
        l = l * sp.alpha + behind;
    }
    l
}

/// The smooth dielectric interface: Fresnel-weighted reflection and refraction.
fn dielectric(
    scene: &Scene,
    hit: &SurfaceHit,
    sp: &crate::material::ShadingPoint,
    depth: u32,
    max_depth: u32,
    w: Vec3,
    ctx: &mut Context,
) -> Vec3 {
    let mat = &scene.materials[hit.material as usize];
    let ior = mat.ior();
    let thin = !mat.is_volume();
    // Normal on the incident side, and η = n_t / n_i from front_face.
    let (n, eta) = orient_interface(hit.front_face, hit.ns, ior);
    let cos_i = hit.wo.dot(n).max(0.0);
    let f = fresnel_dielectric(cos_i, eta);
    let mut l = Vec3::ZERO;
    let r = reflect(hit.wo, n);
    l += branch(
        scene,
        hit.spawn_ray(r),
        depth,
        max_depth,
        w,
        Vec3::splat(f),
        ctx,
    );
    if f < 1.0 {
        if thin {
            // Thin wall: no bending; the base colour tints what passes.
            let k = sp.base_color * (1.0 - f);
            l += branch(scene, hit.spawn_ray(-hit.wo), depth, max_depth, w, k, ctx);
        } else if let Some(dir) = refract(hit.wo, n, eta) {
            // Radiance is scaled by 1/η² across the interface (pbrt-v4 §9.5.2).
            let k = sp.base_color * ((1.0 - f) / (eta * eta));
            l += branch(scene, hit.spawn_ray(dir), depth, max_depth, w, k, ctx);
        }
    }
    l
}
