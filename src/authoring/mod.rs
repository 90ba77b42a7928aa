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
//! - [`scene`]: the in-memory scene model ([`GenScene`]) in Iris's conventions;
//!   [`layers`]: its materials' clearcoat, sheen and diffuse-transmission layers.
//! - [`glb`]: the deterministic GLB writer (its glTF JSON for cameras, lights and
//!   materials in `gltf_json`).

pub mod cuts;
pub mod gem;
pub mod glb;
mod gltf_json;
pub mod lathe;
pub mod layers;
pub mod scene;
pub mod shapes;
pub mod stones;

pub use glb::{encode_glb, write_glb};
pub use layers::{GenClearcoat, GenDiffuseTransmission, GenLayers, GenSheen};
pub use scene::{GenCamera, GenLight, GenMaterial, GenMesh, GenScene, GenVolume};
