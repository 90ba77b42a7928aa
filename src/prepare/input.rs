//! The inputs of a render before any decision: the scene file loaded, validated and built
//! as it is ([`load`]), the environment chosen between `--env` and the file's
//! `iris_environment` ([`resolve_environment`]), and the image size (default and bounds).
//! Sizes are in pixels.

use crate::accel::Backend;
use crate::error::{Error, Result};
use crate::light::env::Environment;
use crate::scene::desc::{CameraDesc, EnvironmentDesc, Projection};
use crate::scene::Scene;
use std::path::Path;
use std::time::{Duration, Instant};

/// Largest accepted image: 2^26 pixels (8192 × 8192, or 8K UHD 7680 × 4320), checked before
/// allocating; SPPM is further limited by [`crate::integrator::check_memory`].
pub const MAX_PIXELS: u64 = 1 << 26;

/// Loads, validates and builds a scene as the file describes it, without its environment
/// (`iris_environment`: the preparation decides it, [`resolve_environment`]) and without any
/// drop-in decision: for tools, benches and tests. Returns the load-and-build time.
pub fn load(path: &Path, accel: Backend) -> Result<(Scene, Duration)> {
    let start = Instant::now();
    let mut desc = crate::load::load_scene(path)?;
    desc.environment = None;
    let scene = Scene::build(desc, accel)?;
    Ok((scene, start.elapsed()))
}

/// The environment to render with: the `--env` choice if given, else the file's
/// (a map is decoded here; errors name the map file).
pub fn resolve_environment(
    flag: Option<Option<Environment>>,
    from_file: Option<EnvironmentDesc>,
) -> Result<Option<Environment>> {
    match (flag, from_file) {
        (Some(choice), _) => Ok(choice),
        (None, None) => Ok(None),
        (None, Some(EnvironmentDesc::Uniform(radiance))) => {
            Ok(Some(Environment::Uniform { radiance }))
        }
        (None, Some(EnvironmentDesc::Map(path))) => {
            Ok(Some(Environment::Map(crate::light::env::load(&path)?)))
        }
        (None, Some(EnvironmentDesc::Sky(params))) => Ok(Some(Environment::Sky(Box::new(
            crate::light::sky::Sky::new(params)?,
        )))),
    }
}

/// The sun of a computed sky as the scene's directional light `sky sun` (travelling away
/// from the sun; colour normalised to a largest component of 1, intensity that component
/// of the irradiance, in Iris's lux); `None` below the horizon.
pub fn sun_light(sky: &crate::light::sky::Sky) -> Option<crate::scene::desc::LightDesc> {
    let (rgb, dir) = sky.sun?;
    let peak = rgb.max_element();
    Some(crate::scene::desc::LightDesc::Directional {
        name: "sky sun".into(),
        direction: -dir,
        color: rgb / peak,
        intensity: peak,
        spectrum: None,
    })
}

/// The default image size: 800 wide at the first camera's aspect ratio (or 4:3).
pub fn default_size(cameras: &[CameraDesc]) -> (u32, u32) {
    let aspect = cameras
        .first()
        .and_then(|c| match c.projection {
            Projection::Perspective { aspect, .. } => aspect,
            Projection::Orthographic { xmag, ymag } => Some(xmag / ymag),
        })
        .filter(|a| a.is_finite() && *a > 0.05 && *a < 20.0)
        .unwrap_or(4.0 / 3.0);
    (800, ((800.0 / aspect).round() as u32).max(1))
}

/// Rejects empty or absurd image sizes before anything is allocated.
pub fn check_size(w: u32, h: u32) -> Result<()> {
    if w == 0 || h == 0 || w as u64 * h as u64 > MAX_PIXELS {
        return Err(Error::Usage(format!(
            "--size {w}x{h}: width and height must be at least 1 and the image at most {MAX_PIXELS} pixels (8192x8192)"
        )));
    }
    Ok(())
}
