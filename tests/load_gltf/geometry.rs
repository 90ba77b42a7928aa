//! Geometry: mirrored instances keep outward winding; strips/fans are converted and
//! points/lines skipped with one warning.

use super::fixtures::*;
use super::{common, load};
use glam::{Mat4, Vec3};
use iris::scene::desc::SceneDesc;
use serde_json::json;

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
