//! Integrators: how radiance along camera rays is estimated. A closed enum; each variant's
//! maths lives in its own module, and the per-hit step shared between them (and with photon
//! tracing) lives below them in [`crate::shading`].

pub mod capability;
pub mod caustic;
pub mod hybrid;
pub mod light_trace;
mod memory;
mod method;
mod pass_paths;
pub use memory::{bytes_per_pixel, check_memory};
pub use method::Method;
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
use path::polarized::Polarization;
use path::LaneWidth;
pub use settings::{
    check_depth, CausticMode, CausticSettings, PhotonMapSettings, PhotonSettings, SppmSettings,
    StoreBudget, MAX_DEPTH, MAX_PHOTONS, MAX_STORED_PHOTONS,
};
use std::ops::Range;

/// An integrator: the method and the settings it uses, and its own render. A closed enum;
/// `auto` is not a variant (the plan resolves it first). What each method can render is
/// its declaration ([`Method::caps`]); polarized transport is one setting,
/// `polarization`, in the variants of the methods that declare it.
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
        /// interfaces ([`path::Dispersion::ALL`] by default; less for comparisons). Polarized
        /// paths keep their hero alone from a crystal on, whatever this says.
        dispersion: path::Dispersion,
        /// Polarized transport ([`path::polarized`]): Stokes vectors, one wavelength a
        /// path, birefringent crystals, a polarizer on the camera; `None`: off.
        polarization: Option<Polarization>,
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
        /// Polarized transport: polarized caustic photons and camera paths; `None`: off.
        polarization: Option<Polarization>,
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
                polarization: None,
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
                polarization: None,
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
            Integrator::Path { .. } => Method::Path,
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
            | Integrator::PhotonMap { max_depth, .. }
            | Integrator::Sppm { max_depth, .. }
            | Integrator::Hybrid { max_depth, .. }
            | Integrator::Vcm { max_depth, .. } => max_depth,
        }
    }

    /// Polarized transport, where the method has it and it is on.
    pub fn polarization(&self) -> Option<Polarization> {
        match *self {
            Integrator::Path { polarization, .. } | Integrator::Hybrid { polarization, .. } => {
                polarization
            }
            _ => None,
        }
    }

    /// This integrator with polarized transport set to `polarization` (the plan's
    /// [`crate::plan::Plan::decide_polarization`]) where its method declares it
    /// ([`capability::Capabilities::polarization`]); other methods are returned unchanged
    /// (the plan has already refused them).
    pub fn with_polarization(mut self, polarization: Option<Polarization>) -> Integrator {
        if let Integrator::Path {
            polarization: p, ..
        }
        | Integrator::Hybrid {
            polarization: p, ..
        } = &mut self
        {
            *p = polarization;
        }
        self
    }

    /// Rejects settings outside the CLI's bounds (`--max-depth` in 1..=[`MAX_DEPTH`], the
    /// photon settings the variant uses) with an error naming the flag, for library
    /// callers.
    pub fn check(&self) -> Result<()> {
        check_depth(self.max_depth())?;
        match self {
            Integrator::Whitted { .. } | Integrator::Path { .. } => Ok(()),
            Integrator::PhotonMap { photons, .. } => photons.check(),
            Integrator::Sppm { sppm, .. } => sppm.check(),
            Integrator::Hybrid { caustics, .. } => caustics.check(),
            Integrator::Vcm { vcm, .. } => vcm.check(),
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

    /// The units a whole render takes ([`capability::Units`]): SPPM's passes, else
    /// `settings.spp` (samples per pixel; the hybrid's passes).
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
    /// ([`crate::image::ExactImage::add`]). Returns the film. The one `match` from a
    /// method to its render.
    pub fn render_units(
        &self,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
        range: Option<Range<u64>>,
        observer: Option<Observer>,
    ) -> Result<(Film, RenderStats)> {
        self.check_scene(scene, camera, settings.spectral)?;
        let method = self.method();
        capability::check_schedule(method, range.is_some(), settings.time_limit.is_some())?;
        check_memory(settings.width, settings.height, method)?;
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
        if let Integrator::Path {
            max_depth,
            polarization: None,
            dispersion,
            ..
        } = *self
        {
            if let Some(tables) = path::kernel::choose(scene, camera, settings)? {
                let run = (range, observer);
                let rules = (max_depth, dispersion);
                return pool.install(|| {
                    path::kernel::render(&tables, scene, camera, settings, run, rules)
                });
            }
        }
        pool.install(|| match *self {
            Integrator::Whitted { max_depth } => {
                PerSample::Whitted { max_depth }.render(scene, camera, settings, range, observer)
            }
            Integrator::Path {
                max_depth,
                polarization: Some(polarization),
                ..
            } => PerSample::Polarized {
                max_depth,
                polarization,
            }
            .render(scene, camera, settings, range, observer),
            Integrator::Path {
                max_depth,
                dispersion,
                ..
            } if width != LaneWidth::Scalar => render_batches(
                camera,
                settings,
                range,
                Prepass::now(),
                observer,
                |starts, jobs, out| {
                    path::estimate_path(
                        scene,
                        ((max_depth, dispersion), width),
                        settings.spectral,
                        starts,
                        jobs,
                        out,
                    )
                },
            ),
            Integrator::Path {
                max_depth,
                dispersion,
                ..
            } => PerSample::Path {
                max_depth,
                dispersion,
            }
            .render(scene, camera, settings, range, observer),
            Integrator::PhotonMap {
                max_depth,
                ref photons,
            } => photon_map::render(scene, camera, max_depth, photons, settings, range, observer),
            Integrator::Sppm {
                max_depth,
                ref sppm,
            } => sppm::render(scene, camera, max_depth, sppm, settings, range, observer),
            Integrator::Hybrid {
                max_depth,
                ref caustics,
                polarization,
            } => hybrid::render(
                scene,
                camera,
                (max_depth, polarization),
                caustics,
                settings,
                range,
                observer,
            ),
            Integrator::Vcm { max_depth, ref vcm } => {
                vcm::render(scene, camera, max_depth, vcm, settings, range, observer)
            }
        })
    }
}

/// The methods that estimate each camera sample alone, with the settings their estimate
/// reads: radiance along one camera ray at the sample's wavelengths.
#[derive(Debug, Clone, Copy)]
enum PerSample {
    /// [`whitted::radiance`].
    Whitted { max_depth: u32 },
    /// [`path::radiance`].
    Path {
        max_depth: u32,
        dispersion: path::Dispersion,
    },
    /// [`path::polarized::radiance`] through the camera's analyzer.
    Polarized {
        max_depth: u32,
        polarization: Polarization,
    },
}

impl PerSample {
    /// Renders the units `range` of camera samples through the sampler driver
    /// ([`render_samples`]), each sample in spectral or RGB transport as the settings say.
    fn render(
        self,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
        range: Option<Range<u64>>,
        observer: Option<Observer>,
    ) -> Result<(Film, RenderStats)> {
        render_samples(
            camera,
            settings,
            range,
            Prepass::now(),
            observer,
            |ray, u, ctx| match settings.spectral {
                true => self.sample::<SampledSpectrum>(scene, camera, ray, u, ctx),
                false => self.sample::<Vec3>(scene, camera, ray, u, ctx),
            },
        )
    }

    /// One camera sample's radiance as linear RGB: wavelengths drawn for spectral transport
    /// from the hero variate `u_lambda` ∈ [0, 1), and the film's conversion
    /// ([`Carrier::to_rgb`], spectrum → XYZ → sRGB).
    fn sample<C: Carrier>(
        self,
        scene: &Scene,
        camera: &Camera,
        ray: &Ray,
        u_lambda: f32,
        ctx: &mut Context,
    ) -> Vec3 {
        let lambda = C::sample_lambda(if C::SPECTRAL { u_lambda } else { 0.0 });
        let l: C = match self {
            PerSample::Whitted { max_depth } => {
                whitted::radiance(scene, ray, max_depth, lambda, ctx)
            }
            PerSample::Path {
                max_depth,
                dispersion,
            } => path::radiance(scene, ray, (max_depth, dispersion), lambda, ctx),
            PerSample::Polarized {
                max_depth,
                polarization,
            } => {
                let a = polarization.analyzer(camera.basis(), ray.dir);
                path::polarized::radiance::<C>(scene, ray, (max_depth, None), lambda, a, ctx)
            }
        };
        l.to_rgb(&lambda)
    }
}
