//! OBJ/MTL loader. STUB: being written.
use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::SceneDesc;
use std::path::Path;

/// Loads an OBJ file (and its MTL libraries) into a world-space scene description.
pub fn load_obj(path: &Path) -> Result<SceneDesc, LoadError> {
    Err(LoadError::new(path, "", LoadErrorKind::Unsupported, "OBJ loader not built yet"))
}
