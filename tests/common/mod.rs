//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;

pub mod alloc;

/// The third-party test scenes in `../shared/assets` (override with `IRIS_SHARED_ASSETS`).
///
/// Outside the project's workplace that folder is absent: the calling test then prints
/// why it skips and returns `None`. CI sets `IRIS_REQUIRE_SHARED=1`, which turns the
/// absence into a failure so CI never skips these tests.
pub fn shared_assets() -> Option<PathBuf> {
    let dir = std::env::var_os("IRIS_SHARED_ASSETS")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/assets"));
    if dir.is_dir() {
        return Some(dir);
    }
    let required = std::env::var("IRIS_REQUIRE_SHARED").is_ok_and(|v| v == "1");
    assert!(
        !required,
        "IRIS_REQUIRE_SHARED=1 but the shared test assets are missing at {}",
        dir.display()
    );
    eprintln!(
        "SKIPPED: shared test assets not found at {} (set IRIS_SHARED_ASSETS, or IRIS_REQUIRE_SHARED=1 to fail)",
        dir.display()
    );
    None
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
pub fn sphere_in_white_environment(
    material: iris::scene::desc::MaterialDesc,
) -> iris::scene::Scene {
    use iris::scene::desc::{MeshDesc, SceneDesc};
    let sphere = iris::gen::shapes::icosphere(1.0, 4);
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
        ..Default::default()
    };
    let desc = iris::scene::validate::validate(desc).expect("valid furnace scene");
    iris::scene::Scene::build(desc, iris::accel::Backend::Auto)
        .expect("build")
        .with_environment(Some(iris::envmap::Environment::Uniform {
            radiance: glam::Vec3::ONE,
        }))
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
pub fn clear_glass(name: &str, ior: f32) -> iris::scene::desc::MaterialDesc {
    iris::scene::desc::MaterialDesc {
        name: name.into(),
        metallic: 0.0,
        roughness: 0.0,
        transmission: 1.0,
        thickness: 1.0,
        ior,
        ..Default::default()
    }
}

/// A white Lambertian material: albedo 1, no specular layer.
pub fn white_lambert() -> iris::scene::desc::MaterialDesc {
    iris::scene::desc::MaterialDesc {
        name: "white".into(),
        metallic: 0.0,
        specular: 0.0,
        ..Default::default()
    }
}

/// The caustic test scene ([`iris::gen::bench_scenes::caustic_sphere`]), built on the
/// automatic backend.
#[allow(dead_code)]
pub fn caustic_sphere(area: Option<f32>) -> (iris::scene::Scene, iris::scene::desc::CameraDesc) {
    let (desc, cam) = iris::gen::bench_scenes::caustic_sphere(area);
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
