//! Compressed and quantized glTF geometry made by real exporters (tests/data/compressed,
//! README there says how each file was made):
//!
//! - KHR_draco_mesh_compression (Blender 5.0.1): the decoded meshes match their
//!   uncompressed twins from the same Blender session triangle for triangle, positions
//!   within one quantization step (`extent / (2^bits − 1)`), normals within the
//!   octahedral step, and the two files render the same image.
//! - EXT_/KHR_meshopt_compression and KHR_mesh_quantization (gltfpack 1.3, glTF-Transform
//!   4.5.1): the world-space geometry (after the node transforms that carry the
//!   dequantization) matches Iris's source asset within the quantization step; the
//!   unquantized gltfpack output (-noq) is the control and matches to float precision.
//! - Hostile variants built here from the good files are clear errors naming the file and
//!   the element, never panics.

use crate::common;

use glam::Vec3;
use iris::accel::Backend;
use iris::camera::Camera;
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::render::RenderSettings;
use iris::scene::desc::{EnvironmentDesc, MeshDesc, SceneDesc};
use iris::scene::Scene;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/compressed")
        .join(name)
}

fn asset(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets")
        .join(rel)
}

fn load(path: &Path) -> SceneDesc {
    iris::load::read_scene(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Largest extent of the axis-aligned box around every mesh of `desc`.
fn extent(desc: &SceneDesc) -> f32 {
    let (lo, hi) = desc
        .meshes
        .iter()
        .flat_map(|m| &m.positions)
        .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    (hi - lo).max_element()
}

/// Corners of every triangle: (position, normal if any).
fn triangles(m: &MeshDesc) -> Vec<[(Vec3, Option<Vec3>); 3]> {
    m.indices
        .iter()
        .map(|t| {
            t.map(|i| {
                let i = i as usize;
                (m.positions[i], m.normals.get(i).copied())
            })
        })
        .collect()
}

/// Asserts that every triangle of `a` has a triangle in `b` (same winding, any rotation)
/// with corners within `pos_tol` and normals within `normal_tol`, and that the counts
/// match. Returns the largest position and normal deviations seen.
fn assert_same_triangles(
    a: &MeshDesc,
    b: &MeshDesc,
    pos_tol: f32,
    normal_tol: f32,
    what: &str,
) -> (f32, f32) {
    assert_eq!(a.indices.len(), b.indices.len(), "{what}: triangle counts");
    let ta = triangles(a);
    let tb = triangles(b);
    let (mut worst_p, mut worst_n) = (0.0f32, 0.0f32);
    for t in &ta {
        let best = tb
            .iter()
            .flat_map(|u| (0..3).map(move |r| [u[r], u[(r + 1) % 3], u[(r + 2) % 3]]))
            .map(|u| {
                let dp = (0..3)
                    .map(|k| (t[k].0 - u[k].0).abs().max_element())
                    .fold(0.0, f32::max);
                let dn = (0..3)
                    .map(|k| match (t[k].1, u[k].1) {
                        (Some(x), Some(y)) => (x - y).abs().max_element(),
                        (None, None) => 0.0,
                        _ => f32::INFINITY,
                    })
                    .fold(0.0, f32::max);
                (dp, dn)
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .expect("a triangle");
        assert!(
            best.0 <= pos_tol && best.1 <= normal_tol,
            "{what}: triangle {t:?} has no match (position off by {}, tolerance {pos_tol}; normal off by {}, tolerance {normal_tol})",
            best.0,
            best.1
        );
        worst_p = worst_p.max(best.0);
        worst_n = worst_n.max(best.1);
    }
    (worst_p, worst_n)
}

/// Meshes of `compressed` against `plain` (matched by name), within the given bits.
fn assert_scene_matches(compressed: &Path, plain: &Path, pos_bits: u32, normal_bits: u32) {
    let c = load(compressed);
    let p = load(plain);
    assert_eq!(c.meshes.len(), p.meshes.len(), "{}", compressed.display());
    // Draco quantizes each primitive over its own box (Blender's exporter: one per mesh).
    let steps = 1.0 / ((1u64 << pos_bits) - 1) as f32;
    // Octahedral normals: one step of 2/(2^bits − 1) per octahedron coordinate moves a
    // unit vector's components by up to about twice that.
    let normal_step = 4.0 / ((1u64 << normal_bits) - 1) as f32;
    for mp in &p.meshes {
        let mc = c
            .meshes
            .iter()
            .find(|m| m.name == mp.name)
            .unwrap_or_else(|| panic!("{}: no mesh {}", compressed.display(), mp.name));
        assert_eq!(mc.material, mp.material, "{}: material", mp.name);
        let step = extent(&SceneDesc {
            meshes: vec![mp.clone()],
            ..SceneDesc::default()
        }) * steps;
        let (dp, dn) = assert_same_triangles(mc, mp, step, normal_step, &mp.name);
        eprintln!(
            "{} {}: position off by {dp:.3e} (step {step:.3e}), normal by {dn:.3e} (step {normal_step:.3e})",
            compressed.display(),
            mp.name
        );
    }
}

#[test]
fn blender_draco_exports_match_their_uncompressed_twins() {
    // Blender's defaults: position 14 bits, normal 10; the q20 file: 20 and 16.
    let diamond = data("round_diamond_blender.glb");
    assert_scene_matches(&data("round_diamond_draco.glb"), &diamond, 14, 10);
    assert_scene_matches(&data("round_diamond_draco_q20.glb"), &diamond, 20, 16);
    // The glass decodes to a few more points than its accessors declare (see
    // src/load/gltf/draco.rs), with a warning; the triangles are the same.
    let glass = data("glass_of_water_draco.glb");
    assert_scene_matches(&glass, &data("glass_of_water_blender.glb"), 14, 10);
    let warnings = load(&glass).warnings.join("\n");
    assert!(
        warnings.contains("Draco decoding produced more points"),
        "{warnings}"
    );
}

/// The file's own scene (lights, camera, environment) at 96×72, Whitted, 16 spp.
fn render(file: &Path, seed: u64) -> Vec<Vec3> {
    const W: u32 = 96;
    const H: u32 = 72;
    let desc = iris::load::load_scene(file).expect("load");
    let cam = desc.cameras.first().expect("a camera").clone();
    let env = match desc.environment {
        Some(EnvironmentDesc::Uniform(radiance)) => {
            Some(iris::light::env::Environment::Uniform { radiance })
        }
        _ => None,
    };
    let scene = Scene::build(
        SceneDesc {
            environment_light: env,
            ..desc
        },
        Backend::Auto,
    )
    .expect("build");
    let settings = RenderSettings::quiet_rgb((W, H), 16, seed, 2);
    let integrator =
        Integrator::new(Method::Whitted, 64, &PhotonSettings::default()).expect("whitted");
    let (img, stats) = integrator
        .render(&scene, &Camera::new(&cam, W, H), &settings)
        .expect("render");
    assert_eq!(stats.bad_samples, 0);
    img.data
}

fn mean_abs_diff(a: &[Vec3], b: &[Vec3]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| f64::from((*x - *y).abs().element_sum()) / 3.0)
        .sum();
    sum / a.len() as f64
}

/// The "done when": a Blender export with Draco renders the same image as the
/// uncompressed file. Same seed: the only difference left is the geometry, which moved by
/// at most one quantization step, so the images must differ by much less than the
/// Monte Carlo noise (the same file under two seeds). Bound: that noise. (A diamond is chaotic: a ray near a facet edge that moved by a
/// quantization step takes another path, so those pixels differ as under another seed;
/// a missing or misplaced triangle would raise the difference far above the noise.)
#[test]
fn draco_and_plain_exports_render_the_same_image() {
    for (draco, plain) in [
        ("round_diamond_draco.glb", "round_diamond_blender.glb"),
        ("glass_of_water_draco.glb", "glass_of_water_blender.glb"),
    ] {
        let a = render(&data(plain), 1);
        let noise = mean_abs_diff(&a, &render(&data(plain), 2));
        let diff = mean_abs_diff(&a, &render(&data(draco), 1));
        let mean = a
            .iter()
            .map(|c| f64::from(c.element_sum()) / 3.0)
            .sum::<f64>()
            / a.len() as f64;
        eprintln!("{draco}: mean {mean:.4}, seed noise {noise:.5}, Draco vs plain {diff:.5}");
        assert!(mean > 0.0 && noise > 0.0, "{plain}: a lit, noisy image");
        assert!(diff < noise, "{draco}: differs by {diff} (noise {noise})");
    }
}

#[test]
fn meshopt_and_quantized_files_match_the_source_asset() {
    let diamond = asset("gems/round_diamond.glb");
    // The unquantized control: float precision (gltfpack only reorders).
    assert_scene_matches_source(&data("round_diamond_gltfpack_noq.glb"), &diamond, 22);
    for file in [
        "round_diamond_gltfpack_q.glb",
        "round_diamond_gltfpack_c.glb",
        "round_diamond_gltfpack_cc.glb",
        "round_diamond_gltfpack_cc_vpf.glb",
        "round_diamond_gltfpack_c_khr.glb",
        "round_diamond_transform_meshopt.glb",
        "round_diamond_transform_quantize.glb",
    ] {
        assert_scene_matches_source(&data(file), &diamond, 14);
    }
    assert_scene_matches_source(
        &data("glass_of_water_gltfpack_cc.glb"),
        &asset("scenes/glass_of_water.glb"),
        14,
    );
}

/// Like [`assert_scene_matches`], but meshes are matched by node order (gltfpack drops
/// mesh names) and normals within 8-bit steps (gltfpack's default).
fn assert_scene_matches_source(file: &Path, source: &Path, pos_bits: u32) {
    let c = load(file);
    let s = load(source);
    assert_eq!(c.meshes.len(), s.meshes.len(), "{}", file.display());
    let meshopt =
        file.to_string_lossy().contains("_c") || file.to_string_lossy().contains("meshopt");
    assert_eq!(
        c.compressed.meshopt_views > 0,
        meshopt,
        "{}",
        file.display()
    );
    let step = extent(&s) / ((1u64 << pos_bits) - 1) as f32;
    let normal_step = 4.0 / 127.0;
    // Material labels are `material N "name"`; exporters may renumber, so compare names.
    let material = |d: &SceneDesc, m: &MeshDesc| {
        m.material.map(|i| {
            let label = &d.materials[i].name;
            label[label.find('"').unwrap_or(0)..].to_string()
        })
    };
    for (mc, ms) in c.meshes.iter().zip(&s.meshes) {
        assert_eq!(material(&c, mc), material(&s, ms), "{}: material", ms.name);
        let (dp, dn) = assert_same_triangles(mc, ms, step, normal_step, &ms.name);
        eprintln!(
            "{} {}: position off by {dp:.3e} (step {step:.3e}), normal by {dn:.3e}",
            file.display(),
            ms.name
        );
    }
}

// ---------------------------------------------------------------------------------------
// Hostile variants.

/// A GLB split into its JSON and binary chunk.
fn read_glb(path: &Path) -> (Value, Vec<u8>) {
    let b = std::fs::read(path).expect("read");
    let jl = u32::from_le_bytes(b[12..16].try_into().unwrap()) as usize;
    let json = serde_json::from_slice(&b[20..20 + jl]).expect("json");
    (json, b[20 + jl + 8..].to_vec())
}

/// Writes a GLB with `json` and `bin`.
fn write_glb(path: &Path, json: &Value, bin: &[u8]) {
    std::fs::write(path, common::glb(json, bin)).expect("write");
}

/// Loads `source` edited by `edit`; asserts an error whose message names the file and
/// contains every string of `expect`.
fn assert_hostile(source: &str, name: &str, edit: impl Fn(&mut Value), expect: &[&str]) {
    let (mut json, bin) = read_glb(&data(source));
    edit(&mut json);
    let path = common::scratch_dir(&format!("load_compressed_{name}")).join(format!("{name}.glb"));
    write_glb(&path, &json, &bin);
    let err = match iris::load::read_scene(&path) {
        Ok(_) => panic!("{name}: loaded"),
        Err(e) => e.to_string(),
    };
    assert!(err.contains(&format!("{name}.glb")), "{name}: {err}");
    for e in expect {
        assert!(err.contains(e), "{name}: {err:?} lacks {e:?}");
    }
    eprintln!("{name}: {err}");
}

fn draco_ext(json: &mut Value) -> &mut Value {
    &mut json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
}

#[test]
fn hostile_draco_files_are_clear_errors() {
    let src = "round_diamond_draco.glb";
    let prim = "mesh 0 \"Round brilliant diamond\" primitive 0";
    assert_hostile(
        src,
        "draco_truncated",
        |j| {
            let view = draco_ext(j)["bufferView"].as_u64().unwrap() as usize;
            let len = j["bufferViews"][view]["byteLength"].as_u64().unwrap();
            j["bufferViews"][view]["byteLength"] = (len / 2).into();
        },
        &[prim, "KHR_draco_mesh_compression"],
    );
    assert_hostile(
        src,
        "draco_wrong_id",
        |j| draco_ext(j)["attributes"]["POSITION"] = 99.into(),
        &[prim, "Draco attribute 99"],
    );
    assert_hostile(
        src,
        "draco_count_mismatch",
        |j| {
            let acc = j["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
                .as_u64()
                .unwrap() as usize;
            let n = j["accessors"][acc]["count"].as_u64().unwrap();
            j["accessors"][acc]["count"] = (n + 5).into();
        },
        &[prim, "POSITION"],
    );
    assert_hostile(
        src,
        "draco_index_count_mismatch",
        |j| {
            let acc = j["meshes"][0]["primitives"][0]["indices"].as_u64().unwrap() as usize;
            j["accessors"][acc]["count"] = 3.into();
        },
        &[prim, "KHR_draco_mesh_compression"],
    );
    assert_hostile(
        src,
        "draco_huge_count",
        |j| {
            let acc = j["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
                .as_u64()
                .unwrap() as usize;
            j["accessors"][acc]["count"] = 4_000_000_000u64.into();
        },
        &[prim, "compressed bytes"],
    );
}

/// The first meshopt-compressed view of `mode` in `json`.
fn meshopt_view(json: &Value, mode: &str) -> usize {
    json["bufferViews"]
        .as_array()
        .unwrap()
        .iter()
        .position(|v| v["extensions"]["EXT_meshopt_compression"]["mode"] == mode)
        .expect("a compressed view")
}

#[test]
fn hostile_meshopt_files_are_clear_errors() {
    let src = "round_diamond_gltfpack_c.glb";
    let set = |mode: &'static str, key: &'static str, value: Value| {
        move |j: &mut Value| {
            let v = meshopt_view(j, mode);
            j["bufferViews"][v]["extensions"]["EXT_meshopt_compression"][key] = value.clone();
        }
    };
    assert_hostile(
        src,
        "meshopt_stride_3",
        set("ATTRIBUTES", "byteStride", 3.into()),
        &["buffer view", "byteStride 3"],
    );
    assert_hostile(
        src,
        "meshopt_stride_300",
        set("ATTRIBUTES", "byteStride", 300.into()),
        &["buffer view", "byteStride 300"],
    );
    assert_hostile(
        src,
        "meshopt_count_overflow",
        set("ATTRIBUTES", "count", u64::MAX.into()),
        &["buffer view", "count"],
    );
    assert_hostile(
        src,
        "meshopt_triangles_not_multiple_of_3",
        set("TRIANGLES", "count", 4.into()),
        &["buffer view", "multiple of 3"],
    );
    assert_hostile(
        src,
        "meshopt_mode",
        set("ATTRIBUTES", "mode", "POINTS".into()),
        &["buffer view", "unknown mode"],
    );
    assert_hostile(
        src,
        "meshopt_filter",
        set("ATTRIBUTES", "filter", "SQUARE".into()),
        &["buffer view", "unknown filter"],
    );
    assert_hostile(
        src,
        "meshopt_corrupt",
        set("ATTRIBUTES", "byteLength", 8.into()),
        &["buffer view", "corrupt"],
    );
    assert_hostile(
        src,
        "meshopt_fallback_without_data",
        |j| {
            let v = meshopt_view(j, "TRIANGLES");
            j["bufferViews"][v]
                .as_object_mut()
                .unwrap()
                .remove("extensions");
        },
        &["fallback buffer"],
    );
}
