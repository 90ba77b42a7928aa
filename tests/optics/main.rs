//! Light transport against closed forms: interfaces, metals, the sky, polarization,
//! absorption and media, furnaces, white under spectral transport, material layers, and the
//! stiff optical cases rendered on every backend.

#[path = "../common/mod.rs"]
mod common;
/// The glTF fixture documents of the loader tests (`tests/load/load_gltf/fixtures.rs`).
#[allow(dead_code)]
#[path = "../load/load_gltf/fixtures.rs"]
mod fixtures;

mod beer_lambert;
mod furnace;
mod material_layers_render;
mod media;
mod metals;
mod nested_media;
mod optics;
mod polarization;
mod sky;
mod stiff_materials;
mod stiff_optics;
mod stiff_renders;
mod white_stays_white;
