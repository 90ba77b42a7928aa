//! Scene loaders: file → plain [`SceneDesc`] → [`validate`](crate::scene::validate).
//! The format is chosen by the file extension (`.gltf`, `.glb`, `.obj`). Referenced files
//! are read through [`files::Files`]; [`fuzz_entry`] runs the same loaders from memory.

pub mod decode;
pub mod files;
pub mod fuzz_entry;
pub mod gltf;
pub mod obj;
pub mod panic_net;

use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::SceneDesc;
use std::path::Path;

/// Reads a scene file into a plain description (not yet validated).
pub fn read_scene(path: &Path) -> Result<SceneDesc, LoadError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "gltf" | "glb" => gltf::load_gltf(path),
        "obj" => obj::load_obj(path),
        _ => Err(LoadError::new(
            path,
            "",
            LoadErrorKind::Unsupported,
            "unknown scene format (expected .gltf, .glb or .obj)",
        )),
    }
}

/// Reads and validates a scene file: the description every render starts from.
pub fn load_scene(path: &Path) -> Result<SceneDesc, LoadError> {
    let desc = read_scene(path)?;
    crate::scene::validate::validate(desc)
}
