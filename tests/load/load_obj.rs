//! OBJ/MTL loading: the shared Cornell boxes, line-numbered errors, and a mutation test
//! showing no input makes the loader panic.

use crate::common;

use iris::load::load_scene;
use iris::material::{ExplicitIor, MaterialDesc};
use iris::scene::desc::SceneDesc;
use iris::LoadErrorKind;
use std::path::{Path, PathBuf};

fn obj_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            obj_files(&path, out);
        } else if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"))
        {
            out.push(path);
        }
    }
}

fn triangles(desc: &SceneDesc) -> usize {
    desc.meshes.iter().map(|m| m.indices.len()).sum()
}

/// The material whose name quotes `name` (names look like `material 3 "water" (… line 9)`).
fn material<'a>(desc: &'a SceneDesc, name: &str) -> &'a MaterialDesc {
    let quoted = format!("\"{name}\"");
    desc.materials
        .iter()
        .find(|m| m.name.contains(&quoted))
        .unwrap_or_else(|| panic!("no material {quoted} in {:?}", desc.source))
}

fn is_dielectric(m: &MaterialDesc, ior: f32) {
    assert_eq!(m.transmission, 1.0, "{}", m.name);
    assert!(m.thickness > 0.0, "{} must bound a volume", m.name);
    assert_eq!((m.metallic, m.roughness), (0.0, 0.0), "{}", m.name);
    assert!((m.ior - ior).abs() < 1e-6, "{}: ior {}", m.name, m.ior);
    assert_eq!(m.base_color.truncate(), glam::Vec3::ONE, "{}", m.name);
}

/// Signed volume enclosed by the meshes named `group "name"` (> 0: wound outwards).
fn signed_volume(desc: &SceneDesc, name: &str) -> f32 {
    let quoted = format!("\"{name}\"");
    let mut volume = 0.0;
    for mesh in desc.meshes.iter().filter(|m| m.name.contains(&quoted)) {
        for [a, b, c] in &mesh.indices {
            let p = |i: &u32| mesh.positions[*i as usize];
            volume += p(a).dot(p(b).cross(p(c))) / 6.0;
        }
    }
    volume
}

#[test]
fn shared_cornell_boxes_load() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let mut files = Vec::new();
    obj_files(&assets.join("obj"), &mut files);
    assert!(
        files.len() >= 3,
        "expected the three Cornell boxes, found {files:?}"
    );
    for path in &files {
        let desc = load_scene(path).unwrap_or_else(|e| panic!("{e}"));
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        eprintln!(
            "{name}: {} meshes, {} triangles",
            desc.meshes.len(),
            triangles(&desc)
        );
        for m in &desc.meshes {
            let mat = m.material.and_then(|i| desc.materials.get(i));
            eprintln!(
                "  {}: {} tris, {:?}",
                m.name,
                m.indices.len(),
                mat.map(|m| &m.name)
            );
        }
        for w in &desc.warnings {
            eprintln!("  warning: {w}");
        }
        // MANIFEST §2 face counts: Original has 18 quads (= 36 triangles), the other two
        // are all triangles already.
        let expected = match name {
            "CornellBox-Original.obj" => Some(36),
            "CornellBox-Sphere.obj" => Some(2188),
            "CornellBox-Water.obj" => Some(7088),
            _ => None,
        };
        match expected {
            Some(n) => assert_eq!(triangles(&desc), n, "{name}"),
            None => assert!(triangles(&desc) > 0, "{name}"),
        }
        // Every Cornell light: emissive, not transmissive, whatever its Tf/illum/Ni say.
        if desc.materials.iter().any(|m| m.name.contains("\"light\"")) {
            let light = material(&desc, "light");
            assert_eq!(light.transmission, 0.0, "{}", light.name);
            assert!(light.emissive.min_element() > 0.0, "{}", light.name);
        }
    }
}

#[test]
fn cornell_glass_and_mirror_materials() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let dir = assets.join("obj/CornellBox-McGuire");
    let sphere = load_scene(&dir.join("CornellBox-Sphere.obj")).unwrap_or_else(|e| panic!("{e}"));
    is_dielectric(material(&sphere, "rightSphere"), 2.5);
    let mirror = material(&sphere, "leftSphere");
    assert_eq!((mirror.metallic, mirror.roughness), (1.0, 0.0));
    assert!((mirror.base_color.x - 0.95).abs() < 1e-6);
    assert_eq!(mirror.transmission, 0.0);
    // The glass sphere's mesh uses the glass material and is wound outwards (CCW).
    let glass = sphere
        .meshes
        .iter()
        .find(|m| m.name == "group \"rightSphere\"")
        .expect("rightSphere mesh");
    let mat = &sphere.materials[glass.material.expect("material")];
    assert!(mat.name.contains("\"rightSphere\""));
    assert!(signed_volume(&sphere, "rightSphere") > 0.0);

    let water = load_scene(&dir.join("CornellBox-Water.obj")).unwrap_or_else(|e| panic!("{e}"));
    is_dielectric(material(&water, "water"), 1.33);
    is_dielectric(material(&water, "rightSphere"), 2.5);
    for diffuse in ["floor", "leftWall", "backWall"] {
        let m = material(&water, diffuse);
        assert_eq!(
            (m.transmission, m.metallic, m.specular),
            (0.0, 0.0, 0.0),
            "{}",
            m.name
        );
    }

    let original =
        load_scene(&dir.join("CornellBox-Original.obj")).unwrap_or_else(|e| panic!("{e}"));
    let light = material(&original, "light");
    assert_eq!(light.emissive, glam::Vec3::new(17.0, 12.0, 4.0));
}

/// Writes `files` into a scratch dir and loads the first one.
fn load_files(test: &str, files: &[(&str, &str)]) -> (PathBuf, Result<SceneDesc, iris::LoadError>) {
    let dir = common::scratch_dir(test);
    for (name, text) in files {
        std::fs::write(dir.join(name), text).expect("write scratch file");
    }
    let path = dir.join(files[0].0);
    let result = load_scene(&path);
    (path, result)
}

/// Asserts the error kind and that the message names `file` (default: the OBJ) and `element`.
fn expect_error_in(
    test: &str,
    files: &[(&str, &str)],
    kind: LoadErrorKind,
    file: &str,
    element: &str,
) {
    let (_, result) = load_files(test, files);
    let e = match result {
        Ok(_) => panic!("{test}: expected {kind:?}"),
        Err(e) => e,
    };
    let msg = e.to_string();
    assert_eq!(e.kind, kind, "{test}: {msg}");
    assert!(msg.contains(file), "{test}: `{file}` not in {msg}");
    assert!(msg.contains(element), "{test}: `{element}` not in {msg}");
}

fn expect_error(test: &str, files: &[(&str, &str)], kind: LoadErrorKind, element: &str) {
    expect_error_in(test, files, kind, files[0].0, element);
}

const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn face_index_out_of_range_names_line() {
    let text = format!("{TRI}f 1 2 3\n# a comment\n\nf 1 2 4\n");
    expect_error(
        "oor",
        &[("oor.obj", &text)],
        LoadErrorKind::IndexOutOfRange,
        "line 7",
    );
    let text = format!("{TRI}vn 0 0 1\nf 1//1 2//1 3//2\n");
    expect_error(
        "oor_vn",
        &[("n.obj", &text)],
        LoadErrorKind::IndexOutOfRange,
        "line 5",
    );
    let text = format!("{TRI}f -1 -2 -3\nf -1 -2 -4\n");
    expect_error(
        "oor_rel",
        &[("rel.obj", &text)],
        LoadErrorKind::IndexOutOfRange,
        "line 5",
    );
    let text = format!("{TRI}f 0 1 2\n");
    expect_error(
        "oor_zero",
        &[("zero.obj", &text)],
        LoadErrorKind::IndexOutOfRange,
        "line 4",
    );
}

#[test]
fn bad_vertices_name_line() {
    let text = format!("{TRI}v nan 0 0\nf 1 2 3\n");
    expect_error(
        "nan",
        &[("nan.obj", &text)],
        LoadErrorKind::NonFinite,
        "line 4",
    );
    let text = format!("# x\n{TRI}v 0 inf 0\nf 1 2 3\n");
    expect_error(
        "inf",
        &[("inf.obj", &text)],
        LoadErrorKind::NonFinite,
        "line 5",
    );
    let text = format!("v 1 x 2\n{TRI}f 1 2 3\n");
    expect_error(
        "parse",
        &[("parse.obj", &text)],
        LoadErrorKind::Parse,
        "line 1",
    );
    let text = format!("{TRI}vt 0.5 zz\nf 1 2 3\n");
    expect_error(
        "parse_vt",
        &[("vt.obj", &text)],
        LoadErrorKind::Parse,
        "line 4",
    );
}

#[test]
fn missing_file_and_no_faces() {
    let dir = common::scratch_dir("missing");
    let e = load_scene(&dir.join("nope.obj")).expect_err("missing");
    assert_eq!(e.kind, LoadErrorKind::Io);
    assert!(e.to_string().contains("nope.obj"));
    expect_error(
        "only_v",
        &[("verts.obj", TRI)],
        LoadErrorKind::NoTriangles,
        "verts.obj",
    );
    expect_error(
        "empty",
        &[("empty.obj", "")],
        LoadErrorKind::NoTriangles,
        "empty.obj",
    );
    // A device as MTL library must neither hang nor exhaust memory: it is a warning.
    if Path::new("/dev/zero").exists() {
        let obj = format!("mtllib /dev/zero\n{TRI}f 1 2 3\n");
        let (_, result) = load_files("device", &[("dev.obj", &obj)]);
        let desc = result.unwrap_or_else(|e| panic!("{e}"));
        assert!(desc.warnings.iter().any(|w| w.contains("/dev/zero")));
    }
}

#[test]
fn negative_ior_names_material() {
    let obj = format!("mtllib m.mtl\n{TRI}usemtl glass\nf 1 2 3\n");
    let mtl = "newmtl glass\nNi -1.5\nillum 7\n";
    expect_error(
        "neg_ior",
        &[("ior.obj", &obj), ("m.mtl", mtl)],
        LoadErrorKind::InvalidIor,
        "\"glass\"",
    );
}

#[test]
fn mtl_cauchy_keys_and_warnings() {
    let obj = format!("mtllib m.mtl\nmtllib gone.mtl\n{TRI}usemtl gem\nf 1 2 3\n");
    let mtl = "newmtl gem\nKd 1 1 1\ncauchy_b 1.5\ncauchy_c 0.0042\nillum 7\nNi 1.51\nmap_Bump b.png\nPs 1\n";
    let (_, result) = load_files("cauchy", &[("c.obj", &obj), ("m.mtl", mtl)]);
    let desc = result.unwrap_or_else(|e| panic!("{e}"));
    let gem = material(&desc, "gem");
    assert_eq!(
        gem.ior_model,
        Some(ExplicitIor::Cauchy { b: 1.5, c: 0.0042 })
    );
    assert!((gem.ior - 1.51).abs() < 1e-6);
    assert_eq!(gem.transmission, 1.0);
    let warnings = desc.warnings.join("\n");
    assert!(warnings.contains("gone.mtl"), "{warnings}");
    let unsupported: Vec<&String> = desc
        .warnings
        .iter()
        .filter(|w| w.contains("MTL statements"))
        .collect();
    assert_eq!(unsupported.len(), 1, "{warnings}");
    assert!(
        unsupported[0].contains("map_Bump") && unsupported[0].contains("Ps"),
        "{warnings}"
    );

    // Errors inside the MTL name the MTL file (and the material, or the line).
    let bad = "newmtl gem\ncauchy_b 1.5\ncauchy_c oops\n";
    expect_error_in(
        "cauchy_bad",
        &[("c.obj", &obj), ("m.mtl", bad)],
        LoadErrorKind::InvalidValue,
        "m.mtl",
        "\"gem\"",
    );
    let bad = "newmtl gem\n\nKd 0.5 x 0.5\n";
    expect_error_in(
        "mtl_parse",
        &[("c.obj", &obj), ("m.mtl", bad)],
        LoadErrorKind::Parse,
        "m.mtl",
        "line 3",
    );
}

#[test]
fn quads_uvs_and_groups() {
    let obj = "mtllib m.mtl\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
               usemtl red\nf 1/1 2/2 3/3 4/4\nusemtl nosuch\nf -4/-4 -2/-2 -1/-1\nl 1 2 3\n";
    let mtl = "newmtl red\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 100\n";
    let (_, result) = load_files("quads", &[("q.obj", obj), ("m.mtl", mtl)]);
    let desc = result.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(triangles(&desc), 3);
    assert_eq!(desc.meshes.len(), 2);
    assert_eq!(desc.meshes[0].name, "object \"quad\" part 1");
    // OBJ v = 0 is the bottom of the image; glTF's v = 1.
    assert!(desc.meshes[0].uvs.contains(&glam::Vec2::new(0.0, 1.0)));
    let red = material(&desc, "red");
    let expected = (2.0f32 / 102.0).powf(0.25);
    assert!((red.roughness - expected).abs() < 1e-6 && red.specular == 0.5);
    let warnings = desc.warnings.join("\n");
    assert!(
        warnings.contains("nosuch") && warnings.contains("`l`"),
        "{warnings}"
    );
}

/// A small deterministic xorshift generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const NASTY: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "1e39",
    "-9223372036854775808",
    "9223372036854775807",
    "0",
    "-0",
    "4294967296",
    "/",
    "//",
    "f",
    "l",
    "mtllib",
    "usemtl",
    "newmtl",
    "g",
    "o",
    "Kd",
    "Ni",
    "d",
    "illum 7",
    "cauchy_b",
    "cauchy_c",
    "map_Kd",
    "\\",
    "é",
    "\r",
    "\n",
    " ",
    "#",
    "-",
    "vt",
    "vn",
];

fn mutate(rng: &mut Rng, text: &str) -> Vec<u8> {
    let mut bytes = text.as_bytes().to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(bytes.len() + 1);
        match rng.below(5) {
            0 if at < bytes.len() => bytes[at] = rng.next() as u8,
            1 if at < bytes.len() => {
                bytes.remove(at);
            }
            2 => bytes.truncate(at),
            3 => {
                let token = NASTY[rng.below(NASTY.len())].as_bytes();
                bytes.splice(at..at, token.iter().copied());
            }
            _ => {
                let token = NASTY[rng.below(NASTY.len())].as_bytes();
                let end = (at + 1 + rng.below(6)).min(bytes.len());
                if at <= end {
                    bytes.splice(at..end, token.iter().copied());
                }
            }
        }
    }
    bytes
}

#[test]
fn mutated_inputs_never_panic() {
    let obj = "# test\nmtllib m.mtl\no box\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1\nvt 0 0\nvt 1 0 0\n\
               vt 1 1\nvn 0 0 1\ng side\nusemtl glass\ns 1\nf 1/1/1 2/2/1 3/3/1\nf -4/-3/-1 -2/-1/-1 -1/-1/-1\n\
               usemtl red\nf 1//1 2//1 3//1 4//1\nf 1 3 4\n";
    let mtl = "newmtl glass\nKd 1 1 1\nNi 1.5\nTf 0.1 0.1 0.1\nillum 7\ncauchy_b 1.5\ncauchy_c 0.004\n\
               newmtl red\nKd 0.8 0.1 0.1\nKs 0.2\nNs 50\nd 0.5\nmap_Kd -s 1 1 1 missing.png\nillum 2\n";
    let dir = common::scratch_dir("mutations");
    let (obj_path, mtl_path) = (dir.join("t.obj"), dir.join("m.mtl"));
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut ok, mut failed) = (0, 0);
    for round in 0..3000 {
        let (o, m) = match round % 3 {
            0 => (mutate(&mut rng, obj), mtl.as_bytes().to_vec()),
            1 => (obj.as_bytes().to_vec(), mutate(&mut rng, mtl)),
            _ => (mutate(&mut rng, obj), mutate(&mut rng, mtl)),
        };
        std::fs::write(&obj_path, &o).expect("write");
        std::fs::write(&mtl_path, &m).expect("write");
        let result = std::panic::catch_unwind(|| load_scene(&obj_path));
        match result {
            Ok(Ok(_)) => ok += 1,
            Ok(Err(e)) => {
                assert!(e.to_string().contains("t.obj") || e.to_string().contains("m.mtl"));
                failed += 1;
            }
            Err(_) => panic!(
                "round {round} panicked on\n--- obj\n{}\n--- mtl\n{}",
                String::from_utf8_lossy(&o),
                String::from_utf8_lossy(&m)
            ),
        }
    }
    eprintln!("mutations: {ok} loaded, {failed} rejected");
    assert!(ok > 0 && failed > 0);
}
