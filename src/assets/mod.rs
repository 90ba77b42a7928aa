//! The scenes Iris ships and tests with, built on the model library ([`crate::authoring`]):
//! small CC0 scenes written as glTF binary (.glb) files, in the library's conventions
//! (metres, +Y up, linear colours, candela/lux lights).
//!
//! - [`paper`]: the figure scenes of Cropp & Zhang, "Light Refraction with Dispersion", shipped in
//!   `assets/paper/`.
//! - [`demos`]: the demonstration scenes shipped in `assets/scenes/` (glass of water,
//!   ruby, prism under the sky, and [`spectral`]: the prism beam of Fig. 5.3.1 and
//!   a diamond; [`media`]: the milky tank, the hazy prism and the opal; [`birefringence`]:
//!   the calcite rhomb, moissanite beside diamond, the tourmaline bars); [`sky`]: the
//!   procedural sky map and its `.hdr` (RGBE) encoder.
//! - [`caustic`]: scenes lit by delta lights for the photon mapper (Fig. 4.5.1's
//!   sphere and prism caustics, a diamond's caustics); [`rainbow`]: the sun-through-a-slit
//!   prism rainbow; [`focus_bench`]: the ball-lens test scene (not an asset);
//!   [`bench`](mod@bench): the caustic sphere of the tests and benchmarks (not an asset).
//! - [`gems`]: the `iris gem` previews shipped in `assets/gems/`.
//! - [`materials`]: iridescence and anisotropy test scenes, and [`material_layers`]: the
//!   clearcoat, sheen and diffuse-transmission test scenes, both shipped in
//!   `assets/materials/`.
//!
//! [`write_all_assets`]`(root)` regenerates them into `root/paper/`, `root/scenes/`,
//! `root/gems/` and `root/materials/` (`iris gen-assets assets`).

pub mod bench;
pub mod birefringence;
pub mod caustic;
pub mod demos;
pub mod focus_bench;
pub mod gems;
pub mod material_layers;
pub mod materials;
pub mod media;
pub mod paper;
mod parts;
pub mod rainbow;
#[cfg(test)]
mod round_trip;
pub mod sky;
pub mod spectral;

pub use demos::write_scene_assets;
pub use paper::write_paper_scenes;

use crate::error::Result;
use std::path::{Path, PathBuf};

/// Sub-directory of the asset root holding the paper's figure scenes.
pub const PAPER_DIR: &str = "paper";
/// Sub-directory of the asset root holding the demonstration scenes and their sky map.
pub const SCENES_DIR: &str = "scenes";
/// Sub-directory of the asset root holding the `iris gem` preview scenes.
pub const GEMS_DIR: &str = "gems";
/// Sub-directory of the asset root holding the material-extension test scenes.
pub const MATERIALS_DIR: &str = "materials";

/// Writes every generated asset under `root`: [`PAPER_DIR`], [`SCENES_DIR`], [`GEMS_DIR`]
/// and [`MATERIALS_DIR`]
/// (directories created as needed, files written atomically); returns the paths written.
pub fn write_all_assets(root: &Path) -> Result<Vec<PathBuf>> {
    let mut written = write_paper_scenes(&root.join(PAPER_DIR))?;
    written.extend(write_scene_assets(&root.join(SCENES_DIR))?);
    written.extend(gems::write_gem_assets(&root.join(GEMS_DIR))?);
    written.extend(materials::write_material_assets(&root.join(MATERIALS_DIR))?);
    written.extend(material_layers::write_material_assets(
        &root.join(MATERIALS_DIR),
    )?);
    Ok(written)
}
