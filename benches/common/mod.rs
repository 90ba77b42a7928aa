//! Helpers shared by the benchmarks (`mod common;` in each bench that needs them).
#![allow(dead_code)]

use iris::accel::Backend;
use std::path::PathBuf;

#[path = "../../tests/common/splitmix.rs"]
pub mod splitmix;

/// `../shared/assets` (or `IRIS_SHARED_ASSETS`) if present; the bench says SKIPPED otherwise.
pub fn shared_assets() -> Option<PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    iris::app::gallery::shared_assets_dir_in(root)
        .ok()
        .flatten()
}

/// The backends compiled in, Embree first.
pub fn backends() -> Vec<(&'static str, Backend)> {
    let mut v = vec![("bvh", Backend::Bvh)];
    if cfg!(feature = "embree") {
        v.insert(0, ("embree", Backend::Embree));
    }
    v
}
