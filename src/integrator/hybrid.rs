//! The hybrid (`--method hybrid`): the path tracer for every path a camera path can reach
//! with next-event estimation or BSDF sampling, and a progressive caustic photon map for
//! exactly the light paths it cannot, L S+ D (light → delta chain → first non-delta
//! surface), optionally light-traced where the camera sees them directly
//! ([`super::light_trace`]). The split, the caustic lights and the radius sequence are
//! [`super::caustic`]'s; the camera side is [`path::camera_path`] with the strategy
//! [`CausticPaths`] ([`split`]).
//!
//! Under polarized transport (the `polarization` of [`super::Integrator::Hybrid`], docs/gem-optics.md) the
//! same passes run with polarized photons ([`crate::photon::polarized`], the map keeping
//! each photon's Stokes vector) and polarized camera paths ([`path::polarized::radiance`]
//! gathering through their analyzer), single rays, map mode only.
//!
//! Each pass (one unit of the progressive driver [`crate::render::drive`], one round):
//! 1. draws ONE set of wavelengths shared by its photons and camera paths (spectral
//!    transport; as SPPM: the map's photon powers are per lane of that set);
//! 2. traces the pass's caustic photons (aimed at the caustic makers, [`caustic`]) and builds
//!    their grid with the pass radius (the first radius, unless given, is 2 pixel
//!    footprints at the median camera distance of the first pass's photons, 1 % of the
//!    scene's diagonal without any);
//!    With `--caustics light|mixed` and a perspective camera, the same photon vertices are
//!    connected to the camera ([`light_trace`]; which ones, and which map photons D₁ then
//!    gathers, is the split proved there), the splats applied in the photon chunks' order
//!    to the pass's splat image;
//! 3. traces one camera sample per pixel (`primary_ray`, sample `pass` of the pixel from
//!    the render's sampler, Sobol' blocks of `--spp`) through the split path tracer (in
//!    map mode, unpolarized, through the structure-of-arrays kernel where the scene is in
//!    its class: [`super::path::kernel`], the same estimates up to float rounding), adds
//!    the pixel's splats (the splat image is a per-pixel estimate of one pass, so the
//!    film's average over passes stays the mean) and adds it to the film's half
//!    `pass mod 2`.
//!
//! So `--spp N` is N passes of one sample per pixel and N caustic maps; the image after N
//! passes is a pure function of the seed (pixels are independent, the map is built in
//! fixed chunks), whatever the thread count or the split into rounds.
//!
//! Shards (`range`, [`crate::app::shard`]): as in SPPM, pass p needs from earlier passes
//! only the radius ([`super::photon_pass`]). A shard starting at p₀ > 0 traces pass 0's
//! caustic photons (not its camera samples) for r₀, then replays the p₀ factors
//! ([`super::photon_pass::RadiusSequence::replay`]): its passes are bit for bit those of
//! one render.

use super::capability::{Capabilities, Photons, Support, Units};
use super::caustic::{self, CausticMap};
use super::light_trace::{self, Splatter};
use super::pass_paths::PassPaths;
use super::path::kernel::{self, Carried, OnScalar, Tables};
use super::path::polarized::{Polarization, PolarizedGather};
use super::path::{Dispersion, LaneWidth};
use super::photon_budget;
use super::photon_pass::{self, first_radius, pass_lambda};
use super::{CausticMode, CausticSettings};
use crate::camera::Camera;
use crate::error::Result;
use crate::polar::Analyzer;
use crate::render::{pixel_sampler, Film, Observer, Prepass, RenderSettings, RenderStats, Round};
use crate::scene::Scene;
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::Vec3;

pub mod split;

pub use split::{CausticPaths, CausticSplit, Gather};

/// What `--method hybrid` renders and how ([`crate::integrator::Method::caps`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    name: "hybrid",
    purpose: "all the light, with the caustics under a stone from photons",
    units: Units::Samples,
    photons: Photons::Caustic,
    media: Support::Yes,
    orthographic: Support::Yes,
    polarization: Support::Yes,
    rayleigh_spectral: Support::No(
        "carries in RGB at the channels' dominant wavelengths (spectrally its photons would \
         keep one wavelength each)",
    ),
    lanes: Support::Yes,
    shards: Support::Yes,
    adaptive: Support::Yes,
    estimate_in_media: Support::No(
        "its volumetric caustic map's blotches look alike in both halves of a tile",
    ),
    progressive: Support::Yes,
    pixel_bytes: 0,
};

/// Renders with the hybrid: `settings.spp` passes of one sample per pixel (a shard: the
/// passes `range`, absolute indices), fewer if the time limit or the observer stops it;
/// `paths` is (the bounces a camera path takes, polarized transport): polarized photons and
/// camera paths when it is on.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    paths: (u32, Option<Polarization>),
    cs: &CausticSettings,
    settings: &RenderSettings,
    range: Option<std::ops::Range<u64>>,
    observer: Option<Observer>,
) -> Result<(Film, RenderStats)> {
    if settings.spectral {
        run::<SampledSpectrum>(scene, camera, paths, cs, settings, range, observer)
    } else {
        run::<Vec3>(scene, camera, paths, cs, settings, range, observer)
    }
}

/// The first radius: [`first_radius`] at the photons of the pass.
fn initial_radius(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    photons: &[crate::photon::store::Photon],
) -> f32 {
    first_radius(
        scene,
        camera,
        settings,
        photons.iter().map(|p| p.position()),
    )
}

fn run<C: Carried>(
    scene: &Scene,
    camera: &Camera,
    (max_depth, polarization): (u32, Option<Polarization>),
    cs: &CausticSettings,
    settings: &RenderSettings,
    range: Option<std::ops::Range<u64>>,
    observer: Option<Observer>,
) -> Result<(Film, RenderStats)> {
    let lanes = LaneWidth::choose(scene)?;
    // The kernel takes the camera paths of the map's split (not light tracing's, not
    // polarized ones) where the scene is in its class.
    let tables = match (cs.mode, polarization) {
        (CausticMode::Map, None) => kernel::choose(scene, camera, settings)?,
        _ => None,
    };
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    let emitter = caustic::emitter(scene);
    let schedule =
        crate::render::schedule(u64::from(settings.spp.max(1)), range, 1, false, "hybrid");
    let mut setup = Prepass::now();
    let (budget, mut map) = caustic_budget::<C>(
        scene,
        camera,
        settings,
        (max_depth, polarization),
        cs,
        &emitter,
    )?;
    if let Some(b) = &budget {
        setup.rays += b.rays;
        setup.photons += b.photons;
    }
    let n_photons = caustic::photons_per_pass(cs.photons, pixels);
    let mut last_n = n_photons;
    let splatter = match cs.mode {
        CausticMode::Map => None,
        CausticMode::Light | CausticMode::Mixed => Splatter::new(
            scene,
            camera,
            (settings.width, settings.height),
            max_depth,
            cs.mode == CausticMode::Light,
        ),
    };
    if schedule.first > 0 {
        let n0 = budget.map_or(n_photons, |b| b.per_pass(pixels, map.radius()));
        let shard = (schedule.first, n0, max_depth);
        let (rays, photons) =
            replay_to_shard::<C>(scene, camera, settings, &mut map, &emitter, shard)?;
        setup.rays += rays;
        setup.photons += photons;
    }
    let (film, mut stats) = photon_pass::passes::<C>(
        settings,
        schedule,
        setup,
        observer,
        |film, pass, lambda, env| {
            // 1. The pass's wavelengths are `lambda` (the photon pass's).
            // 2. The caustic map.
            let mut round = Round::default();
            let mut splats = Vec::new();
            if !emitter.is_empty() {
                // The pilot's count grows with the pass as the radius shrinks.
                let n_photons = budget.map_or(n_photons, |b| b.per_pass(pixels, map.radius()));
                last_n = n_photons;
                let (rays, s) = map.trace_pass::<C>(
                    scene,
                    &emitter,
                    settings.seed,
                    pass,
                    n_photons,
                    lambda,
                    max_depth,
                    splatter.as_ref(),
                )?;
                (round.rays, splats) = (round.rays + rays, s);
                round.photons = n_photons;
            }
            let image = splatter
                .is_some()
                .then(|| light_trace::splat_image(&splats, pixels as usize));
            let r = map.begin_gather(|ph| initial_radius(scene, camera, settings, ph));
            let rv = map
                .volume
                .as_ref()
                .map(super::volume_map::VolumeMap::radius);
            // 3. Camera samples.
            let (rays, bad) = camera_pass::<C>(
                scene,
                camera,
                (max_depth, cs.dispersion(), polarization),
                (settings, lanes, tables.as_ref()),
                lambda,
                (&map, image.as_deref(), cs.mode),
                film,
            );
            round.rays += rays;
            round.bad += bad;
            map.end_pass(pass);
            env.bar.inc(film.tiles() as u64);
            round.note = format!(", r {r:.3e}, {} caustic photons", map.photons.len());
            if let (Some(rv), Some(v)) = (rv, &map.volume) {
                round.note += &format!(", volume r {rv:.3e}, {} volume photons", v.photons.len());
            }
            Ok(round)
        },
    )?;
    stats.photons_per_pass = last_n;
    Ok((film, stats))
}

/// A shard starting at pass `first`: the radius of its first pass, as one render reaches it
/// (pass 0's `n0` photons choose r₀ unless --radius or the pilot gave it; the volume map's
/// always comes from pass 0's photons, traced as many as one render's pass 0 traces).
/// Returns the rays and photons traced for it.
fn replay_to_shard<C: Carrier>(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    map: &mut CausticMap,
    emitter: &crate::photon::emit::PhotonEmitter,
    (first, n0, max_depth): (u64, u64, u32),
) -> Result<(u64, u64)> {
    let mut traced = (0, 0);
    let volume_unset = map.volume.as_ref().is_some_and(|v| v.radius() == 0.0);
    if !emitter.is_empty() && (map.radius() == 0.0 || volume_unset) {
        let lambda = pass_lambda::<C>(0, settings.seed);
        let (rays, _) = map.trace_pass::<C>(
            scene,
            emitter,
            settings.seed,
            0,
            n0,
            lambda,
            max_depth,
            None,
        )?;
        traced = (rays, n0);
    }
    map.begin_gather(|ph| initial_radius(scene, camera, settings, ph));
    map.replay(first);
    Ok(traced)
}

/// Without `--photons` in map mode, the pilot's budget ([`photon_budget`]: the photons a
/// pass and the first radius, the same in every shard) and a map with its first radius;
/// otherwise no budget and a map with `--radius` (or none yet). In a scene with media the
/// map comes with an empty volume map ([`super::volume_map`]).
fn caustic_budget<C: Carrier>(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    (max_depth, polarization): (u32, Option<Polarization>),
    cs: &CausticSettings,
    emitter: &crate::photon::emit::PhotonEmitter,
) -> Result<(Option<photon_budget::PhotonBudget>, CausticMap)> {
    let polarize = |m: CausticMap| match polarization {
        Some(_) => m.polarized(),
        None => m,
    };
    let mut map = polarize(CausticMap::new(cs.radius, cs.alpha));
    if scene.has_media() {
        map.volume = Some(super::volume_map::VolumeMap::new(cs.alpha));
    }
    if cs.photons > 0 || cs.mode != CausticMode::Map || emitter.is_empty() {
        return Ok((None, map));
    }
    let b = photon_budget::choose::<C>(
        scene,
        camera,
        settings,
        (max_depth, cs.dispersion()),
        emitter,
        (cs.radius, cs.alpha),
    )?;
    let mut first = polarize(CausticMap::new(Some(b.first_radius), cs.alpha));
    first.volume = map.volume;
    Ok((Some(b), first))
}

/// One camera sample per pixel of the active tiles (each tile's next unit,
/// [`PassPaths::trace`]) at the pass's wavelengths `lambda`, split with the pass's caustic
/// map, plus the pass's light-traced splats (`Some` in mixed mode: the map is then gathered
/// only through delta bounces); through the kernel with its `tables` when given (map mode,
/// unpolarized, a scene without media: the split is the map's alone). Returns the rays
/// and bad samples.
fn camera_pass<C: Carried>(
    scene: &Scene,
    camera: &Camera,
    (max_depth, dispersion, polarization): (u32, Dispersion, Option<Polarization>),
    (settings, lanes, tables): (&RenderSettings, LaneWidth, Option<&Tables>),
    lambda: C::Lambda,
    (map, splats, mode): (&CausticMap, Option<&[Vec3]>, CausticMode),
    film: &mut Film,
) -> (u64, u64) {
    let gather = |s: &crate::shading::Surface<C>, l: &C::Lambda| map.density(s, l, false);
    let polarized = |s: &crate::shading::Surface<C>, l: &C::Lambda, a: &Analyzer| {
        map.density_polarized(s, l, a)
    };
    let later = |s: &crate::shading::Surface<C>, l: &C::Lambda| map.density(s, l, true);
    let beam = |ray: &crate::math::Ray, seg: &crate::shading::media::Segment<'_>, l: &C::Lambda| {
        map.volume.as_ref().map_or(C::ZERO, |v| v.beam(ray, seg, l))
    };
    let split = match (splats, mode) {
        _ if map.volume.is_some() => CausticSplit::Volume {
            surface: &gather,
            beam: &beam,
        },
        (None, _) | (_, CausticMode::Map) => CausticSplit::Map(&gather),
        (Some(_), CausticMode::Light) => CausticSplit::Mixed {
            through: &gather,
            direct: None,
        },
        (Some(_), CausticMode::Mixed) => CausticSplit::Mixed {
            through: &gather,
            direct: Some(&later),
        },
    };
    let strategy = CausticPaths { split, dispersion };
    let vertex = OnScalar {
        max_depth,
        strategy,
    };
    let kernel = tables.map(|t| (t, C::rules(&vertex, Some(lambda))));
    let paths = PassPaths {
        scene,
        camera,
        sampler: pixel_sampler(settings, u64::from(settings.spp.max(1))),
        max_depth,
        lambda,
        strategy,
        lanes,
        polarized: polarization.map(|p| (p, &polarized as PolarizedGather<C>)),
        cancel: &settings.cancel,
        kernel,
    };
    let width = settings.width as usize;
    let mut nothing = vec![(); film.slots()];
    paths.trace(film, &mut nothing, true, |(x, y), l, _, _| {
        let mut rgb = l.to_rgb(&lambda);
        if let Some(img) = splats {
            rgb += img[y as usize * width + x as usize];
        }
        rgb
    })
}
