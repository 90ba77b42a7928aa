//! Validation of a [`SceneDesc`]. STUB: being written.
use crate::error::LoadError;
use crate::scene::desc::SceneDesc;

/// Checks every invariant of the description and returns it, or the first error found.
pub fn validate(desc: SceneDesc) -> Result<SceneDesc, LoadError> {
    Ok(desc)
}
