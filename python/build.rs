//! Links the extension module against the Embree and Open Image Denoise libraries that the
//! `iris` crate's build script located (its metadata, `links = "iris_native"`), so that an
//! installed module finds them wherever it is installed.
//!
//! - The libraries of the pinned wheels' caches (`DEP_IRIS_NATIVE_BUNDLE`) are staged in
//!   `$OUT_DIR/lib/`, every file under its own name (the linker's `lib*.so` names aside), and
//!   maturin puts that directory into the wheel's package next to the module, as `iris/lib/`
//!   (pyproject.toml: `include`, `from = "out-dir"`; maturin installs the module as
//!   `iris/iris.abi3.so` with an `__init__.py`). The module's RUNPATH is `$ORIGIN/lib`, so
//!   nothing points back into the source checkout. The names and the directory's name `lib`
//!   are what the libraries expect: OIDN's core loads its CPU device module by file name from
//!   its own directory, and OIDN's libraries find each other through their RPATH
//!   `$ORIGIN/../lib`.
//! - Libraries from `EMBREE_DIR` / `OIDN_DIR` or pkg-config are the machine's: their
//!   directories go into the RUNPATH as they are, and the wheel does not carry them.
#![forbid(unsafe_code)]

use std::env;
use std::fs;
use std::path::{Path, PathBuf};

/// Where the wheel's libraries are staged, relative to `OUT_DIR` and to the module.
const STAGED: &str = "lib";

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let dirs = |var: &str| -> Vec<PathBuf> {
        println!("cargo:rerun-if-env-changed={var}");
        let value = env::var(var).unwrap_or_default();
        value
            .split(':')
            .filter(|d| !d.is_empty())
            .map(PathBuf::from)
            .collect()
    };
    let (rpath, bundle) = (
        dirs("DEP_IRIS_NATIVE_RPATH"),
        dirs("DEP_IRIS_NATIVE_BUNDLE"),
    );
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    let staged = out.join(STAGED);
    let _ = fs::remove_dir_all(&staged);
    for dir in &bundle {
        println!("cargo:rerun-if-changed={}", dir.display());
        if let Err(e) = stage(dir, &staged) {
            eprintln!(
                "\nerror: cannot stage the libraries of {} for the wheel: {e}\n",
                dir.display()
            );
            std::process::exit(1);
        }
    }
    if !bundle.is_empty() {
        println!("cargo:rustc-link-arg=-Wl,-rpath,$ORIGIN/{STAGED}");
    }
    for dir in rpath.iter().filter(|d| !bundle.contains(d)) {
        println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
    }
}

/// Puts every file of `dir` into `staged` (symlinks resolved: a wheel holds no links), as a
/// hard link where it can and a copy where it cannot; leaves out the linker's `lib*.so` names,
/// which nothing loads at run time.
fn stage(dir: &Path, staged: &Path) -> Result<(), String> {
    fs::create_dir_all(staged).map_err(at(staged))?;
    for entry in fs::read_dir(dir).map_err(at(dir))? {
        let path = entry.map_err(at(dir))?.path();
        let name = path
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let file = fs::canonicalize(&path).map_err(at(&path))?;
        if name.ends_with(".so") || !file.is_file() {
            continue;
        }
        let dest = staged.join(&name);
        if fs::hard_link(&file, &dest).is_err() {
            fs::copy(&file, &dest).map_err(at(&dest))?;
        }
    }
    Ok(())
}

/// `map_err` helper: prefixes an error with the path it concerns.
fn at(path: &Path) -> impl FnOnce(std::io::Error) -> String + '_ {
    move |e| format!("{}: {e}", path.display())
}
