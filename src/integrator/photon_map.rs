//! Classic two-pass photon mapping (`--method photon`; Jensen 1996, "Global Illumination
//! using Photon Maps", and Jensen 2001, "Realistic Image Synthesis Using Photon Mapping").
//!
//! Pass 1 traces `photons` photons ([`crate::photon`]) and builds two kd-tree maps:
//! - the **caustic map**: photons whose path is L S+ D (specular or near-specular bounces
//!   only, then a diffuse-like surface);
//! - the **global map**: every photon at a diffuse-like surface.
//!
//! One rule splits the surfaces ([`crate::bsdf::Bsdf::is_diffuse_like`]): photons are
//! stored, and the maps queried, only at diffuse-like surfaces; every other surface (delta,
//! or glossy below [`crate::shading::GLOSSY_ALPHA`]) is an S vertex that camera paths,
//! gather rays and the caustic flag all pass through by BSDF sampling. A glossy mirror is
//! thus never a gather point: the light it reflects onto a diffuse surface is the caustic
//! map's alone.
//!
//! Photon `i` is emitted from Halton point `i` (digit-permuted by the seed,
//! [`crate::photon::emit::PhotonNumbers`]), aimed at the
//! caustic makers ([`crate::photon::emit::DEFAULT_AIM`], unbiased); its path after emission
//! draws from `Rng::new(&[seed, i, 0x9E07_0001])`.
//!
//! Pass 2 follows camera paths with the path tracer's loop ([`path::camera_path`]) through
//! specular and glossy bounces to the first diffuse-like hit x, and adds there
//! - direct light from shadow rays (the path tracer's next-event estimation),
//! - the caustic map's radiance estimate: the k nearest caustic photons with Jensen's cone
//!   filter (k_cone = 1.1; L = Σ f Φ w_p / ((1 − 2/(3 k_cone)) π r²), w_p = 1 − d/(k_cone r)),
//! - one final-gather ray per camera sample: BSDF-sampled from x, through S surfaces
//!   (and the uncovered part of alpha-BLEND ones) to the next diffuse-like hit y,
//!   where the global map's k-nearest estimate gives the radiance leaving y toward x. Each
//!   hit is the per-hit step of camera and photon paths ([`crate::shading::step`]).
//!   Emission and the environment seen by gather rays are skipped (they are direct light or
//!   caustics, already counted).
//!
//! Spectral scenes: photons are traced spectrally (4 random wavelengths each, a dispersive
//! interface keeps the hero, as in Cropp & Zhang, "Light Refraction with Dispersion": one
//! wavelength per photon), and each stored photon's flux is converted to linear RGB
//! through the film's conversion ([`Carrier::to_rgb`]) when it is stored; camera paths and
//! gathering are RGB (dispersive glass seen directly uses n_d). `--method sppm` is fully spectral.
//!
//! Flux in the maps is per emitted photon (already divided by their number).

use super::capability::{
    Capabilities, Photons, Support, Units, NO_MEDIA, NO_POLARIZATION, SINGLE_RAYS,
};
use super::path::{self, VisiblePoint};
use super::sppm::VisiblePoints;
use super::{Context, PhotonMapSettings, StoreBudget};
use crate::bsdf::TransportMode;
use crate::camera::Camera;
use crate::error::Result;
use crate::math::{Frame, Ray, Rng};
use crate::medium_stack::MediumStack;
use crate::photon::emit::{PhotonEmitter, PhotonNumbers, DEFAULT_AIM};
use crate::photon::kdtree::PhotonMap;
use crate::photon::store::Photon;
use crate::photon::trace::{self, TraceSettings};
use crate::render::{render_samples, Film, Observer, Prepass, RenderSettings, RenderStats};
use crate::scene::Scene;
use crate::shading::{self, Event};
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::time::Instant;

/// What `--method photon` renders and how ([`crate::integrator::Method::caps`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    name: "photon",
    purpose: "caustics fast from a photon map, slightly blurred",
    units: Units::Samples,
    photons: Photons::Map,
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

/// Photons when `--photons` is not given.
pub const DEFAULT_PHOTONS: u64 = 500_000;
/// Jensen's cone-filter constant k.
const CONE_K: f32 = 1.1;
/// Photons traced per parallel work item.
const CHUNK: u64 = 4096;
/// Most surfaces a final-gather ray scatters at (the last one diffuse-like); BLEND surfaces
/// it passes through do not count.
const GATHER_SPECULAR: u32 = 16;

/// Where a map is queried: a position and its BSDF in the local frame.
struct GatherPoint {
    p: Vec3,
    frame: Frame,
    /// Direction toward the viewer, local.
    wo: Vec3,
    bsdf: crate::bsdf::Bsdf<Vec3>,
}

/// The two photon maps.
pub struct PhotonMaps {
    /// L S+ D photons.
    pub caustic: PhotonMap,
    /// All photons at diffuse-like surfaces.
    pub global: PhotonMap,
    /// Largest gather radius, squared.
    pub max_r2: f32,
    /// Rays traced building the maps.
    pub rays: u64,
    /// Photons emitted.
    pub emitted: u64,
}

/// Traces `n` photons and builds the maps (photon powers are per emitted photon); an error
/// if they would be stored more than [`super::MAX_STORED_PHOTONS`] times.
pub fn build_maps(
    scene: &Scene,
    n: u64,
    settings: &TraceSettings,
    seed: u64,
    spectral: bool,
) -> Result<(Vec<Photon>, Vec<Photon>, u64)> {
    let emitter = PhotonEmitter::new(scene);
    let numbers = PhotonNumbers::new(seed);
    let inv_n = 1.0 / n.max(1) as f32;
    let chunks = n.div_ceil(CHUNK);
    let budget = StoreBudget::default();
    let per_chunk: Vec<(Vec<Photon>, Vec<Photon>, u64)> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let (mut caustic, mut global, mut rays) = (Vec::new(), Vec::new(), 0);
            for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                let mut rng = Rng::new(&[seed, i, 0x9E07_0001]);
                let Some(ph) = emitter.emit_index(scene, &numbers, i, DEFAULT_AIM) else {
                    continue;
                };
                let before = caustic.len() + global.len();
                let mut keep = |p: Vec3, wi: Vec3, rgb: Vec3, is_caustic: bool| {
                    let photon = Photon::new(p, wi, (rgb * inv_n).to_lanes(), 0);
                    if is_caustic {
                        caustic.push(photon);
                    }
                    global.push(photon);
                };
                rays += if spectral {
                    let lambda = SampledSpectrum::sample_lambda(rng.next_f32());
                    trace::trace::<SampledSpectrum>(
                        scene,
                        &ph,
                        lambda,
                        settings,
                        &mut rng,
                        |v, l| {
                            if v.surface.bsdf.is_diffuse_like() {
                                keep(v.p, v.wi, v.power.to_rgb(l), v.caustic)
                            }
                        },
                    )
                } else {
                    trace::trace::<Vec3>(scene, &ph, (), settings, &mut rng, |v, _| {
                        if v.surface.bsdf.is_diffuse_like() {
                            keep(v.p, v.wi, v.power, v.caustic)
                        }
                    })
                };
                if !budget.add(caustic.len() + global.len() - before) {
                    break;
                }
            }
            (caustic, global, rays)
        })
        .collect();
    budget.check(n, settings.max_depth)?;
    let (mut caustic, mut global, mut rays) = (Vec::new(), Vec::new(), 0);
    for (c, g, r) in per_chunk {
        caustic.extend(c);
        global.extend(g);
        rays += r;
    }
    Ok((caustic, global, rays))
}

impl PhotonMaps {
    /// Reflected radiance at `at` from the k nearest photons of `map` within the largest
    /// radius, cone-filtered (`cone`) or not.
    fn estimate(
        &self,
        map: &PhotonMap,
        k: usize,
        at: &GatherPoint,
        cone: bool,
        buf: &mut Vec<(f32, u32)>,
    ) -> Vec3 {
        if map.is_empty() {
            return Vec3::ZERO;
        }
        let found = map.knn(at.p, k, self.max_r2, buf);
        if buf.is_empty() {
            return Vec3::ZERO;
        }
        // Fewer than k photons within the largest radius: the density is over that disc.
        let r2 = if buf.len() < k { self.max_r2 } else { found };
        if r2.is_nan() || r2 <= 0.0 {
            return Vec3::ZERO;
        }
        let r = r2.sqrt();
        let mut sum = Vec3::ZERO;
        for &(d2, i) in buf.iter() {
            let Some(ph) = map.get(i as usize) else {
                continue;
            };
            let f = at
                .bsdf
                .eval(at.wo, at.frame.to_local(ph.wi()), TransportMode::Radiance);
            let wgt = if cone {
                1.0 - d2.sqrt() / (CONE_K * r)
            } else {
                1.0
            };
            sum += f * Vec3::from_lanes(ph.power()) * wgt;
        }
        let norm = if cone {
            1.0 - 2.0 / (3.0 * CONE_K)
        } else {
            1.0
        };
        sum / (norm * std::f32::consts::PI * r2)
    }

    /// Caustics plus one final-gather sample at a visible point.
    fn indirect(
        &self,
        scene: &Scene,
        vp: &VisiblePoint<Vec3>,
        k: (usize, usize),
        ctx: &mut Context,
        buf: &mut Vec<(f32, u32)>,
    ) -> Vec3 {
        let at = GatherPoint {
            p: vp.p,
            frame: vp.frame,
            wo: vp.wo,
            bsdf: vp.bsdf,
        };
        let l = self.estimate(&self.caustic, k.0, &at, true, buf);
        // Final gather.
        let uc = ctx.sample.rng.next_f32();
        let u = Vec2::new(ctx.sample.rng.next_f32(), ctx.sample.rng.next_f32());
        let Some(bs) = shading::sample_bsdf(&vp.bsdf, vp.wo, uc, u, TransportMode::Radiance) else {
            return l;
        };
        let beta = bs.f * (bs.wi.z.abs() / bs.pdf);
        let ray = vp.hit.spawn_ray(vp.frame.to_world(bs.wi));
        l + self.gather(scene, ray, beta, k.1, ctx, buf)
    }

    /// The global map's estimate where `ray` (throughput `beta`) first meets a diffuse-like
    /// surface, followed through the others by BSDF sampling and through BLEND
    /// pass-through; zero if it escapes.
    fn gather(
        &self,
        scene: &Scene,
        mut ray: Ray,
        mut beta: Vec3,
        k: usize,
        ctx: &mut Context,
        buf: &mut Vec<(f32, u32)>,
    ) -> Vec3 {
        // Gather rays start outside volumes (visible points are on opaque surfaces).
        let mut media = MediumStack::new();
        for _ in 0..GATHER_SPECULAR {
            let s = loop {
                let Some(at) = shading::arrive::<Vec3>(scene, &ray, &media, &(), &mut ctx.rays)
                else {
                    return Vec3::ZERO;
                };
                beta *= at.transmittance;
                match at.event(scene, media, &mut beta, &mut (), &mut ctx.sample.rng) {
                    Event::PassThrough(next) => ray = next,
                    Event::Scatter(s) => break s,
                }
            };
            if s.bsdf.is_diffuse_like() {
                let at = GatherPoint {
                    p: s.hit.p,
                    frame: s.frame,
                    wo: s.wo,
                    bsdf: s.bsdf,
                };
                return beta * self.estimate(&self.global, k, &at, false, buf);
            }
            let uc = ctx.sample.rng.next_f32();
            let u = if s.bsdf.is_delta() {
                Vec2::ZERO
            } else {
                Vec2::new(ctx.sample.rng.next_f32(), ctx.sample.rng.next_f32())
            };
            let Some(bs) = s.sample(uc, u, TransportMode::Radiance) else {
                break;
            };
            beta *= bs.f * (bs.wi.z.abs() / bs.pdf);
            media = s.media_after(bs.transmission);
            ray = s.spawn(bs.wi);
        }
        Vec3::ZERO
    }
}

/// Renders with classic photon mapping: builds the maps once, then takes camera samples in
/// progressive rounds ([`render_samples`]; the observer sees checkpoints 1, 2, 4, … spp).
/// A shard (`range`, absolute sample indices) builds the same maps (a pure function of the
/// seed and the scene) and takes its share of the camera samples.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    max_depth: u32,
    ps: &PhotonMapSettings,
    settings: &RenderSettings,
    range: Option<std::ops::Range<u64>>,
    observer: Option<Observer>,
) -> Result<(Film, RenderStats)> {
    let start = Instant::now();
    let n = if ps.photons > 0 {
        ps.photons
    } else {
        DEFAULT_PHOTONS
    };
    let ts = TraceSettings {
        max_depth,
        roulette: ps.roulette,
    };
    let (caustic, global, rays) = build_maps(scene, n, &ts, settings.seed, settings.spectral)?;
    let max_r = ps.radius.unwrap_or_else(|| {
        // 16 pixel footprints at the distance of the scene's centre.
        let c = 0.5 * (scene.bounds().0 + scene.bounds().1);
        let o = camera
            .generate_ray(Vec2::new(settings.width as f32, settings.height as f32) * 0.5)
            .origin;
        16.0 * super::photon_pass::pixel_footprint(camera, settings, o.distance(c))
    });
    let maps = PhotonMaps {
        caustic: PhotonMap::build(caustic),
        global: PhotonMap::build(global),
        max_r2: max_r * max_r,
        rays,
        emitted: n,
    };
    let k = (ps.k_caustic.max(1), ps.k_global.max(1));
    let setup = Prepass {
        start,
        rays: maps.rays,
        photons: maps.emitted,
    };
    render_samples(
        camera,
        settings,
        range,
        setup,
        observer,
        |ray, _u_lambda, ctx| {
            let stop = VisiblePoints {
                spectral_mis: false,
            };
            let (ld, vp) = path::camera_path::<Vec3, _>(scene, ray, (max_depth, &stop), (), ctx);
            let Some(vp) = vp else {
                return ld;
            };
            let mut buf = Vec::with_capacity(k.0.max(k.1));
            ld + vp.beta * maps.indirect(scene, &vp, k, ctx, &mut buf)
        },
    )
}
