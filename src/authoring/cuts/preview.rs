//! `iris gem`: a named stone in a standard cut, written as .glb, bare or in a preview
//! scene (the list shipped in `assets/gems/` is `crate::assets::gems`).
//!
//! Units: metres, +Y up, linear RGB; emitters are black diffuse quads emitting their
//! radiance from the face turned to the stone (as in the demonstration scenes).
//!
//! - **bare** (`--bare`): one mesh, the stone in the frame of [`super::Cut`] (girdle
//!   plane y = 0, table up), the stone's material ([`Stone::material`]); no camera, light,
//!   floor or environment (a renderer frames and lights it itself).
//! - **preview** (default): the stone table up, its lowest point 2 % of the size above a
//!   white (0.85) floor 20 sizes square; a key panel (1.6 × 1.6 sizes, radiance
//!   [`KEY_RADIANCE`]) 15 sizes from the stone, 55° up, front-left; a rim panel (1 × 1
//!   size, radiance [`RIM_RADIANCE`]) 15 sizes away, 40° up, behind-right; a faint uniform
//!   environment (`iris_environment` [`AMBIENT`]); a camera 35° above the horizon, 25°
//!   round from +Z towards +X, yfov 25°, 4:3, at the distance that fits the stone's
//!   bounding sphere in the vertical field with 10 % margin. Everything scales with the
//!   size, so the picture is the same for any `--size`.

use super::super::glb::write_glb;
use super::super::lathe::sin_cos;
use super::super::scene::{look_at, placed};
use super::super::shapes::{ground_plane, TriMesh};
use super::super::stones::Stone;
use super::{size_metres, Cut};
use crate::error::{Error, Result};
use crate::material::MaterialDesc;
use crate::scene::desc::{CameraDesc, EnvironmentDesc, SceneDesc};
use glam::{DVec3, Vec3};
use std::path::Path;

/// Radiance of the preview's key panel.
pub const KEY_RADIANCE: f32 = 80.0;
/// Radiance of the preview's rim panel.
pub const RIM_RADIANCE: f32 = 40.0;
/// Uniform environment radiance of the preview.
pub const AMBIENT: f32 = 0.03;

/// What `iris gem` writes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GemSpec {
    /// The cut.
    pub cut: Cut,
    /// The material.
    pub stone: Stone,
    /// Girdle diameter (round) or length (emerald, oval, pear), millimetres.
    pub size_mm: f64,
    /// Only the stone (no camera, lights, floor).
    pub bare: bool,
}

fn cut_title(cut: Cut) -> &'static str {
    match cut {
        Cut::Round => "Round brilliant",
        Cut::Emerald => "Emerald cut",
        Cut::Oval => "Oval brilliant",
        Cut::Pear => "Pear brilliant",
    }
}

/// The scene of `spec` (see the module docs); `--size` out of range is a usage error.
pub fn gem_scene(spec: &GemSpec) -> Result<SceneDesc> {
    let size = size_metres(spec.size_mm)?;
    let stone = spec.cut.mesh(size);
    let (lo, hi) = bounds(&stone);
    let mut s = SceneDesc {
        name: format!(
            "{}, {}, {} mm",
            cut_title(spec.cut),
            spec.stone.title(),
            spec.size_mm
        ),
        ..SceneDesc::default()
    };
    s.materials.push(spec.stone.material((hi.y - lo.y) as f32));
    let name = format!("{} {}", cut_title(spec.cut), spec.stone.name());
    if spec.bare {
        s.meshes.push(placed(&name, stone, 0, None));
        return Ok(s);
    }
    let lift = 0.02 * size - lo.y;
    let at = DVec3::new(0.0, lift, 0.0).as_vec3();
    s.meshes.push(placed(&name, stone, 0, Some(at)));
    let centre = 0.5 * (lo + hi) + DVec3::new(0.0, lift, 0.0);
    add_setting(&mut s, centre, size);
    let radius = 0.5 * (hi - lo).length();
    s.cameras
        .push(preview_camera(centre, radius, (35.0, 25.0), 4.0 / 3.0));
    Ok(s)
}

/// Adds the preview's setting around stones centred at `centre` (metres) whose size
/// (girdle diameter or length) is `size` metres, as the module docs give it: the faint
/// uniform environment (scene extras), the white floor at y = 0, the key and the rim
/// panels. Appends its materials and meshes after those already in `s`.
pub fn add_setting(s: &mut SceneDesc, centre: DVec3, size: f64) {
    s.environment = Some(EnvironmentDesc::Uniform(Vec3::splat(AMBIENT)));
    s.materials
        .push(MaterialDesc::diffuse("Floor", Vec3::splat(0.85)));
    let half = (10.0 * size) as f32;
    let floor = s.materials.len() - 1;
    s.meshes
        .push(placed("Floor", ground_plane(half, half), floor, None));
    let key = direction(55.0, -40.0);
    let rim = direction(40.0, 150.0);
    add_panel(
        s,
        "Key light",
        KEY_RADIANCE,
        centre + 15.0 * size * key,
        key,
        0.8 * size,
    );
    add_panel(
        s,
        "Rim light",
        RIM_RADIANCE,
        centre + 15.0 * size * rim,
        rim,
        0.5 * size,
    );
}

/// The preview's camera ("Preview", yfov 25°, +Y up) looking at `centre` from
/// `(elevation, azimuth)` degrees ([`direction`]), at the distance that fits a sphere of
/// `radius` metres about `centre` in the vertical field with 10 % margin; `aspect` is
/// width / height.
pub fn preview_camera(
    centre: DVec3,
    radius: f64,
    (elevation, azimuth): (f64, f64),
    aspect: f32,
) -> CameraDesc {
    let yfov = 25.0f64;
    let (half_sin, _) = sin_cos((0.5 * yfov).to_radians());
    let eye = centre + 1.1 * radius / half_sin * direction(elevation, azimuth);
    let fov = yfov.to_radians() as f32;
    look_at(
        "Preview",
        eye.as_vec3(),
        centre.as_vec3(),
        Vec3::Y,
        fov,
        Some(aspect),
    )
}

/// Unit vector `elevation` degrees above the horizon, `azimuth` degrees round from +Z
/// towards +X.
pub fn direction(elevation: f64, azimuth: f64) -> DVec3 {
    let (se, ce) = sin_cos(elevation.to_radians());
    let (sa, ca) = sin_cos(azimuth.to_radians());
    DVec3::new(ce * sa, se, ce * ca)
}

/// Axis-aligned bounds of a mesh, f64.
fn bounds(m: &TriMesh) -> (DVec3, DVec3) {
    m.positions.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(p.as_dvec3()), hi.max(p.as_dvec3())),
    )
}

/// Adds a square emitter of half side `half` centred at `at`, facing −`dir` (towards
/// the stone when `dir` points from the stone to `at`).
fn add_panel(s: &mut SceneDesc, name: &str, radiance: f32, at: DVec3, dir: DVec3, half: f64) {
    let u = DVec3::Y.cross(dir).normalize() * half;
    // u × v = −dir, so the corners below run counter-clockwise seen from the stone.
    let v = u.cross(dir);
    let corners = [at - u - v, at + u - v, at + u + v, at - u + v];
    let n = -dir;
    let mut quad = TriMesh::default();
    for c in corners {
        quad.positions.push(c.as_vec3());
        quad.normals.push(n.as_vec3());
    }
    quad.indices = vec![[0, 1, 2], [0, 2, 3]];
    s.materials
        .push(MaterialDesc::emitter(name, Vec3::splat(radiance)));
    let material = s.materials.len() - 1;
    s.meshes.push(placed(name, quad, material, None));
}

/// `iris gem`: checks the output name (must end in `.glb`) and `--size`, builds the scene
/// and writes it atomically; nothing is written on error.
pub fn write_gem(path: &Path, spec: &GemSpec) -> Result<()> {
    let is_glb = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    if !is_glb {
        return Err(Error::Usage(format!(
            "-o {}: `iris gem` writes binary glTF: the output name must end in .glb",
            path.display()
        )));
    }
    write_glb(path, &gem_scene(spec)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn preview_has_camera_lights_floor_and_the_stone_above_it() {
        let spec = GemSpec {
            cut: Cut::Emerald,
            stone: Stone::Sapphire,
            size_mm: 8.0,
            bare: false,
        };
        let s = gem_scene(&spec).expect("scene");
        assert_eq!(s.meshes.len(), 4);
        assert!(s.cameras.len() == 1 && s.environment.is_some());
        let lowest = s.meshes[0]
            .positions
            .iter()
            .map(|p| p.y)
            .fold(f32::MAX, f32::min);
        // 2 % of 8 mm = 0.16 mm above the floor (f32 rounding ~1e-9 m).
        assert!((lowest - 0.00016).abs() < 1e-8, "{lowest}");
        let bare = gem_scene(&GemSpec { bare: true, ..spec }).expect("bare");
        assert_eq!(bare.meshes.len(), 1);
        assert!(bare.cameras.is_empty() && bare.lights.is_empty() && bare.environment.is_none());
    }
}
