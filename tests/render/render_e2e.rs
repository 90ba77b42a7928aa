//! End to end: render the project's scenes through `iris::app` and check properties of the
//! images: determinism (same seed → identical bytes, whatever the thread count), agreement
//! between the Embree and BVH backends, and that a node with a negative-determinant
//! transform renders exactly like its mirrored mesh.

use crate::common;

use glam::{Mat3, Quat, Vec3};
use iris::accel::Backend;
use iris::app::{render_command, RenderOptions};
use iris::image::ImageRgb;
use iris::integrator::{Method, PhotonSettings};
use iris::output::{read_exr, DisplayOptions};
use std::path::{Path, PathBuf};

fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/paper")
        .join(name)
}

fn opts(scene: &Path, out: &Path, accel: Backend, threads: usize) -> RenderOptions {
    RenderOptions {
        scene: scene.to_path_buf(),
        output: Some(out.to_path_buf()),
        size: Some((96, 72)),
        spp: 3,
        method: Method::Whitted,
        max_depth: 64,
        time_limit: None,
        checkpoint: None,
        watch: false,
        photon: Default::default(),
        accel,
        seed: 7,
        sampler: Default::default(),
        threads,
        camera: None,
        look_at: None,
        display: DisplayOptions::default(),
        quiet: true,
        spectral: Default::default(),
        polarization: Default::default(),
        polarizer: None,
        env: None,
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
    }
}

fn rmse(a: &ImageRgb, b: &ImageRgb) -> (f64, f64) {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let mut se = 0.0f64;
    let mut mean = 0.0f64;
    for (x, y) in a.data.iter().zip(&b.data) {
        let d = (*x - *y).as_dvec3();
        se += d.length_squared() / 3.0;
        mean += (x.x + x.y + x.z) as f64 / 3.0;
    }
    let n = a.data.len() as f64;
    ((se / n).sqrt(), mean / n)
}

#[test]
fn same_seed_gives_identical_bytes_across_thread_counts() {
    let dir = common::scratch_dir("e2e_determinism");
    let scene = asset("fig7_1_spheres.glb");
    let mut files = Vec::new();
    for (i, threads) in [1usize, 2, 2].into_iter().enumerate() {
        let out = dir.join(format!("run{i}.png"));
        render_command(&opts(&scene, &out, Backend::Auto, threads)).expect("render");
        files.push(std::fs::read(&out).expect("read png"));
    }
    assert!(files[0].len() > 1000);
    assert_eq!(files[0], files[1], "1 thread vs 2 threads differ");
    assert_eq!(files[1], files[2], "two 2-thread runs differ");
    // A different seed must change the image (the test can fail).
    let out = dir.join("other_seed.png");
    let mut o = opts(&scene, &out, Backend::Auto, 2);
    o.seed = 8;
    render_command(&o).expect("render");
    assert_ne!(std::fs::read(&out).unwrap(), files[0]);
}

#[test]
fn embree_and_bvh_images_agree() {
    if !cfg!(feature = "embree") {
        eprintln!("SKIPPED: built without the embree feature; nothing to compare the BVH with");
        return;
    }
    let dir = common::scratch_dir("e2e_backends");
    for name in [
        "fig7_1_spheres.glb",
        "fig7_2_bubble.glb",
        "fig4_4_1_prism.glb",
    ] {
        let scene = asset(name);
        let a = dir.join(format!("{name}.embree.exr"));
        let b = dir.join(format!("{name}.bvh.exr"));
        render_command(&opts(&scene, &a, Backend::Embree, 2)).expect("embree render");
        render_command(&opts(&scene, &b, Backend::Bvh, 2)).expect("bvh render");
        let (ia, ib) = (read_exr(&a).unwrap(), read_exr(&b).unwrap());
        let (e, mean) = rmse(&ia, &ib);
        let mean_b = ib
            .data
            .iter()
            .map(|p| (p.x + p.y + p.z) as f64 / 3.0)
            .sum::<f64>()
            / ib.data.len() as f64;
        let differing = ia
            .data
            .iter()
            .zip(&ib.data)
            .filter(|(x, y)| ((**x - **y).abs().max_element() as f64) > 0.05 * mean)
            .count();
        // Same rays and seeds: only a ray that grazes an edge can take another branch, and
        // then Russian roulette may send that pixel's path elsewhere (its value can change
        // by a whole branch weight). So: at most 0.5% of pixels may differ by more than 5%
        // of the mean, the image means agree within 0.5%, and the RMSE stays under 5% of the
        // mean. A systematic disagreement (wrong normals, a missed mesh) breaks all three.
        let limit = ia.data.len() / 200;
        assert!(
            differing <= limit,
            "{name}: {differing} pixels differ (limit {limit})"
        );
        assert!(
            (mean - mean_b).abs() <= 0.005 * mean,
            "{name}: means {mean} vs {mean_b}"
        );
        assert!(e <= 0.05 * mean, "{name}: RMSE {e} vs mean {mean}");
    }
}

/// Writes a .gltf + .bin with a floor, a glass prism (mirrored by the node or in the data),
/// a point light and a camera.
fn write_prism_gltf(dir: &Path, name: &str, mirror_in_node: bool) -> PathBuf {
    let floor = iris::authoring::shapes::ground_plane(2.0, 2.0);
    let prism = iris::authoring::shapes::prism(0.5, 0.8)
        .transformed(Mat3::from_rotation_y(0.6), Vec3::new(0.35, 0.3, 0.1));
    let mirror = Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0));
    // `transformed` flips winding for a negative determinant, as the loader must.
    let prism = if mirror_in_node {
        prism
    } else {
        prism.transformed(mirror, Vec3::ZERO)
    };
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    for mesh in [&floor, &prism] {
        let pos_off = bin.len();
        for p in &mesh.positions {
            for c in p.to_array() {
                bin.extend_from_slice(&c.to_le_bytes());
            }
        }
        let idx_off = bin.len();
        for t in &mesh.indices {
            for i in t {
                bin.extend_from_slice(&i.to_le_bytes());
            }
        }
        let (lo, hi) = mesh.positions.iter().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(l, h), p| (l.min(*p), h.max(*p)),
        );
        let v = views.len();
        views.push(serde_json::json!({"buffer": 0, "byteOffset": pos_off, "byteLength": idx_off - pos_off}));
        views.push(serde_json::json!({"buffer": 0, "byteOffset": idx_off, "byteLength": bin.len() - idx_off}));
        let a = accessors.len();
        accessors.push(serde_json::json!({"bufferView": v, "componentType": 5126, "count": mesh.positions.len(), "type": "VEC3", "min": lo.to_array(), "max": hi.to_array()}));
        accessors.push(serde_json::json!({"bufferView": v + 1, "componentType": 5125, "count": mesh.indices.len() * 3, "type": "SCALAR"}));
        meshes.push(serde_json::json!({"primitives": [{"attributes": {"POSITION": a}, "indices": a + 1, "material": meshes.len()}]}));
    }
    std::fs::write(dir.join(format!("{name}.bin")), &bin).unwrap();
    let cam = iris::camera::look_at(Vec3::new(0.4, 1.3, 2.2), Vec3::new(0.0, 0.2, 0.0), Vec3::Y);
    let (_, rot, pos) = cam.to_scale_rotation_translation();
    let light_rot = Quat::IDENTITY;
    let prism_node = if mirror_in_node {
        serde_json::json!({"mesh": 1, "scale": [-1.0, 1.0, 1.0]})
    } else {
        serde_json::json!({"mesh": 1})
    };
    let doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_volume", "KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 40.0}]}},
        "buffers": [{"uri": format!("{name}.bin"), "byteLength": bin.len()}],
        "bufferViews": views,
        "accessors": accessors,
        "meshes": meshes,
        "materials": [
            {"pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.6, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.8}},
            {"pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.0},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                            "KHR_materials_volume": {"thicknessFactor": 0.5}}}
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 1.333}}],
        "nodes": [
            {"mesh": 0},
            prism_node,
            {"camera": 0, "rotation": rot.to_array(), "translation": pos.to_array()},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [1.0, 2.5, 1.5], "rotation": light_rot.to_array()}
        ],
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "scene": 0
    });
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, serde_json::to_vec_pretty(&doc).unwrap()).unwrap();
    path
}

#[test]
fn negative_determinant_node_renders_like_its_mirrored_mesh() {
    let dir = common::scratch_dir("e2e_mirror");
    let by_node = write_prism_gltf(&dir, "by_node", true);
    let in_data = write_prism_gltf(&dir, "in_data", false);
    for backend in [Backend::Bvh, Backend::Auto] {
        let a = dir.join("by_node.exr");
        let b = dir.join("in_data.exr");
        render_command(&opts(&by_node, &a, backend, 2)).expect("render by_node");
        render_command(&opts(&in_data, &b, backend, 2)).expect("render in_data");
        let (ia, ib) = (read_exr(&a).unwrap(), read_exr(&b).unwrap());
        let (e, mean) = rmse(&ia, &ib);
        assert!(mean > 0.0, "image is black");
        // The same floats reach the renderer in the same order, so the images are identical.
        assert!(e == 0.0, "{backend:?}: RMSE {e} (mean {mean})");
    }
}

#[test]
fn emissive_triangles_light_the_cornell_box() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let dir = common::scratch_dir("e2e_cornell");
    let scene = shared.join("obj/CornellBox-McGuire/CornellBox-Original.obj");
    let out = dir.join("cornell.exr");
    // The file has no camera: look into the open front of the box (the default
    // three-quarter view from 35° above sees mostly its unlit outside).
    let preview = iris::app::PreviewOptions {
        view: Some(iris::framing::View::Front),
        ..Default::default()
    };
    let summary = render_command(&RenderOptions {
        preview,
        ..opts(&scene, &out, Backend::Auto, 2)
    })
    .expect("render");
    // The ceiling light (Ke) is the only light: no default lights may be added.
    assert!(
        !summary.notes.iter().any(|n| n.contains("default key")),
        "{:?}",
        summary.notes
    );
    let img = read_exr(&out).unwrap();
    // Direct light from the emitter: a good share of the visible walls and floor is lit.
    let lit = img.data.iter().filter(|p| p.max_element() > 0.05).count();
    assert!(lit > img.data.len() / 10, "only {lit} lit pixels");
    assert!(img.data.iter().all(|p| p.is_finite()));
}

/// A white-environment furnace for direct light: a Lambertian sphere (albedo 0.8, no
/// specular layer) under a uniform environment of radiance 1 sees the whole unoccluded
/// hemisphere at every point, so its radiance is exactly 0.8 and the background is 1.
/// Per-sample std of the env estimator is ≈ 1.03 (f·cos/pdf = 3.2·cos on half the
/// sphere); 256 spp over 144 central pixels gives a standard error of ≈ 0.005, so the 3 %
/// tolerance (0.024) is about 5σ, while a missing cos, a wrong pdf or a 1/π slip is off by
/// 20 % or more.
#[test]
fn lambertian_sphere_in_uniform_environment_has_albedo_radiance() {
    let scene = common::sphere_in_white_environment(iris::material::MaterialDesc {
        name: "white".into(),
        base_color: glam::Vec4::new(0.8, 0.8, 0.8, 1.0),
        metallic: 0.0,
        specular: 0.0,
        ..Default::default()
    });
    assert!(
        scene.lights().is_empty(),
        "the environment replaces the default lights"
    );
    let cam = iris::camera::Camera::new(
        &iris::scene::desc::CameraDesc {
            name: "c".into(),
            projection: iris::scene::desc::Projection::Perspective {
                yfov: 0.6,
                aspect: None,
            },
            world_from_camera: iris::camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y),
        },
        32,
        32,
    );
    let integrator =
        iris::integrator::Integrator::new(Method::Whitted, 8, &PhotonSettings::default())
            .expect("a resolved method");
    let settings = iris::render::RenderSettings::quiet_rgb((32, 32), 256, 3, 2);
    let (img, _) = integrator.render(&scene, &cam, &settings).unwrap();
    // The sphere (radius 1 at distance 5, yfov 0.6) spans ~ ±0.2 rad: pixels within 6 of the
    // centre are on it; corners are background.
    let mut sum = 0.0f64;
    let mut n = 0;
    for y in 10..22u32 {
        for x in 10..22u32 {
            let p = img.data[(y * 32 + x) as usize];
            sum += p.x as f64;
            n += 1;
        }
    }
    let mean = sum / n as f64;
    assert!(
        (mean - 0.8).abs() < 0.024,
        "sphere radiance {mean}, expected 0.8"
    );
    assert_eq!(
        img.data[0],
        Vec3::ONE,
        "background must be the environment radiance"
    );
}
