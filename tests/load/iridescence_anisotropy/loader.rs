//! Loader half of `tests/load/iridescence_anisotropy/mod.rs`: KHR_materials_iridescence and
//! KHR_materials_anisotropy properties, textures, the TANGENT attribute, bad values, and
//! the Khronos SunglassesKhronos lens.

use super::common;
use super::fixtures::{cube_doc, data_uri, png_2x2, write_json};
use glam::Vec3;
use iris::load::load_scene;
use iris::scene::desc::SceneDesc;
use iris::LoadErrorKind;
use serde_json::{json, Value};
use std::path::PathBuf;

/// The cube with `material` as material 0 (named "Film") and one 2×2 PNG texture.
fn gltf_with(test: &str, material: Value) -> PathBuf {
    let dir = common::scratch_dir(test);
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(["KHR_materials_iridescence", "KHR_materials_anisotropy"]);
    let mut m = material;
    m["name"] = json!("Film");
    doc["materials"] = json!([m]);
    doc["images"] = json!([{"uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0}]);
    write_json(&dir, "scene.gltf", &doc)
}

fn loaded(test: &str, material: Value) -> SceneDesc {
    load_scene(&gltf_with(test, material)).unwrap_or_else(|e| panic!("{test}: {e}"))
}

fn expect_error(test: &str, material: Value, kind: LoadErrorKind, says: &str) {
    let e = match load_scene(&gltf_with(test, material)) {
        Ok(_) => panic!("{test}: loaded but should fail"),
        Err(e) => e,
    };
    let text = e.to_string();
    assert_eq!(e.kind, kind, "{test}: {text}");
    assert!(text.contains("scene.gltf"), "{test}: {text}");
    assert!(text.contains("material 0 \"Film\""), "{test}: {text}");
    assert!(text.contains(says), "{test}: {text} lacks {says}");
}

#[test]
fn every_property_and_texture_is_read() {
    let desc = loaded(
        "film_props",
        json!({"extensions": {
            "KHR_materials_iridescence": {
                "iridescenceFactor": 0.7, "iridescenceIor": 1.45,
                "iridescenceThicknessMinimum": 120.0, "iridescenceThicknessMaximum": 480.0,
                "iridescenceTexture": {"index": 0},
                "iridescenceThicknessTexture": {"index": 0, "texCoord": 1}},
            "KHR_materials_anisotropy": {
                "anisotropyStrength": 0.6, "anisotropyRotation": 1.25,
                "anisotropyTexture": {"index": 0}}}}),
    );
    let film = &desc.materials[0];
    let i = film.iridescence.expect("iridescence");
    assert_eq!(
        (i.factor, i.ior, i.thickness_min, i.thickness_max),
        (0.7, 1.45, 120.0, 480.0)
    );
    assert!(i.texture.is_some());
    assert_eq!(i.thickness_texture.map(|t| t.texcoord), Some(1));
    let a = film.anisotropy.expect("anisotropy");
    assert_eq!((a.strength, a.rotation), (0.6, 1.25));
    assert!(a.texture.is_some());
    // texCoord 1 is sampled with TEXCOORD_0, and said so; the extensions are not "unsupported".
    assert!(
        desc.warnings.iter().any(|w| w.contains("texCoord 1")),
        "{:?}",
        desc.warnings
    );
    assert!(
        !desc.warnings.iter().any(|w| w.contains("not supported")),
        "{:?}",
        desc.warnings
    );
    // Defaults: ior 1.3, 100–400 nm; strength 0, rotation 0.
    let desc = loaded(
        "film_defaults",
        json!({"extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1.0},
                              "KHR_materials_anisotropy": {}}}),
    );
    let film = &desc.materials[0];
    let i = film.iridescence.expect("iridescence");
    assert_eq!(
        (i.ior, i.thickness_min, i.thickness_max),
        (1.3, 100.0, 400.0)
    );
    let a = film.anisotropy.expect("anisotropy");
    assert_eq!((a.strength, a.rotation, a.texture), (0.0, 0.0, None));
    // `iris info`'s material line shows both.
    assert_eq!(
        desc.materials[0].describe_extensions(),
        "iridescence 1 (film n 1.3, 100–400 nm); anisotropy 0 (rotation 0 rad)"
    );
}

#[test]
fn bad_values_are_errors_naming_the_material() {
    let ir = |v: Value| json!({"extensions": {"KHR_materials_iridescence": v}});
    let an = |v: Value| json!({"extensions": {"KHR_materials_anisotropy": v}});
    use LoadErrorKind::{IndexOutOfRange, InvalidValue};
    let cases = [
        (
            "film_neg",
            ir(json!({"iridescenceThicknessMinimum": -5.0})),
            InvalidValue,
            "must not be negative",
        ),
        (
            "film_minmax",
            ir(json!({"iridescenceThicknessMinimum": 500.0})),
            InvalidValue,
            "exceeds",
        ),
        (
            "film_factor",
            ir(json!({"iridescenceFactor": 1.5})),
            InvalidValue,
            "iridescenceFactor",
        ),
        (
            "film_str",
            ir(json!({"iridescenceIor": "high"})),
            InvalidValue,
            "iridescenceIor must be a number",
        ),
        (
            "film_obj",
            ir(json!(3)),
            InvalidValue,
            "must be a JSON object",
        ),
        (
            "film_tex",
            ir(json!({"iridescenceTexture": {"index": 7}})),
            IndexOutOfRange,
            "iridescenceTexture.index 7",
        ),
        (
            "film_tex2",
            an(json!({"anisotropyTexture": {"index": -1}})),
            InvalidValue,
            "anisotropyTexture.index",
        ),
        (
            "film_strength",
            an(json!({"anisotropyStrength": -0.1})),
            InvalidValue,
            "anisotropyStrength",
        ),
    ];
    for (test, m, kind, says) in cases {
        expect_error(test, m, kind, says);
    }
    // NaN cannot be written in JSON: the same rule at validation (other loaders, edits).
    let mut desc = loaded("film_nan", ir(json!({"iridescenceFactor": 1.0})));
    if let Some(i) = desc.materials[0].iridescence.as_mut() {
        i.thickness_max = f32::NAN;
    }
    let e = iris::scene::validate::validate(desc).expect_err("NaN thickness");
    assert_eq!(e.kind, InvalidValue);
    assert!(e.to_string().contains("material 0 \"Film\""), "{e}");
    assert!(e.to_string().contains("iridescenceThicknessMaximum"), "{e}");
}

/// One triangle in the xz plane facing +Y with NORMAL and TANGENT (w = −1), under node
/// `scale` (a mirror when negative).
fn tangent_doc(scale_x: f32) -> Value {
    let pos: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]];
    let nrm = [[0.0f32, 1.0, 0.0]; 3];
    let tan = [[1.0f32, 0.0, 0.0, -1.0]; 3];
    let mut bin = Vec::new();
    for v in pos.iter().flatten().chain(nrm.iter().flatten()) {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    for v in tan.iter().flatten() {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    json!({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "scale": [scale_x, 1.0, 1.0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2}}]}],
        "buffers": [{"byteLength": bin.len(), "uri": data_uri("application/octet-stream", &bin)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 36},
            {"buffer": 0, "byteOffset": 72, "byteLength": 48}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [1.0, 0.0, 1.0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"}]
    })
}

#[test]
fn tangent_attribute_is_read_and_mirrored() {
    let dir = common::scratch_dir("film_tangent");
    let path = write_json(&dir, "t.gltf", &tangent_doc(1.0));
    let desc = load_scene(&path).expect("load");
    let t = &desc.meshes[0].tangents;
    assert_eq!(t.len(), 3);
    assert!(
        (t[0] - glam::Vec4::new(1.0, 0.0, 0.0, -1.0)).length() < 1e-6,
        "{t:?}"
    );
    // Mirrored in x: the tangent flips with the geometry and the bitangent B = w (n × t)
    // keeps pointing where M·B does, so w changes sign.
    let path = write_json(&dir, "m.gltf", &tangent_doc(-1.0));
    let desc = load_scene(&path).expect("load");
    let t = desc.meshes[0].tangents[0];
    let n = desc.meshes[0].normals[0];
    assert!((t.truncate() - Vec3::NEG_X).length() < 1e-6, "{t}");
    // Local B = −1·(Y × X) = +Z; M·B = +Z.
    let b = n.cross(t.truncate()) * t.w;
    assert!((b - Vec3::Z).length() < 1e-6, "b {b}, t {t}, n {n}");
    // A NaN in TANGENT is an error naming the primitive's attribute.
    let mut doc = tangent_doc(1.0);
    let mut bin = Vec::new();
    for v in [[0.0f32, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
        .iter()
        .flatten()
    {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    for _ in 0..3 {
        for v in [0.0f32, 1.0, 0.0] {
            bin.extend_from_slice(&v.to_le_bytes());
        }
    }
    for v in [f32::NAN, 0.0, 0.0, 1.0].repeat(3) {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    doc["buffers"][0]["uri"] = json!(data_uri("application/octet-stream", &bin));
    let path = write_json(&dir, "nan.gltf", &doc);
    let e = load_scene(&path).expect_err("NaN tangent");
    assert_eq!(e.kind, LoadErrorKind::InvalidValue);
    assert!(e.to_string().contains("TANGENT"), "{e}");
}

/// Khronos SunglassesKhronos (shared assets): the lens's iridescence is read as written
/// (factor 1, film ior 2, thickness max 300.01 nm, default min 100), the extension is no
/// longer "unsupported", and validation warns once that the film is not applied to the
/// lens's transmission lobe.
#[test]
fn sunglasses_lens_iridescence_is_read() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let path = assets.join("khronos/SunglassesKhronos/SunglassesKhronos.glb");
    let desc = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let lens = desc
        .materials
        .iter()
        .find(|m| m.name.contains("lens_exterior"))
        .expect("lens_exterior");
    let i = lens.iridescence.expect("iridescence read");
    assert_eq!((i.factor, i.ior, i.thickness_min), (1.0, 2.0, 100.0));
    assert!((i.thickness_max - 300.01).abs() < 1e-3);
    let mentions: Vec<&String> = desc
        .warnings
        .iter()
        .filter(|w| w.contains("KHR_materials_iridescence"))
        .collect();
    assert_eq!(mentions.len(), 1, "{:?}", desc.warnings);
    assert!(mentions[0].contains("lens_exterior") && !mentions[0].contains("not supported"));
}
