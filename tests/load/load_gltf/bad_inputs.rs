//! Broken files written by the tests: each fails with the right kind, and the message
//! names the file and the element.

use super::fixtures::*;
use super::{common, expect_error, load, triangles};
use iris::LoadErrorKind;
use serde_json::json;

#[test]
fn truncated_glb_is_a_parse_error() {
    let dir = common::scratch_dir("gltf_truncated");
    let bytes = cube_glb();
    let full = dir.join("whole.glb");
    std::fs::write(&full, &bytes).expect("write");
    assert_eq!(triangles(&load(&full)), 12);
    for cut in [bytes.len() - 1, bytes.len() / 2, 30, 13, 5] {
        let path = dir.join(format!("cut{cut}.glb"));
        std::fs::write(&path, &bytes[..cut]).expect("write");
        expect_error(&path, LoadErrorKind::Parse, "GLB");
    }
}

#[test]
fn missing_external_buffer_names_the_buffer() {
    let dir = common::scratch_dir("gltf_missing_bin");
    let (positions, tris) = cube();
    let (mut doc, bin) = mesh_doc(&positions, &tris);
    doc["buffers"][0]["uri"] = json!("cube%20geometry.bin");
    let path = write_json(&dir, "external.gltf", &doc);
    let err = expect_error(&path, LoadErrorKind::MissingBuffer, "buffer 0 \"geometry\"");
    assert!(err.to_string().contains("cube geometry.bin"), "{err}");

    // With the (percent-decoded) file present it loads; a short file is MissingBuffer too.
    std::fs::write(dir.join("cube geometry.bin"), &bin).expect("write bin");
    assert_eq!(triangles(&load(&path)), 12);
    std::fs::write(dir.join("cube geometry.bin"), &bin[..bin.len() - 4]).expect("write bin");
    expect_error(&path, LoadErrorKind::MissingBuffer, "buffer 0 \"geometry\"");
}

#[test]
fn index_out_of_range_names_the_mesh() {
    let dir = common::scratch_dir("gltf_index_range");
    let (positions, mut tris) = cube();
    tris[5][1] = 8;
    let (mut doc, bin) = mesh_doc(&positions, &tris);
    doc["buffers"][0]["uri"] = json!(data_uri("application/octet-stream", &bin));
    let path = write_json(&dir, "bad_index.gltf", &doc);
    expect_error(
        &path,
        LoadErrorKind::IndexOutOfRange,
        "node 0 \"Cube\" mesh 0 \"CubeMesh\" primitive 0",
    );

    // An accessor running past its buffer view is reported for the same element.
    let mut doc = cube_doc();
    doc["accessors"][0]["count"] = json!(9);
    let path = write_json(&dir, "long_accessor.gltf", &doc);
    expect_error(
        &path,
        LoadErrorKind::MissingBuffer,
        "mesh 0 \"CubeMesh\" primitive 0",
    );
}

#[test]
fn malformed_cauchy_extras_name_the_material() {
    let dir = common::scratch_dir("gltf_cauchy_bad");
    let bad = [
        json!({"cauchy": {"b": 1.5}}),
        json!({"cauchy": {"b": "1.5", "c": 0.004}}),
        json!({"cauchy": {"b": 0.9, "c": 0.004}}),
        json!({"cauchy": {"b": 1.5, "c": -0.1}}),
        json!({"cauchy": {"b": 1.5, "c": 1e300}}),
        json!({"cauchy": [1.5, 0.004]}),
    ];
    for (i, extras) in bad.into_iter().enumerate() {
        let mut doc = cube_doc();
        doc["materials"][0]["extras"] = extras;
        let path = write_json(&dir, &format!("cauchy{i}.gltf"), &doc);
        expect_error(&path, LoadErrorKind::InvalidValue, "material 0 \"Glass\"");
    }
}

#[test]
fn required_compressed_geometry_is_read_and_unknown_extensions_warn() {
    let dir = common::scratch_dir("gltf_draco");
    // Compressed geometry is decoded (tests/load/load_compressed.rs): requiring it is no
    // error and no warning.
    for ext in [
        "KHR_draco_mesh_compression",
        "EXT_meshopt_compression",
        "KHR_meshopt_compression",
    ] {
        let mut doc = cube_doc();
        doc["extensionsUsed"] = json!([ext]);
        doc["extensionsRequired"] = json!([ext]);
        let desc = load(&write_json(&dir, &format!("{ext}.gltf"), &doc));
        assert!(desc.warnings.is_empty(), "{ext}: {:?}", desc.warnings);
    }
    // Other unknown required extensions only warn.
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!([
        "KHR_materials_variants",
        "KHR_materials_volume",
        "KHR_animation_pointer"
    ]);
    doc["extensionsRequired"] = json!(["KHR_materials_variants", "KHR_materials_volume"]);
    let desc = load(&write_json(&dir, "required.gltf", &doc));
    assert_eq!(desc.warnings.len(), 2, "{:?}", desc.warnings);
    assert!(desc
        .warnings
        .iter()
        .all(|w| !w.contains("KHR_materials_volume")));
    assert_eq!(
        desc.warnings
            .iter()
            .filter(|w| w.contains("KHR_materials_variants"))
            .count(),
        1
    );
    assert_eq!(
        desc.warnings
            .iter()
            .filter(|w| w.contains("KHR_animation_pointer"))
            .count(),
        1
    );
}

#[test]
fn other_bad_files_fail_cleanly() {
    let dir = common::scratch_dir("gltf_other_bad");
    expect_error(&dir.join("absent.gltf"), LoadErrorKind::Io, "");
    let path = dir.join("garbage.gltf");
    std::fs::write(&path, b"{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [").expect("write");
    expect_error(&path, LoadErrorKind::Parse, "JSON");
    // A node hierarchy with a cycle.
    let mut doc = cube_doc();
    doc["nodes"] =
        json!([{"name": "A", "children": [1]}, {"name": "B", "mesh": 0, "children": [0]}]);
    expect_error(
        &write_json(&dir, "cycle.gltf", &doc),
        LoadErrorKind::Parse,
        "cycle",
    );
    // A dangling material index is caught by structural validation.
    let mut doc = cube_doc();
    doc["meshes"][0]["primitives"][0]["material"] = json!(7);
    expect_error(
        &write_json(&dir, "dangling.gltf", &doc),
        LoadErrorKind::IndexOutOfRange,
        "material",
    );
    // An image that is not an image.
    let mut doc = cube_doc();
    doc["images"] = json!([{"uri": data_uri("image/png", b"not a png")}]);
    doc["textures"] = json!([{"source": 0}]);
    doc["materials"][0]["pbrMetallicRoughness"] = json!({"baseColorTexture": {"index": 0}});
    expect_error(
        &write_json(&dir, "bad_image.gltf", &doc),
        LoadErrorKind::MissingBuffer,
        "image 0",
    );
}
