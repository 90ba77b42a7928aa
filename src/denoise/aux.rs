//! The auxiliary pass for the denoiser: per pixel, the albedo and the shading normal of the
//! first non-specular surface the camera sees, followed through glass and mirrors (Cycles'
//! denoising features, `kernel/film/denoising_passes.h`; OIDN's docs, "RT" filter, Albedos and
//! Normals: "follow perfect specular (delta) paths and store features for the first diffuse
//! or glossy surface hit"). A separate pass over camera rays, like
//! [`crate::render::coverage`]; the integrators are untouched.
//!
//! Per pixel, `samples` camera rays jittered as the render's samples are, so the features
//! have the beauty image's pixel filter (a box; OIDN asks for the same reconstruction in
//! every input): the render's sampler over a block of max(spp, `samples`) samples
//! ([`crate::render::primary_ray`]; with `samples` ≤ spp, ray k is the render's sample k;
//! every ray goes through the pixel centre when the render takes 1 spp), each followed by the shared per-hit
//! step ([`crate::shading::arrive`], RGB transport) through delta surfaces — smooth glass
//! and thin walls reflect or refract as their BSDF samples it (Fresnel, with the sample's
//! scheduled lobe number, so the choice is stratified over the pixel), smooth mirrors
//! reflect — multiplying the throughput by the sampled lobe's weight f·|cos θ|/pdf (the
//! transmission tint, the mirror's colour; in importance mode, so without radiance's 1/η²)
//! and by Beer–Lambert transmittance, for at most [`AUX_MAX_DELTA`] delta bounces. Rays only
//! ever leave surfaces through the intersection layer's spawn rules. At the first
//! non-specular surface:
//! - albedo = throughput × the surface's reflectance ([`crate::bsdf::Bsdf::albedo`]: OIDN's
//!   diffuse colour, a metal's normal-incidence reflectance, the tint of rough glass) plus
//!   its emission (clamped to [0, 1]: Cycles adds an emitter's contribution to the
//!   denoising albedo), and
//!   normal = its world-space shading normal, turned to face the arriving ray;
//! - a ray that escapes: albedo = throughput × the environment radiance it sees clamped to
//!   [0, 1] (what Cycles writes for the background, `film_write_emission_or_background_pass`),
//!   normal = 0; without an environment both are 0;
//! - a path still specular after [`AUX_MAX_DELTA`] bounces: the throughput and that
//!   surface's normal.
//!
//! The pixel's value is the mean over its rays. Deterministic: the numbers are the render's
//! sampler's (seed, pixel, sample), whatever the thread count. Units: albedo dimensionless
//! in [0, 1]; normals world-space, length ≤ 1.

use super::AuxImages;
use crate::bsdf::TransportMode;
use crate::camera::Camera;
use crate::image::ImageRgb;
use crate::medium_stack::MediumStack;
use crate::render::{pixel_sampler, primary_ray, RenderSettings};
use crate::sampler::SampleStream;
use crate::scene::Scene;
use crate::shading::{arrive, Event};
use glam::Vec3;
use rayon::prelude::*;

/// Most camera rays per pixel the pass takes ([`aux_samples`]).
pub const AUX_SAMPLES: u64 = 16;

/// Camera rays per pixel for a render of `spp` samples: 2·spp, at most [`AUX_SAMPLES`].
///
/// The features must be averaged over the pixel like the beauty image, and their own noise
/// (at glass, where the Fresnel choice splits the rays) leaks into the result. Measured on
/// the paper's Fig. 7.1 spheres (96×72, path tracer, relative MSE of the denoised image
/// over the raw one's against 256 spp, 8 seeds): at 4 spp, 4 rays 0.21–0.44, 8 rays
/// 0.17–0.37, 16 rays 0.15–0.30; at 8 spp, 8 rays 0.35–0.49, 16 rays 0.29–0.40; one
/// jittered ray at 4 spp (aliased features under an anti-aliased image) 0.75–1.2, no gain.
/// A ray costs about 0.4 of a path-traced sample there (800×600, 16 rays: 15.2 s, one
/// path-traced spp: 2.3 s, same loaded 2 cores), so 2·spp keeps the pass within about the
/// render's own cost at low spp and far below it at high spp.
pub fn aux_samples(spp: u32) -> u64 {
    (2 * u64::from(spp.max(1))).min(AUX_SAMPLES)
}

/// Most delta bounces followed per ray (a gem's facets: a ray inside a brilliant reflects
/// a few times before leaving).
pub const AUX_MAX_DELTA: u32 = 16;

/// The (albedo, normal) one camera ray sees (see the module docs); `sample` supplies the
/// Fresnel and layer choices.
fn features(scene: &Scene, ray: &crate::math::Ray, sample: &mut SampleStream) -> (Vec3, Vec3) {
    let mut ray = *ray;
    let mut beta = Vec3::ONE;
    let mut media = MediumStack::new();
    let mut rays = 0u64;
    let clamp01 =
        |v: Vec3| Vec3::select(v.is_finite_mask(), v, Vec3::ZERO).clamp(Vec3::ZERO, Vec3::ONE);
    let mut vertex = 0u32;
    // Passes through BLEND surfaces do not count as delta bounces but are bounded too.
    for _ in 0..(2 * AUX_MAX_DELTA + 2) {
        let Some(at) = arrive::<Vec3>(scene, &ray, &media, &(), &mut rays) else {
            let env = scene
                .environment()
                .as_ref()
                .map_or(Vec3::ZERO, |e| e.eval(ray.dir.normalize()));
            return (beta * clamp01(env), Vec3::ZERO);
        };
        beta *= at.transmittance;
        let emission = at.sp.emissive;
        let mut u = sample.bounce(vertex);
        let s = match at.event(scene, media, &mut beta, &mut (), &mut u) {
            Event::PassThrough(next) => {
                ray = next;
                continue;
            }
            Event::Scatter(s) => s,
        };
        let n = s.hit.ns;
        let facing = if n.dot(s.hit.wo) < 0.0 { -n } else { n };
        if !s.bsdf.is_delta() || vertex >= AUX_MAX_DELTA {
            let own = if s.bsdf.is_delta() {
                Vec3::ONE
            } else {
                s.bsdf.albedo() + emission
            };
            return (clamp01(beta * clamp01(own)), facing);
        }
        let (uc, uv) = (u.bsdf_lobe(), u.bsdf_direction());
        let Some(bs) = s.sample(uc, uv, TransportMode::Importance) else {
            return (Vec3::ZERO, facing);
        };
        beta *= bs.f * (bs.wi.z.abs() / bs.pdf);
        media = s.media_after(bs.transmission);
        ray = s.spawn(bs.wi);
        vertex += 1;
    }
    (Vec3::ZERO, Vec3::ZERO)
}

/// The auxiliary images of the render `settings` describe, from `samples` camera rays per
/// pixel (at least 1), on the current rayon pool.
pub fn aux_pass(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    samples: u64,
) -> AuxImages {
    let (w, h) = (settings.width, settings.height);
    let n = samples.max(1);
    let sampler = pixel_sampler(settings, u64::from(settings.spp.max(1)).max(n));
    let rows: Vec<Vec<(Vec3, Vec3)>> = (0..h)
        .into_par_iter()
        .map(|y| {
            (0..w)
                .map(|x| {
                    let (mut albedo, mut normal) = (Vec3::ZERO, Vec3::ZERO);
                    for k in 0..n {
                        let mut sample = sampler.start(x, y, k);
                        let ray = primary_ray(camera, x, y, settings.spp <= 1, &mut sample);
                        let (a, nrm) = features(scene, &ray, &mut sample);
                        albedo += a;
                        normal += nrm;
                    }
                    (albedo / n as f32, normal / n as f32)
                })
                .collect()
        })
        .collect();
    let mut albedo = ImageRgb::new(w, h);
    let mut normal = ImageRgb::new(w, h);
    for (i, (a, nrm)) in rows.into_iter().flatten().enumerate() {
        albedo.data[i] = a;
        normal.data[i] = nrm;
    }
    AuxImages { albedo, normal }
}
