//! The stone's facet planes from the .glb `iris gem --bare` writes.
//!
//! `iris gem` writes every facet with its own vertices and its (flat) normal, and the
//! stone is convex (src/authoring/gem.rs checks it), so its facet planes are exactly the
//! distinct vertex normals, each at the offset of its vertices. indicatrix renders a
//! stone as the intersection of half-spaces `n . x + d <= 0`, so handing it these planes
//! gives it the very solid Iris renders (to f32 rounding), not an approximation.

use glam::{DVec3, Vec3};
use indicatrix::geometry::GpuFacetPlane;
use serde_json::Value;

/// The planes, scaled so that the girdle radius is 1 (indicatrix's convention: its cameras
/// and standard cuts are in girdle radii), and the girdle radius in the file's units.
pub struct StonePlanes {
    pub planes: Vec<GpuFacetPlane>,
    /// Girdle radius of the file, in its units (metres for `iris gem`).
    pub radius: f64,
    /// Largest distance of any vertex outside any plane, in girdle radii (convexity check).
    pub worst_outside: f64,
    /// Table height and culet depth below the girdle plane (y = 0), in girdle radii.
    pub y_max: f64,
    pub y_min: f64,
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

fn f32_at(b: &[u8], at: usize) -> f32 {
    f32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

/// Reads accessor `index` as a list of VEC3 f32 values.
fn vec3s(json: &Value, bin: &[u8], index: usize) -> Vec<Vec3> {
    let acc = &json["accessors"][index];
    assert_eq!(acc["componentType"], 5126, "accessor {index} is not f32");
    assert_eq!(acc["type"], "VEC3", "accessor {index} is not VEC3");
    let count = acc["count"].as_u64().unwrap() as usize;
    let view = &json["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    let base = view["byteOffset"].as_u64().unwrap_or(0) as usize
        + acc["byteOffset"].as_u64().unwrap_or(0) as usize;
    let stride = view["byteStride"].as_u64().unwrap_or(12) as usize;
    (0..count)
        .map(|i| {
            let at = base + i * stride;
            Vec3::new(f32_at(bin, at), f32_at(bin, at + 4), f32_at(bin, at + 8))
        })
        .collect()
}

pub fn read_planes(path: &str) -> StonePlanes {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("reading {path}: {e}"));
    assert_eq!(&bytes[0..4], b"glTF", "{path} is not a .glb");
    let json_len = u32_at(&bytes, 12) as usize;
    assert_eq!(&bytes[16..20], b"JSON");
    let json: Value = serde_json::from_slice(&bytes[20..20 + json_len]).expect("glb JSON");
    let bin_at = 20 + json_len;
    assert_eq!(&bytes[bin_at + 4..bin_at + 8], b"BIN\0");
    let bin = &bytes[bin_at + 8..];
    // `iris gem --bare`: one node, no transform, one primitive.
    let node = &json["nodes"][0];
    assert!(
        node.get("matrix").is_none()
            && node.get("translation").is_none()
            && node.get("rotation").is_none()
            && node.get("scale").is_none(),
        "expected an untransformed node (iris gem --bare)"
    );
    let prim = &json["meshes"][0]["primitives"][0];
    let positions = vec3s(&json, bin, prim["attributes"]["POSITION"].as_u64().unwrap() as usize);
    let normals = vec3s(&json, bin, prim["attributes"]["NORMAL"].as_u64().unwrap() as usize);

    let radius = positions
        .iter()
        .map(|p| f64::from(p.x).hypot(f64::from(p.z)))
        .fold(0.0, f64::max);
    // Group vertices by their (bit-identical) facet normal.
    let mut facets: Vec<([u32; 3], Vec<DVec3>)> = Vec::new();
    for (p, n) in positions.iter().zip(&normals) {
        let key = n.to_array().map(f32::to_bits);
        let p = p.as_dvec3() / radius;
        match facets.iter_mut().find(|(k, _)| *k == key) {
            Some((_, ps)) => ps.push(p),
            None => facets.push((key, vec![p])),
        }
    }
    let mut planes = Vec::with_capacity(facets.len());
    let mut unit_normals = Vec::with_capacity(facets.len());
    for (key, ps) in &facets {
        let n = Vec3::from_array(key.map(f32::from_bits)).as_dvec3().normalize();
        let m = ps.iter().map(|p| n.dot(*p)).sum::<f64>() / ps.len() as f64;
        assert!(m > 0.0, "the origin must be inside the stone");
        unit_normals.push((n, m));
        planes.push(GpuFacetPlane::new(n.as_vec3(), -m as f32));
    }
    let worst_outside = positions
        .iter()
        .map(|p| {
            let p = p.as_dvec3() / radius;
            unit_normals
                .iter()
                .map(|(n, m)| n.dot(p) - m)
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .fold(f64::NEG_INFINITY, f64::max);
    let y_max = positions.iter().map(|p| f64::from(p.y)).fold(f64::MIN, f64::max) / radius;
    let y_min = positions.iter().map(|p| f64::from(p.y)).fold(f64::MAX, f64::min) / radius;
    StonePlanes {
        planes,
        radius,
        worst_outside,
        y_max,
        y_min,
    }
}
