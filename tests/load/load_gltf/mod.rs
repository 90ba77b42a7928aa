//! Integration tests of the glTF loader (`iris::load::read_scene` on .gltf/.glb), one
//! module per concern: the shared third-party assets, hand-written bad inputs (each must
//! fail with the right `LoadErrorKind`, naming file and element), geometry (mirrored
//! instances, primitive modes), materials/lights/cameras, and mutation "fuzzing" that must
//! never panic. Fixture documents are built in `load_gltf/fixtures.rs`.

mod assets;
mod axes;
mod bad_inputs;
use crate::common;
pub mod fixtures;
mod fuzz;
mod geometry;
mod layers;
mod materials;
mod media;

use iris::load::read_scene;
use iris::material::MaterialDesc;
use iris::scene::desc::SceneDesc;
use iris::{LoadError, LoadErrorKind};
use std::path::{Path, PathBuf};

pub fn triangles(desc: &SceneDesc) -> usize {
    desc.meshes.iter().map(|m| m.indices.len()).sum()
}

pub fn material<'a>(desc: &'a SceneDesc, name: &str) -> &'a MaterialDesc {
    let quoted = format!("{name:?}");
    desc.materials
        .iter()
        .find(|m| m.name.ends_with(&quoted))
        .unwrap_or_else(|| {
            panic!(
                "no material {name} in {:?}",
                desc.materials.iter().map(|m| &m.name).collect::<Vec<_>>()
            )
        })
}

pub fn load(path: &Path) -> SceneDesc {
    read_scene(path).unwrap_or_else(|e| panic!("{} failed to load: {e}", path.display()))
}

pub fn expect_error(path: &Path, kind: LoadErrorKind, element: &str) -> LoadError {
    let err = match read_scene(path) {
        Ok(_) => panic!("{} loaded but should fail with {kind:?}", path.display()),
        Err(e) => e,
    };
    let text = err.to_string();
    assert_eq!(err.kind, kind, "{text}");
    let file_name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or_default();
    assert!(
        text.contains(file_name),
        "message does not name the file: {text}"
    );
    assert!(
        text.contains(element),
        "message does not name {element}: {text}"
    );
    err
}

pub fn gltf_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            gltf_files(&path, out);
        } else if matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("gltf" | "glb")
        ) {
            out.push(path);
        }
    }
}
