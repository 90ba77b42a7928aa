//! Integrators: how radiance along camera rays is estimated. A closed enum; each variant's
//! maths lives in its own module, and the per-hit step shared between them (and with photon
//! tracing) lives below them in [`crate::shading`].

pub mod capability;
pub mod caustic;
pub mod hybrid;
pub mod light_trace;
mod memory;
mod pass_paths;
pub use memory::{bytes_per_pixel, check_memory};
pub mod path;
pub mod photon_budget;
pub mod photon_map;
pub mod photon_pass;
mod settings;
pub mod sppm;
pub mod vcm;
pub mod volume_map;
pub mod whitted;

use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::image::ImageRgb;
use crate::math::Ray;
pub use crate::render::Context;
use crate::render::{
    render_batches, render_samples, Film, Observer, Prepass, RenderSettings, RenderStats,
};
use crate::scene::Scene;
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::Vec3;
use path::LaneWidth;
pub use settings::{
    check_depth, CausticMode, CausticSettings, PhotonMapSettings, PhotonSettings, SppmSettings,
    StoreBudget, MAX_DEPTH, MAX_PHOTONS, MAX_STORED_PHOTONS,
};
use std::ops::Range;

/// The rendering method (`--method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Recursive ray tracing after Cropp & Zhang, "Light Refraction with Dispersion", §4:
    /// direct light from punctual lights, Fresnel-weighted reflection and refraction branches.
    Whitted,
    /// Unidirectional path tracing with next-event estimation and MIS.
    Path,
    /// Classic photon mapping (Jensen): direct light by shadow rays, a caustic map gathered
    /// at the first diffuse hit, a global map reached by final gathering.
    Photon,
    /// Stochastic progressive photon mapping in passes (Hachisuka & Jensen 2009, radius
    /// sequence of Knaus & Zwicker 2011).
    Sppm,
    /// The path tracer with a progressive caustic photon map for exactly the light paths it
    /// cannot sample (light → delta chain → first non-delta surface): [`hybrid`].
    Hybrid,
    /// Vertex connection and merging: bidirectional connections and photon merging under
    /// one multiple importance sampling ([`vcm`]).
    Vcm,
    /// Bidirectional path tracing: [`vcm`] without merging (unbiased).
    Bpt,
    /// `Path`, `Bpt`, `Hybrid`, `Vcm` or `Sppm` from the materials and the photon probes: a
    /// choice the render plan makes ([`crate::plan::resolve_method`]) before an
    /// [`Integrator`] exists; [`Integrator::new`] rejects it unresolved.
    Auto,
}

impl Method {
    /// Every method, in the order `--method` lists them.
    pub const ALL: [Method; 8] = [
        Method::Whitted,
        Method::Path,
        Method::Photon,
        Method::Sppm,
        Method::Hybrid,
        Method::Vcm,
        Method::Bpt,
        Method::Auto,
    ];

    /// The method's command-line name, also the run name in reports and file names.
    pub fn name(self) -> &'static str {
        match self {
            Method::Whitted => "whitted",
            Method::Path => "path",
            Method::Photon => "photon",
            Method::Sppm => "sppm",
            Method::Hybrid => "hybrid",
            Method::Vcm => "vcm",
            Method::Bpt => "bpt",
            Method::Auto => "auto",
        }
    }

    /// What a method is good for, in a sentence for someone choosing how to light a gem.
    pub fn purpose(self) -> &'static str {
        match self {
            Method::Whitted => "a quick look: sharp reflections and refractions, no soft light",
            Method::Path => "all the light, soft and exact; caustics come slowly and noisy",
            Method::Photon => "caustics fast from a photon map, slightly blurred",
            Method::Sppm => "sharp caustics through glass, refining pass by pass",
            Method::Hybrid => "all the light, with the caustics under a stone from photons",
            Method::Vcm => "the hardest light: caustics seen in mirrors and through glass",
            Method::Bpt => "small lights and caustics seen directly, without bias",
            Method::Auto => "chosen from the scene",
        }
    }

    /// Parses `--method NAME` ([`crate::error::parse_name`]).
    pub fn parse(s: &str) -> Result<Method> {
        let names = Method::ALL.map(|m| (m.name(), m));
        crate::error::parse_name("--method", s, &names)
    }
}

/// An integrator: the method and the settings it uses, and its own render. A closed enum;
/// `auto` is not a variant (the plan resolves it first).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// Recursive ray tracing ([`whitted`]).
    Whitted {
        /// Recursion depth, at most [`MAX_DEPTH`].
        max_depth: u32,
    },
    /// Path tracing with next-event estimation and MIS ([`path`]).
    Path {
        /// Bounces per path, at most [`MAX_DEPTH`].
        max_depth: u32,
        /// Spectral transport: what camera paths keep of their wavelengths at dispersive
        /// interfaces ([`path::Dispersion::ALL`] by default; less for comparisons).
        dispersion: path::Dispersion,
    },
    /// The path tracer with polarized transport ([`path::polarized`]): Stokes vectors, one
    /// wavelength a path, birefringent crystals, a polarizer on the camera.
    Polarized {
        /// Bounces per path, at most [`MAX_DEPTH`].
        max_depth: u32,
        /// What the camera looks through.
        polarization: path::polarized::Polarization,
    },
    /// Classic photon mapping with a final gather ([`photon_map`]).
    PhotonMap {
        /// Bounces per camera path and non-delta bounces per photon.
        max_depth: u32,
        /// Photons, radius, roulette and gather counts.
        photons: PhotonMapSettings,
    },
    /// Stochastic progressive photon mapping ([`sppm`]).
    Sppm {
        /// Bounces per camera path and non-delta bounces per photon.
        max_depth: u32,
        /// Photons per pass, radius sequence, passes and roulette.
        sppm: SppmSettings,
    },
    /// The path tracer plus a progressive caustic photon map ([`hybrid`]).
    Hybrid {
        /// Bounces per camera path.
        max_depth: u32,
        /// Caustic photons per pass, initial radius and α.
        caustics: CausticSettings,
    },
    /// Vertex connection and merging, or bidirectional path tracing ([`vcm`]).
    Vcm {
        /// Non-delta vertices per full path.
        max_depth: u32,
        /// Radius sequence and whether to merge.
        vcm: vcm::VcmSettings,
    },
}

impl Integrator {
    /// The integrator for a resolved `method`, taking from `photon` what it uses. An
    /// unresolved [`Method::Auto`] is an error (resolve it with the plan,
    /// [`crate::plan::resolve_method`]).
    pub fn new(method: Method, max_depth: u32, photon: &PhotonSettings) -> Result<Integrator> {
        Ok(match method {
            Method::Whitted => Integrator::Whitted { max_depth },
            Method::Path => Integrator::Path {
                max_depth,
                dispersion: path::Dispersion::ALL,
            },
            Method::Photon => Integrator::PhotonMap {
                max_depth,
                photons: photon.photon_map(),
            },
            Method::Sppm => Integrator::Sppm {
                max_depth,
                sppm: photon.sppm(),
            },
            Method::Hybrid => Integrator::Hybrid {
                max_depth,
                caustics: photon.caustics(),
            },
            Method::Vcm | Method::Bpt => Integrator::Vcm {
                max_depth,
                vcm: photon.vcm(method == Method::Vcm),
            },
            Method::Auto => {
                return Err(Error::Usage(
                    "--method auto must be resolved by the render plan before rendering".into(),
                ))
            }
        })
    }

    /// The method this integrator implements.
    pub fn method(&self) -> Method {
        match self {
            Integrator::Whitted { .. } => Method::Whitted,
            Integrator::Path { .. } | Integrator::Polarized { .. } => Method::Path,
            Integrator::PhotonMap { .. } => Method::Photon,
            Integrator::Sppm { .. } => Method::Sppm,
            Integrator::Hybrid { .. } => Method::Hybrid,
            Integrator::Vcm { vcm, .. } if vcm.merge => Method::Vcm,
            Integrator::Vcm { .. } => Method::Bpt,
        }
    }

    /// Bounces per path (recursion depth for Whitted).
    pub fn max_depth(&self) -> u32 {
        match *self {
            Integrator::Whitted { max_depth }
            | Integrator::Path { max_depth, .. }
            | Integrator::Polarized { max_depth, .. }
            | Integrator::PhotonMap { max_depth, .. }
            | Integrator::Sppm { max_depth, .. }
            | Integrator::Hybrid { max_depth, .. }
            | Integrator::Vcm { max_depth, .. } => max_depth,
        }
    }

    /// Rejects settings outside the CLI's bounds (`--max-depth` in 1..=[`MAX_DEPTH`], the
    /// photon settings the variant uses) with an error naming the flag, for library
    /// callers.
    pub fn check(&self) -> Result<()> {
        check_depth(self.max_depth())?;
        match self {
            Integrator::Whitted { .. } | Integrator::Path { .. } | Integrator::Polarized { .. } => {
                Ok(())
            }
            Integrator::PhotonMap { photons, .. } => photons.check(),
            Integrator::Sppm { sppm, .. } => sppm.check(),
            Integrator::Hybrid { caustics, .. } => caustics.check(),
            Integrator::Vcm { vcm, .. } => vcm.check(),
        }
    }

    /// Radiance arriving along `ray` at the sample's wavelengths `lambda` (linear RGB when
    /// `C` is [`Vec3`]) for the per-sample methods; `None` for the photon methods and the
    /// hybrid, whose estimates need their maps or passes.
    pub fn radiance<C: Carrier>(
        &self,
        scene: &Scene,
        ray: &Ray,
        lambda: C::Lambda,
        ctx: &mut Context,
    ) -> Option<C> {
        match *self {
            Integrator::Whitted { max_depth } => {
                Some(whitted::radiance(scene, ray, max_depth, lambda, ctx))
            }
            Integrator::Path {
                max_depth,
                dispersion,
            } => Some(path::radiance(
                scene,
                ray,
                (max_depth, dispersion),
                lambda,
                ctx,
            )),
            Integrator::PhotonMap { .. }
            | Integrator::Polarized { .. }
            | Integrator::Sppm { .. }
            | Integrator::Hybrid { .. }
            | Integrator::Vcm { .. } => None,
        }
    }

    /// This integrator with polarized transport when `polarization` says so (the plan's
    /// [`crate::plan::Plan::decide_polarization`]): the path tracer becomes
    /// [`Integrator::Polarized`], the hybrid traces polarized photons and camera paths;
    /// other methods are returned unchanged (the plan has already refused them).
    pub fn polarized(self, polarization: Option<path::polarized::Polarization>) -> Integrator {
        match (self, polarization) {
            (Integrator::Path { max_depth, .. }, Some(polarization)) => Integrator::Polarized {
                max_depth,
                polarization,
            },
            (
                Integrator::Hybrid {
                    max_depth,
                    mut caustics,
                },
                p @ Some(_),
            ) => {
                caustics.polarization = p;
                Integrator::Hybrid {
                    max_depth,
                    caustics,
                }
            }
            (other, _) => other,
        }
    }

    /// Renders `scene` through `camera` to the end (no observer).
    pub fn render(
        &self,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
    ) -> Result<(ImageRgb, RenderStats)> {
        self.render_progressive(scene, camera, settings, None)
    }

    /// Renders progressively through the one driver ([`crate::render::drive`]), stopping at
    /// `settings.spp` samples per pixel (path, Whitted, photon, hybrid), the SPPM passes,
    /// `settings.time_limit`, or when the observer says [`crate::render::Control::Stop`] —
    /// whichever first. The observer is called at checkpoints 1, 2, 4, 8, … samples (or
    /// passes) and at the end (`done`). Runs on its own pool of `settings.threads`.
    pub fn render_progressive(
        &self,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
        observer: Option<Observer>,
    ) -> Result<(ImageRgb, RenderStats)> {
        let (film, stats) = self.render_units(scene, camera, settings, None, observer)?;
        Ok((film.mean(), stats))
    }

    /// The units a whole render takes: SPPM's passes, else `settings.spp` (samples per
    /// pixel; the hybrid's passes).
    pub fn total_units(&self, settings: &RenderSettings) -> u64 {
        match self {
            Integrator::Sppm { sppm, .. } => u64::from(sppm.passes.max(1)),
            _ => u64::from(settings.spp.max(1)),
        }
    }

    /// [`Integrator::render_progressive`] of the units `range` only (absolute indices
    /// within `0..`[`Integrator::total_units`]; `None` = all): a shard. Unit k of a shard is
    /// unit k of the whole render (the sampler's blocks are the whole render's; SPPM and
    /// the hybrid compute the whole render's radius sequence up to the shard's first
    /// pass), so the shards' exact sums add up to the whole render's
    /// ([`crate::image::ExactImage::add`]). Returns the film.
    pub fn render_units(
        &self,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
        range: Option<Range<u64>>,
        observer: Option<Observer>,
    ) -> Result<(Film, RenderStats)> {
        self.check_scene(scene, camera, settings.spectral)?;
        check_memory(settings.width, settings.height, self.method())?;
        let total = self.total_units(settings);
        if let Some(r) = &range {
            if r.start >= r.end || r.end > total {
                return Err(Error::Usage(format!(
                    "units {}..{} are not a part of the render's {total}",
                    r.start, r.end
                )));
            }
        }
        let pool = crate::render::thread_pool(settings)?;
        let width = LaneWidth::choose(scene)?;
        match self {
            Integrator::Path {
                max_depth,
                dispersion,
            } if width != LaneWidth::Scalar => {
                let rules = (*max_depth, *dispersion);
                pool.install(|| {
                    render_batches(
                        camera,
                        settings,
                        range,
                        Prepass::now(),
                        observer,
                        |starts, jobs, out| {
                            path::estimate_path(
                                scene,
                                (rules, width),
                                settings.spectral,
                                starts,
                                jobs,
                                out,
                            )
                        },
                    )
                })
            }
            Integrator::Whitted { .. } | Integrator::Path { .. } | Integrator::Polarized { .. } => {
                pool.install(|| {
                    render_samples(
                        camera,
                        settings,
                        range,
                        Prepass::now(),
                        observer,
                        |ray, u, ctx| {
                            self.per_sample(scene, camera, settings.spectral, ray, u, ctx)
                        },
                    )
                })
            }
            Integrator::PhotonMap { max_depth, photons } => pool.install(|| {
                photon_map::render(
                    scene, camera, *max_depth, photons, settings, range, observer,
                )
            }),
            Integrator::Sppm { max_depth, sppm } => pool.install(|| {
                sppm::render(scene, camera, *max_depth, sppm, settings, range, observer)
            }),
            Integrator::Hybrid {
                max_depth,
                caustics,
            } => pool.install(|| {
                hybrid::render(
                    scene, camera, *max_depth, caustics, settings, range, observer,
                )
            }),
            Integrator::Vcm { max_depth, vcm } => pool
                .install(|| vcm::render(scene, camera, *max_depth, vcm, settings, range, observer)),
        }
    }

    /// One camera sample of a per-sample method: the polarized path tracer with its
    /// camera's analyzer, or [`Integrator::sample`] in spectral or RGB transport.
    fn per_sample(
        &self,
        scene: &Scene,
        camera: &Camera,
        spectral: bool,
        ray: &Ray,
        u: f32,
        ctx: &mut Context,
    ) -> Vec3 {
        match self {
            Integrator::Polarized {
                max_depth,
                polarization,
            } => {
                let a = polarization.analyzer(camera.basis(), ray.dir);
                let lambda = SampledSpectrum::sample_lambda(u);
                path::polarized::radiance::<SampledSpectrum>(
                    scene,
                    ray,
                    (*max_depth, None),
                    lambda,
                    a,
                    ctx,
                )
                .to_rgb(&lambda)
            }
            _ if spectral => self.sample::<SampledSpectrum>(scene, ray, u, ctx),
            _ => self.sample::<Vec3>(scene, ray, u, ctx),
        }
    }

    /// One camera sample's radiance as linear RGB: wavelengths drawn for spectral transport
    /// from the hero variate `u_lambda` ∈ [0, 1), and the film's conversion
    /// ([`Carrier::to_rgb`], spectrum → XYZ → sRGB).
    fn sample<C: Carrier>(
        &self,
        scene: &Scene,
        ray: &Ray,
        u_lambda: f32,
        ctx: &mut Context,
    ) -> Vec3 {
        let lambda = C::sample_lambda(if C::SPECTRAL { u_lambda } else { 0.0 });
        self.radiance::<C>(scene, ray, lambda, ctx)
            .map_or(Vec3::ZERO, |l| l.to_rgb(&lambda))
    }
}
