//! Textured materials end to end through the `iris` binary: `texCoord`, KHR_texture_transform
//! and textured emitters. The helpers (`gltf` documents, `render` of them, `texture` images,
//! `features` and `emitter` layouts) are shared by the three test modules
//! (`photon/photon_mirror.rs` includes `gltf` and `render` too).

#[path = "../common/mod.rs"]
mod common;

mod emitter;
mod features;
mod gltf;
mod render;
mod texture;

mod texture_coords;
mod texture_transform;
mod textured_emitter;
