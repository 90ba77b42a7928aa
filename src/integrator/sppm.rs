//! Stochastic progressive photon mapping (`--method sppm`): Hachisuka & Jensen 2009
//! ("Stochastic Progressive Photon Mapping"), with the per-pass radius sequence of Knaus &
//! Zwicker 2011 ("Progressive Photon Mapping: A Probabilistic Approach"):
//! r²ᵢ₊₁ = r²ᵢ · (i + α)/(i + 1), α = 2/3 by default, and the image is the plain average of
//! the passes' estimates, so it converges (bias and variance both vanish) with memory that
//! does not grow with the number of passes.
//!
//! Each pass (following pbrt-v4's `SPPMIntegrator`):
//! 1. draws ONE set of wavelengths shared by all its camera paths and photons (spectral
//!    transport), so a caustic of a dispersive prism is estimated per wavelength set and
//!    colours converge without splotches;
//! 2. traces one camera path per pixel with the path tracer's loop ([`path::camera_path`]):
//!    emission, direct light (NEE with MIS) and glossy/specular bounces are the path
//!    tracer's; the path stops at its first diffuse-like hit, the visible point, where
//!    direct light is estimated once more without MIS. In spectral transport a camera
//!    path keeps its 4 wavelengths at rough dispersive interfaces with spectral MIS under
//!    its own hero, drawn independently of the photons' (`path::own_hero` proves the
//!    gather unbiased; [`SppmSettings::spectral_mis`] off keeps the hero only there);
//! 3. traces `photons` photons from the lights ([`crate::photon`]) and keeps every photon
//!    vertex after at least one bounce (direct light was the camera path's: no path is
//!    counted twice);
//! 4. gathers, at each visible point, the photons within the pass radius r:
//!    L = β · Σ f(wo, wi_p) Φ_p / (N_photons π r²) (a constant kernel).
//!
//! Gathering is a pixel-parallel query of a hash grid over the pass's photons
//! ([`crate::photon::store::HashGrid`]), so each pixel sums its photons in a fixed order:
//! the image is the same whatever the thread count.
//!
//! The initial radius, unless given, is 2 pixel footprints at the median visible point of
//! the first pass.
//!
//! The pass's wavelengths, the radius sequence, the shard replay and the pass loop are the
//! photon pass's ([`crate::integrator::photon_pass`]). Shards (`range`,
//! [`crate::app::shard`]): pass p depends on nothing from earlier passes but the radius
//! (visible points, photons and the grid are rebuilt every pass; the wavelengths, camera
//! samples and photon numbers are functions of p). A shard starting at p₀ > 0 computes r₀
//! as pass 0 does (pass 0's camera paths only, not added to its film: one path per pixel)
//! and replays the p₀ factors ([`RadiusSequence::replay`]), so its passes are bit for bit
//! those of one render, and the merge of the shards is exact.
//!
//! Progress: each pass adds its per-pixel estimate (direct + photons) to the one film
//! ([`crate::render::Film`], pass p in half p mod 2), one pass per round of the progressive
//! driver ([`photon_pass::passes`]): checkpoints after 1, 2, 4, … passes, the
//! observer, the time limit and stop requests between passes are the driver's. Camera rays
//! are the per-sample methods' [`crate::render::primary_ray`] (jittered; stream
//! `Rng::new(&[seed, pass, x, y])`). Visible points are kept per film slot.
//!
//! Photons: photon `i` of pass `p` is emitted from Halton point `p·photons + i`
//! (digit-permuted by the seed, [`crate::photon::emit::PhotonNumbers`]) (each pass continues the sequence, as pbrt-v4 SPPM does),
//! aimed at the caustic makers ([`crate::photon::emit::DEFAULT_AIM`], unbiased); its path
//! after emission draws from `Rng::new(&[seed, pass, i, 0x9E07])`.

mod gather;
mod visible;

pub use visible::VisiblePoints;

use super::capability::{
    Capabilities, Photons, Support, Units, NO_MEDIA, NO_POLARIZATION, SINGLE_RAYS,
};
use super::pass_paths::PassPaths;
use super::path::{LaneWidth, VisiblePoint};
use super::photon_pass::{self, first_radius, pass_lambda, RadiusSequence};
use super::{SppmSettings, StoreBudget, MAX_PHOTONS};
use crate::camera::Camera;
use crate::error::Result;
use crate::math::Rng;
use crate::photon::emit::{PhotonEmitter, PhotonNumbers, DEFAULT_AIM};
use crate::photon::grid::HashGrid;
use crate::photon::store::Photon;
use crate::photon::trace::{self, TraceSettings};
use crate::render::{
    pixel_sampler, Film, Observer, Prepass, RenderSettings, RenderStats, Round, TILE_PIXELS,
};
use crate::scene::Scene;
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::Vec3;
use rayon::prelude::*;

/// What `--method sppm` renders and how ([`crate::integrator::Method::caps`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    name: "sppm",
    purpose: "sharp caustics through glass, refining pass by pass",
    units: Units::Passes,
    photons: Photons::Passes,
    media: NO_MEDIA,
    orthographic: Support::Yes,
    polarization: NO_POLARIZATION,
    rayleigh_spectral: Support::Yes,
    lanes: SINGLE_RAYS,
    shards: Support::Yes,
    adaptive: Support::No("every pixel's visible point takes part in every pass"),
    estimate_in_media: Support::Yes,
    progressive: Support::Yes,
    pixel_bytes: std::mem::size_of::<Option<VisiblePoint<SampledSpectrum>>>(),
};

/// Photons traced per parallel work item (the split is fixed, so results are deterministic).
const CHUNK: u64 = 4096;

/// Renders with SPPM: `passes` passes (a shard: the passes `range`, absolute indices),
/// fewer if the time limit or the observer stops it.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    max_depth: u32,
    sppm: &SppmSettings,
    settings: &RenderSettings,
    range: Option<std::ops::Range<u64>>,
    observer: Option<Observer>,
) -> Result<(Film, RenderStats)> {
    if settings.spectral {
        run::<SampledSpectrum>(scene, camera, max_depth, sppm, settings, range, observer)
    } else {
        run::<Vec3>(scene, camera, max_depth, sppm, settings, range, observer)
    }
}

/// The state SPPM keeps across passes: per film slot the visible point of the current
/// pass, the pass's photons and their grid, and the radius sequence.
struct Passes<C: Carrier> {
    vps: Vec<Option<VisiblePoint<C>>>,
    photons: Vec<Photon>,
    grid: HashGrid,
    radius: RadiusSequence,
}

fn run<C: Carrier>(
    scene: &Scene,
    camera: &Camera,
    max_depth: u32,
    ps: &SppmSettings,
    settings: &RenderSettings,
    range: Option<std::ops::Range<u64>>,
    observer: Option<Observer>,
) -> Result<(Film, RenderStats)> {
    let n_pix = settings.width as u64 * settings.height as u64;
    let n_photons = if ps.photons > 0 {
        ps.photons
    } else {
        n_pix.min(MAX_PHOTONS)
    };
    let emitter = PhotonEmitter::new(scene);
    let trace_settings = TraceSettings {
        max_depth,
        roulette: ps.roulette,
    };
    let mut state = Passes::<C> {
        vps: Vec::new(),
        photons: Vec::new(),
        grid: HashGrid::new(),
        radius: RadiusSequence::new(ps.radius, ps.alpha),
    };
    // Every pixel's visible point takes part in every pass (its radius and flux statistics
    // are per pass), so SPPM never rests tiles: its declaration says no.
    let schedule = crate::render::Schedule {
        adaptive: CAPABILITIES.adaptive.is_yes(),
        ..crate::render::schedule(u64::from(ps.passes.max(1)), range, 1, true, "sppm passes")
    };
    let mut setup = Prepass::now();
    if schedule.first > 0 {
        // A shard: the radius of its first pass, as one render reaches it.
        if !state.radius.is_chosen() {
            let mut scratch = Film::new(settings.width, settings.height, 0);
            state.vps.resize(scratch.slots(), None);
            let lambda = pass_lambda::<C>(0, settings.seed);
            let (rays, _) = camera_pass(
                scene,
                camera,
                max_depth,
                settings,
                (ps.passes.max(1), ps.spectral_mis),
                lambda,
                &mut scratch,
                &mut state.vps,
            );
            setup.rays += rays;
            state.radius(scene, camera, settings);
        }
        state.radius.replay(schedule.first);
    }
    photon_pass::passes::<C>(
        settings,
        schedule,
        setup,
        observer,
        |film, pass, lambda, env| {
            let mut round = Round::default();
            // 1. The pass's wavelengths are `lambda`.
            // 2. Camera paths: direct light into the film, visible points per slot.
            state.vps.resize(film.slots(), None);
            let direct = camera_pass(
                scene,
                camera,
                max_depth,
                settings,
                (ps.passes.max(1), ps.spectral_mis),
                lambda,
                film,
                &mut state.vps,
            );
            round.rays += direct.0;
            round.bad += direct.1;
            let r = state.radius(scene, camera, settings);
            // 3. Photons, in fixed chunks.
            round.rays += photon_pass::<C>(
                scene,
                &emitter,
                &trace_settings,
                settings.seed,
                pass,
                n_photons,
                lambda,
                &mut state.photons,
            )?;
            round.photons = n_photons;
            // 4. Gather into the same film half.
            round.bad += state.gather_pass(film, pass, r);
            state.radius.end_pass(pass);
            env.bar.inc(film.tiles() as u64);
            round.note = format!(", r {r:.3e}, {} photons stored", state.photons.len());
            Ok(round)
        },
    )
}

/// Traces one camera path per pixel through [`primary_ray`] (sample `pass` of the pixel
/// from the render's sampler, Sobol' blocks of `--passes`),
/// adds its direct light to the film's half `pass mod 2` and keeps its visible point in the
/// pixel's slot. Returns the rays and bad samples.
#[allow(clippy::too_many_arguments)]
fn camera_pass<C: Carrier>(
    scene: &Scene,
    camera: &Camera,
    max_depth: u32,
    settings: &RenderSettings,
    (passes, spectral_mis): (u32, bool),
    lambda: C::Lambda,
    film: &mut Film,
    vps: &mut [Option<VisiblePoint<C>>],
) -> (u64, u64) {
    let paths = PassPaths {
        scene,
        camera,
        sampler: pixel_sampler(settings, u64::from(passes)),
        max_depth,
        lambda,
        strategy: VisiblePoints { spectral_mis },
        lanes: LaneWidth::Scalar,
        polarized: None,
        cancel: &settings.cancel,
        kernel: None,
    };
    paths.trace(film, vps, false, |_, l, vp, slot| {
        *slot = vp;
        l.to_rgb(&lambda)
    })
}

/// Traces `n_photons` photons of pass `pass` in fixed chunks of [`CHUNK`] and keeps, in
/// `photons`, every vertex after at least one bounce (powers divided by `n_photons`).
/// Returns the rays traced; an error when the store budget is crossed.
#[allow(clippy::too_many_arguments)]
fn photon_pass<C: Carrier>(
    scene: &Scene,
    emitter: &PhotonEmitter,
    trace_settings: &TraceSettings,
    seed: u64,
    pass: u32,
    n_photons: u64,
    lambda: C::Lambda,
    photons: &mut Vec<Photon>,
) -> Result<u64> {
    let chunks = n_photons.div_ceil(CHUNK);
    let budget = StoreBudget::default();
    let numbers = PhotonNumbers::new(seed);
    let per_chunk: Vec<(Vec<Photon>, u64)> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut out = Vec::new();
            let mut rays = 0;
            let inv_n = 1.0 / n_photons as f32;
            for i in c * CHUNK..((c + 1) * CHUNK).min(n_photons) {
                let mut rng = Rng::new(&[seed, pass as u64, i, 0x9E07]);
                // Halton over the global photon index: each pass continues the sequence.
                let index = pass as u64 * n_photons + i;
                let Some(ph) = emitter.emit_index(scene, &numbers, index, DEFAULT_AIM) else {
                    continue;
                };
                let before = out.len();
                rays += trace::trace::<C>(scene, &ph, lambda, trace_settings, &mut rng, |v, l| {
                    if v.bounces > 0 {
                        let flags = if C::is_hero_only(l) {
                            Photon::HERO_ONLY
                        } else {
                            0
                        };
                        out.push(Photon::new(v.p, v.wi, (v.power * inv_n).to_lanes(), flags));
                    }
                });
                if !budget.add(out.len() - before) {
                    break;
                }
            }
            (out, rays)
        })
        .collect();
    budget.check(n_photons, trace_settings.max_depth)?;
    photons.clear();
    // Exact reservation: the buffer's capacity is the largest pass's photon count, not a
    // doubling of it.
    photons.reserve_exact(per_chunk.iter().map(|c| c.0.len()).sum());
    let mut rays = 0;
    for (p, r) in per_chunk {
        photons.extend_from_slice(&p);
        rays += r;
    }
    Ok(rays)
}

impl<C: Carrier> Passes<C> {
    /// The radius of the current pass; on the first pass without `--radius`, 2 pixel
    /// footprints at the median visible point (1 % of the scene's diagonal when no pixel
    /// has one).
    fn radius(&mut self, scene: &Scene, camera: &Camera, settings: &RenderSettings) -> f32 {
        let vps = &self.vps;
        self.radius.or_first(|| {
            let points = vps.iter().flatten().map(|v| v.p);
            first_radius(scene, camera, settings, points)
        })
    }

    /// Gathers the pass's photons within `r` at every visible point into the film's half
    /// `pass mod 2` (L = β Σ f Φ / (π r²)) and marks the pass done in every tile. Returns
    /// the bad samples.
    fn gather_pass(&mut self, film: &mut Film, pass: u32, r: f32) -> u64 {
        self.grid.rebuild(&self.photons, r);
        let area = std::f64::consts::PI * self.radius.r2();
        let (photons, grid) = (&self.photons, &self.grid);
        film.par_tiles_mut()
            .zip(self.vps.par_chunks(TILE_PIXELS))
            .map(|(mut tile, vp_tile)| {
                let mut bad = 0;
                for (i, vp) in vp_tile.iter().enumerate() {
                    if let (Some(vp), true) = (vp, area > 0.0) {
                        let phi = gather::gather(vp, photons, grid, r);
                        let l = (vp.beta * phi).to_rgb(&vp.lambda).as_dvec3() / area;
                        tile.add(i, u64::from(pass), l, &mut bad);
                    }
                }
                tile.done_until(u64::from(pass) + 1);
                bad
            })
            .sum()
    }
}
