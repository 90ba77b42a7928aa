//! Every shipped scene read back: written by [`super::write_all_assets`], loaded by the glTF
//! loader, it gives the description it was written from. Materials and lights compare as
//! whole descriptions, Iris's `extras` keys with the typed fields they are read into (the
//! loader names a material `material I "NAME"` and lists every extension the writer wrote
//! as stated; emission and directions come back to rounding); meshes come back as written,
//! cameras with their translation exact and their axes to rounding, the environment and the
//! fog as written (a map's path resolved against the file's folder).

use super::demos::SCENES;
use super::gems::GEM_ASSETS;
use super::paper::PAPER_SCENES;
use crate::authoring::cuts::preview::gem_scene;

use crate::material::MaterialDesc;
use crate::scene::desc::{CameraDesc, EnvironmentDesc, LightDesc, SceneDesc};
use glam::Vec3;
use std::path::Path;

/// (sub-directory, file name, the scene written there) for every generated `.glb`.
fn generated() -> Vec<(&'static str, &'static str, SceneDesc)> {
    let mut out: Vec<(&str, &str, SceneDesc)> = Vec::new();
    out.extend(PAPER_SCENES.map(|(name, build)| (super::PAPER_DIR, name, build())));
    out.extend(SCENES.map(|(name, build)| (super::SCENES_DIR, name, build())));
    for (name, spec) in GEM_ASSETS {
        let scene = gem_scene(&spec).expect("gem scene");
        out.push((super::GEMS_DIR, name, scene));
    }
    let materials = super::materials::FILES.into_iter();
    out.extend(
        materials
            .zip(super::materials::material_scenes())
            .map(|(name, scene)| (super::MATERIALS_DIR, name, scene)),
    );
    out.extend(
        super::material_layers::MATERIAL_SCENES
            .map(|(name, build)| (super::MATERIALS_DIR, name, build())),
    );
    out
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() <= 1e-6 * b.length().max(1.0)
}

/// The material the loader gives for `written` (index `i`), given what it read (`read`)
/// for the values that come back only to rounding.
fn expected_material(i: usize, written: &MaterialDesc, read: &MaterialDesc) -> MaterialDesc {
    let mut m = written.clone();
    m.name = format!("material {i} {:?}", written.name);
    assert!(close(read.emissive, m.emissive), "{}: emission", m.name);
    m.emissive = read.emissive;
    assert!(m.stated.is_subset(&read.stated), "{}: stated", m.name);
    m.stated = read.stated.clone();
    m
}

fn check_lights(file: &str, written: &[LightDesc], read: &[LightDesc]) {
    assert_eq!(written.len(), read.len(), "{file}: lights");
    for (w, r) in written.iter().zip(read) {
        let direction = |l: &LightDesc| match l {
            LightDesc::Spot { direction, .. } | LightDesc::Directional { direction, .. } => {
                Some(*direction)
            }
            LightDesc::Point { .. } => None,
        };
        let (dw, dr) = (direction(w), direction(r));
        assert_eq!(dw.is_some(), dr.is_some(), "{file}: {}", w.name());
        if let (Some(dw), Some(dr)) = (dw, dr) {
            assert!(close(dr, dw.normalize()), "{file}: {} direction", w.name());
        }
        let mut expected = w.clone();
        if let (
            LightDesc::Spot { direction, .. } | LightDesc::Directional { direction, .. },
            Some(d),
        ) = (&mut expected, dr)
        {
            *direction = d;
        }
        assert_eq!(&expected, r, "{file}");
    }
}

fn check_meshes(file: &str, written: &SceneDesc, read: &SceneDesc) {
    assert_eq!(written.meshes.len(), read.meshes.len(), "{file}: meshes");
    for (w, r) in written.meshes.iter().zip(&read.meshes) {
        assert_eq!(w.positions, r.positions, "{file}: {} positions", w.name);
        assert_eq!(w.indices, r.indices, "{file}: {} indices", w.name);
        assert_eq!(w.material, r.material, "{file}: {} material", w.name);
        assert_eq!(w.normals.len(), r.normals.len(), "{file}: {}", w.name);
        let normals = w.normals.iter().zip(&r.normals);
        assert!(normals.into_iter().all(|(&a, &b)| close(b, a.normalize())));
        assert_eq!(w.uvs, r.uvs, "{file}: {} uvs", w.name);
    }
}

/// The loader keeps a camera's matrix with its axes made orthonormal again in `f64`
/// (`load::gltf::scene`): the translation comes back exactly, the axes to rounding.
fn check_cameras(file: &str, written: &[CameraDesc], read: &[CameraDesc]) {
    assert_eq!(written.len(), read.len(), "{file}: cameras");
    for (w, r) in written.iter().zip(read) {
        assert_eq!((&w.name, w.projection), (&r.name, r.projection), "{file}");
        let (mw, mr) = (w.world_from_camera, r.world_from_camera);
        assert_eq!(mw.w_axis, mr.w_axis, "{file}: eye");
        assert!(mw.abs_diff_eq(mr, 1e-6), "{file}: {} axes", w.name);
    }
}

fn check_scene(file: &str, written: &SceneDesc, read: &SceneDesc) {
    assert_eq!(written.name, read.name, "{file}");
    assert_eq!(written.materials.len(), read.materials.len(), "{file}");
    for (i, (w, r)) in written.materials.iter().zip(&read.materials).enumerate() {
        assert_eq!(&expected_material(i, w, r), r, "{file}");
    }
    check_lights(file, &written.lights, &read.lights);
    check_meshes(file, written, read);
    check_cameras(file, &written.cameras, &read.cameras);
    let environment = written.environment.clone().map(|e| match e {
        EnvironmentDesc::Map(name) => EnvironmentDesc::Map(read.source.with_file_name(name)),
        other => other,
    });
    assert_eq!(environment, read.environment, "{file}");
    assert_eq!(written.fog, read.fog, "{file}");
}

/// The one shipped scene with fog keeps it: its specification is a constant that parses.
#[test]
fn the_hazy_prism_has_its_fog() {
    assert!(super::media::hazy_prism().fog.is_some());
}

#[test]
fn every_generated_scene_reads_back_as_written() {
    let root = std::env::temp_dir().join(format!("iris-round-trip-{}", std::process::id()));
    let written = super::write_all_assets(&root).expect("write assets");
    let glb = written
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "glb"));
    let scenes = generated();
    assert_eq!(scenes.len(), glb.count());
    for (dir, name, written) in &scenes {
        let path = root.join(dir).join(name);
        let read = crate::load::gltf::load_gltf(Path::new(&path)).expect("load");
        check_scene(name, written, &read);
    }
    let _ = std::fs::remove_dir_all(&root);
}
