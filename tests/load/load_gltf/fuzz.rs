//! Mutation robustness: byte flips and truncations of a GLB, and hostile JSON values
//! and structural deletions in a .gltf; `read_scene` must return Ok or Err, never panic.

use super::fixtures::*;
use super::{common, load, triangles};
use iris::load::read_scene;
use serde_json::json;

#[test]
fn mutated_glb_never_panics() {
    let dir = common::scratch_dir("gltf_fuzz");
    let mut doc = cube_doc();
    doc["buffers"][0]
        .as_object_mut()
        .expect("buffer")
        .remove("uri");
    doc["images"] = json!([{"uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0}]);
    doc["materials"][0]["extras"] = json!({"cauchy": {"b": 1.5, "c": 0.004}});
    doc["materials"][0]["pbrMetallicRoughness"] = json!({"baseColorTexture": {"index": 0}});
    doc["nodes"][0]["scale"] = json!([-1.0, 1.0, 1.0]);
    let (positions, tris) = cube();
    let base = glb(&doc, &buffer_bytes(&positions, &tris));
    let path = dir.join("fuzz.glb");
    std::fs::write(&path, &base).expect("write");
    assert_eq!(triangles(&load(&path)), 12);

    let mut variants: Vec<Vec<u8>> = Vec::new();
    // Deterministic byte flips over the whole file.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for i in 0..1500usize {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let mut bytes = base.clone();
        let pos = if i < base.len() {
            i
        } else {
            (state as usize) % base.len()
        };
        bytes[pos] = match i % 4 {
            0 => bytes[pos] ^ 0xff,
            1 => bytes[pos].wrapping_add(1),
            2 => b'9',
            _ => (state >> 32) as u8,
        };
        variants.push(bytes);
    }
    // Truncations at many lengths.
    variants.extend((0..base.len()).step_by(7).map(|n| base[..n].to_vec()));

    let (mut ok, mut err) = (0, 0);
    for bytes in &variants {
        std::fs::write(&path, bytes).expect("write");
        match std::panic::catch_unwind(|| read_scene(&path)) {
            Ok(Ok(_)) => ok += 1,
            Ok(Err(_)) => err += 1,
            Err(_) => panic!("read_scene panicked; input kept at {}", path.display()),
        }
    }
    println!("fuzz: {ok} loaded, {err} rejected of {}", variants.len());
    assert!(err > 0 && ok > 0);
}

/// Every number and string of a small but feature-rich document replaced by hostile
/// values (indices, offsets, counts, strides, enum codes …): Ok or Err, never a panic.
#[test]
fn mutated_json_values_never_panic() {
    let dir = common::scratch_dir("gltf_fuzz_json");
    let mut doc = cube_doc();
    doc["images"] = json!([{"uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0, "sampler": 0}]);
    doc["samplers"] = json!([{"magFilter": 9729}]);
    doc["materials"][0]["pbrMetallicRoughness"] = json!({"baseColorTexture": {"index": 0}});
    doc["materials"][0]["extensions"] = json!({"KHR_materials_dispersion": {"dispersion": 1.0},
        "KHR_materials_volume": {"thicknessFactor": 1.0}});
    doc["materials"][0]["extras"] = json!({"cauchy": {"b": 1.5, "c": 0.004}});
    doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "spot", "spot": {"outerConeAngle": 0.5}}]}});
    doc["cameras"] = json!([{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.1}}]);
    doc["nodes"] = json!([
        {"name": "Cube", "mesh": 0, "children": [1]},
        {"camera": 0, "extensions": {"KHR_lights_punctual": {"light": 0}}}
    ]);
    // A sparse accessor overriding one position.
    doc["accessors"][0]["sparse"] = json!({"count": 1,
        "indices": {"bufferView": 1, "componentType": 5125},
        "values": {"bufferView": 0, "byteOffset": 12}});
    assert_eq!(triangles(&load(&write_json(&dir, "base.gltf", &doc))), 12);

    /// Paths to every value (`leaf_only`: only numbers, strings, bools and nulls).
    fn paths(v: &serde_json::Value, at: Vec<String>, leaf_only: bool, out: &mut Vec<Vec<String>>) {
        let children: Vec<(String, &serde_json::Value)> = match v {
            serde_json::Value::Object(map) => map.iter().map(|(k, x)| (k.clone(), x)).collect(),
            serde_json::Value::Array(items) => items
                .iter()
                .enumerate()
                .map(|(i, x)| (i.to_string(), x))
                .collect(),
            _ => Vec::new(),
        };
        if children.is_empty() || !leaf_only {
            out.push(at.clone());
        }
        for (key, child) in children {
            let mut p = at.clone();
            p.push(key);
            paths(child, p, leaf_only, out);
        }
    }
    fn slot<'v>(doc: &'v mut serde_json::Value, at: &[String]) -> &'v mut serde_json::Value {
        at.iter().fold(doc, |v, key| match v {
            serde_json::Value::Array(items) => &mut items[key.parse::<usize>().expect("index")],
            other => &mut other[key.as_str()],
        })
    }
    let mut mutants = Vec::new();
    let mut leaves = Vec::new();
    paths(&doc, Vec::new(), true, &mut leaves);
    let replacements = [
        json!(0),
        json!(1),
        json!(-1),
        json!(3),
        json!(5),
        json!(255),
        json!(4294967295u64),
        json!(1e30),
        json!(0.5),
        json!(""),
        json!("x"),
        json!(null),
        json!([]),
    ];
    for leaf in &leaves {
        for value in &replacements {
            let mut mutant = doc.clone();
            *slot(&mut mutant, leaf) = value.clone();
            mutants.push((format!("{leaf:?} = {value}"), mutant));
        }
    }
    // Structural mutations: every object member removed, every value replaced by `{}`.
    let mut all = Vec::new();
    paths(&doc, Vec::new(), false, &mut all);
    for at in all.iter().filter(|p| !p.is_empty()) {
        let (parent, key) = at.split_at(at.len() - 1);
        let mut mutant = doc.clone();
        if let Some(map) = slot(&mut mutant, parent).as_object_mut() {
            map.remove(&key[0]);
            mutants.push((format!("{at:?} removed"), mutant));
        }
        let mut mutant = doc.clone();
        *slot(&mut mutant, at) = json!({});
        mutants.push((format!("{at:?} = {{}}"), mutant));
    }
    let path = dir.join("mutant.gltf");
    let (mut ok, mut err) = (0, 0);
    for (what, mutant) in &mutants {
        std::fs::write(&path, serde_json::to_vec(mutant).expect("json")).expect("write");
        match std::panic::catch_unwind(|| read_scene(&path)) {
            Ok(Ok(_)) => ok += 1,
            Ok(Err(_)) => err += 1,
            Err(_) => panic!("read_scene panicked with {what}"),
        }
    }
    println!(
        "json fuzz: {ok} loaded, {err} rejected of {}",
        mutants.len()
    );
    assert!(ok > 0 && err > 0);
}
