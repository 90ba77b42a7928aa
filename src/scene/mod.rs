//! Scenes: the plain description loaders produce ([`desc`]), its validation
//! ([`validate`]), and the immutable render `Scene` that integrators read.

pub mod desc;
pub mod validate;
