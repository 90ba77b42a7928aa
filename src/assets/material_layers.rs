//! Test scenes for the KHR material layer extensions, shipped (CC0) in `assets/materials/`:
//! generated stand-ins for the Khronos sample models ClearCoatTest, SheenCloth/SheenChair and
//! DiffuseTransmissionTest, which this workplace cannot download.
//!
//! Units are metres, +Y up, linear RGB; point and spot intensities in candela; emitters are
//! black diffuse quads whose `emissiveFactor` × `KHR_materials_emissive_strength` is the
//! radiance below, emitting from their front face. Every scene has its camera and its own
//! lights and NO environment, no dispersion and no Iris-only extras, so that Blender Cycles
//! can render the same file for a cross-check. Each file is < 200 KB: every sphere is an
//! icosphere (3 subdivisions, 1280 triangles, smooth normals) in world space.
//!
//! | file | objects | materials | lights | camera |
//! |---|---|---|---|---|
//! | `clearcoat.glb` | 4 spheres r = [`SPHERE_RADIUS`] in a row ([`row`]) over a grey floor | base (0.6, 0.08, 0.05), roughness 0.6; clearcoat ([`CLEARCOATS`]) 0, 0.5, 1 with coat roughness 0, then 1 with coat roughness 0.5 | one 30 × 30 cm panel of radiance 400 at [`CLEARCOAT_LIGHT`], facing the row's centre, outside the view | [`sphere_camera`] |
//! | `sheen.glb` | 5 spheres in a row over a grey floor | dark base 0.03, roughness 1; [`SHEENS`]: none, white 0.3, white 0.8, blue 0.3, blue 0.8 | a 4 × 0.6 m panel of radiance 20 behind and above ([`SHEEN_BACK_LIGHT`]), out of view; a 20 cd point fill at (0, 2, 4) | [`sphere_camera`] |
//! | `diffuse_transmission.glb` | 3 upright double-sided 0.8 m square sheets facing +Z at [`SHEET_CENTRES`], over a grey floor | white 0.8, roughness 1, [`DIFFUSE_TRANSMISSION`] 0, 0.5, 1 with colour [`TRANSMISSION_COLOR`] | behind each sheet a spot (2 cd, cone 0.3/0.42 rad, 0.9 m back) that lights only its sheet; a 1.5 cd point fill at (0, 2.5, 2.5) | eye (0, 1, 4) → (0, 0.5, 0), yfov 35°, 4:3 |

use super::paper::SceneBuilder;
use super::parts::{add_mesh, add_panel, camera};
use crate::authoring::glb::write_glb;
use crate::authoring::shapes::{ground_plane, icosphere, quarter_turn_x};
use crate::error::{Error, Result};
use crate::material::MaterialDesc;
use crate::scene::desc::LightDesc;
use crate::scene::desc::{CameraDesc, SceneDesc};
use glam::{Mat3, Quat, Vec3};
use std::path::{Path, PathBuf};

/// File names and builders, in the order [`write_material_assets`] writes them.
pub const MATERIAL_SCENES: [(&str, SceneBuilder); 3] = [
    ("clearcoat.glb", clearcoat),
    ("sheen.glb", sheen),
    ("diffuse_transmission.glb", diffuse_transmission),
];

/// Radius of the test spheres, metres.
pub const SPHERE_RADIUS: f32 = 0.35;
/// Height of the sphere centres (5 cm of air below each sphere), metres.
pub const SPHERE_Y: f32 = 0.4;
/// Distance between neighbouring sphere centres along X, metres.
pub const SPHERE_SPACING: f32 = 0.9;
/// (clearcoatFactor, clearcoatRoughnessFactor) of the clearcoat spheres, left to right.
pub const CLEARCOATS: [(f32, f32); 4] = [(0.0, 0.0), (0.5, 0.0), (1.0, 0.0), (1.0, 0.5)];
/// Centre of the clearcoat scene's panel light (it faces the row's centre).
pub const CLEARCOAT_LIGHT: Vec3 = Vec3::new(0.0, 2.6, 3.0);
/// (sheenColorFactor, sheenRoughnessFactor) of the sheen spheres, left to right; `None` =
/// no KHR_materials_sheen.
pub const SHEENS: [Option<(Vec3, f32)>; 5] = [
    None,
    Some((Vec3::ONE, 0.3)),
    Some((Vec3::ONE, 0.8)),
    Some((Vec3::new(0.2, 0.6, 1.0), 0.3)),
    Some((Vec3::new(0.2, 0.6, 1.0), 0.8)),
];
/// Centre of the sheen scene's back panel (it faces the row's centre).
pub const SHEEN_BACK_LIGHT: Vec3 = Vec3::new(0.0, 3.5, -2.5);
/// Half side of the diffuse-transmission sheets, metres.
pub const SHEET_HALF: f32 = 0.4;
/// Centres of the sheets, left to right.
pub const SHEET_CENTRES: [Vec3; 3] = [
    Vec3::new(-1.1, 0.5, 0.0),
    Vec3::new(0.0, 0.5, 0.0),
    Vec3::new(1.1, 0.5, 0.0),
];
/// diffuseTransmissionFactor of the sheets, left to right.
pub const DIFFUSE_TRANSMISSION: [f32; 3] = [0.0, 0.5, 1.0];
/// diffuseTransmissionColorFactor of every sheet (orange).
pub const TRANSMISSION_COLOR: Vec3 = Vec3::new(1.0, 0.45, 0.1);

/// Centres of a row of `n` spheres along X, centred on x = 0, [`SPHERE_SPACING`] apart.
pub fn row(n: usize) -> Vec<Vec3> {
    let first = -0.5 * (n as f32 - 1.0) * SPHERE_SPACING;
    (0..n)
        .map(|i| Vec3::new(first + i as f32 * SPHERE_SPACING, SPHERE_Y, 0.0))
        .collect()
}

/// The camera of the sphere rows: eye (0, 1, 5) → (0, 0.4, 0), yfov 40°, 4:3.
pub fn sphere_camera() -> CameraDesc {
    camera(
        Vec3::new(0.0, 1.0, 5.0),
        Vec3::new(0.0, SPHERE_Y, 0.0),
        40.0,
        4.0 / 3.0,
    )
}

/// Writes [`MATERIAL_SCENES`] into `dir` (created if missing), each atomically; returns
/// their paths in order.
pub fn write_material_assets(dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::Output {
        path: dir.to_path_buf(),
        reason: format!("cannot create directory: {e}"),
    })?;
    let mut written = Vec::with_capacity(MATERIAL_SCENES.len());
    for (name, build) in MATERIAL_SCENES {
        let path = dir.join(name);
        write_glb(&path, &build())?;
        written.push(path);
    }
    Ok(written)
}

/// ≈ ClearCoatTest: a rough red base under clearcoats of increasing factor and one rough coat.
pub fn clearcoat() -> SceneDesc {
    let mut s = scene_with_floor("Clearcoat test");
    let spheres = CLEARCOATS.iter().zip(row(CLEARCOATS.len()));
    for (i, (&(factor, roughness), at)) in spheres.enumerate() {
        let mut m = MaterialDesc::diffuse(
            &format!("Clearcoat {factor} roughness {roughness}"),
            Vec3::new(0.6, 0.08, 0.05),
        );
        m.roughness = 0.6;
        m.layers.clearcoat = factor;
        m.layers.clearcoat_roughness = roughness;
        m.stated.insert("KHR_materials_clearcoat".into());
        add_sphere(&mut s, &format!("Sphere {}", i + 1), m, at);
    }
    add_facing_panel(&mut s, "Key panel", 400.0, (0.15, 0.15), CLEARCOAT_LIGHT);
    s.cameras.push(sphere_camera());
    s
}

/// ≈ SheenCloth / SheenChair: dark cloth-like spheres with and without sheen, back-lit.
pub fn sheen() -> SceneDesc {
    let mut s = scene_with_floor("Sheen test");
    for (i, (sheen, at)) in SHEENS.iter().zip(row(SHEENS.len())).enumerate() {
        let name = match sheen {
            None => "No sheen".to_string(),
            Some((c, r)) => format!("Sheen ({}, {}, {}) roughness {r}", c.x, c.y, c.z),
        };
        let mut m = MaterialDesc::diffuse(&name, Vec3::splat(0.03));
        if let Some((color, roughness)) = *sheen {
            m.layers.sheen_color = color;
            m.layers.sheen_roughness = roughness;
            m.stated.insert("KHR_materials_sheen".into());
        }
        add_sphere(&mut s, &format!("Sphere {}", i + 1), m, at);
    }
    add_facing_panel(&mut s, "Back panel", 20.0, (2.0, 0.3), SHEEN_BACK_LIGHT);
    s.lights.push(LightDesc::Point {
        name: "Front fill".into(),
        position: Vec3::new(0.0, 2.0, 4.0),
        color: Vec3::ONE,
        intensity: 20.0,
        range: None,
        spectrum: None,
    });
    s.cameras.push(sphere_camera());
    s
}

/// ≈ DiffuseTransmissionTest: thin sheets lit from behind, seen from the front.
pub fn diffuse_transmission() -> SceneDesc {
    let mut s = scene_with_floor("Diffuse transmission test");
    let sheet = ground_plane(SHEET_HALF, SHEET_HALF).transformed(quarter_turn_x(), Vec3::ZERO);
    for (i, (&factor, &at)) in DIFFUSE_TRANSMISSION.iter().zip(&SHEET_CENTRES).enumerate() {
        let mut m =
            MaterialDesc::diffuse(&format!("Diffuse transmission {factor}"), Vec3::splat(0.8));
        m.double_sided = true;
        m.layers.diffuse_transmission = factor;
        m.layers.diffuse_transmission_color = TRANSMISSION_COLOR;
        m.stated.insert("KHR_materials_diffuse_transmission".into());
        add_mesh(
            &mut s,
            &format!("Sheet {}", i + 1),
            sheet.clone(),
            m,
            Some(at),
        );
        s.lights.push(LightDesc::Spot {
            name: format!("Back spot {}", i + 1),
            position: at - Vec3::new(0.0, 0.0, 0.9),
            direction: Vec3::Z,
            color: Vec3::ONE,
            intensity: 2.0,
            inner_cone: 0.3,
            outer_cone: 0.42,
            range: None,
            spectrum: None,
        });
    }
    s.lights.push(LightDesc::Point {
        name: "Front fill".into(),
        position: Vec3::new(0.0, 2.5, 2.5),
        color: Vec3::ONE,
        intensity: 1.5,
        range: None,
        spectrum: None,
    });
    s.cameras.push(camera(
        Vec3::new(0.0, 1.0, 4.0),
        Vec3::new(0.0, 0.5, 0.0),
        35.0,
        4.0 / 3.0,
    ));
    s
}

/// A scene holding only a 12 × 12 m grey (0.5) floor at y = 0.
fn scene_with_floor(name: &str) -> SceneDesc {
    let mut s = SceneDesc {
        name: name.into(),
        ..SceneDesc::default()
    };
    let floor = MaterialDesc::diffuse("Floor", Vec3::splat(0.5));
    add_mesh(&mut s, "Floor", ground_plane(6.0, 6.0), floor, None);
    s
}

/// Adds a sphere of radius [`SPHERE_RADIUS`] centred at `at` (all spheres share geometry).
fn add_sphere(s: &mut SceneDesc, name: &str, m: MaterialDesc, at: Vec3) {
    add_mesh(s, name, icosphere(SPHERE_RADIUS, 3), m, Some(at));
}

/// Adds a white emitter of radiance `radiance` and half extents `half`, centred at `at`,
/// facing the row's centre (0, [`SPHERE_Y`], 0).
fn add_facing_panel(s: &mut SceneDesc, name: &str, radiance: f32, half: (f32, f32), at: Vec3) {
    let facing = (Vec3::new(0.0, SPHERE_Y, 0.0) - at).normalize();
    let turn = Mat3::from_quat(Quat::from_rotation_arc(Vec3::Y, facing));
    add_panel(s, name, radiance, half, turn, at);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scenes_encode_deterministically_small_and_without_environment() {
        for (name, build) in MATERIAL_SCENES {
            let scene = build();
            assert!(scene.environment.is_none(), "{name}: no environment");
            let a = crate::authoring::glb::encode_glb(&scene).expect(name);
            assert_eq!(a, crate::authoring::glb::encode_glb(&build()).expect(name));
            assert!(a.len() < 200_000, "{name} is {} bytes", a.len());
        }
    }

    #[test]
    fn panels_face_the_row() {
        let s = clearcoat();
        let panel = s.meshes.last().expect("panel");
        let n = panel.normals[0];
        let to_row = (Vec3::new(0.0, SPHERE_Y, 0.0) - CLEARCOAT_LIGHT).normalize();
        assert!(n.dot(to_row) > 0.999, "{n} vs {to_row}");
        let row = row(4);
        assert_eq!(row.len(), 4);
        assert!((row[0].x + row[3].x).abs() < 1e-6 && row[1].x < 0.0);
    }
}
