//! What a method can render, declared once beside the method ([`Capabilities`]: each
//! method's module holds its `CAPABILITIES`, and [`Method::caps`] is the one registry), and
//! the refusals read from those declarations, checked before anything is rendered
//! ([`Integrator::check_scene`]): `iris render` calls it when it makes its plan, `iris
//! converge` for every method it was asked for (and its reference's) before the first run,
//! and every render calls it again at its start.
//!
//! A "no" carries its reason, a clause completing "--method NAME …"; the refusal quotes it
//! and names the methods whose declarations say yes ([`alternatives`]). The refusals, each
//! a usage error naming the flag or what in the scene:
//! - the settings' own bounds ([`Integrator::check`]);
//! - scattering media ([`Capabilities::media`]);
//! - an orthographic camera ([`Capabilities::orthographic`]);
//! - polarized transport ([`Capabilities::polarization`], [`check_polarization`]): it is
//!   spectral and does not trace scattering media, whatever the method;
//! - the hybrid's caustic modes: light tracing does not trace scattering media, and the
//!   polarized hybrid counts caustics with its map only;
//! - a shard ([`Capabilities::shards`]) or a time limit ([`Capabilities::progressive`]);
//! - a `--radius` outside [[`MIN_RELATIVE_RADIUS`], [`MAX_RELATIVE_RADIUS`]] × the scene's
//!   scale, or outside [[`MIN_RADIUS`], [`MAX_RADIUS`]] scene units ([`check_radius`]).

use super::{CausticMode, Integrator, Method};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::scene::Scene;

/// A capability a method has, or lacks with the reason the user reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Support {
    /// Supported.
    Yes,
    /// Not supported: why, a clause completing "--method NAME …" that the refusal (or the
    /// plan's reason) quotes.
    No(&'static str),
}

impl Support {
    /// Whether the capability is there.
    pub fn is_yes(self) -> bool {
        self == Support::Yes
    }

    /// The reason it is not, if it is not.
    pub fn why_not(self) -> Option<&'static str> {
        match self {
            Support::Yes => None,
            Support::No(why) => Some(why),
        }
    }
}

/// The reason of the methods that trace no scattering media.
pub const NO_MEDIA: Support = Support::No("does not trace scattering media");
/// The reason of the methods that trace no polarized light.
pub const NO_POLARIZATION: Support = Support::No("does not trace polarized light");
/// The reason of the methods whose camera paths do not run in lanes.
pub const SINGLE_RAYS: Support = Support::No("traces one ray at a time");

/// What a method counts in units: a shard's range, a checkpoint's count, `--spp` or
/// `--passes`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    /// Samples per pixel (`--spp`; the hybrid and VCM take one photon pass per sample).
    Samples,
    /// Photon passes, each one camera path per pixel (`--passes`).
    Passes,
}

impl Units {
    /// "samples" or "passes".
    pub fn name(self) -> &'static str {
        match self {
            Units::Samples => "samples",
            Units::Passes => "passes",
        }
    }

    /// The flag that fixes the count: `--spp` or `--passes`.
    pub fn flag(self) -> &'static str {
        match self {
            Units::Samples => "--spp",
            Units::Passes => "--passes",
        }
    }
}

/// What photons a method traces from the lights: whether the plan's photons stage runs,
/// what `--photons` budgets, and what the render's summary counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Photons {
    /// None: every camera sample is estimated alone.
    None,
    /// One photon map before the camera samples (`--photons` in all).
    Map,
    /// A photon pass per unit (`--photons` a pass).
    Passes,
    /// A pass of caustic photons per sample (`--photons` a pass; 0: from a pilot).
    Caustic,
    /// A light subpath per pixel and pass (connected to the camera paths, and merged).
    LightSubpaths,
}

/// What a method renders and how, declared once in the method's module (its
/// `CAPABILITIES`) and read by the plan, the budget, adaptive sampling, the summary, the
/// view, the turntable, `iris converge` and the refusals; every field is written out in
/// every declaration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Capabilities {
    /// The command-line name (`--method NAME`), also the run name in reports and files.
    pub name: &'static str,
    /// What it is good for, in a sentence for someone choosing how to light a gem.
    pub purpose: &'static str,
    /// What it counts in units.
    pub units: Units,
    /// What photons it traces.
    pub photons: Photons,
    /// Scattering media (fog, milky or hazy volumes).
    pub media: Support,
    /// An orthographic camera.
    pub orthographic: Support,
    /// Polarized transport (Stokes vectors; then spectral, without media).
    pub polarization: Support,
    /// Under `--spectral auto`, whether a medium scattering by Rayleigh's λ⁻⁴ law turns
    /// spectral transport on; a "no" says what carries the law in RGB instead.
    pub rayleigh_spectral: Support,
    /// Camera paths traced in packets ([`super::path::LaneWidth`]).
    pub lanes: Support,
    /// A part of the units rendered alone, merged bit for bit with the others
    /// (`--shard`).
    pub shards: Support,
    /// Adaptive sampling (converged tiles rest).
    pub adaptive: Support,
    /// In a scene with scattering media, whether the half-buffer error estimate can be
    /// trusted from the first units (adaptive sampling under `--adaptive auto`, the
    /// error-target stop's first check); a "no" says why not.
    pub estimate_in_media: Support,
    /// Stopping after any unit (`--time`, an error target, an observer's stop).
    pub progressive: Support,
    /// Bytes each pixel costs beyond the film's own buffers ([`super::bytes_per_pixel`]).
    pub pixel_bytes: usize,
}

/// The names of the methods (in [`Method::ALL`] order, `auto` included) whose declaration
/// says yes to `cap`: "path, hybrid or auto", what a refusal proposes instead.
pub fn alternatives(cap: impl Fn(&Capabilities) -> Support) -> String {
    let names: Vec<&str> = Method::ALL
        .iter()
        .filter(|m| cap(m.caps()).is_yes())
        .map(|m| m.name())
        .collect();
    match names.split_last() {
        None => String::new(),
        Some((last, [])) => last.to_string(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
    }
}

/// Smallest `--radius` over the scene's scale ([`Scene::scale`]): below about a millionth
/// of the coordinates' magnitude, photon positions are not resolved (f32 positions carry a
/// relative rounding of 2⁻²⁴ ≈ 6·10⁻⁸, and the ray offset rule moves points by more).
pub const MIN_RELATIVE_RADIUS: f32 = 1e-6;
/// Largest `--radius` over the scene's scale: a disc a million times the scene gathers
/// nothing a smaller one would not.
pub const MAX_RELATIVE_RADIUS: f32 = 1e6;
/// Smallest `--radius` in scene units, whatever the scene: π r² and 1/(π r²) stay normal
/// f32 numbers.
pub const MIN_RADIUS: f32 = 1e-15;
/// Largest `--radius` in scene units, whatever the scene (r² stays a finite f32).
pub const MAX_RADIUS: f32 = 1e15;

/// Rejects a gather radius `r` (`--radius`) outside the bounds of the module docs for
/// `scene`, naming the flag, the bound and the scene's scale.
pub fn check_radius(r: f32, scene: &Scene) -> Result<()> {
    let scale = scene.scale();
    let lo = (MIN_RELATIVE_RADIUS * scale).max(MIN_RADIUS);
    let hi = if scale > 0.0 {
        (MAX_RELATIVE_RADIUS * scale).min(MAX_RADIUS)
    } else {
        MAX_RADIUS
    };
    let why = if r < lo {
        format!(
            "below the smallest gather radius for this scene, {lo:.3e} scene units \
             ({MIN_RELATIVE_RADIUS:e} of its scale {scale:.3e}, and at least {MIN_RADIUS:e}): \
             smaller discs do not resolve photon positions"
        )
    } else if r > hi {
        format!(
            "above the largest gather radius for this scene, {hi:.3e} scene units \
             ({MAX_RELATIVE_RADIUS:e} times its scale {scale:.3e}, and at most {MAX_RADIUS:e})"
        )
    } else {
        return Ok(());
    };
    Err(Error::Usage(format!(
        "--radius {r:e}: {why}; without --radius the radius is chosen from the pixel footprint"
    )))
}

/// Refuses `method` on `scene` through `camera` where its declaration says no: scattering
/// media, an orthographic camera.
pub fn check_method(method: Method, scene: &Scene, camera: &Camera) -> Result<()> {
    let caps = method.caps();
    if let (true, Some(why)) = (scene.has_media(), caps.media.why_not()) {
        let what = crate::shading::media::summary(scene);
        return Err(Error::Usage(format!(
            "--method {} {why} ({what}); use --method {}",
            caps.name,
            alternatives(|c| c.media)
        )));
    }
    if let (false, Some(why)) = (camera.is_perspective(), caps.orthographic.why_not()) {
        return Err(Error::Usage(format!(
            "--method {}: {why}; this scene's is orthographic (use --method {})",
            caps.name,
            alternatives(|c| c.orthographic)
        )));
    }
    Ok(())
}

/// Refuses polarized transport where it cannot run: under a method whose declaration says
/// no, in RGB transport (`spectral` false), in a scene with scattering media.
pub fn check_polarization(method: Method, scene: &Scene, spectral: bool) -> Result<()> {
    if let Some(why) = method.caps().polarization.why_not() {
        return Err(Error::Usage(format!(
            "--method {} {why}; use --method {}, or --polarization off",
            method.name(),
            alternatives(|c| c.polarization)
        )));
    }
    if !spectral {
        return Err(Error::Usage(
            "polarized transport is spectral: drop --spectral off, or use --polarization off"
                .into(),
        ));
    }
    if scene.has_media() {
        let what = crate::shading::media::summary(scene);
        return Err(Error::Usage(format!(
            "polarized transport does not trace scattering media ({what}): {}; use --polarization off",
            crate::integrator::path::polarized::WHY_NO_MEDIA
        )));
    }
    Ok(())
}

/// Refuses a shard (`range` given) or a time limit where the method's declaration says no.
pub fn check_schedule(method: Method, shard: bool, time_limit: bool) -> Result<()> {
    let caps = method.caps();
    if let (true, Some(why)) = (shard, caps.shards.why_not()) {
        return Err(Error::Usage(format!(
            "--shard: --method {} {why}",
            caps.name
        )));
    }
    if let (true, Some(why)) = (time_limit, caps.progressive.why_not()) {
        return Err(Error::Usage(format!(
            "--time: --method {} {why}",
            caps.name
        )));
    }
    Ok(())
}

impl Integrator {
    /// Every refusal of the module docs for rendering `scene` through `camera` (with
    /// `spectral` transport): the first one that applies, as a usage error.
    pub fn check_scene(&self, scene: &Scene, camera: &Camera, spectral: bool) -> Result<()> {
        self.check()?;
        let method = self.method();
        check_method(method, scene, camera)?;
        if self.polarization().is_some() {
            check_polarization(method, scene, spectral)?;
        }
        let radius = match self {
            Integrator::Whitted { .. } | Integrator::Path { .. } => None,
            Integrator::PhotonMap { photons, .. } => photons.radius,
            Integrator::Sppm { sppm, .. } => sppm.radius,
            Integrator::Hybrid {
                caustics,
                polarization,
                ..
            } => {
                check_caustic_modes(scene, caustics.mode, polarization.is_some())?;
                caustics.radius
            }
            Integrator::Vcm { vcm, .. } => vcm.radius,
        };
        match radius {
            Some(r) => check_radius(r, scene),
            None => Ok(()),
        }
    }
}

/// The usage errors of the hybrid's caustic modes: light tracing (`--caustics
/// light|mixed`) does not trace scattering media; the polarized hybrid counts its caustics
/// with the map alone.
fn check_caustic_modes(scene: &Scene, mode: CausticMode, polarized: bool) -> Result<()> {
    let usage = |m: &str| Err(Error::Usage(m.into()));
    if scene.has_media() && mode != CausticMode::Map {
        return usage("--caustics light|mixed does not trace scattering media; use --caustics map");
    }
    if polarized && mode != CausticMode::Map {
        return usage(
            "the polarized hybrid counts caustics with its map only: use --caustics map, or \
             --polarization off",
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests;
