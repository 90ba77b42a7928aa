#![allow(dead_code)]
//! Small glTF scenes written by the texture tests: flat quads with TEXCOORD_0 (and
//! optionally TEXCOORD_1), materials given as glTF JSON, one camera, KHR_lights_punctual
//! lights, and textures as sibling PNG files (one texture per image, no sampler: bilinear,
//! repeat, as glTF defaults). The buffer is a sibling `.bin` file.
//!
//! Conventions: positions in metres, right-handed, +Y up; a quad's corners are given
//! counter-clockwise seen from its front (the normal side); texture coordinates are
//! glTF's, (0, 0) at the image's top-left, v down.

use image::RgbaImage;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// One triangle mesh of the scene (one primitive).
pub struct Mesh {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub uv0: Vec<[f32; 2]>,
    /// TEXCOORD_1, when the mesh has a second set.
    pub uv1: Option<Vec<[f32; 2]>>,
    pub indices: Vec<u32>,
    /// Index into [`Doc::materials`].
    pub material: usize,
}

/// A quad with corners `c` (counter-clockwise seen from the front) and texture
/// coordinates `uv` at those corners; the flat normal faces the front.
pub fn quad(c: [[f32; 3]; 4], uv: [[f32; 2]; 4], material: usize) -> Mesh {
    let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let (e1, e2) = (sub(c[1], c[0]), sub(c[2], c[0]));
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let n = n.map(|x| x / len);
    Mesh {
        positions: c.to_vec(),
        normals: vec![n; 4],
        uv0: uv.to_vec(),
        uv1: None,
        indices: vec![0, 1, 2, 0, 2, 3],
        material,
    }
}

/// A scene to write as `.gltf` + `.bin` + PNGs.
pub struct Doc {
    pub meshes: Vec<Mesh>,
    /// glTF material objects; texture `i` is image `i` of [`Doc::images`].
    pub materials: Vec<Value>,
    pub images: Vec<RgbaImage>,
    /// The glTF camera object (`{"type": …, …}`).
    pub camera: Value,
    /// The camera node's `translation` and `rotation` (quaternion x, y, z, w).
    pub camera_at: ([f32; 3], [f32; 4]),
    /// KHR_lights_punctual light objects with their nodes' `translation` and `rotation`.
    pub lights: Vec<(Value, [f32; 3], [f32; 4])>,
}

/// The rotation (x, y, z, w) that turns a camera's or light's −Z to look straight down
/// (−Y), its +Y becoming −Z.
pub const LOOK_DOWN: [f32; 4] = [
    -std::f32::consts::FRAC_1_SQRT_2,
    0.0,
    0.0,
    std::f32::consts::FRAC_1_SQRT_2,
];

/// An orthographic camera seeing `[-half, half]²` of the plane in front of it.
pub fn orthographic(half: f32) -> Value {
    json!({"type": "orthographic",
           "orthographic": {"xmag": half, "ymag": half, "znear": 0.01, "zfar": 100.0}})
}

/// A perspective camera with vertical field of view `yfov` (radians), square aspect.
pub fn perspective(yfov: f32) -> Value {
    json!({"type": "perspective",
           "perspective": {"yfov": yfov, "aspectRatio": 1.0, "znear": 0.01}})
}

/// The document's one binary buffer with its views and accessors.
#[derive(Default)]
struct Buffer {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Buffer {
    /// Appends `bytes` as a new 4-byte-aligned buffer view and the accessor `desc` on it
    /// (its `bufferView` filled in); returns the accessor's index.
    fn accessor(&mut self, bytes: Vec<u8>, mut desc: Value) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.views
            .push(json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()}));
        self.bin.extend_from_slice(&bytes);
        desc["bufferView"] = json!(self.views.len() - 1);
        self.accessors.push(desc);
        self.accessors.len() - 1
    }

    /// An f32 VEC2 or VEC3 accessor.
    fn floats<const K: usize>(&mut self, v: &[[f32; K]], extra: Value) -> usize {
        let bytes = v
            .as_flattened()
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let mut desc = json!({"componentType": 5126, "count": v.len(), "type": format!("VEC{K}")});
        for (k, x) in extra.as_object().into_iter().flatten() {
            desc[k] = x.clone();
        }
        self.accessor(bytes, desc)
    }

    /// The primitive of `m`.
    fn mesh(&mut self, m: &Mesh) -> Value {
        let (lo, hi) = bounds(&m.positions);
        let mut attributes = json!({
            "POSITION": self.floats(&m.positions, json!({"min": lo, "max": hi})),
            "NORMAL": self.floats(&m.normals, json!({})),
            "TEXCOORD_0": self.floats(&m.uv0, json!({})),
        });
        if let Some(uv1) = &m.uv1 {
            attributes["TEXCOORD_1"] = json!(self.floats(uv1, json!({})));
        }
        let indices = m.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let indices = self.accessor(
            indices,
            json!({"componentType": 5125, "count": m.indices.len(), "type": "SCALAR"}),
        );
        json!({"primitives": [{"attributes": attributes, "indices": indices,
                               "material": m.material}]})
    }
}

impl Doc {
    /// Writes `dir/<name>.gltf` (with `<name>.bin` and `<name>_<i>.png`) and returns its
    /// path. `extensionsUsed` lists every extension named in the document.
    pub fn write(&self, dir: &Path, name: &str) -> PathBuf {
        let mut buffer = Buffer::default();
        let meshes: Vec<Value> = self.meshes.iter().map(|m| buffer.mesh(m)).collect();
        let bin_name = format!("{name}.bin");
        std::fs::write(dir.join(&bin_name), &buffer.bin).expect("write buffer");
        let mut images = Vec::new();
        for (i, img) in self.images.iter().enumerate() {
            let file = format!("{name}_{i}.png");
            img.save(dir.join(&file)).expect("write png");
            images.push(json!({"uri": file}));
        }
        let textures: Vec<Value> = (0..self.images.len())
            .map(|i| json!({"source": i}))
            .collect();
        let mut nodes: Vec<Value> = (0..self.meshes.len()).map(|i| json!({"mesh": i})).collect();
        nodes.push(
            json!({"camera": 0, "translation": self.camera_at.0, "rotation": self.camera_at.1}),
        );
        for (i, (_, t, r)) in self.lights.iter().enumerate() {
            nodes.push(json!({"translation": t, "rotation": r,
                              "extensions": {"KHR_lights_punctual": {"light": i}}}));
        }
        let mut doc = json!({
            "asset": {"version": "2.0"},
            "scene": 0,
            "scenes": [{"nodes": (0..nodes.len()).collect::<Vec<_>>()}],
            "nodes": nodes,
            "meshes": meshes,
            "materials": self.materials,
            "cameras": [self.camera],
            "buffers": [{"uri": bin_name, "byteLength": buffer.bin.len()}],
            "bufferViews": buffer.views,
            "accessors": buffer.accessors,
        });
        if !self.images.is_empty() {
            doc["images"] = json!(images);
            doc["textures"] = json!(textures);
        }
        if !self.lights.is_empty() {
            let lights: Vec<&Value> = self.lights.iter().map(|l| &l.0).collect();
            doc["extensions"] = json!({"KHR_lights_punctual": {"lights": lights}});
        }
        let mut used = std::collections::BTreeSet::new();
        extension_names(&doc, &mut used);
        if !used.is_empty() {
            doc["extensionsUsed"] = json!(used);
        }
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, serde_json::to_vec_pretty(&doc).expect("json")).expect("write gltf");
        path
    }
}

fn bounds(p: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for v in p {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    (lo, hi)
}

/// Every key of every `extensions` object in `v`.
fn extension_names(v: &Value, out: &mut std::collections::BTreeSet<String>) {
    match v {
        Value::Object(map) => {
            for (k, x) in map {
                if k == "extensions" {
                    if let Value::Object(e) = x {
                        out.extend(e.keys().cloned());
                    }
                }
                extension_names(x, out);
            }
        }
        Value::Array(a) => a.iter().for_each(|x| extension_names(x, out)),
        _ => {}
    }
}
