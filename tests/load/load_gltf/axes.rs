//! Directions read from a glTF file (issue 48): an `iris_crystal` optic axis, an
//! `iris_polarizer` axis, a light's or camera's node transform. Any finite non-zero vector
//! is its direction, however long or short (normalised after scaling by its largest
//! component), the same on a crystal and a polarizer; zero and unreadable ones are errors
//! naming the file, the material and the key; a polarizer's axis along its sheet's normal
//! is an error naming the mesh.

use super::fixtures::*;
use super::{common, expect_error, load, material};
use glam::Vec3;
use iris::scene::desc::{CameraDesc, LightDesc};
use iris::LoadErrorKind;
use serde_json::{json, Value};

/// The cube with its material a clear glass volume (a crystal needs one) or a thin-walled
/// transmissive sheet (a polarizer needs one), with `extras`.
fn cube_with(volume: bool, extras: Value) -> Value {
    let mut doc = cube_doc();
    let mut ext = json!({"KHR_materials_transmission": {"transmissionFactor": 1.0}});
    if volume {
        ext["KHR_materials_volume"] = json!({"thicknessFactor": 0.1});
    }
    doc["materials"][0]["extensions"] = ext;
    doc["materials"][0]["pbrMetallicRoughness"] = json!({"metallicFactor": 0.0});
    doc["materials"][0]["extras"] = extras;
    doc
}

/// Writes `doc` as raw text with `axis` (JSON number text, e.g. `1e400`) in place of the
/// string `"AXIS"`: numbers no JSON library writes.
fn write_raw(dir: &std::path::Path, name: &str, doc: &Value, axis: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    let text = doc.to_string().replace("\"AXIS\"", axis);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn huge_and_tiny_axes_are_their_direction_on_crystals_and_polarizers() {
    let dir = common::scratch_dir("gltf_axes_extreme");
    let diagonal = Vec3::new(1.0, 1.0, 0.0) / 2f32.sqrt();
    for (i, axis) in ["[3e38, 3e38, 0]", "[1e300, 1e300, 0]", "[1e-30, 1e-30, 0]"]
        .into_iter()
        .enumerate()
    {
        let crystal = cube_with(
            true,
            json!({"iris_crystal": {"stone": "calcite", "optic_axis": "AXIS"}}),
        );
        let desc = load(&write_raw(
            &dir,
            &format!("crystal{i}.gltf"),
            &crystal,
            axis,
        ));
        let c = material(&desc, "Glass").crystal.expect("a crystal");
        assert!(
            (c.axes.z_axis - diagonal).length() < 1e-6,
            "{axis}: {}",
            c.axes
        );
        assert!(
            (c.axes.determinant() - 1.0).abs() < 1e-5,
            "{axis}: {}",
            c.axes
        );
        let sheet = cube_with(false, json!({"iris_polarizer": {"axis": "AXIS"}}));
        let desc = load(&write_raw(&dir, &format!("sheet{i}.gltf"), &sheet, axis));
        let p = material(&desc, "Glass").polarizer.expect("a polarizer");
        assert!((p - diagonal).length() < 1e-6, "{axis}: {p}");
    }
}

#[test]
fn zero_and_unreadable_axes_are_refused_alike_naming_the_material_and_key() {
    let dir = common::scratch_dir("gltf_axes_bad");
    for (i, (axis, says)) in [
        ("[0, 0, 0]", "is zero"),
        ("[0, -0.0, 0]", "is zero"),
        ("[1e400, 0, 0]", "cannot be read"),
        ("[0, \"up\", 0]", "must be [x, y, z]"),
    ]
    .into_iter()
    .enumerate()
    {
        let crystal = cube_with(
            true,
            json!({"iris_crystal": {"stone": "calcite", "optic_axis": "AXIS"}}),
        );
        let path = write_raw(&dir, &format!("crystal{i}.gltf"), &crystal, axis);
        let e = expect_error(&path, LoadErrorKind::InvalidValue, "material 0 \"Glass\"");
        let text = e.to_string();
        assert!(
            text.contains("iris_crystal") && text.contains(says),
            "{axis}: {text}"
        );
        let sheet = cube_with(false, json!({"iris_polarizer": {"axis": "AXIS"}}));
        let path = write_raw(&dir, &format!("sheet{i}.gltf"), &sheet, axis);
        let e = expect_error(&path, LoadErrorKind::InvalidValue, "material 0 \"Glass\"");
        let text = e.to_string();
        assert!(
            text.contains("iris_polarizer") && text.contains(says),
            "{axis}: {text}"
        );
    }
}

/// Another extras key holding a number beyond f64 does not hide Iris's keys.
#[test]
fn an_unreadable_foreign_extras_key_does_not_hide_iris_keys() {
    let dir = common::scratch_dir("gltf_axes_foreign");
    let crystal = cube_with(
        true,
        json!({"exporter_weight": "AXIS", "iris_crystal": {"stone": "calcite"}}),
    );
    let desc = load(&write_raw(&dir, "foreign.gltf", &crystal, "1e999"));
    assert!(material(&desc, "Glass").crystal.is_some());
}

#[test]
fn a_polarizer_axis_along_its_sheets_normal_is_refused_naming_the_mesh() {
    let dir = common::scratch_dir("gltf_axes_sheet");
    // The cube's ±Z faces have normal ±Z.
    for (i, axis) in [[0.0, 0.0, 1.0], [0.0, 0.01, -1.0]].into_iter().enumerate() {
        let sheet = cube_with(false, json!({"iris_polarizer": {"axis": axis}}));
        let path = write_json(&dir, &format!("along{i}.gltf"), &sheet);
        let e = iris::load::load_scene(&path).expect_err("an axis along the normal");
        let text = e.to_string();
        assert_eq!(e.kind, LoadErrorKind::InvalidValue, "{text}");
        assert!(
            text.contains(&format!("along{i}.gltf"))
                && text.contains("material 0 \"Glass\"")
                && text.contains("along the sheet's normal")
                && text.contains("CubeMesh"),
            "{axis:?}: {text}"
        );
    }
    // 2° from the normal is an axis (the renderer projects it); so is one in the plane.
    for axis in [[0.0, 0.035, 1.0], [1.0, 1.0, 0.0]] {
        let sheet = cube_with(false, json!({"iris_polarizer": {"axis": axis}}));
        iris::load::load_scene(&write_json(&dir, "ok.gltf", &sheet)).expect("an axis");
    }
}

/// Lights and cameras on nodes scaled by 1e20 and 1e-25 (their −Z's squared length
/// overflows or underflows f32) keep their direction.
#[test]
fn lights_and_cameras_on_extremely_scaled_nodes_keep_their_direction() {
    let dir = common::scratch_dir("gltf_axes_nodes");
    let half = std::f32::consts::FRAC_1_SQRT_2;
    for (i, s) in [1e20f32, 1e-25].into_iter().enumerate() {
        let mut doc = cube_doc();
        doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
        doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [
            {"name": "Sun", "type": "directional", "intensity": 3.0}
        ]}});
        doc["cameras"] =
            json!([{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.01}}]);
        // +90° about X maps local −Z to world +Y.
        doc["nodes"] = json!([
            {"name": "Cube", "mesh": 0},
            {"name": "SunNode", "rotation": [half, 0.0, 0.0, half], "scale": [s, s, s],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "CamNode", "camera": 0, "translation": [0.0, 0.0, 5.0],
             "scale": [s, s, s]}
        ]);
        doc["scenes"][0]["nodes"] = json!([0, 1, 2]);
        let desc = load(&write_json(&dir, &format!("scaled{i}.gltf"), &doc));
        match &desc.lights[0] {
            LightDesc::Directional { direction, .. } => {
                assert!((*direction - Vec3::Y).length() < 1e-6, "{s}: {direction}")
            }
            other => panic!("{other:?}"),
        }
        let CameraDesc {
            world_from_camera, ..
        } = &desc.cameras[0];
        let forward = -world_from_camera.z_axis.truncate();
        assert!((forward + Vec3::Z).length() < 1e-6, "{s}: {forward}");
    }
}
