//! What the loader reads from the writer's file, for what the shipped assets do not
//! use (an orthographic camera, a coloured environment, a sky, a mesh without material).

use super::glb::encode_glb;
use crate::authoring::scene::{look_at, placed};
use crate::authoring::shapes::cuboid;
use crate::light::sky::SkyParams;
use crate::scene::desc::{CameraDesc, EnvironmentDesc, Projection, SceneDesc};
use glam::{Mat4, Vec3};

fn read(scene: &SceneDesc) -> SceneDesc {
    let dir = std::env::temp_dir().join(format!("iris-glb-read-back-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join(format!("{}.glb", scene.name));
    std::fs::write(&path, encode_glb(scene).expect("encode")).expect("write");
    let read = crate::load::gltf::load_gltf(&path).expect("load");
    let _ = std::fs::remove_file(&path);
    read
}

#[test]
fn cameras_environment_and_bare_meshes_come_back() {
    let mut bare = placed("Bare", cuboid(Vec3::ONE), 0, Some(Vec3::X));
    bare.material = None;
    let ortho = CameraDesc {
        name: "Top".into(),
        projection: Projection::Orthographic {
            xmag: 2.0,
            ymag: 1.5,
        },
        world_from_camera: Mat4::from_rotation_translation(
            glam::Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2),
            Vec3::new(0.0, 5.0, 0.0),
        ),
    };
    let persp = look_at(
        "Side",
        Vec3::new(3.0, 1.0, 2.0),
        Vec3::ZERO,
        Vec3::Y,
        0.6,
        Some(1.5),
    );
    for env in [
        EnvironmentDesc::Uniform(Vec3::new(0.1, 0.2, 0.3)),
        EnvironmentDesc::Uniform(Vec3::splat(0.25)),
        EnvironmentDesc::Sky(SkyParams {
            elevation: 12.5,
            azimuth: -30.0,
            turbidity: 3.0,
        }),
    ] {
        let scene = SceneDesc {
            name: "read-back".into(),
            meshes: vec![bare.clone()],
            cameras: vec![ortho.clone(), persp.clone()],
            environment: Some(env.clone()),
            ..SceneDesc::default()
        };
        let r = read(&scene);
        assert_eq!(r.name, "read-back");
        assert_eq!(r.environment, Some(env));
        assert_eq!(r.meshes[0].material, None);
        assert_eq!(r.meshes[0].positions, bare.positions);
        assert_eq!(r.cameras.len(), 2);
        for (w, r) in [&ortho, &persp].into_iter().zip(&r.cameras) {
            assert_eq!((&w.name, w.projection), (&r.name, r.projection));
            assert_eq!(w.world_from_camera.w_axis, r.world_from_camera.w_axis);
            assert!(r.world_from_camera.abs_diff_eq(w.world_from_camera, 1e-6));
        }
    }
}

/// The camera node's `matrix` loads exactly as the translation and rotation it was
/// made from: the same camera, bit for bit, as a file with the look-at node written
/// as T·R (so images of such files do not move).
#[test]
fn a_look_at_matrix_loads_as_its_translation_and_rotation() {
    let eye = Vec3::new(1.25, 0.75, 0.1);
    let target = Vec3::new(0.3, 0.0, 0.05);
    let scene = SceneDesc {
        name: "look-at".into(),
        cameras: vec![look_at("Cam", eye, target, Vec3::Y, 0.6, Some(16.0 / 9.0))],
        ..SceneDesc::default()
    };
    let from_matrix = read(&scene);
    let forward = target.as_dvec3() - eye.as_dvec3();
    let rotation =
        crate::authoring::gltf_json::look_rotation(forward, glam::DVec3::Y).expect("rotation");
    let bytes = encode_glb(&scene).expect("encode");
    let json_len = u32::from_le_bytes([bytes[12], bytes[13], bytes[14], bytes[15]]) as usize;
    let mut doc: serde_json::Value =
        serde_json::from_slice(&bytes[20..20 + json_len]).expect("json");
    let node = &mut doc["nodes"][0];
    node.as_object_mut().expect("node").remove("matrix");
    node["translation"] = serde_json::json!(eye.to_array());
    node["rotation"] = serde_json::json!(rotation);
    let dir = std::env::temp_dir().join(format!("iris-glb-trs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join("trs.gltf");
    std::fs::write(&path, serde_json::to_vec(&doc).expect("json")).expect("write");
    let from_trs = crate::load::gltf::load_gltf(&path).expect("load");
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(from_matrix.cameras, from_trs.cameras);
}
