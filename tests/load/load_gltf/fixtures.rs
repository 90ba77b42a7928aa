//! Small glTF documents written by the tests: a closed unit cube (CCW, outward normals)
//! as JSON with a data-URI or external buffer, or as GLB. Positions are f32 VEC3, indices
//! u32 SCALAR, one material "Glass" with room for extras and extensions.

use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// A closed cube on [-1,1]^3: 8 vertices, 12 counter-clockwise (outward) triangles.
pub fn cube() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let positions: Vec<[f32; 3]> = (0..8u32)
        .map(|i| {
            let s = |bit: u32| if i & bit != 0 { 1.0 } else { -1.0 };
            [s(1), s(2), s(4)]
        })
        .collect();
    // Each face: the 4 corners with coordinate `axis` equal to `sign`, in cyclic order.
    let mut triangles = Vec::new();
    for axis in 0..3usize {
        for sign in [-1.0f32, 1.0] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let corner = |cu: f32, cv: f32| -> u32 {
                let mut p = [0.0f32; 3];
                p[axis] = sign;
                p[u] = cu;
                p[v] = cv;
                let bit = |c: f32, b: u32| if c > 0.0 { b } else { 0 };
                bit(p[0], 1) | bit(p[1], 2) | bit(p[2], 4)
            };
            // (u,v) order is right-handed with `axis`, so this quad is CCW seen from +axis.
            let mut quad = [
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ];
            if sign < 0.0 {
                quad.reverse();
            }
            triangles.push([quad[0], quad[1], quad[2]]);
            triangles.push([quad[0], quad[2], quad[3]]);
        }
    }
    (positions, triangles)
}

/// The same cube mirrored in x, written directly: x negated and winding reversed so it
/// stays CCW seen from outside.
pub fn mirrored_cube() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let (positions, triangles) = cube();
    let positions = positions.into_iter().map(|[x, y, z]| [-x, y, z]).collect();
    let triangles = triangles.into_iter().map(|[a, b, c]| [a, c, b]).collect();
    (positions, triangles)
}

/// Binary buffer: positions (f32) then indices (u32).
pub fn buffer_bytes(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> Vec<u8> {
    let mut bin = Vec::new();
    for v in positions.iter().flatten() {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    for i in triangles.iter().flatten() {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    bin
}

/// A document for the mesh with a buffer of `bin_len` bytes and no `uri` yet.
pub fn mesh_doc(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> (Value, Vec<u8>) {
    let bin = buffer_bytes(positions, triangles);
    let pos_len = positions.len() * 12;
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "Cube", "mesh": 0}],
        "meshes": [{"name": "CubeMesh", "primitives": [
            {"attributes": {"POSITION": 0}, "indices": 1, "material": 0}
        ]}],
        "materials": [{"name": "Glass"}],
        "buffers": [{"name": "geometry", "byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": pos_len},
            {"buffer": 0, "byteOffset": pos_len, "byteLength": bin.len() - pos_len}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": positions.len(), "type": "VEC3",
             "min": [-1.0, -1.0, -1.0], "max": [1.0, 1.0, 1.0]},
            {"bufferView": 1, "componentType": 5125, "count": triangles.len() * 3, "type": "SCALAR"}
        ]
    });
    (doc, bin)
}

/// The cube document with its buffer embedded as a base64 data URI.
pub fn cube_doc() -> Value {
    let (positions, triangles) = cube();
    let (mut doc, bin) = mesh_doc(&positions, &triangles);
    doc["buffers"][0]["uri"] = json!(data_uri("application/octet-stream", &bin));
    doc
}

/// `data:<mime>;base64,<payload>`.
pub fn data_uri(mime: &str, bytes: &[u8]) -> String {
    format!("data:{mime};base64,{}", base64(bytes))
}

/// Standard base64 with padding (RFC 4648 §4).
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

pub use super::common::glb;

/// The cube as a GLB (buffer 0 = BIN chunk).
pub fn cube_glb() -> Vec<u8> {
    let (positions, triangles) = cube();
    let (doc, bin) = mesh_doc(&positions, &triangles);
    glb(&doc, &bin)
}

/// Writes `doc` as `dir/name` and returns the path.
pub fn write_json(dir: &Path, name: &str, doc: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec_pretty(doc).expect("serialize")).expect("write gltf");
    path
}

/// A tiny RGBA PNG (2×2) encoded with the `image` crate.
pub fn png_2x2() -> Vec<u8> {
    let img = image::RgbaImage::from_raw(
        2,
        2,
        vec![255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 128],
    )
    .expect("2x2 image");
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .expect("encode png");
    out.into_inner()
}
