//! What an integrator can render, checked before anything is rendered
//! ([`Integrator::check_scene`]): `iris render` calls it when it makes its plan, `iris
//! converge` for every method it was asked for (and its reference's) before the first
//! run, and every render calls it again at its start.
//!
//! The refusals, each a usage error naming the flag or what in the scene:
//! - the settings' own bounds ([`Integrator::check`]);
//! - scattering media: only the path tracer and the hybrid trace them ([`check_media`]);
//! - VCM and BPT connect light paths to the camera: a perspective camera only;
//! - the hybrid's caustic modes: light tracing and the polarized hybrid do not trace
//!   scattering media, and the polarized hybrid is spectral;
//! - a `--radius` outside [[`MIN_RELATIVE_RADIUS`], [`MAX_RELATIVE_RADIUS`]] × the scene's
//!   scale, or outside [[`MIN_RADIUS`], [`MAX_RADIUS`]] scene units ([`check_radius`]).

use super::{CausticMode, Integrator};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::scene::Scene;

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

/// Only the path tracer and the hybrid (with its volumetric caustic map) trace light
/// through scattering media ([`crate::volume`]); another method on a scene with media is a
/// usage error naming what scatters.
fn check_media(integrator: &Integrator, scene: &Scene) -> Result<()> {
    if !scene.has_media()
        || matches!(
            integrator,
            Integrator::Path { .. } | Integrator::Hybrid { .. }
        )
    {
        return Ok(());
    }
    let what = crate::shading::media::summary(scene);
    Err(Error::Usage(format!(
        "--method {} does not trace scattering media ({what}); use --method path, hybrid or auto",
        integrator.method().name()
    )))
}

impl Integrator {
    /// Every refusal of the module docs for rendering `scene` through `camera` (with
    /// `spectral` transport): the first one that applies, as a usage error.
    pub fn check_scene(&self, scene: &Scene, camera: &Camera, spectral: bool) -> Result<()> {
        self.check()?;
        check_media(self, scene)?;
        let radius = match self {
            Integrator::Whitted { .. } | Integrator::Path { .. } | Integrator::Polarized { .. } => {
                None
            }
            Integrator::PhotonMap { photons, .. } => photons.radius,
            Integrator::Sppm { sppm, .. } => sppm.radius,
            Integrator::Hybrid { caustics, .. } => {
                check_caustic_modes(scene, caustics, spectral)?;
                caustics.radius
            }
            Integrator::Vcm { vcm, .. } => {
                if !camera.is_perspective() {
                    return Err(Error::Usage(format!(
                        "--method {}: connecting light paths to the camera needs a \
                         perspective camera; this scene's is orthographic (use --method \
                         path or sppm)",
                        self.method().name()
                    )));
                }
                vcm.radius
            }
        };
        match radius {
            Some(r) => check_radius(r, scene),
            None => Ok(()),
        }
    }
}

/// The usage errors of the hybrid's caustic settings: light tracing (`--caustics
/// light|mixed`) does not trace scattering media; the polarized hybrid is spectral,
/// without media, and counts its caustics with the map alone.
fn check_caustic_modes(scene: &Scene, cs: &super::CausticSettings, spectral: bool) -> Result<()> {
    let usage = |m: &str| Err(Error::Usage(m.into()));
    if scene.has_media() && cs.mode != CausticMode::Map {
        return usage("--caustics light|mixed does not trace scattering media; use --caustics map");
    }
    if cs.polarization.is_some() && (cs.mode != CausticMode::Map || scene.has_media() || !spectral)
    {
        return usage(
            "the polarized hybrid is spectral and counts caustics with its map only, without \
             scattering media: use --caustics map, or --polarization off",
        );
    }
    Ok(())
}
