//! Iris's own scene generator: small CC0 scenes written as glTF binary (.glb) files.
//!
//! - [`shapes`]: mesh builders (sphere, box, prism, plane, checkerboard), CCW-outward.
//! - [`lathe`]: surfaces of revolution; the glass of water (glass and water sharing their
//!   interface vertices exactly).
//! - [`gem`]: the round brilliant cut; [`cuts`]: the cuts of `iris gem` (round
//!   brilliant, emerald, oval, pear) and their preview scenes; [`stones`]: named gem materials.
//! - [`sky`]: the procedural sky map and its `.hdr` (RGBE) encoder.
//! - [`model`]: the in-memory scene model ([`GenScene`]) in Iris's conventions (metres,
//!   +Y up, linear colours, candela/lux lights).
//! - [`glb`]: the deterministic GLB writer.
//! - [`paper`]: the seed paper's figure scenes shipped in `assets/paper/`.
//! - [`scenes`]: the demonstration scenes shipped in `assets/scenes/` (glass of water,
//!   ruby, prism under the sky, and [`spectral_scenes`]: the prism beam of Fig. 5.3.1 and
//!   a diamond).
//! - [`caustic_scenes`]: scenes lit by delta lights for the photon mapper (Fig. 4.5.1's
//!   sphere and prism caustics, a diamond's caustics); [`rainbow`]: the sun-through-a-slit
//!   prism rainbow; [`focus_bench`]: the ball-lens test scene (not an asset).
//!
//! [`write_all_assets`]`(root)` regenerates them into `root/paper/`, `root/scenes/` and
//! `root/gems/` (`iris gen-assets assets`).

pub mod bench_scenes;
pub mod caustic_scenes;
pub mod cuts;
pub mod focus_bench;
pub mod gem;
pub mod glb;
mod gltf_json;
pub mod lathe;
pub mod model;
pub mod paper;
mod parts;
pub mod rainbow;
pub mod scenes;
pub mod shapes;
pub mod sky;
pub mod spectral_scenes;
pub mod stones;

pub use glb::{encode_glb, write_glb};
pub use model::{GenCamera, GenLight, GenMaterial, GenMesh, GenScene, GenVolume};
pub use paper::write_paper_scenes;
pub use scenes::write_scene_assets;

use crate::error::Result;
use std::path::{Path, PathBuf};

/// Sub-directory of the asset root holding the paper's figure scenes.
pub const PAPER_DIR: &str = "paper";
/// Sub-directory of the asset root holding the demonstration scenes and their sky map.
pub const SCENES_DIR: &str = "scenes";
/// Sub-directory of the asset root holding the `iris gem` preview scenes.
pub const GEMS_DIR: &str = "gems";

/// Writes every generated asset under `root`: [`PAPER_DIR`], [`SCENES_DIR`] and [`GEMS_DIR`]
/// (directories created as needed, files written atomically); returns the paths written.
pub fn write_all_assets(root: &Path) -> Result<Vec<PathBuf>> {
    let mut written = write_paper_scenes(&root.join(PAPER_DIR))?;
    written.extend(write_scene_assets(&root.join(SCENES_DIR))?);
    written.extend(cuts::preview::write_gem_assets(&root.join(GEMS_DIR))?);
    Ok(written)
}
