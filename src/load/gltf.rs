//! glTF 2.0 loader (.gltf and .glb). STUB: being written.
use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::SceneDesc;
use std::path::Path;

/// Loads a glTF/GLB file into a world-space scene description.
pub fn load_gltf(path: &Path) -> Result<SceneDesc, LoadError> {
    Err(LoadError::new(path, "", LoadErrorKind::Unsupported, "glTF loader not built yet"))
}
