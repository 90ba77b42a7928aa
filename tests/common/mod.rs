//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;

pub mod alloc;
pub mod optics;
pub mod splitmix;
pub mod view;

/// The third-party test scenes in `../shared/assets` (override with `IRIS_SHARED_ASSETS`).
///
/// Outside the project's workplace that folder is absent: the calling test then prints
/// why it skips and returns `None`. CI sets `IRIS_REQUIRE_SHARED=1`, which turns the
/// absence into a failure so CI never skips these tests.
pub fn shared_assets() -> Option<PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    // The rule is the gallery's (`iris::app::gallery::shared_assets_dir_in`); an error here
    // is IRIS_REQUIRE_SHARED=1 with the folder missing.
    let found = iris::app::gallery::shared_assets_dir_in(root).unwrap_or_else(|e| panic!("{e}"));
    if found.is_none() {
        eprintln!(
            "SKIPPED: shared test assets not found at {} (no MANIFEST.md there; set IRIS_SHARED_ASSETS, or IRIS_REQUIRE_SHARED=1 to fail)",
            iris::app::gallery::shared_assets_candidate(root).display()
        );
    }
    found
}

/// A scratch directory unique to one test, emptied first.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}

/// A unit sphere (icosphere, 5120 triangles, smooth normals) at the origin with one
/// material, under a uniform environment of radiance 1: the furnace-test scene.
pub fn sphere_in_white_environment(material: iris::material::MaterialDesc) -> iris::scene::Scene {
    use iris::scene::desc::{MeshDesc, SceneDesc};
    let sphere = iris::authoring::shapes::icosphere(1.0, 4);
    let desc = SceneDesc {
        source: "furnace".into(),
        meshes: vec![MeshDesc {
            name: "sphere".into(),
            positions: sphere.positions,
            normals: sphere.normals,
            indices: sphere.indices,
            material: Some(0),
            ..Default::default()
        }],
        materials: vec![material],
        environment_light: Some(iris::light::env::Environment::Uniform {
            radiance: glam::Vec3::ONE,
        }),
        ..Default::default()
    };
    build_scene(desc)
}

/// Validates `desc` and builds it on the automatic backend.
pub fn build_scene(desc: iris::scene::desc::SceneDesc) -> iris::scene::Scene {
    let desc = iris::scene::validate::validate(desc).expect("valid scene");
    iris::scene::Scene::build(desc, iris::accel::Backend::Auto).expect("build")
}

/// A white point light "bulb" of intensity 1 (candela) at `position`.
pub fn white_point_light(position: glam::Vec3) -> iris::scene::desc::LightDesc {
    iris::scene::desc::LightDesc::Point {
        name: "bulb".into(),
        position,
        color: glam::Vec3::ONE,
        intensity: 1.0,
        range: None,
        spectrum: None,
    }
}

/// Every backend compiled in: the BVH, then Embree when the `embree` feature is on.
pub fn backends() -> Vec<iris::accel::Backend> {
    let mut b = vec![iris::accel::Backend::Bvh];
    if cfg!(feature = "embree") {
        b.push(iris::accel::Backend::Embree);
    }
    b
}

/// A clear, smooth, volumetric dielectric (KHR transmission 1, volume thickness 1) of index
/// `ior`.
pub fn clear_glass(name: &str, ior: f32) -> iris::material::MaterialDesc {
    iris::material::MaterialDesc {
        name: name.into(),
        metallic: 0.0,
        roughness: 0.0,
        transmission: 1.0,
        thickness: 1.0,
        ior,
        ..Default::default()
    }
}

/// A mesh description of a generated triangle mesh, with material `material`.
pub fn mesh(
    name: &str,
    m: iris::authoring::shapes::TriMesh,
    material: usize,
) -> iris::scene::desc::MeshDesc {
    m.into_mesh_desc(name, material)
}

/// A white Lambertian material: albedo 1, no specular layer.
pub fn white_lambert() -> iris::material::MaterialDesc {
    iris::material::MaterialDesc {
        name: "white".into(),
        metallic: 0.0,
        specular: 0.0,
        ..Default::default()
    }
}

/// The caustic test scene ([`iris::assets::bench::caustic_sphere`]), built on the
/// automatic backend.
#[allow(dead_code)]
pub fn caustic_sphere(area: Option<f32>) -> (iris::scene::Scene, iris::scene::desc::CameraDesc) {
    let (desc, cam) = iris::assets::bench::caustic_sphere(area);
    let desc = iris::scene::validate::validate(desc).expect("valid caustic scene");
    let scene = iris::scene::Scene::build(desc, iris::accel::Backend::Auto).expect("build");
    (scene, cam)
}

/// Runs the `iris` binary with `args` in `cwd`.
pub fn iris(args: &[&str], cwd: &std::path::Path) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_iris"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("run iris")
}

/// A command's standard error as text.
pub fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The file names in `dir`, sorted.
pub fn entries(dir: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// A box of size `s` centred at `c` as (positions, triangles), outward-wound.
pub fn cuboid(s: [f32; 3], c: [f32; 3]) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let p = (0..8)
        .map(|i| {
            let sign = |bit: u32| if i & bit == 0 { -0.5 } else { 0.5 };
            [
                c[0] + sign(1) * s[0],
                c[1] + sign(2) * s[1],
                c[2] + sign(4) * s[2],
            ]
        })
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let t = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (p, t)
}

/// Writes an OBJ of `p` and `t` (0-based) as `dir/<name>.obj` (`@` → `_`).
pub fn write_obj(
    dir: &std::path::Path,
    name: &str,
    p: &[[f32; 3]],
    t: &[[u32; 3]],
) -> std::path::PathBuf {
    use std::fmt::Write as _;
    let mut s = String::new();
    for v in p {
        let _ = writeln!(s, "v {:e} {:e} {:e}", v[0], v[1], v[2]);
    }
    for f in t {
        let _ = writeln!(s, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    let path = dir.join(format!("{}.obj", name.replace('@', "_")));
    std::fs::write(&path, s).expect("write obj");
    path
}

/// The scene formats Iris reads (file extensions, lower case).
pub const SCENE_EXTS: [&str; 3] = ["glb", "gltf", "obj"];

/// Files under `dir`, recursively, whose extension (any case) is one of `exts`, sorted by
/// path; an unreadable directory contributes nothing.
pub fn files_with_ext(dir: &std::path::Path, exts: &[&str]) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(rd) = std::fs::read_dir(&d) else {
            continue;
        };
        for p in rd.filter_map(|e| e.ok().map(|e| e.path())) {
            if p.is_dir() {
                stack.push(p);
            } else if p
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| exts.contains(&e.to_ascii_lowercase().as_str()))
            {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// 4 × 4 block means of the channel mean of `img` (its width and height multiples of 4):
/// the agreement tests' unit of comparison.
#[allow(dead_code)]
pub fn blocks(img: &iris::image::ImageRgb) -> Vec<f64> {
    let (w, h) = (img.width, img.height);
    let mut out = Vec::new();
    for by in 0..h / 4 {
        for bx in 0..w / 4 {
            let mut s = 0.0;
            for y in by * 4..by * 4 + 4 {
                for x in bx * 4..bx * 4 + 4 {
                    let p = img.data[(y * w + x) as usize];
                    s += (p.x + p.y + p.z) as f64 / 3.0;
                }
            }
            out.push(s / 16.0);
        }
    }
    out
}

/// Of block means `b` ([`blocks`], `bw × bh` blocks): the 3 × 3 blocks around the block
/// brightest relative to its 8 neighbours (the focused light under a glass sphere), and that
/// excess relative to the neighbours' mean.
#[allow(dead_code)]
pub fn caustic_region(b: &[f64], (bw, bh): (i32, i32)) -> (Vec<usize>, f64) {
    let at = |x: i32, y: i32| b[(y * bw + x) as usize];
    let mut best = (f64::MIN, 0, 0, 0.0);
    for y in 1..bh - 1 {
        for x in 1..bw - 1 {
            let mut n = 0.0;
            for dy in -1..=1 {
                for dx in -1..=1 {
                    if (dx, dy) != (0, 0) {
                        n += at(x + dx, y + dy) / 8.0;
                    }
                }
            }
            if at(x, y) - n > best.0 {
                best = (at(x, y) - n, x, y, n);
            }
        }
    }
    let (excess, cx, cy, ring) = best;
    let region = (cy - 1..=cy + 1)
        .flat_map(|y| (cx - 1..=cx + 1).map(move |x| (y * bw + x) as usize))
        .collect();
    (region, excess / ring)
}

/// The mean of `v`.
#[allow(dead_code)]
pub fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// RMSE of `a` against `b`, relative to `b`'s mean.
#[allow(dead_code)]
pub fn relative_rmse(a: &[f64], b: &[f64]) -> f64 {
    let mse = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / a.len() as f64;
    mse.sqrt() / mean(b)
}

/// A GLB container (glTF 2.0 §4.4): JSON chunk padded with spaces, BIN chunk with zeros.
pub fn glb(doc: &serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(doc).expect("serialize");
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// Quiet RGB settings of `width`×`height` at `spp` with `seed` on `threads` (0 = all
/// cores), the default sampler, no time limit, uniform sampling.
pub fn render_settings(
    (width, height): (u32, u32),
    spp: u32,
    seed: u64,
    threads: usize,
) -> iris::render::RenderSettings {
    iris::render::RenderSettings::quiet_rgb((width, height), spp, seed, threads)
}

/// A perspective camera's projection, for the plan of a scene built without a camera.
#[allow(dead_code)]
pub const PINHOLE: iris::scene::desc::Projection = iris::scene::desc::Projection::Perspective {
    yfov: 0.9,
    aspect: None,
};

/// A perspective camera of vertical field `yfov` (radians) 4 m from the origin on +Z,
/// looking at it: the view of [`sphere_in_white_environment`]'s unit sphere.
#[allow(dead_code)]
pub fn camera_facing_origin(yfov: f32) -> iris::scene::desc::CameraDesc {
    iris::scene::desc::CameraDesc {
        name: "c".into(),
        projection: iris::scene::desc::Projection::Perspective { yfov, aspect: None },
        world_from_camera: iris::camera::look_at(
            glam::Vec3::new(0.0, 0.0, 4.0),
            glam::Vec3::ZERO,
            glam::Vec3::Y,
        ),
    }
}

/// An icosphere mesh of `radius` and `subdivisions` centred at `centre`.
#[allow(dead_code)]
pub fn sphere_mesh(
    name: &str,
    radius: f32,
    subdivisions: u32,
    centre: glam::Vec3,
    material: usize,
) -> iris::scene::desc::MeshDesc {
    let s = iris::authoring::shapes::icosphere(radius, subdivisions);
    iris::scene::desc::MeshDesc {
        name: name.into(),
        positions: s.positions.iter().map(|p| *p + centre).collect(),
        normals: s.normals,
        indices: s.indices,
        material: Some(material),
        ..Default::default()
    }
}

/// The image mean per linear-RGB channel.
#[allow(dead_code)]
pub fn channel_means(img: &iris::image::ImageRgb) -> [f64; 3] {
    let s = img
        .data
        .iter()
        .fold(glam::DVec3::ZERO, |a, p| a + p.as_dvec3());
    (s / img.data.len() as f64).to_array()
}

/// Per value: the mean over the renders and the standard error of that mean.
#[allow(dead_code)]
pub fn mean_and_error(values: &[Vec<f64>]) -> Vec<(f64, f64)> {
    let k = values.len() as f64;
    (0..values[0].len())
        .map(|i| {
            let m = values.iter().map(|v| v[i]).sum::<f64>() / k;
            let var = values.iter().map(|v| (v[i] - m).powi(2)).sum::<f64>() / (k - 1.0);
            (m, (var / k).sqrt())
        })
        .collect()
}
