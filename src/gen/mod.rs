//! Iris's own scene generator: small CC0 scenes written as glTF binary (.glb) files.
//!
//! - [`shapes`]: mesh builders (sphere, box, prism, plane, checkerboard), CCW-outward.
//! - [`model`]: the in-memory scene model ([`GenScene`]) in Iris's conventions (metres,
//!   +Y up, linear colours, candela/lux lights).
//! - [`glb`]: the deterministic GLB writer.
//! - [`paper`]: the seed paper's figure scenes shipped in `assets/paper/`;
//!   [`write_paper_scenes`] regenerates them (`iris gen-assets DIR`).

pub mod glb;
mod gltf_json;
pub mod model;
pub mod paper;
pub mod shapes;

pub use glb::{encode_glb, write_glb};
pub use model::{GenCamera, GenLight, GenMaterial, GenMesh, GenScene, GenVolume};
pub use paper::write_paper_scenes;
