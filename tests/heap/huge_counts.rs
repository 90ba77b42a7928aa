//! Huge declared counts (issue 7, "Huge counts"): files that *declare* far more data than
//! they hold, or than Iris will allocate, must end in a clear error naming the file and
//! the element, before anything of that size is allocated.
//!
//! Library cases load files written to a scratch dir through `iris::load::load_scene` (the
//! path every render takes) under a counting global allocator, and assert the peak heap
//! growth while loading stays under [`PEAK_LIMIT`]. CLI cases run `iris render` and assert
//! a non-zero exit, the element in stderr, and no output file.

use iris::LoadErrorKind;
use serde_json::json;
use std::path::Path;

use crate::common;

/// Most heap a rejected file may make the loader allocate: generous next to the few KiB
/// these files hold, and far below the GiBs their counts declare (2^31 VEC3 floats would
/// be 24 GiB; a 10⁵ × 10⁵ RGBA8 image 40 GB).
const PEAK_LIMIT: usize = 64 << 20;

/// Serialises the tests that count heap bytes so that one test's allocations do not show
/// up in another's peak.
use crate::common::alloc::SERIAL;

/// Runs `f`, returning its result and the peak heap growth while it ran.
fn peak_during<R>(f: impl FnOnce() -> R) -> (R, usize) {
    let base = common::alloc::start_peak();
    let r = f();
    let peak = common::alloc::peak_growth(base);
    (r, peak)
}

/// Loads `path` and asserts: an error of `kind`, whose text names the file and contains
/// each of `needles`, with peak heap growth below [`PEAK_LIMIT`].
fn assert_rejected(path: &Path, kind: LoadErrorKind, needles: &[&str]) {
    let (result, peak) = peak_during(|| iris::load::load_scene(path));
    let err = match result {
        Ok(_) => panic!("{} loaded, expected a {kind:?} error", path.display()),
        Err(e) => e,
    };
    let text = err.to_string();
    assert_eq!(err.kind, kind, "{text}");
    assert_eq!(err.file, path, "{text}");
    for n in needles {
        assert!(text.contains(n), "{text:?} does not name {n:?}");
    }
    assert!(
        peak < PEAK_LIMIT,
        "{}: peak heap {peak} bytes while rejecting ({text})",
        path.display()
    );
}

fn data_uri(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::from("data:application/octet-stream;base64,");
    for c in bytes.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// A one-triangle glTF (3 float positions, 3 u16 indices in a 44-byte buffer); `edit`
/// then changes the JSON to declare something absurd.
fn triangle_gltf(edit: impl FnOnce(&mut serde_json::Value)) -> serde_json::Value {
    let mut buf = Vec::new();
    for v in [0f32, 0., 0., 1., 0., 0., 0., 1., 0.] {
        buf.extend_from_slice(&v.to_le_bytes());
    }
    for i in [0u16, 1, 2, 0] {
        buf.extend_from_slice(&i.to_le_bytes());
    }
    let mut doc = json!({
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}], "scene": 0,
        "nodes": [{"mesh": 0}],
        "meshes": [{"name": "Gem", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6}
        ],
        "buffers": [{"byteLength": buf.len(), "uri": data_uri(&buf)}]
    });
    edit(&mut doc);
    doc
}

fn write_gltf(dir: &Path, name: &str, doc: &serde_json::Value) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec(doc).unwrap()).unwrap();
    path
}

/// A PNG made of the signature and an IHDR chunk declaring `w`×`h` RGBA8 pixels, with a
/// correct CRC (PNG spec §5.5) and one empty IDAT: a valid header, no pixel data.
fn png_header(w: u32, h: u32) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }
    fn chunk(out: &mut Vec<u8>, ty: &[u8; 4], data: &[u8]) {
        out.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let mut body = ty.to_vec();
        body.extend_from_slice(data);
        out.extend_from_slice(&body);
        out.extend_from_slice(&crc32(&body).to_be_bytes());
    }
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 6, 0, 0, 0]); // 8-bit RGBA, deflate, no filter, no interlace
    chunk(&mut out, b"IHDR", &ihdr);
    chunk(&mut out, b"IDAT", &[]);
    chunk(&mut out, b"IEND", &[]);
    out
}

#[test]
fn gltf_declaring_huge_counts_is_rejected_before_allocating() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = common::scratch_dir("huge_counts_gltf");
    let element = "mesh 0 \"Gem\" primitive 0";
    for count in [1u64 << 31, (1u64 << 32) - 1] {
        // Vertices: a POSITION accessor declaring `count` elements in a 36-byte view.
        let doc = triangle_gltf(|d| d["accessors"][0]["count"] = json!(count));
        let path = write_gltf(&dir, &format!("vertices_{count}.gltf"), &doc);
        assert_rejected(
            &path,
            LoadErrorKind::MissingBuffer,
            &[element, "POSITION", "accessor 0", &count.to_string()],
        );
        // Indices.
        let doc = triangle_gltf(|d| d["accessors"][1]["count"] = json!(count));
        let path = write_gltf(&dir, &format!("indices_{count}.gltf"), &doc);
        assert_rejected(
            &path,
            LoadErrorKind::MissingBuffer,
            &[element, "indices", "accessor 1"],
        );
        // No buffer view: `count` zeros (+ sparse substitutions) would be allocated.
        let doc = triangle_gltf(|d| {
            d["accessors"][0]["count"] = json!(count);
            d["accessors"][0]
                .as_object_mut()
                .unwrap()
                .remove("bufferView");
            d["accessors"][0]["sparse"] = json!({
                "count": 1,
                "indices": {"bufferView": 1, "componentType": 5123},
                "values": {"bufferView": 0}
            });
        });
        let path = write_gltf(&dir, &format!("zeros_{count}.gltf"), &doc);
        assert_rejected(
            &path,
            LoadErrorKind::TooLarge,
            &[element, "POSITION", "accessor 0"],
        );
        // A sparse accessor declaring `count` substitutions.
        let doc = triangle_gltf(|d| {
            d["accessors"][0]["sparse"] = json!({
                "count": count,
                "indices": {"bufferView": 1, "componentType": 5123},
                "values": {"bufferView": 0}
            });
        });
        let path = write_gltf(&dir, &format!("sparse_{count}.gltf"), &doc);
        assert_rejected(
            &path,
            LoadErrorKind::MissingBuffer,
            &[element, "POSITION", "accessor 0", "sparse"],
        );
        // A buffer declaring `count` bytes that its data URI does not hold.
        let doc = triangle_gltf(|d| d["buffers"][0]["byteLength"] = json!(count));
        let path = write_gltf(&dir, &format!("buffer_{count}.gltf"), &doc);
        assert_rejected(&path, LoadErrorKind::MissingBuffer, &["buffer 0"]);
    }
    // A sparse index far past the accessor's count.
    let doc = triangle_gltf(|d| {
        let mut buf = Vec::new();
        for v in [0f32, 0., 0., 1., 0., 0., 0., 1., 0.] {
            buf.extend_from_slice(&v.to_le_bytes());
        }
        buf.extend_from_slice(&u32::MAX.to_le_bytes());
        d["buffers"][0] = json!({"byteLength": buf.len(), "uri": data_uri(&buf)});
        d["bufferViews"][1] = json!({"buffer": 0, "byteOffset": 36, "byteLength": 4});
        d["meshes"][0]["primitives"][0]
            .as_object_mut()
            .unwrap()
            .remove("indices");
        d["accessors"][0]["sparse"] = json!({
            "count": 1,
            "indices": {"bufferView": 1, "componentType": 5125},
            "values": {"bufferView": 0}
        });
    });
    let path = write_gltf(&dir, "sparse_index.gltf", &doc);
    assert_rejected(
        &path,
        LoadErrorKind::IndexOutOfRange,
        &[element, "sparse index 4294967295"],
    );
}

#[test]
fn embedded_image_claiming_1e5_squared_pixels_is_rejected_before_decoding() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = common::scratch_dir("huge_counts_image");
    let png = png_header(100_000, 100_000);
    let doc = triangle_gltf(|d| {
        d["images"] = json!([{"name": "huge", "uri": data_uri(&png)}]);
        d["textures"] = json!([{"source": 0}]);
        d["materials"] = json!([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]);
        d["meshes"][0]["primitives"][0]["material"] = json!(0);
    });
    let path = write_gltf(&dir, "huge_image.gltf", &doc);
    assert_rejected(
        &path,
        LoadErrorKind::TooLarge,
        &["image 0 \"huge\"", "100000×100000"],
    );
}

/// The render plan's "textures" stage: a material no mesh uses keeps its factors but its
/// texture is never decoded, so even the 10⁵×10⁵ image above costs nothing there; the
/// plan counts the slot. (The same image on a used material is rejected, above.)
#[test]
fn textures_of_materials_no_mesh_uses_are_not_decoded() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = common::scratch_dir("huge_counts_unused_texture");
    let png = png_header(100_000, 100_000);
    let doc = triangle_gltf(|d| {
        d["images"] = json!([{"name": "huge", "uri": data_uri(&png)}]);
        d["textures"] = json!([{"source": 0}]);
        d["materials"] = json!([
            {"name": "used", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}},
            {"name": "unused", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
             "emissiveTexture": {"index": 0}}
        ]);
        d["meshes"][0]["primitives"][0]["material"] = json!(0);
    });
    let path = write_gltf(&dir, "unused_texture.gltf", &doc);
    let (desc, peak) = peak_during(|| iris::load::load_scene(&path).expect("loads"));
    assert!(peak < 64 << 20, "peak heap {peak} bytes");
    assert!(desc.images.is_empty());
    assert_eq!(desc.skipped_textures, 2);
    assert_eq!(desc.materials.len(), 2);
    assert!(desc.materials[1].base_color_texture.is_none());
    let plan = iris::app::load(&path, iris::accel::Backend::Bvh)
        .map(|(scene, _)| {
            iris::plan::Plan::new(
                &scene,
                &common::PINHOLE,
                iris::integrator::Method::Whitted,
                iris::app::SpectralMode::Auto,
            )
            .text()
        })
        .expect("plan");
    assert!(
        plan.contains("2 texture slots of materials on no mesh left undecoded"),
        "{plan}"
    );
    // OBJ: `map_kd` of a material no face uses is not even opened (a missing file there
    // gives no warning); on the used material it is (a warning naming the file).
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl used\nKd 0.5 0.5 0.5\nmap_Kd missing_a.png\n\
         newmtl unused\nKd 1 0 0\nmap_Kd missing_b.png\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("t.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl used\nf 1 2 3\n",
    )
    .unwrap();
    let desc = iris::load::load_scene(&dir.join("t.obj")).expect("obj loads");
    assert_eq!(desc.skipped_textures, 1);
    let warnings = desc.warnings.join("\n");
    assert!(warnings.contains("missing_a.png"), "{warnings}");
    assert!(!warnings.contains("missing_b.png"), "{warnings}");
}

#[test]
fn obj_with_absurd_indices_is_rejected() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = common::scratch_dir("huge_counts_obj");
    let cases = [
        ("f 1 2 4294967296\n", "line 4"),
        ("f 1 2 2147483648\n", "line 4"),
        ("f 1 2 -99999999999999999999\n", "line 4"),
        ("f 1/99999999999 2 3\n", "line 4"),
        ("f 1//4294967295 2//1 3//1\n", "line 4"),
    ];
    for (k, (face, line)) in cases.iter().enumerate() {
        let path = dir.join(format!("absurd_{k}.obj"));
        std::fs::write(&path, format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{face}")).unwrap();
        let (result, peak) = peak_during(|| iris::load::load_scene(&path));
        let err = result.expect_err(face);
        let text = err.to_string();
        assert!(
            matches!(
                err.kind,
                LoadErrorKind::IndexOutOfRange | LoadErrorKind::Parse
            ),
            "{text}"
        );
        assert!(text.contains(line), "{text:?} does not name {line}");
        assert!(peak < PEAK_LIMIT, "peak heap {peak} bytes for {face:?}");
    }
}

/// `iris render` on `args` must fail, name `needles` on stderr and leave no `out.png`.
fn assert_cli_fails(dir: &Path, args: &[&str], needles: &[&str]) {
    let out = common::iris(args, dir);
    let err = common::stderr(&out);
    assert!(!out.status.success(), "iris {args:?} succeeded: {err}");
    for n in needles {
        assert!(err.contains(n), "stderr {err:?} does not name {n:?}");
    }
    assert!(
        !dir.join("out.png").exists(),
        "iris {args:?} wrote an output file"
    );
}

#[test]
fn cli_rejects_huge_requests_with_no_output() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = common::scratch_dir("huge_counts_cli");
    let ok = write_gltf(&dir, "ok.gltf", &triangle_gltf(|_| {}));
    let ok = ok.to_str().unwrap();
    assert_cli_fails(
        &dir,
        &["render", ok, "--size", "1000000x1000000", "-o", "out.png"],
        &["--size", "1000000x1000000"],
    );
    let doc = triangle_gltf(|d| d["accessors"][0]["count"] = json!(1u64 << 31));
    let huge = write_gltf(&dir, "huge.gltf", &doc);
    assert_cli_fails(
        &dir,
        &["render", huge.to_str().unwrap(), "-o", "out.png"],
        &["huge.gltf", "mesh 0 \"Gem\" primitive 0", "accessor 0"],
    );
    // Environment maps whose headers declare 10⁵ × 10⁵ texels.
    let hdr = dir.join("huge.hdr");
    std::fs::write(
        &hdr,
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n\x02\x02\x00\x08",
    )
    .unwrap();
    assert_cli_fails(
        &dir,
        &["render", ok, "--env", "huge.hdr", "-o", "out.png"],
        &["huge.hdr", "header", "100000×100000"],
    );
    let exr = dir.join("huge.exr");
    std::fs::write(&exr, exr_claiming(&dir, 99_999, 99_999)).unwrap();
    assert_cli_fails(
        &dir,
        &["render", ok, "--env", "huge.exr", "-o", "out.png"],
        &["huge.exr", "layer 0", "too large"],
    );
}

/// A small EXR written by Iris, with its data and display windows patched to declare
/// `(w+1)×(h+1)` pixels (OpenEXR file layout: `box2i` attributes are four little-endian
/// i32 `xMin yMin xMax yMax`); the small file is written in the calling test's `dir`.
fn exr_claiming(dir: &Path, w: i32, h: i32) -> Vec<u8> {
    let path = dir.join("small.exr");
    let mut img = iris::image::ImageRgb::new(4, 2);
    img.data.iter_mut().for_each(|p| *p = glam::Vec3::ONE);
    iris::output::write_image(&path, &img, &Default::default()).unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    for attr in [&b"dataWindow\0box2i\0"[..], &b"displayWindow\0box2i\0"[..]] {
        let at = bytes
            .windows(attr.len())
            .position(|w| w == attr)
            .expect("EXR window attribute")
            + attr.len()
            + 4;
        bytes[at + 8..at + 12].copy_from_slice(&w.to_le_bytes());
        bytes[at + 12..at + 16].copy_from_slice(&h.to_le_bytes());
    }
    bytes
}

#[test]
fn huge_environment_maps_are_rejected_before_allocating() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = common::scratch_dir("huge_counts_env");
    let hdr = dir.join("huge.hdr");
    std::fs::write(
        &hdr,
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n\x02\x02\x00\x08",
    )
    .unwrap();
    let exr = dir.join("huge.exr");
    std::fs::write(&exr, exr_claiming(&dir, 99_999, 99_999)).unwrap();
    for path in [hdr, exr] {
        let (result, peak) = peak_during(|| iris::light::env::load(&path));
        let err = result.expect_err("huge map loaded");
        let text = err.to_string();
        match &err {
            iris::Error::Load(e) => {
                assert_eq!(e.kind, LoadErrorKind::TooLarge, "{text}");
                assert_eq!(e.file, path, "{text}");
                assert!(!e.element.is_empty(), "no element in {text:?}");
            }
            other => panic!("expected a load error, got {other}"),
        }
        assert!(peak < PEAK_LIMIT, "peak heap {peak} bytes for {text}");
    }
}

#[test]
fn device_files_are_not_read_as_buffers() {
    // `file:///dev/zero` never ends: reading it whole would exhaust memory. The loader reads
    // only regular files, so this is a quick `MissingBuffer` error naming the buffer.
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = common::scratch_dir("huge_counts_device");
    if !Path::new("/dev/zero").exists() {
        eprintln!("SKIPPED: no /dev/zero on this system");
        return;
    }
    let doc = triangle_gltf(|d| d["buffers"][0]["uri"] = json!("file:///dev/zero"));
    let path = write_gltf(&dir, "dev_zero.gltf", &doc);
    assert_rejected(
        &path,
        LoadErrorKind::MissingBuffer,
        &["buffer 0", "not a regular file"],
    );
}
