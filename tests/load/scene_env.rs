//! The glTF scene-level `extras.iris_environment` (an environment light named by the file):
//! a map path relative to the glTF file, a grey value, `[r, g, b]` or a computed sky
//! (`"sky:elevation=…"`, which also brings its sun as a directional light); bad values are
//! load errors naming the file and the element; `--env` overrides it and `--env none` turns
//! it off.

use crate::common;

use glam::Vec3;
use iris::accel::Backend;
use iris::app::{render_command, resolve_environment, RenderOptions};
use iris::assets::sky::encode_hdr;
use iris::authoring::shapes::cuboid;
use iris::authoring::{encode_glb, look_at, placed};
use iris::error::Error;
use iris::integrator::Method;
use iris::light::env::Environment;
use iris::material::MaterialDesc;
use iris::output::{read_exr, DisplayOptions};
use iris::scene::desc::{EnvironmentDesc, SceneDesc};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// A box behind a camera that looks at the empty sky.
fn scene() -> SceneDesc {
    SceneDesc {
        name: "env test".into(),
        meshes: vec![placed(
            "Box",
            cuboid(Vec3::splat(0.1)),
            0,
            Some(Vec3::new(0.0, 0.0, 5.0)),
        )],
        materials: vec![MaterialDesc::diffuse("Grey", Vec3::splat(0.5))],
        lights: vec![],
        cameras: vec![look_at(
            "Cam",
            Vec3::ZERO,
            Vec3::NEG_Z,
            Vec3::Y,
            0.5,
            Some(1.0),
        )],
        ..SceneDesc::default()
    }
}

/// Writes `scene()` as `dir/name` with `extras` (any JSON, also what no description
/// holds) set on its glTF scene, and returns its path.
fn write(dir: &Path, name: &str, extras: Option<Value>) -> PathBuf {
    let bytes = encode_glb(&scene()).expect("encode");
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().expect("length")) as usize;
    let mut doc: Value = serde_json::from_slice(&bytes[20..20 + json_len]).expect("json");
    let bin = &bytes[20 + json_len + 8..];
    if let Some(extras) = extras {
        doc["scenes"][0]["extras"] = extras;
    }
    let path = dir.join(name);
    std::fs::write(&path, common::glb(&doc, bin)).expect("write");
    path
}

/// A tiny uniform 8×4 `.hdr` map of radiance `c`.
fn write_hdr(path: &Path, c: f64) {
    let texels = vec![glam::DVec3::splat(c); 32];
    std::fs::write(path, encode_hdr(8, 4, &texels)).expect("write hdr");
}

fn load_err(path: &Path) -> String {
    match iris::load::load_scene(path) {
        Ok(d) => panic!("{}: loaded {:?}", path.display(), d.environment),
        Err(e) => e.to_string(),
    }
}

#[test]
fn good_values_are_read_and_paths_resolve_next_to_the_file() {
    let dir = common::scratch_dir("scene_env_good");
    std::fs::create_dir_all(dir.join("maps")).expect("mkdir");
    write_hdr(&dir.join("maps/sky.HDR"), 1.0);
    let cases = [
        (
            json!({"iris_environment": "maps/sky.HDR"}),
            Some(EnvironmentDesc::Map(dir.join("maps/sky.HDR"))),
        ),
        (
            json!({"iris_environment": 0.25}),
            Some(EnvironmentDesc::Uniform(Vec3::splat(0.25))),
        ),
        (
            json!({"iris_environment": [1, 0.5, 0]}),
            Some(EnvironmentDesc::Uniform(Vec3::new(1.0, 0.5, 0.0))),
        ),
        (
            json!({"iris_environment": "sky:elevation=20, azimuth=45"}),
            Some(EnvironmentDesc::Sky(iris::light::sky::SkyParams {
                elevation: 20.0,
                azimuth: 45.0,
                turbidity: 2.0,
            })),
        ),
        (json!({"other": 1}), None),
        (json!("not an object"), None),
    ];
    for (i, (extras, expected)) in cases.into_iter().enumerate() {
        let path = write(&dir, &format!("s{i}.glb"), Some(extras.clone()));
        let desc = iris::load::load_scene(&path).unwrap_or_else(|e| panic!("{extras}: {e}"));
        assert_eq!(desc.environment, expected, "{extras}");
    }
    let none = write(&dir, "none.glb", None);
    assert_eq!(
        iris::load::load_scene(&none).expect("load").environment,
        None
    );
}

#[test]
fn bad_values_name_the_file_and_the_element() {
    let dir = common::scratch_dir("scene_env_bad");
    std::fs::write(dir.join("sky.png"), b"not a map").expect("write");
    let cases = [
        (
            json!("missing.hdr"),
            "missing.hdr: No such file or directory",
        ),
        (json!("sky.png"), ".exr or .hdr"),
        (json!(""), "expected a .exr/.hdr file name"),
        (json!(-1.0), "finite and ≥ 0"),
        (json!([1, 2]), "expected a .exr/.hdr file name"),
        (json!([1, -2, 3]), "finite numbers ≥ 0"),
        (json!([1, "x", 3]), "finite numbers ≥ 0"),
        (json!(true), "expected a .exr/.hdr file name"),
        (json!("sky:elevation=100"), "elevation 100 is outside"),
        (json!("sky:azimuth=3"), "elevation=DEG is required"),
    ];
    for (i, (value, reason)) in cases.into_iter().enumerate() {
        let path = write(
            &dir,
            &format!("b{i}.glb"),
            Some(json!({"iris_environment": value})),
        );
        let msg = load_err(&path);
        for part in [
            path.display().to_string().as_str(),
            "scene 0 \"env test\" extras.iris_environment",
            reason,
        ] {
            assert!(msg.contains(part), "{value}: {msg:?} lacks {part:?}");
        }
    }
    // A map that exists but is not a valid .hdr fails when the environment is built,
    // naming the map file.
    std::fs::write(dir.join("broken.hdr"), b"garbage").expect("write");
    let path = write(
        &dir,
        "broken.glb",
        Some(json!({"iris_environment": "broken.hdr"})),
    );
    let desc = iris::load::load_scene(&path).expect("load");
    let err = resolve_environment(None, desc.environment).expect_err("broken map");
    assert!(
        matches!(&err, Error::Load(_)) && err.to_string().contains("broken.hdr"),
        "{err}"
    );
}

#[test]
fn flag_overrides_the_file_and_none_turns_it_off() {
    let grey = Some(EnvironmentDesc::Uniform(Vec3::splat(0.3)));
    let red = Environment::Uniform { radiance: Vec3::X };
    let radiance = |e: Option<Environment>| match e {
        Some(Environment::Uniform { radiance }) => Some(radiance),
        Some(Environment::Map(_) | Environment::Sky(_)) => Some(Vec3::NAN),
        None => None,
    };
    let r = |flag, file| radiance(resolve_environment(flag, file).expect("resolve"));
    assert_eq!(r(None, grey.clone()), Some(Vec3::splat(0.3)));
    assert_eq!(r(Some(Some(red.clone())), grey.clone()), Some(Vec3::X));
    assert_eq!(r(Some(None), grey), None);
    assert_eq!(r(None, None), None);
}

/// Mean linear colour of an EXR render of `scene` with the given `--env` choice.
fn render_mean(scene: &Path, env: Option<Option<Environment>>, out: &Path) -> Vec3 {
    let opts = RenderOptions {
        scene: scene.to_path_buf(),
        output: Some(out.to_path_buf()),
        size: Some((8, 8)),
        spp: 1,
        method: Method::Path,
        max_depth: 4,
        time_limit: None,
        checkpoint: None,
        watch: false,
        photon: Default::default(),
        accel: Backend::Bvh,
        seed: 1,
        sampler: Default::default(),
        threads: 1,
        camera: None,
        look_at: None,
        display: DisplayOptions::default(),
        quiet: true,
        spectral: Default::default(),
        polarization: Default::default(),
        polarizer: None,
        env,
        fog: None,
        measure: Default::default(),
        preview: Default::default(),
        looks: Vec::new(),
        explain: false,
        denoise: Default::default(),
        adaptive: Default::default(),
        spin: None,
        exr_copy: None,
        shard: None,
    };
    render_command(&opts).expect("render");
    let img = read_exr(out).expect("read");
    img.data.iter().copied().sum::<Vec3>() / img.data.len() as f32
}

#[test]
fn renders_use_the_file_environment_unless_overridden() {
    let dir = common::scratch_dir("scene_env_render");
    write_hdr(&dir.join("sky.hdr"), 0.5);
    let grey = write(
        &dir,
        "grey.glb",
        Some(json!({"iris_environment": [0.25, 0.5, 1.0]})),
    );
    let mapped = write(
        &dir,
        "mapped.glb",
        Some(json!({"iris_environment": "sky.hdr"})),
    );
    let out = dir.join("out.exr");
    // The camera sees only sky, so every pixel is the environment's radiance (RGBE keeps
    // 0.5 exactly; 1e-6 allows for float summation).
    let close = |a: Vec3, b: Vec3| (a - b).abs().max_element() < 1e-6;
    let m = render_mean(&grey, None, &out);
    assert!(close(m, Vec3::new(0.25, 0.5, 1.0)), "{m}");
    let m = render_mean(&mapped, None, &out);
    assert!(close(m, Vec3::splat(0.5)), "{m}");
    let red = Environment::Uniform { radiance: Vec3::X };
    let m = render_mean(&grey, Some(Some(red)), &out);
    assert!(close(m, Vec3::X), "{m}");
    let m = render_mean(&grey, Some(None), &out);
    assert!(close(m, Vec3::ZERO), "--env none: {m}");
}

#[test]
fn cli_env_flag_defaults_to_the_file_and_none_turns_it_off() {
    let dir = common::scratch_dir("scene_env_cli");
    let scene = write(&dir, "grey.glb", Some(json!({"iris_environment": 0.5})));
    let run = |extra: &[&str]| -> Vec3 {
        let out = dir.join("cli.exr");
        let mut args = vec!["render", scene.to_str().expect("utf-8 path"), "-o"];
        args.extend([
            out.to_str().expect("utf-8 path"),
            "--size",
            "4x4",
            "--quiet",
        ]);
        args.extend(["--spp", "1", "--method", "path"]);
        args.extend(extra);
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_iris"))
            .args(&args)
            .output()
            .expect("run iris");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let img = read_exr(&out).expect("read");
        img.data.iter().copied().sum::<Vec3>() / img.data.len() as f32
    };
    // Sky-only view: pixels equal the environment radiance (1e-6: float summation).
    assert!((run(&[]) - Vec3::splat(0.5)).abs().max_element() < 1e-6);
    assert!(
        (run(&["--env", "2"]) - Vec3::splat(2.0))
            .abs()
            .max_element()
            < 1e-6
    );
    assert_eq!(run(&["--env", "none"]), Vec3::ZERO);
}

/// A file's sky becomes the scene's environment, and its sun a directional light travelling
/// away from the sun (down, towards −X for a sun in the +X sky), orange-white at 20°.
#[test]
fn a_sky_in_the_file_brings_its_sun() {
    let dir = common::scratch_dir("scene_env_sky");
    let path = write(
        &dir,
        "sky.glb",
        Some(json!({"iris_environment": "sky:elevation=20,azimuth=90"})),
    );
    let p = iris::prepare::prepare(&path, &Default::default()).expect("prepare");
    assert!(matches!(p.scene.environment(), Some(Environment::Sky(_))));
    let suns: Vec<_> = p
        .scene
        .lights()
        .iter()
        .filter_map(|l| match l.light {
            iris::light::Light::Directional {
                direction,
                illuminance,
            } => Some((direction, illuminance)),
            _ => None,
        })
        .collect();
    assert_eq!(suns.len(), 1, "{:?}", p.scene.lights());
    let (dir, e) = suns[0];
    let want = -Vec3::new(20f32.to_radians().cos(), 20f32.to_radians().sin(), 0.0);
    assert!(dir.abs_diff_eq(want, 1e-4), "{dir} vs {want}");
    assert!(e.x > e.y && e.y > e.z && e.z > 0.0, "{e}");
}
