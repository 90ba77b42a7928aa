//! Helpers shared by the benchmarks (`mod common;` in each bench that needs them).
#![allow(dead_code)]

use iris::accel::Backend;
use std::path::PathBuf;

/// `../shared/assets` (or `IRIS_SHARED_ASSETS`) if present; the bench says SKIPPED otherwise.
pub fn shared_assets() -> Option<PathBuf> {
    let dir = std::env::var_os("IRIS_SHARED_ASSETS")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/assets"));
    dir.is_dir().then_some(dir)
}

/// The backends compiled in, Embree first.
pub fn backends() -> Vec<(&'static str, Backend)> {
    let mut v = vec![("bvh", Backend::Bvh)];
    if cfg!(feature = "embree") {
        v.insert(0, ("embree", Backend::Embree));
    }
    v
}
