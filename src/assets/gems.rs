//! The stones shipped in `assets/gems/` (`iris gen-assets`): the [`GemSpec`]s of the
//! `iris gem` previews written under their file names. Units: sizes in millimetres
//! ([`GemSpec::size_mm`]); the scenes are [`gem_scene`]'s (metres, +Y up).

use crate::authoring::cuts::preview::{gem_scene, GemSpec};
use crate::authoring::cuts::Cut;
use crate::authoring::glb::write_glb;
use crate::authoring::stones::Stone;
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// The stones shipped in `assets/gems/`: file name and what it holds. The four previews
/// carry camera, lights and floor; `round_diamond_bare.glb` is the stone alone (what an
/// artist's file usually is), for the drop-in preview.
pub const GEM_ASSETS: [(&str, GemSpec); 5] = [
    (
        "round_diamond.glb",
        spec(Cut::Round, Stone::Diamond, 6.5, false),
    ),
    (
        "emerald_sapphire.glb",
        spec(Cut::Emerald, Stone::Sapphire, 8.0, false),
    ),
    ("oval_ruby.glb", spec(Cut::Oval, Stone::Ruby, 8.0, false)),
    (
        "pear_cubic_zirconia.glb",
        spec(Cut::Pear, Stone::CubicZirconia, 8.0, false),
    ),
    (
        "round_diamond_bare.glb",
        spec(Cut::Round, Stone::Diamond, 6.5, true),
    ),
];

const fn spec(cut: Cut, stone: Stone, size_mm: f64, bare: bool) -> GemSpec {
    GemSpec {
        cut,
        stone,
        size_mm,
        bare,
    }
}

/// Writes [`GEM_ASSETS`] (preview scenes) into `dir` (created if missing), each
/// atomically; returns their paths in order.
pub fn write_gem_assets(dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::Output {
        path: dir.to_path_buf(),
        reason: format!("cannot create directory: {e}"),
    })?;
    let mut written = Vec::with_capacity(GEM_ASSETS.len());
    for (name, spec) in GEM_ASSETS {
        let path = dir.join(name);
        write_glb(&path, &gem_scene(&spec)?)?;
        written.push(path);
    }
    Ok(written)
}
