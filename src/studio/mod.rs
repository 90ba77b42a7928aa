//! Studio lighting for files that bring no light of their own (the drop-in preview): a
//! procedural soft environment plus small spot key lights, placed relative to
//! the model's bounding box and the camera, and an optional white floor ([`ground`]).
//!
//! ## When it applies
//! When the file has no punctual light, no emissive material and no environment, and
//! `--env` is not given (`--env none` keeps today's directional key/fill lights, as does
//! `--studio none`); for a file that brings its own light only when `--studio NAME` asks
//! ([`crate::prepare::Authored`]): the keys are then added to the file's lights and the
//! studio's environment replaces the file's. A file's own lights are never removed.
//!
//! ## Frames and units
//! - World frame: right-handed, +Y up, metres (glTF). Directions of the studio are given
//!   as an **elevation** above the horizontal plane and an **azimuth** round +Y measured
//!   from the camera's side of the model: azimuth 0° = the camera's direction seen from the
//!   model's centre, +90° = camera-right, ±180° = behind the model.
//! - Environment radiance in nits (cd/m², the renderer's radiance unit, linear Rec.709 RGB);
//!   key-light intensities in candela, chosen so that the illuminance at the model's centre
//!   is the preset's `key_lux`: I = E·d² with d the light's distance. Everything scales with
//!   the model's bounding radius R (keys at [`KEY_DISTANCE`]·R), so the picture is the same
//!   for a 1 mm gem and a 1 m vase.
//!
//! ## Presets ([`Studio`])
//! | preset | background (ground → horizon → zenith), nits | softboxes | keys |
//! |---|---|---|---|
//! | `soft` (default; `jeweller` for gems, [`default_for`]) | 0.15 → 0.35 → 0.6 grey | large overhead behind the model 12 nits, camera-left 8, camera-right 6 | one spot, 20 lx, front-left above |
//! | `jeweller` | 0.004 → 0.01 → 0.02 (near black) | four narrow strips at 300 nits round the model | two spots, 60 lx and 40 lx |
//! | `bright` | 1.5 → 2.0 → 2.5 white | overhead 6 nits, front wrap 4 nits | one spot, 8 lx |
//! | `tent` | 0.8 → 1.0 → 1.2 white | the lit top of the tent, 3 nits | none |
//!
//! `jeweller` is the classic dark-field gem setup: small, very bright sources on black make
//! each facet flash on or off and split white light into colour (fire) in dispersive
//! stones; `bright` is high-key product photography (white on white); `tent` is a
//! faceter's light tent, a translucent white dome lit from outside: even light from
//! everywhere shows each facet's brightness (the pattern a cut is judged by) with little
//! fire, and with no small source a sparkle needs fewer samples (BENCHMARKS.md, "Judging
//! the picture written").

pub mod env;
pub mod ground;
pub mod instrument;

use crate::error::{Error, Result};
use crate::light::env::Environment;
use crate::scene::desc::{AddedLights, CameraDesc, SceneDesc, SpotKey};
use glam::Vec3;

pub use ground::GroundMode;

/// Key lights stand this many bounding radii from the model's centre.
pub const KEY_DISTANCE: f32 = 8.0;

/// Half-width of the lit pool, in bounding radii at the model: the spot's outer cone is
/// atan(KEY_POOL / KEY_DISTANCE) ≈ 17.4°, so the model and its nearby floor (shadow and
/// caustics) are lit and the far floor falls off to the environment's light.
pub const KEY_POOL: f32 = 2.5;

/// A studio preset (`--studio NAME`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Studio {
    /// Grey gradient, three broad softboxes, one key (the default).
    #[default]
    Soft,
    /// Near-black gradient, narrow bright strips, two strong keys: fire and scintillation.
    Jeweller,
    /// White high-key gradient, broad softboxes, a gentle key.
    Bright,
    /// A faceter's light tent: an even white surround with a brighter top, no key.
    Tent,
    /// No studio: the directional key and fill lights of [`crate::light::default_lights`].
    None,
}

/// The preset the drop-in preview uses when `--studio` is not given: `jeweller` for a file
/// holding a transmissive, dispersive material (a gem: fire needs small bright sources on a
/// dark field), else `soft`. Evidence (BENCHMARKS.md, "Default studio for gems"): on the
/// four bare diamond cuts, `jeweller` shows the most fire (noise-free median chroma) and
/// the highest scintillation, at equal brilliance.
pub fn default_for(desc: &SceneDesc) -> Studio {
    let gem = desc.materials.iter().any(|m| {
        let m = crate::material::Material::new(m.clone());
        m.is_transmissive() && m.is_dispersive()
    });
    if gem {
        Studio::Jeweller
    } else {
        Studio::Soft
    }
}

/// What each preset is made of (see the table in the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PresetSpec {
    /// Background radiance below the horizon, at the horizon and at the zenith, nits.
    pub gradient: [f32; 3],
    /// Softboxes of the environment.
    pub softboxes: &'static [env::Softbox],
    /// Key lights: (elevation°, azimuth°, illuminance at the model centre in lux).
    pub keys: &'static [(f32, f32, f32)],
}

const SOFT_BOXES: [env::Softbox; 3] = [
    env::Softbox::new(60.0, 180.0, 28.0, 16.0, 12.0),
    env::Softbox::new(30.0, -70.0, 10.0, 14.0, 8.0),
    env::Softbox::new(25.0, 80.0, 7.0, 10.0, 6.0),
];
const JEWELLER_BOXES: [env::Softbox; 4] = [
    env::Softbox::new(50.0, 150.0, 2.5, 9.0, 300.0),
    env::Softbox::new(50.0, -150.0, 2.5, 9.0, 300.0),
    env::Softbox::new(40.0, 60.0, 2.0, 7.0, 300.0),
    env::Softbox::new(40.0, -60.0, 2.0, 7.0, 300.0),
];
const TENT_BOXES: [env::Softbox; 1] = [env::Softbox::new(80.0, 0.0, 40.0, 12.0, 3.0)];
const BRIGHT_BOXES: [env::Softbox; 2] = [
    env::Softbox::new(70.0, 180.0, 40.0, 20.0, 6.0),
    env::Softbox::new(20.0, 0.0, 60.0, 15.0, 4.0),
];

impl Studio {
    /// All preset names, in the order the help lists them.
    pub const NAMES: &'static str = "soft, jeweller, bright, tent or none";

    /// Parses `--studio NAME` (case-insensitive; `jeweler` is accepted too).
    pub fn parse(s: &str) -> Result<Studio> {
        match s.trim().to_ascii_lowercase().as_str() {
            "soft" => Ok(Studio::Soft),
            "jeweller" | "jeweler" => Ok(Studio::Jeweller),
            "bright" => Ok(Studio::Bright),
            "tent" => Ok(Studio::Tent),
            "none" => Ok(Studio::None),
            _ => Err(Error::Usage(format!(
                "--studio {s:?}: unknown studio preset (expected {})",
                Self::NAMES
            ))),
        }
    }

    /// The preset's name as written on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Studio::Soft => "soft",
            Studio::Jeweller => "jeweller",
            Studio::Bright => "bright",
            Studio::Tent => "tent",
            Studio::None => "none",
        }
    }

    /// The preset's recipe; `None` for [`Studio::None`].
    pub fn spec(self) -> Option<PresetSpec> {
        match self {
            Studio::Soft => Some(PresetSpec {
                gradient: [0.15, 0.35, 0.6],
                softboxes: &SOFT_BOXES,
                keys: &[(55.0, -40.0, 20.0)],
            }),
            Studio::Jeweller => Some(PresetSpec {
                gradient: [0.004, 0.01, 0.02],
                softboxes: &JEWELLER_BOXES,
                keys: &[(60.0, -35.0, 60.0), (45.0, 120.0, 40.0)],
            }),
            Studio::Bright => Some(PresetSpec {
                gradient: [1.5, 2.0, 2.5],
                softboxes: &BRIGHT_BOXES,
                keys: &[(50.0, -30.0, 8.0)],
            }),
            Studio::Tent => Some(PresetSpec {
                gradient: [0.8, 1.0, 1.2],
                softboxes: &TENT_BOXES,
                keys: &[],
            }),
            Studio::None => None,
        }
    }
}

/// The studio's lights and environment for a model with bounds `bounds` seen by `camera`.
#[derive(Debug, Clone)]
pub struct StudioSetup {
    /// Spot key lights (candela), aimed at the model's centre.
    pub keys: Vec<SpotKey>,
    /// The procedural environment.
    pub environment: Environment,
}

/// The camera's azimuth round the model's centre `centre`, radians (atan2(x, z) of the
/// horizontal direction from the centre to the camera); 0 (+Z) for a camera straight above.
pub fn camera_azimuth(camera: &CameraDesc, centre: Vec3) -> f32 {
    let eye = camera.world_from_camera.transform_point3(Vec3::ZERO);
    let mut d = eye - centre;
    if !d.is_finite() || d.x * d.x + d.z * d.z <= 1e-12 * d.length_squared().max(1e-30) {
        // Straight above or below: use the camera's own up vector's opposite (the image's
        // bottom points towards the viewer's side).
        d = -camera.world_from_camera.transform_vector3(Vec3::Y);
    }
    let a = d.x.atan2(d.z);
    if a.is_finite() {
        a
    } else {
        0.0
    }
}

/// Unit direction at `elevation` and `azimuth` (degrees, studio convention of the module
/// docs) for a camera at world azimuth `cam_azimuth` (radians).
pub fn studio_direction(elevation: f32, azimuth: f32, cam_azimuth: f32) -> Vec3 {
    let (se, ce) = elevation.to_radians().sin_cos();
    let (sa, ca) = (azimuth.to_radians() + cam_azimuth).sin_cos();
    Vec3::new(ce * sa, se, ce * ca)
}

/// Builds `preset`'s lights and environment for a model with world bounds `bounds` (the
/// file's own geometry, not the added floor) seen by `camera`; `None` for
/// [`Studio::None`].
pub fn setup(preset: Studio, bounds: (Vec3, Vec3), camera: &CameraDesc) -> Option<StudioSetup> {
    let spec = preset.spec()?;
    let (centre, radius) = bounding_sphere(bounds);
    let cam_az = camera_azimuth(camera, centre);
    let d = KEY_DISTANCE * radius;
    let cos_outer = (KEY_POOL / KEY_DISTANCE).atan().cos();
    // Full intensity within 70 % of the outer half-angle: a soft-edged pool.
    let cos_inner = (0.7 * (KEY_POOL / KEY_DISTANCE).atan()).cos();
    let keys = spec
        .keys
        .iter()
        .map(|&(el, az, lux)| {
            let dir = studio_direction(el, az, cam_az);
            SpotKey {
                position: centre + dir * d,
                direction: -dir,
                // E = I / d² at the centre (inverse-square law), so I = E·d².
                intensity: lux * d * d,
                cos_inner,
                cos_outer,
            }
        })
        .collect();
    Some(StudioSetup {
        keys,
        environment: env::environment(&spec, cam_az),
    })
}

/// Centre and radius of the sphere round the box `bounds` (radius ≥ a tiny positive
/// floor, so a degenerate model still gets finite lights).
pub fn bounding_sphere(bounds: (Vec3, Vec3)) -> (Vec3, f32) {
    let (lo, hi) = bounds;
    if !lo.is_finite() || !hi.is_finite() {
        return (Vec3::ZERO, 1.0);
    }
    let centre = 0.5 * (lo + hi);
    let radius = (0.5 * (hi - lo).length()).max(1e-6 * centre.abs().max_element().max(1.0));
    (centre, radius)
}

/// Writes `preset`'s studio into the description of a file with no light (given no
/// environment): its spot keys ([`AddedLights::Studio`]) and soft environment, placed for
/// `camera` round the file's own geometry (`subject_bounds`, else every mesh). Returns the
/// number of keys, or `None` for [`Studio::None`] (nothing written). The caller checks that
/// the file has no light ([`crate::scene::lighting::is_lit`]).
pub fn light(desc: &mut SceneDesc, preset: Studio, camera: &CameraDesc) -> Option<usize> {
    let bounds = desc
        .subject_bounds
        .unwrap_or_else(|| ground::desc_bounds(desc));
    let s = setup(preset, bounds, camera)?;
    let keys = s.keys.len();
    desc.added_lights = AddedLights::Studio(s.keys);
    desc.environment_light = Some(s.environment);
    Some(keys)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::framing::{frame_points, View};

    /// The automatic camera for the box `bounds` (its 8 corners).
    fn frame_bounds(bounds: (Vec3, Vec3), aspect: f32) -> CameraDesc {
        let corners: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::select(
                    glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0),
                    bounds.1,
                    bounds.0,
                )
            })
            .collect();
        frame_points(&corners, View::default(), aspect)
    }

    #[test]
    fn parses_names_and_rejects_others() {
        assert_eq!(Studio::parse("SOFT").unwrap(), Studio::Soft);
        assert_eq!(Studio::parse("jeweler").unwrap(), Studio::Jeweller);
        assert_eq!(Studio::parse("none").unwrap(), Studio::None);
        for s in [Studio::Soft, Studio::Jeweller, Studio::Bright, Studio::None] {
            assert_eq!(Studio::parse(s.name()).unwrap(), s);
        }
        let e = Studio::parse("disco").unwrap_err().to_string();
        assert!(e.contains("disco") && e.contains("jeweller"), "{e}");
    }

    #[test]
    fn keys_give_the_stated_illuminance_at_the_centre() {
        let bounds = (Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.5, 1.0));
        let cam = frame_bounds(bounds, 4.0 / 3.0);
        for preset in [Studio::Soft, Studio::Jeweller, Studio::Bright] {
            let s = setup(preset, bounds, &cam).unwrap();
            let spec = preset.spec().unwrap();
            assert_eq!(s.keys.len(), spec.keys.len());
            let (centre, _) = bounding_sphere(bounds);
            for (l, k) in s.keys.iter().zip(spec.keys) {
                let l = crate::scene::lighting::spot(l);
                let e = l.sample_li(centre).unwrap().irradiance.x;
                // f32 inverse-square arithmetic: a few ulps.
                assert!(
                    (e - k.2).abs() < 1e-4 * k.2,
                    "{preset:?}: {e} lx vs {}",
                    k.2
                );
            }
        }
        assert!(setup(Studio::None, bounds, &cam).is_none());
    }

    #[test]
    fn azimuth_zero_points_at_the_camera() {
        let bounds = (Vec3::splat(-1.0), Vec3::splat(1.0));
        let cam = frame_bounds(bounds, 1.0);
        let eye = cam.world_from_camera.transform_point3(Vec3::ZERO);
        let a = camera_azimuth(&cam, Vec3::ZERO);
        let d = studio_direction(0.0, 0.0, a);
        let h = Vec3::new(eye.x, 0.0, eye.z).normalize();
        assert!(d.dot(h) > 0.9999, "{d} vs {h}");
        // +90° is camera-right: the camera's +X axis.
        let right = cam.world_from_camera.transform_vector3(Vec3::X).normalize();
        assert!(studio_direction(0.0, 90.0, a).dot(right) > 0.999);
    }
}
