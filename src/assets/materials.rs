//! Small test scenes for the thin-film and brushed-metal material extensions, shipped (CC0)
//! in `assets/materials/`: generated equivalents of the Khronos samples
//! IridescenceSuzanne / IridescenceLamp (KHR_materials_iridescence) and AnisotropyBarnLamp
//! / AnisotropyRotationTest (KHR_materials_anisotropy), for Iris's tests and a Cycles
//! comparison.
//!
//! Units are metres, +Y up, linear RGB; point intensities in candela.
//!
//! | file | object | material | light | camera |
//! |---|---|---|---|---|
//! | `iridescence_sphere.glb` | sphere r 0.5 (icosphere, 1280 triangles) at the origin | dark dielectric (base 0.05, roughness 0.15, ior 1.5) with iridescence factor 1, film ior 1.3, thickness 100–400 nm (no texture: 400 nm) | scene extras `iris_environment: 1` (uniform white) | eye (0, 0, 2.2) → origin, yfov 30° |
//! | `iridescence_metal.glb` | the same sphere | grey metal (base 0.6, roughness 0.2) with iridescence factor 1, film ior 1.8, thickness 300 nm | as above | as above |
//! | `anisotropy_plate.glb` | plate 1 × 1 m in y = 0 with TEXCOORD_0 = (x + 0.5, z + 0.5) (tangent = +X) | white metal (base 0.9, roughness 0.3) with anisotropy strength 0.5, rotation 0 | point light 20 cd at (0.05, 1.5, 0) | eye (0, 1.5, 0) looking down (up −Z), yfov 40° |
//! | `anisotropy_rotation.glb` | as above | as above, rotation π/2 (brushing along +Z) | as above | as above |
//!
//! On the plates the highlight is stretched along the anisotropy direction (world X, image
//! x for rotation 0; world Z, image y for π/2): the tests measure that.

use crate::authoring::glb::write_glb;
use crate::authoring::scene::{look_at, placed};
use crate::authoring::shapes::{ground_plane, icosphere};
use crate::error::Result;
use crate::material::MaterialDesc;
use crate::material::{AnisotropyDesc, IridescenceDesc};
use crate::scene::desc::LightDesc;
use crate::scene::desc::{EnvironmentDesc, MeshDesc, SceneDesc};
use glam::{Vec2, Vec3, Vec4};
use std::path::{Path, PathBuf};

/// File names written by [`write_material_assets`], in order.
pub const FILES: [&str; 4] = [
    "iridescence_sphere.glb",
    "iridescence_metal.glb",
    "anisotropy_plate.glb",
    "anisotropy_rotation.glb",
];

fn sphere_scene(name: &str, material: MaterialDesc) -> SceneDesc {
    SceneDesc {
        name: name.into(),
        meshes: vec![placed("sphere", icosphere(0.5, 3), 0, None)],
        materials: vec![material],
        cameras: vec![look_at(
            "camera",
            Vec3::new(0.0, 0.0, 2.2),
            Vec3::ZERO,
            Vec3::Y,
            30f32.to_radians(),
            Some(1.0),
        )],
        environment: Some(EnvironmentDesc::Uniform(Vec3::splat(1.0))),
        ..Default::default()
    }
}

/// The iridescent dark dielectric sphere (IridescenceSuzanne's material on a sphere).
pub fn iridescence_sphere() -> SceneDesc {
    let mut m = MaterialDesc::diffuse("iridescent dielectric", Vec3::splat(0.05));
    m.roughness = 0.15;
    m.ior = 1.5;
    m.stated.insert("KHR_materials_ior".into());
    m.iridescence = Some(IridescenceDesc {
        factor: 1.0,
        ior: 1.3,
        ..Default::default()
    });
    sphere_scene("iridescence sphere", m)
}

/// The iridescent metal sphere (a thin oxide on grey metal, as IridescenceLamp's shade).
pub fn iridescence_metal() -> SceneDesc {
    let mut m = MaterialDesc::diffuse("iridescent metal", Vec3::splat(0.6));
    m.metallic = 1.0;
    m.roughness = 0.2;
    m.iridescence = Some(IridescenceDesc {
        factor: 1.0,
        ior: 1.8,
        thickness_min: 300.0,
        thickness_max: 300.0,
        ..Default::default()
    });
    sphere_scene("iridescence metal", m)
}

/// The brushed plate under a point light, brushing rotated by `rotation` (radians).
pub fn anisotropy_plate(rotation: f32) -> SceneDesc {
    let plate = ground_plane(0.5, 0.5);
    let uvs: Vec<Vec2> = plate
        .positions
        .iter()
        .map(|p| Vec2::new(p.x + 0.5, p.z + 0.5))
        .collect();
    let material = MaterialDesc {
        base_color: Vec4::new(0.9, 0.9, 0.9, 1.0),
        metallic: 1.0,
        roughness: 0.3,
        anisotropy: Some(AnisotropyDesc {
            strength: 0.5,
            rotation,
            texture: None,
        }),
        ..MaterialDesc::diffuse("brushed metal", Vec3::ONE)
    };
    SceneDesc {
        name: "anisotropy plate".into(),
        meshes: vec![MeshDesc {
            uvs,
            ..placed("plate", plate, 0, None)
        }],
        materials: vec![material],
        lights: vec![LightDesc::Point {
            name: "lamp".into(),
            position: Vec3::new(0.05, 1.5, 0.0),
            color: Vec3::ONE,
            intensity: 20.0,
            range: None,
            spectrum: None,
        }],
        cameras: vec![look_at(
            "camera",
            Vec3::new(0.0, 1.5, 0.0),
            Vec3::ZERO,
            Vec3::NEG_Z,
            40f32.to_radians(),
            Some(1.0),
        )],
        ..Default::default()
    }
}

/// The four scenes of the module doc, in [`FILES`] order.
pub fn material_scenes() -> [SceneDesc; 4] {
    [
        iridescence_sphere(),
        iridescence_metal(),
        anisotropy_plate(0.0),
        anisotropy_plate(std::f32::consts::FRAC_PI_2),
    ]
}

/// Writes [`FILES`] into `dir` (created as needed); returns the paths written.
pub fn write_material_assets(dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| crate::error::Error::Output {
        path: dir.to_path_buf(),
        reason: format!("cannot create directory: {e}"),
    })?;
    let mut out = Vec::new();
    for (name, scene) in FILES.iter().zip(material_scenes()) {
        let path = dir.join(name);
        write_glb(&path, &scene)?;
        out.push(path);
    }
    Ok(out)
}
