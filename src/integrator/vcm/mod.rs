//! Vertex connection and merging (`--method vcm`; Georgiev, Křivánek, Davidovič,
//! Slusallek 2012; SmallVCM is the reference implementation) and, without merging,
//! bidirectional path tracing (`--method bpt`; Veach 1997 ch. 10) with the same code.
//!
//! Each pass (one unit of the progressive driver [`crate::render::drive`]):
//! 1. draws ONE set of wavelengths shared by its light and camera subpaths (spectral
//!    transport; as SPPM and the hybrid), so that every connection and merge meets the same
//!    lanes;
//! 2. traces one light subpath per pixel ([`light_paths`]; at most [`MAX_LIGHT_PATHS`], then
//!    pixels share them in turn): each non-delta vertex is kept and connected to the camera
//!    (light tracing);
//! 3. builds the merging grid over those vertices with the pass's radius (VCM only);
//! 4. traces one camera subpath per pixel ([`camera`]), sample `pass` of the pixel from the
//!    render's sampler, which reads emission, samples a light, connects to every vertex of
//!    the light subpath with the pixel's index, and merges; adds the pixel's light-traced
//!    splats and puts the sum on the film's half `pass mod 2`.
//!
//! Every contribution is weighted by the balance heuristic over all the ways the same full
//! path could have been sampled ([`mis`]), so no path is counted twice and none lost: BPT is
//! unbiased; VCM is consistent (its merges have the kernel's bias, which vanishes as the
//! radius shrinks).
//!
//! Radius: the first is `--radius` or half a pixel footprint at the median camera distance
//! of the first pass's light vertices ([`RADIUS_SCALE`] × the photon pass's rule); pass
//! p's follows the photon pass's sequence ([`super::photon_pass::RadiusSequence`], Knaus &
//! Zwicker 2011), as do the wavelengths and the pass loop.
//!
//! Shards: pass p needs from earlier passes only the radius, a pure function of r₀ and p. A
//! shard starting later traces pass 0's light subpaths for r₀ (unless `--radius` gave it)
//! and replays the sequence to its pass: its passes are bit for bit those of one render,
//! whatever the thread count.
//!
//! Limits: connections and light tracing need a pinhole: an orthographic camera is
//! refused. Connections treat a BLEND surface as opaque (as next-event estimation does
//! everywhere in Iris). Both subpaths keep only the hero wavelength past a smooth
//! dispersive interface (no split, no spectral MIS at rough ones).

mod camera;
mod light_paths;
pub mod mis;

use super::photon_pass::{self, first_radius, pass_lambda, RadiusSequence};
use crate::camera::Camera;
use crate::error::Result;
use crate::integrator::capability::{
    Capabilities, Photons, Support, Units, NO_MEDIA, NO_POLARIZATION, SINGLE_RAYS,
};
use crate::integrator::light_trace::{self, Splatter};
use crate::photon::emit::{PhotonEmitter, PhotonNumbers};
use crate::photon::grid::HashGrid;
use crate::render::{
    pixel_sampler, primary_ray, Context, Film, Observer, Prepass, RenderSettings, RenderStats,
    Round,
};
use crate::scene::Scene;
use crate::spectrum::{Carrier, SampledSpectrum};
use camera::CameraKit;
use glam::Vec3;
use light_paths::{LightKit, LightPaths, LightVertex};
use rayon::prelude::*;

/// What `--method vcm` renders and how ([`crate::integrator::Method::caps`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    name: "vcm",
    purpose: "the hardest light: caustics seen in mirrors and through glass",
    units: Units::Samples,
    photons: Photons::LightSubpaths,
    media: NO_MEDIA,
    orthographic: PINHOLE,
    polarization: NO_POLARIZATION,
    rayleigh_spectral: Support::Yes,
    lanes: SINGLE_RAYS,
    shards: Support::Yes,
    adaptive: Support::Yes,
    estimate_in_media: Support::Yes,
    progressive: Support::Yes,
    pixel_bytes: 0,
};

/// What `--method bpt` renders and how ([`crate::integrator::Method::caps`]): VCM's
/// declaration, the same code without merging.
pub const BPT_CAPABILITIES: Capabilities = Capabilities {
    name: "bpt",
    purpose: "small lights and caustics seen directly, without bias",
    ..CAPABILITIES
};

/// Why VCM and BPT refuse an orthographic camera.
const PINHOLE: Support =
    Support::No("connecting light paths to the camera needs a perspective camera");

/// What `--method vcm` and `--method bpt` use.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VcmSettings {
    /// The first merging radius in scene units (`None`: from the pixel footprint).
    pub radius: Option<f32>,
    /// The radius sequence's α ∈ (0, 1).
    pub alpha: f32,
    /// Merge (VCM); without, bidirectional path tracing.
    pub merge: bool,
}

impl VcmSettings {
    /// Rejects a radius or α outside the CLI's bounds (as [`super::PhotonSettings::check`]).
    pub fn check(&self) -> Result<()> {
        super::PhotonSettings {
            radius: self.radius,
            alpha: self.alpha,
            ..super::PhotonSettings::default()
        }
        .check()
    }
}

/// Renders with VCM or BPT: `settings.spp` passes (a shard: the passes `range`), fewer if
/// the time limit or the observer stops it.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    max_depth: u32,
    vcm: &VcmSettings,
    settings: &RenderSettings,
    range: Option<std::ops::Range<u64>>,
    observer: Option<Observer>,
) -> Result<(Film, RenderStats)> {
    let run = Run {
        scene,
        camera,
        max_depth,
        vcm,
        settings,
        emitter: PhotonEmitter::new(scene),
        numbers: PhotonNumbers::new(settings.seed),
    };
    if settings.spectral {
        run.render::<SampledSpectrum>(range, observer)
    } else {
        run.render::<Vec3>(range, observer)
    }
}

/// One render's fixed inputs.
struct Run<'a> {
    scene: &'a Scene,
    camera: &'a Camera,
    max_depth: u32,
    vcm: &'a VcmSettings,
    settings: &'a RenderSettings,
    emitter: PhotonEmitter,
    numbers: PhotonNumbers,
}

/// VCM's first radius over the photon pass's ([`first_radius`]: 2 pixel footprints): half a pixel
/// footprint. With SPPM's radius the merges' share (η = π r² n_light) outweighs light
/// tracing where a caustic is seen directly and blurs it; a smaller radius trades that
/// against noise where merging carries the light (BENCHMARKS.md, "Vertex connection and
/// merging", has the error at ×1, ×¼ and ×⅒).
pub const RADIUS_SCALE: f32 = 0.25;

/// Most light subpaths a pass traces (a light vertex takes about 0.5 kB; a pass keeps
/// all of its subpaths' vertices): one per pixel up to 2¹⁹ pixels (724 × 724), then
/// pixel i pairs with subpath i mod 2¹⁹.
pub const MAX_LIGHT_PATHS: usize = 1 << 19;

impl Run<'_> {
    /// Light subpaths per pass: one per pixel, at most [`MAX_LIGHT_PATHS`].
    fn light_paths(&self) -> usize {
        (self.settings.width as usize * self.settings.height as usize).min(MAX_LIGHT_PATHS)
    }

    fn light_kit(&self) -> LightKit<'_> {
        let size = (self.settings.width, self.settings.height);
        LightKit {
            scene: self.scene,
            emitter: &self.emitter,
            numbers: &self.numbers,
            splatter: Splatter::every(self.scene, self.camera, size),
            max_depth: self.max_depth,
            seed: self.settings.seed,
        }
    }

    /// The light subpaths of pass `pass`; with `r0` unknown (pass 0 without `--radius`),
    /// the first radius from their vertices first: the merge factors need it before the
    /// subpaths' weights. Light subpaths' weights depend on the radius only through
    /// [`mis::Pass`], so pass 0 is traced for r₀ with a unit radius and then again.
    fn r0<C: Carrier>(&self) -> f32 {
        if let Some(r) = self.vcm.radius {
            return r;
        }
        let lambda = pass_lambda::<C>(0, self.settings.seed);
        let n = self.light_paths();
        let kit = LightKit {
            splatter: None,
            ..self.light_kit()
        };
        let paths: LightPaths<C> = kit.trace(0, n, lambda, &mis::Pass::new(1.0, n as f32, false));
        let r = first_radius(
            self.scene,
            self.camera,
            self.settings,
            paths.vertices().map(light_paths::position),
        );
        r * RADIUS_SCALE
    }

    fn render<C: Carrier>(
        &self,
        range: Option<std::ops::Range<u64>>,
        observer: Option<Observer>,
    ) -> Result<(Film, RenderStats)> {
        let settings = self.settings;
        let label = if self.vcm.merge { "vcm" } else { "bpt" };
        let schedule =
            crate::render::schedule(u64::from(settings.spp.max(1)), range, 1, false, label);
        let mut setup = Prepass::now();
        let n = self.light_paths();
        let r0 = if self.vcm.merge { self.r0::<C>() } else { 0.0 };
        if self.vcm.merge && self.vcm.radius.is_none() {
            setup.photons += n as u64;
        }
        let kit = self.light_kit();
        let sampler = pixel_sampler(settings, u64::from(settings.spp.max(1)));
        let mut grid = HashGrid::new();
        photon_pass::passes::<C>(
            settings,
            schedule,
            setup,
            observer,
            |film, pass, lambda, env| {
                let r = RadiusSequence::new(Some(r0), self.vcm.alpha)
                    .at_pass(pass)
                    .radius();
                let weights = mis::Pass::new(r, n as f32, self.vcm.merge);
                let lights: LightPaths<C> = kit.trace(pass, n, lambda, &weights);
                // The vertices merging reads by the grid's index (8 bytes each, beside their 0.5 kB).
                let mut merged: Vec<&LightVertex<C>> = Vec::new();
                if weights.merges() {
                    merged.extend(lights.vertices());
                    grid.rebuild_with(merged.len(), |i| light_paths::position(merged[i]), r);
                }
                let pixels = settings.width as usize * settings.height as usize;
                let splats = light_trace::splat_image(&lights.splats(), pixels);
                let cam = CameraKit {
                    scene: self.scene,
                    camera: self.camera,
                    emitter: &self.emitter,
                    lights: &lights,
                    merged: &merged,
                    grid: &grid,
                    radius: r,
                    mis: weights,
                    max_depth: self.max_depth,
                    width: settings.width as usize,
                };
                let (rays, bad) = camera_pass(&cam, &sampler, lambda, &splats, film);
                env.bar.inc(film.tiles() as u64);
                Ok(Round {
                    rays: rays + lights.rays,
                    bad,
                    photons: n as u64,
                    note: format!(", r {r:.3e}, {} light vertices", lights.len()),
                })
            },
        )
    }
}

/// One camera subpath per pixel of the active tiles (each tile's next unit), plus the
/// pixel's splats, added to the film. Returns the rays and bad samples.
fn camera_pass<C: Carrier>(
    kit: &CameraKit<'_, C>,
    sampler: &crate::sampler::PixelSampler,
    lambda: C::Lambda,
    splats: &[Vec3],
    film: &mut Film,
) -> (u64, u64) {
    let width = kit.width;
    film.par_tiles_mut()
        .map(|mut tile| {
            if !tile.active() {
                return (0, 0);
            }
            let k = tile.next_unit();
            let (mut rays, mut bad) = (0, 0);
            for i in 0..tile.slots() {
                let Some((x, y)) = tile.pixel(i) else {
                    continue;
                };
                let mut ctx = Context {
                    sample: sampler.start(x, y, k),
                    rays: 0,
                };
                let ray = primary_ray(kit.camera, x, y, false, &mut ctx.sample);
                let pixel = y as usize * width + x as usize;
                let l = kit.radiance(ray, pixel % kit.lights.count(), lambda, &mut ctx);
                let rgb = l.to_rgb(&lambda) + splats[pixel];
                tile.add(i, k, rgb.as_dvec3(), &mut bad);
                rays += ctx.rays;
            }
            tile.take(1, rays);
            (rays, bad)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1))
}
