//! The model-building library: meshes, gem cuts, gem materials and the in-memory scene model,
//! written as glTF binary (.glb). `iris gem` uses it alone; the shipped scenes
//! ([`crate::assets`]) are built on it, never the reverse.
//!
//! Conventions: metres, right-handed, +Y up; triangles wind counter-clockwise seen from
//! outside (normals point out); colours are linear RGB; point and spot intensities in
//! candela, directional ones in lux (KHR_lights_punctual).
//!
//! - [`shapes`]: mesh builders (sphere, box, prism, plane, checkerboard), CCW-outward.
//! - [`lathe`]: surfaces of revolution; the glass of water (glass and water sharing their
//!   interface vertices exactly).
//! - [`gem`]: the round brilliant cut; [`cuts`]: the cuts of `iris gem` (round
//!   brilliant, emerald, oval, pear) and their preview scene; [`stones`]: named gem materials.
//! - [`scene`]: the generator's scenes are the description the loaders fill
//!   ([`crate::scene::desc::SceneDesc`]); this places meshes and look-at cameras in one and
//!   checks one for the writer; [`material`]: the materials' constructors, checks and glTF JSON;
//!   [`layers`]: their clearcoat, sheen and diffuse-transmission extensions.
//! - [`glb`]: the deterministic GLB writer, the inverse of the glTF loader for these
//!   scenes (its glTF JSON for cameras and lights in `gltf_json`).

pub mod cuts;
pub mod gem;
pub mod glb;
#[cfg(test)]
mod glb_read_back;
mod gltf_json;
mod invalid;
mod json_number;
pub mod lathe;
pub mod layers;
pub mod material;
pub mod scene;
pub mod shapes;
pub mod stones;

pub use glb::{encode_glb, write_glb};
pub use scene::{look_at, placed};
