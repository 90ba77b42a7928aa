//! Geometry: mirrored instances keep outward winding; strips/fans are converted and
//! points/lines skipped with one warning.

use super::fixtures::*;
use super::{common, load};
use glam::{Mat4, Vec3};
use iris::scene::desc::SceneDesc;
use serde_json::json;
use std::path::Path;

/// Triangles as position triples, rotated to start at the smallest vertex (keeping the
/// cyclic order, i.e. the winding), then sorted.
fn triangle_set(desc: &SceneDesc) -> Vec<[[i32; 3]; 3]> {
    let key = |p: Vec3| {
        [
            (p.x * 1000.0).round() as i32,
            (p.y * 1000.0).round() as i32,
            (p.z * 1000.0).round() as i32,
        ]
    };
    let mut out: Vec<[[i32; 3]; 3]> = desc
        .meshes
        .iter()
        .flat_map(|m| {
            m.indices
                .iter()
                .map(move |t| t.map(|i| key(m.positions[i as usize])))
        })
        .map(|t| {
            let start = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
            [t[start], t[(start + 1) % 3], t[(start + 2) % 3]]
        })
        .collect();
    out.sort();
    out
}

fn assert_outward(desc: &SceneDesc) {
    for mesh in &desc.meshes {
        let n = mesh.positions.len() as f32;
        let centroid = mesh.positions.iter().copied().sum::<Vec3>() / n;
        for t in &mesh.indices {
            let [p0, p1, p2] = t.map(|i| mesh.positions[i as usize]);
            let ng = (p1 - p0).cross(p2 - p0);
            assert!(
                ng.dot((p0 + p1 + p2) / 3.0 - centroid) > 0.0,
                "{}: {t:?} faces inward",
                mesh.name
            );
        }
    }
}

#[test]
fn mirrored_node_keeps_outward_winding() {
    let dir = common::scratch_dir("gltf_mirror");
    let plain = load(&write_json(&dir, "plain.gltf", &cube_doc()));
    assert_outward(&plain);

    let mut doc = cube_doc();
    doc["nodes"][0]["scale"] = json!([-1.0, 1.0, 1.0]);
    let mirrored = load(&write_json(&dir, "mirrored.gltf", &doc));
    assert_outward(&mirrored);

    let (positions, tris) = mirrored_cube();
    let (mut doc, bin) = mesh_doc(&positions, &tris);
    doc["buffers"][0]["uri"] = json!(data_uri("application/octet-stream", &bin));
    let direct = load(&write_json(&dir, "direct.gltf", &doc));
    assert_outward(&direct);
    assert_eq!(triangle_set(&mirrored), triangle_set(&direct));

    // The same through a parent node with a mirroring matrix, plus translation.
    let mut doc = cube_doc();
    doc["scenes"][0]["nodes"] = json!([1]);
    let m = Mat4::from_translation(Vec3::new(5.0, 0.0, 0.0))
        * Mat4::from_scale(Vec3::new(1.0, 1.0, -2.0));
    doc["nodes"]
        .as_array_mut()
        .expect("nodes")
        .push(json!({"name": "Mirror", "matrix": m.to_cols_array(), "children": [0]}));
    let nested = load(&write_json(&dir, "nested.gltf", &doc));
    assert_outward(&nested);
    assert!(nested.meshes[0]
        .name
        .starts_with("node 0 \"Cube\" mesh 0 \"CubeMesh\" primitive 0"));
    assert!((nested.meshes[0].positions[7] - Vec3::new(6.0, 1.0, -2.0)).length() < 1e-6);
}

#[test]
fn strips_fans_and_skipped_modes() {
    let dir = common::scratch_dir("gltf_modes");
    let mut doc = cube_doc();
    let prim = doc["meshes"][0]["primitives"][0].clone();
    let mut strip = prim.clone();
    strip["mode"] = json!(5);
    let mut fan = prim.clone();
    fan["mode"] = json!(6);
    let mut lines = prim.clone();
    lines["mode"] = json!(1);
    let mut points = prim.clone();
    points["mode"] = json!(0);
    let mut no_position = prim;
    no_position["attributes"] = json!({});
    doc["meshes"][0]["primitives"] = json!([strip, fan, lines, points, no_position]);
    let desc = load(&write_json(&dir, "modes.gltf", &doc));
    assert_eq!(desc.meshes.len(), 2);
    assert!(desc.meshes.iter().all(|m| !m.indices.is_empty()));
    let skipped: Vec<_> = desc
        .warnings
        .iter()
        .filter(|w| w.contains("points or lines"))
        .collect();
    assert_eq!(skipped.len(), 1, "{:?}", desc.warnings);
    assert_eq!(desc.warnings.len(), 2, "{:?}", desc.warnings);
    assert!(desc
        .warnings
        .iter()
        .any(|w| w.contains("POSITION") && w.contains("primitive 4")));
    assert!(
        skipped[0].contains("primitive 2 (LINES)") && skipped[0].contains("primitive 3 (POINTS)")
    );
}

/// EXT_mesh_gpu_instancing: the node's mesh is placed once per instance at
/// node · T · R · S (a mirroring scale keeps outward winding); children are not instanced;
/// mismatched counts and bad rotations are errors naming the node.
#[test]
fn gpu_instancing_places_each_instance() {
    let dir = common::scratch_dir("gltf_instancing");
    let (positions, triangles) = cube();
    let (mut doc, mut bin) = mesh_doc(&positions, &triangles);
    let translations: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [5.0, 0.0, 0.0], [0.0, 7.0, 0.0]];
    // Instance 2 is turned a quarter about +Z; instance 1 is mirrored in x.
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let rotations: [[f32; 4]; 3] = [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 1.0], [0.0, 0.0, h, h]];
    let scales: [[f32; 3]; 3] = [[1.0, 1.0, 1.0], [-1.0, 1.0, 1.0], [2.0, 1.0, 1.0]];
    let mut add_view = |doc: &mut serde_json::Value, floats: Vec<f32>, ty: &str| {
        let offset = bin.len();
        for f in &floats {
            bin.extend_from_slice(&f.to_le_bytes());
        }
        let views = doc["bufferViews"].as_array_mut().unwrap();
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": floats.len() * 4}));
        let view = views.len() - 1;
        let accs = doc["accessors"].as_array_mut().unwrap();
        accs.push(json!({"bufferView": view, "componentType": 5126, "count": 3, "type": ty}));
        accs.len() - 1
    };
    let t = add_view(
        &mut doc,
        translations.iter().flatten().copied().collect(),
        "VEC3",
    );
    let r = add_view(
        &mut doc,
        rotations.iter().flatten().copied().collect(),
        "VEC4",
    );
    let s = add_view(&mut doc, scales.iter().flatten().copied().collect(), "VEC3");
    doc["buffers"][0]["byteLength"] = json!(bin.len());
    doc["buffers"][0]["uri"] = json!(data_uri("application/octet-stream", &bin));
    doc["extensionsUsed"] = json!(["EXT_mesh_gpu_instancing"]);
    doc["extensionsRequired"] = json!(["EXT_mesh_gpu_instancing"]);
    doc["nodes"] = json!([
        {"name": "Cube", "mesh": 0, "translation": [0.0, 0.0, 10.0], "children": [1],
         "extensions": {"EXT_mesh_gpu_instancing": {"attributes":
            {"TRANSLATION": t, "ROTATION": r, "SCALE": s}}}},
        {"name": "Child", "mesh": 0, "translation": [0.0, 0.0, 20.0]}
    ]);
    let desc = load(&write_json(&dir, "instanced.gltf", &doc));
    assert!(desc.warnings.is_empty(), "{:?}", desc.warnings);
    // Three instances plus the child, which is not instanced.
    assert_eq!(
        desc.meshes.len(),
        4,
        "{:?}",
        desc.meshes.iter().map(|m| &m.name).collect::<Vec<_>>()
    );
    assert!(
        desc.meshes[1].name.ends_with("instance 1"),
        "{}",
        desc.meshes[1].name
    );
    let centroid = |m: &iris::scene::desc::MeshDesc| {
        m.positions.iter().copied().sum::<Vec3>() / m.positions.len() as f32
    };
    let expect = [
        Vec3::new(0.0, 0.0, 10.0),
        Vec3::new(5.0, 0.0, 10.0),
        Vec3::new(0.0, 7.0, 10.0),
        // The child sits under the node itself (10 + 20), once.
        Vec3::new(0.0, 0.0, 30.0),
    ];
    for (m, e) in desc.meshes.iter().zip(expect) {
        assert!(
            (centroid(m) - e).length() < 1e-4,
            "{}: {} vs {e}",
            m.name,
            centroid(m)
        );
    }
    // Instance 2: scale 2 along x, then the quarter turn maps x to y: extent 4 in y.
    let ys: Vec<f32> = desc.meshes[2].positions.iter().map(|p| p.y).collect();
    let extent =
        ys.iter().cloned().fold(f32::MIN, f32::max) - ys.iter().cloned().fold(f32::MAX, f32::min);
    assert!((extent - 4.0).abs() < 1e-4, "{extent}");
    assert_outward(&desc);

    // Mismatched counts and a zero quaternion are errors naming the node.
    let mut bad = doc.clone();
    bad["accessors"][s]["count"] = json!(2);
    let err = iris::load::load_scene(&write_json(&dir, "counts.gltf", &bad))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("node 0 \"Cube\"") && err.contains("counts"),
        "{err}"
    );
    let mut bad = doc.clone();
    bad["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["ROTATION"] = json!(99);
    let err = iris::load::load_scene(&write_json(&dir, "index.gltf", &bad))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("node 0 \"Cube\"") && err.contains("accessor 99"),
        "{err}"
    );
}

/// A real exporter's EXT_mesh_gpu_instancing file (Blender 5.0.1, tests/data/instancing)
/// loads to the same world-space triangles as the same scene exported without it.
#[test]
fn blender_gpu_instances_match_the_plain_export() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/instancing");
    let instanced = load(&dir.join("spheres_instanced.glb"));
    let plain = load(&dir.join("spheres_plain.glb"));
    assert_eq!(instanced.meshes.len(), 5);
    assert_eq!(plain.meshes.len(), 5);
    // Triangles as sorted vertex triples, compared within 1e-5 m (float export round-off).
    let triangles = |d: &SceneDesc| {
        let mut t: Vec<[f32; 9]> = d
            .meshes
            .iter()
            .flat_map(|m| {
                m.indices.iter().map(move |t| {
                    let mut v = t.map(|i| m.positions[i as usize].to_array());
                    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
                    [v[0], v[1], v[2]].concat().try_into().unwrap()
                })
            })
            .collect();
        t.sort_by(|a, b| a.partial_cmp(b).unwrap());
        t
    };
    let (a, b) = (triangles(&instanced), triangles(&plain));
    assert_eq!(a.len(), b.len());
    let worst = a
        .iter()
        .zip(&b)
        .flat_map(|(x, y)| x.iter().zip(y).map(|(p, q)| (p - q).abs()))
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-5, "largest vertex difference {worst} m");
    assert_outward(&instanced);
}
