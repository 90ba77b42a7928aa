//! KHR_materials_clearcoat, _sheen and _diffuse_transmission: every parameter and texture
//! read, the clearcoat normal map noted once, and invalid values rejected naming the
//! material and the property.

use super::fixtures::*;
use super::{common, expect_error, load, material};
use glam::Vec3;
use iris::LoadErrorKind;
use serde_json::{json, Value};

const USED: [&str; 3] = [
    "KHR_materials_clearcoat",
    "KHR_materials_sheen",
    "KHR_materials_diffuse_transmission",
];

/// The cube with one material "M" carrying `extensions` (and a 2×2 image as textures 0, 1).
fn doc_with(extensions: Value) -> Value {
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(USED);
    doc["images"] = json!([{"uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0}, {"source": 0}]);
    doc["materials"] = json!([{"name": "M", "extensions": extensions}]);
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    doc
}

#[test]
fn layer_parameters_and_textures_are_read() {
    let dir = common::scratch_dir("gltf_layers");
    let doc = doc_with(json!({
        "KHR_materials_clearcoat": {
            "clearcoatFactor": 0.75, "clearcoatTexture": {"index": 0},
            "clearcoatRoughnessFactor": 0.25, "clearcoatRoughnessTexture": {"index": 1},
            "clearcoatNormalTexture": {"index": 0, "scale": 1.0}},
        "KHR_materials_sheen": {
            "sheenColorFactor": [0.5, 0.25, 0.125], "sheenColorTexture": {"index": 0},
            "sheenRoughnessFactor": 0.5, "sheenRoughnessTexture": {"index": 1}},
        "KHR_materials_diffuse_transmission": {
            "diffuseTransmissionFactor": 0.5, "diffuseTransmissionTexture": {"index": 0},
            "diffuseTransmissionColorFactor": [1.0, 0.5, 0.0],
            "diffuseTransmissionColorTexture": {"index": 1, "texCoord": 1}}
    }));
    let desc = load(&write_json(&dir, "layers.gltf", &doc));
    let l = material(&desc, "M").layers;
    assert_eq!((l.clearcoat, l.clearcoat_roughness), (0.75, 0.25));
    assert_eq!(l.sheen_color, Vec3::new(0.5, 0.25, 0.125));
    assert_eq!(l.sheen_roughness, 0.5);
    assert_eq!(l.diffuse_transmission, 0.5);
    assert_eq!(l.diffuse_transmission_color, Vec3::new(1.0, 0.5, 0.0));
    for t in [
        l.clearcoat_texture,
        l.clearcoat_roughness_texture,
        l.sheen_color_texture,
        l.sheen_roughness_texture,
        l.diffuse_transmission_texture,
    ] {
        assert_eq!(t.map(|t| (t.image, t.texcoord)), Some((0, 0)));
    }
    assert_eq!(
        l.diffuse_transmission_color_texture.map(|t| t.texcoord),
        Some(1)
    );
    let w = &desc.warnings;
    assert!(!w.iter().any(|w| w.contains("not supported")), "{w:?}");
    let normal: Vec<_> = w
        .iter()
        .filter(|w| w.contains("clearcoatNormalTexture"))
        .collect();
    assert_eq!(normal.len(), 1, "{w:?}");
    assert!(normal[0].contains("material 0 \"M\""), "{w:?}");
    // Defaults: an empty extension object is "no layer".
    let empty = doc_with(
        json!({"KHR_materials_clearcoat": {}, "KHR_materials_sheen": {},
        "KHR_materials_diffuse_transmission": {}}),
    );
    let desc = load(&write_json(&dir, "empty.gltf", &empty));
    let l = material(&desc, "M").layers;
    assert!(!l.any());
    assert_eq!(l.diffuse_transmission_color, Vec3::ONE);
    assert_eq!(l, iris::material::LayerDesc::default());
}

#[test]
fn invalid_layer_values_name_the_material() {
    let dir = common::scratch_dir("gltf_layers_bad");
    let cases = [
        (
            "KHR_materials_clearcoat",
            json!({"clearcoatFactor": -0.5}),
            "clearcoatFactor",
        ),
        (
            "KHR_materials_clearcoat",
            json!({"clearcoatRoughnessFactor": 1.5}),
            "clearcoatRoughnessFactor",
        ),
        (
            "KHR_materials_clearcoat",
            json!({"clearcoatFactor": "NaN"}),
            "clearcoatFactor",
        ),
        (
            "KHR_materials_sheen",
            json!({"sheenColorFactor": [0.5, 0.5]}),
            "sheenColorFactor",
        ),
        (
            "KHR_materials_sheen",
            json!({"sheenColorFactor": [0.5, -1.0, 0.5]}),
            "sheenColorFactor",
        ),
        (
            "KHR_materials_sheen",
            json!({"sheenRoughnessFactor": null}),
            "sheenRoughnessFactor",
        ),
        (
            "KHR_materials_diffuse_transmission",
            json!({"diffuseTransmissionFactor": 2.0}),
            "diffuseTransmissionFactor",
        ),
        (
            "KHR_materials_diffuse_transmission",
            json!({"diffuseTransmissionColorFactor": [2.0, 1.0, 1.0]}),
            "diffuseTransmissionColorFactor",
        ),
        (
            "KHR_materials_diffuse_transmission",
            json!({"diffuseTransmissionTexture": {"texCoord": 0}}),
            "diffuseTransmissionTexture",
        ),
        ("KHR_materials_sheen", json!([1, 2]), "KHR_materials_sheen"),
    ];
    for (i, (ext, value, property)) in cases.into_iter().enumerate() {
        let doc = doc_with(json!({ ext: value }));
        let path = write_json(&dir, &format!("bad{i}.gltf"), &doc);
        let e = expect_error(&path, LoadErrorKind::InvalidValue, "material 0 \"M\"");
        assert!(e.to_string().contains(property), "{e}");
    }
    let doc = doc_with(json!({"KHR_materials_clearcoat": {"clearcoatTexture": {"index": 7}}}));
    let path = write_json(&dir, "bad_index.gltf", &doc);
    let e = expect_error(&path, LoadErrorKind::IndexOutOfRange, "material 0 \"M\"");
    assert!(e.to_string().contains("clearcoatTexture"), "{e}");
    assert!(e.to_string().contains("texture 7"), "{e}");
}
