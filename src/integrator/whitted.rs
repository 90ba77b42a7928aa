//! Whitted-style recursive ray tracing, as in Cropp & Zhang, "Light Refraction with
//! Dispersion", §4: at a dielectric the ray splits into a reflected and a refracted branch
//! weighted by the exact Fresnel equations (total internal reflection sends everything to
//! the reflected branch); opaque surfaces
//! get direct light (punctual, emissive triangles, environment); smooth metals recurse as
//! mirrors (Schlick from the base colour, or a measured metal's complex Fresnel). Entering vs exiting comes from `front_face`; each branch carries the stack of
//! media it is inside ([`crate::medium_stack`]), so η is the ratio of the indices on the two
//! sides (glass → water is 1.33/1.5, not 1.33/1), and Beer–Lambert absorption applies to
//! the medium a segment actually crossed.
//!
//! Each hit arrives through the shared step ([`crate::shading::arrive`]: the surface
//! really met, its material, the segment's transmittance); the rest is this tracer's own
//! branching, alpha-BLEND coverage included (a deterministic α / 1 − α split where the
//! other loops choose stochastically).
//!
//! What it does with each lobe of [`crate::bsdf::Bsdf`]: it samples none. A material's
//! opaque lobe ([`crate::material::Material::opaque_bsdf`]: the glTF mix or a measured
//! conductor) is asked only for its value under each light ([`crate::bsdf::Bsdf::eval`]
//! in [`crate::shading::direct_light`]; a delta lobe, [`crate::bsdf::Bsdf::is_delta`],
//! answers 0 there); the reflections and refractions are the deterministic Fresnel
//! branches above, from the material's parameters, so the transmitting lobes (dielectric,
//! thin wall) are never built and smooth metals (roughness < 0.1) recurse as mirrors.
//!
//! Branches whose weight falls below [`RR_WEIGHT`] continue by Russian roulette (unbiased),
//! so a gem's branching stays bounded; `max_depth` bounds the recursion.

use super::capability::{
    Capabilities, Photons, Support, Units, NO_MEDIA, NO_POLARIZATION, SINGLE_RAYS,
};
use super::Context;
use crate::material::AlphaMode;
use crate::math::Ray;
use crate::medium_stack::MediumStack;
use crate::optics::{fresnel_conductor_c, fresnel_dielectric, fresnel_schlick, reflect, refract};
use crate::scene::Scene;
use crate::shading::termination::{roulette, Draw};
use crate::shading::{self, Arrival};
use crate::spectrum::Carrier;

/// What `--method whitted` renders and how ([`crate::integrator::Method::caps`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    name: "whitted",
    purpose: "a quick look: sharp reflections and refractions, no soft light",
    units: Units::Samples,
    photons: Photons::None,
    media: NO_MEDIA,
    orthographic: Support::Yes,
    polarization: NO_POLARIZATION,
    rayleigh_spectral: Support::Yes,
    lanes: SINGLE_RAYS,
    shards: Support::Yes,
    adaptive: Support::Yes,
    estimate_in_media: Support::Yes,
    progressive: Support::Yes,
    pixel_bytes: 0,
};

/// Branch weight (max RGB component) below which Russian roulette decides survival.
pub const RR_WEIGHT: f32 = 0.01;

/// Where a branch is: its depth, the limit, and the media it is inside.
#[derive(Debug, Clone, Copy)]
struct Path<C: Carrier> {
    depth: u32,
    max_depth: u32,
    media: MediumStack,
    /// The sample's wavelengths (marked hero-only past a dispersive interface).
    lambda: C::Lambda,
}

/// Radiance along `ray` (the camera is in air) at the sample's wavelengths `lambda`.
pub fn radiance<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    max_depth: u32,
    lambda: C::Lambda,
    ctx: &mut Context,
) -> C {
    let path = Path {
        depth: 0,
        max_depth,
        media: MediumStack::new(),
        lambda,
    };
    trace(scene, ray, path, C::ONE, ctx)
}

/// Continues a branch with weight `w` (relative to the pixel): returns the weight to
/// multiply its radiance by, or `None` if Russian roulette ends it.
fn survive<C: Carrier>(w: C, ctx: &mut Context) -> Option<f32> {
    let m = w.max_element();
    if m >= RR_WEIGHT {
        return Some(1.0);
    }
    let p = m / RR_WEIGHT;
    roulette(p, Draw::UnlessDead, || ctx.sample.rng.next_f32()).map(|p| 1.0 / p)
}

fn trace<C: Carrier>(scene: &Scene, ray: &Ray, path: Path<C>, w: C, ctx: &mut Context) -> C {
    if path.depth >= path.max_depth {
        return C::ZERO;
    }
    let Some(at) = shading::arrive::<C>(scene, ray, &path.media, &path.lambda, &mut ctx.rays)
    else {
        return scene.environment().map_or(C::ZERO, |e| {
            C::illuminant(e.eval(ray.dir.normalize()), &path.lambda)
        });
    };
    // Beer–Lambert over the segment just travelled, inside the current medium.
    shade(scene, &at, path, w, ctx) * at.transmittance
}

/// Follows a child branch of weight `w·k` with the media `media`.
fn branch<C: Carrier>(
    scene: &Scene,
    ray: Ray,
    path: Path<C>,
    media: MediumStack,
    w: C,
    k: C,
    ctx: &mut Context,
) -> C {
    let wk = w * k;
    let child = Path {
        depth: path.depth + 1,
        media,
        ..path
    };
    match survive(wk, ctx) {
        Some(s) => k * s * trace(scene, &ray, child, wk * s, ctx),
        None => C::ZERO,
    }
}

/// Radiance leaving the surface arrived at toward the branch: emission, the dielectric's
/// Fresnel split, direct light and mirror reflection on the opaque part, and BLEND's
/// uncovered part continued straight on.
fn shade<C: Carrier>(
    scene: &Scene,
    at: &Arrival<'_, C>,
    path: Path<C>,
    w: C,
    ctx: &mut Context,
) -> C {
    let (hit, mat, sp) = (&at.hit, at.mat, &at.sp);
    let mut l = C::emitted(sp.emissive, mat.emitter_shape(), &path.lambda);
    let t = sp.transmission;
    if t > 0.0 {
        l += dielectric(scene, at, path, w * t, ctx) * t;
    }
    let opaque = 1.0 - t;
    if opaque > 0.0 {
        let mut u = ctx.sample.bounce(path.depth);
        let mut o = shading::direct_light(scene, at, &path.lambda, &mut u, &mut ctx.rays);
        // Smooth metals reflect the scene as mirrors.
        if sp.metallic > 0.0 && sp.roughness < 0.1 {
            let n = if hit.wo.dot(hit.ns) >= 0.0 {
                hit.ns
            } else {
                -hit.ns
            };
            let r = reflect(hit.wo, n);
            if r.dot(hit.ng) * hit.wo.dot(hit.ng) > 0.0 {
                let cos = hit.wo.dot(n);
                let fresnel = match mat.conductor_index::<C>(&path.lambda) {
                    Some((eta, k)) => fresnel_conductor_c(cos, eta, k),
                    None => fresnel_schlick(C::reflectance(sp.base_color, &path.lambda), cos),
                };
                let f = fresnel * sp.metallic;
                o += branch(
                    scene,
                    hit.spawn_ray(r),
                    path,
                    path.media,
                    w * opaque,
                    f,
                    ctx,
                );
            }
        }
        l += o * opaque;
    }
    // glTF BLEND: partial coverage lets the rest of the light through unchanged.
    if matches!(mat.desc.alpha_mode, AlphaMode::Blend) && sp.alpha < 1.0 {
        let k = C::splat(1.0 - sp.alpha);
        let behind = branch(scene, hit.spawn_ray(-hit.wo), path, path.media, w, k, ctx);
        l = l * sp.alpha + behind;
    }
    l
}

/// The smooth dielectric interface: Fresnel-weighted reflection and refraction.
fn dielectric<C: Carrier>(
    scene: &Scene,
    at: &Arrival<'_, C>,
    path: Path<C>,
    w: C,
    ctx: &mut Context,
) -> C {
    let (hit, mat, sp) = (&at.hit, at.mat, &at.sp);
    let tint = C::reflectance(sp.base_color, &path.lambda);
    // Normal on the incident side.
    let n = if hit.front_face { hit.ns } else { -hit.ns };
    let cos_i = hit.wo.dot(n).max(0.0);
    if !mat.is_volume() {
        // Thin wall: no bending, the media do not change; the base colour tints what passes.
        let f = fresnel_dielectric(cos_i, mat.ior());
        let r = branch(
            scene,
            hit.spawn_ray(reflect(hit.wo, n)),
            path,
            path.media,
            w,
            C::splat(f),
            ctx,
        );
        let k = tint * (1.0 - f);
        return r + branch(scene, hit.spawn_ray(-hit.wo), path, path.media, w, k, ctx);
    }
    // Coincident faces of touching volumes are crossed as one interface.
    // In spectral transport a dispersive interface keeps the hero wavelength only, on both
    // branches (the Fresnel split depends on λ too).
    let (n_i, n_t, media_t, dispersive) =
        shading::interface::<C>(scene, hit, &at.coincident, path.media, &path.lambda);
    let mut path = path;
    let mut hero = C::ONE;
    if dispersive {
        hero = hero.keep_hero(&mut path.lambda);
    }
    // η = n_t / n_i; both infinite (inside an `ior: 0` medium) behaves as no interface.
    let eta = if n_i == n_t { 1.0 } else { n_t / n_i };
    let f = fresnel_dielectric(cos_i, eta);
    let mut l = branch(
        scene,
        hit.spawn_ray(reflect(hit.wo, n)),
        path,
        path.media,
        w,
        hero * f,
        ctx,
    );
    if f < 1.0 {
        if let Some(dir) = refract(hit.wo, n, eta) {
            // Radiance is scaled by 1/η² across the interface (pbrt-v4 §9.5.2).
            let k = hero * tint * ((1.0 - f) / (eta * eta));
            l += branch(scene, hit.spawn_ray(dir), path, media_t, w, k, ctx);
        }
    }
    l
}
