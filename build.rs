//! Locates (or provisions) the C libraries behind two cargo features, each described once
//! ([`Lib`]: [`EMBREE`] for `embree`, [`OIDN`] for `denoise`) and found by one routine
//! ([`provide`]); a feature that is off costs nothing.
//!
//! Search order per library, first hit wins:
//! 1. `<DIR env>` (`EMBREE_DIR`, `OIDN_DIR`): a prefix holding the library in `lib/`,
//!    `lib64/` or the directory itself. If set but unusable, the build fails instead of
//!    silently trying something else.
//! 2. pkg-config (`embree4` >= 4.0, `OpenImageDenoise` >= 2.0): distribution packages.
//! 3. A project-local copy taken from a pinned Python wheel (fetched by name with
//!    `python3 -m pip download`, or where python3 has no pip (pip's build isolation) with
//!    Python's standard library from the package index, `build/fetch_wheel.py`; SHA-256
//!    checked either way; `build/wheel.rs`), of which only the named shared libraries
//!    are extracted into `.cache/<name>/lib/` (override the directory that holds `lib/` with
//!    `IRIS_EMBREE_CACHE` / `IRIS_OIDN_CACHE`). The cache is written to a temporary sibling
//!    and renamed into place, so an interrupted build never leaves half a cache.
//!    - Embree 4.4.0 from `embreex==4.4.0.post1` (manylinux_2_28): `libembree4-*.so.4` and the
//!      TBB it names (`libtbb-*.so.12`, renamed by auditwheel; Embree's RPATH is `$ORIGIN`).
//!    - Open Image Denoise 2.5.1 from `pyoidn==2.5.1.0` (manylinux2014): the API library
//!      `libOpenImageDenoise.so.2.5.1` (SONAME `.so.2`), `libOpenImageDenoise_core.so.2.5.1`
//!      (its DT_NEEDED), the CPU device module `libOpenImageDenoise_device_cpu.so.2.5.1`
//!      (loaded by the core from its own directory at device creation; needs `libtbb.so.12`)
//!      and `libtbb.so.12` (oneTBB 2023.1). The CUDA, HIP and SYCL modules (and SYCL's
//!      runtime, ~80 % of the wheel) are left out: Iris asks for the CPU device only.
//!
//! The chosen library directories are added to the link search path and baked into the
//! binaries' RUNPATH, so `target/release/iris`, tests and benches need no LD_LIBRARY_PATH.
//! `embree4-sys` emits `rustc-link-lib=embree4` itself; this script links
//! `OpenImageDenoise`. How each was found is exported to the crate as `IRIS_EMBREE_SOURCE` /
//! `IRIS_OIDN_SOURCE`. For the Python module's build script (python/build.rs) the metadata
//! `rpath` lists every library directory and `bundle` those of the wheel caches (whose files
//! the Python wheel carries, `DEP_IRIS_NATIVE_RPATH` / `DEP_IRIS_NATIVE_BUNDLE`).
#![forbid(unsafe_code)]

#[path = "build/wheel.rs"]
mod wheel;

use std::env;
use std::path::{Path, PathBuf};

/// One C library and every way of providing it.
struct Lib {
    /// The cargo feature that needs it (`CARGO_FEATURE_<upper>`).
    feature: &'static str,
    /// The name in messages.
    name: &'static str,
    /// The environment variable naming an installation prefix.
    dir_env: &'static str,
    /// Files marking a library directory, in order of preference; the first one found is
    /// what the linker is given.
    markers: &'static [&'static str],
    /// `rustc-link-lib` value for a marker file name, when this script must link the library
    /// (`None`: a `-sys` crate does).
    link: Option<fn(&str) -> String>,
    /// pkg-config package, minimum version and an example of a package providing it.
    pkg: (&'static str, &'static str, &'static str),
    /// The wheel: `name==version` pin, SHA-256, pip `--platform`.
    wheel: (&'static str, &'static str, &'static str),
    /// Directory of the wheel holding the libraries (ends in `/`).
    wheel_dir: &'static str,
    /// Files to extract, as names with at most one `*`; each must match exactly one file.
    extract: &'static [&'static str],
    /// Symlinks to create in the cache: (link name, pattern of the file it points to).
    links: &'static [(&'static str, &'static str)],
    /// Environment variable overriding the cache directory, and its default (relative to the
    /// manifest directory).
    cache: (&'static str, &'static str),
    /// The `rustc-env` variable telling the crate where the library came from.
    source_env: &'static str,
    /// The cargo command that builds without this library.
    without: &'static str,
}

const EMBREE: Lib = Lib {
    feature: "embree",
    name: "Embree 4",
    dir_env: "EMBREE_DIR",
    markers: &["libembree4.so"],
    link: None,
    pkg: ("embree4", "4.0", "e.g. Debian 13 libembree-dev"),
    wheel: (
        "embreex==4.4.0.post1",
        "2cd0f7d5c6342e6247e31f700761689cae7829454d8c6de0c41e62124a023e1f",
        "manylinux_2_28_x86_64",
    ),
    wheel_dir: "embreex.libs/",
    extract: &["libembree4-*.so.4", "libtbb-*.so.12"],
    links: &[("libembree4.so", "libembree4-*.so.4")],
    cache: ("IRIS_EMBREE_CACHE", ".cache/embree4-4.4.0"),
    source_env: "IRIS_EMBREE_SOURCE",
    without: "cargo build --no-default-features",
};

const OIDN: Lib = Lib {
    feature: "denoise",
    name: "Intel Open Image Denoise 2",
    dir_env: "OIDN_DIR",
    markers: &["libOpenImageDenoise.so", "libOpenImageDenoise.so.2"],
    link: Some(oidn_link),
    pkg: (
        "OpenImageDenoise",
        "2.0",
        "a distribution's OIDN 2 development package",
    ),
    wheel: (
        "pyoidn==2.5.1.0",
        "32ad13368f8de1ef63001942ad05b02a00cd732d1206d97f352d3a3f606d823e",
        "manylinux2014_x86_64",
    ),
    wheel_dir: "pyoidn/oidn/lib/",
    extract: &[
        "libOpenImageDenoise.so.2.5.1",
        "libOpenImageDenoise_core.so.2.5.1",
        "libOpenImageDenoise_device_cpu.so.2.5.1",
        "libtbb.so.12",
    ],
    links: &[
        ("libOpenImageDenoise.so", "libOpenImageDenoise.so.2.5.1"),
        ("libOpenImageDenoise.so.2", "libOpenImageDenoise.so.2.5.1"),
    ],
    cache: ("IRIS_OIDN_CACHE", ".cache/oidn-2.5.1"),
    source_env: "IRIS_OIDN_SOURCE",
    without: "cargo build --no-default-features --features embree",
};

/// `-lOpenImageDenoise`, or the versioned file itself when a prefix has no unversioned link.
fn oidn_link(marker: &str) -> String {
    if marker == "libOpenImageDenoise.so" {
        "dylib=OpenImageDenoise".into()
    } else {
        format!("dylib:+verbatim={marker}")
    }
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=build");
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    let (mut rpaths, mut bundle) = (Vec::new(), Vec::new());
    for lib in [&EMBREE, &OIDN] {
        println!("cargo:rerun-if-env-changed={}", lib.dir_env);
        println!("cargo:rerun-if-env-changed={}", lib.cache.0);
        let feature = format!("CARGO_FEATURE_{}", lib.feature.to_uppercase());
        if env::var_os(feature).is_some() {
            provide(lib, &mut rpaths, &mut bundle);
        }
    }
    // For dependents' build scripts (DEP_IRIS_NATIVE_*): python/build.rs.
    let join = |dirs: &[PathBuf]| {
        let dirs: Vec<String> = dirs.iter().map(|d| d.display().to_string()).collect();
        dirs.join(":")
    };
    println!("cargo:rpath={}", join(&rpaths));
    println!("cargo:bundle={}", join(&bundle));
}

/// Finds `lib` and tells cargo how to link it (search path and RUNPATH once per directory in
/// `rpaths`; a wheel cache's also in `bundle`), or ends the build with the ways to provide it.
fn provide(lib: &Lib, rpaths: &mut Vec<PathBuf>, bundle: &mut Vec<PathBuf>) {
    match locate(lib) {
        Ok(found) => {
            if found.from_wheel {
                bundle.extend(found.dirs.iter().cloned());
            }
            for dir in found.dirs {
                if !rpaths.contains(&dir) {
                    println!("cargo:rustc-link-search=native={}", dir.display());
                    println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
                    rpaths.push(dir);
                }
            }
            if let Some(link) = lib.link {
                println!("cargo:rustc-link-lib={}", link(&found.marker));
            }
            println!("cargo:rustc-env={}={}", lib.source_env, found.source);
        }
        Err(reasons) => {
            let (pin, (pkg, min, example)) = (lib.wheel.0, lib.pkg);
            eprintln!(
                "\nerror: the `{}` feature needs {}, which was not found:\n{reasons}\n\
                 Provide it one of three ways:\n\
                 \x20 1. {}=<prefix containing lib/{}>\n\
                 \x20 2. a system package visible to `pkg-config {pkg}` (>= {min}; {example})\n\
                 \x20 3. the automatic download of the pinned {pin} wheel, which needs python3 and\n\
                 \x20    network access to the package index (pip's; else PIP_INDEX_URL or PyPI)\n\
                 or build without it: {}\n",
                lib.feature, lib.name, lib.dir_env, lib.markers[0], lib.without
            );
            std::process::exit(1);
        }
    }
}

/// Where a library was found.
struct Found {
    /// Directories to link from.
    dirs: Vec<PathBuf>,
    /// The marker file found there (what the linker is given).
    marker: String,
    /// How it was found, for `IRIS_*_SOURCE`.
    source: String,
    /// Whether it is a wheel cache (a directory of this library's files alone).
    from_wheel: bool,
}

/// Tries the three ways in order; the error lists why each failed.
fn locate(lib: &Lib) -> Result<Found, String> {
    if let Some(dir) = env::var_os(lib.dir_env) {
        let dir = PathBuf::from(dir);
        return match lib_dir_in(lib, &dir) {
            Some((found, marker)) => {
                rerun_if_changed(&found.join(marker));
                Ok(Found {
                    source: format!("{} ({})", lib.dir_env, found.display()),
                    dirs: vec![found],
                    marker: marker.into(),
                    from_wheel: false,
                })
            }
            None => Err(format!(
                "  - {}={} has no {m} in lib/, lib64/ or itself",
                lib.dir_env,
                dir.display(),
                m = lib.markers.join(" or ")
            )),
        };
    }
    let (pkg, min, _) = lib.pkg;
    let pkg_err = match pkg_config::Config::new()
        .atleast_version(min)
        .cargo_metadata(false)
        .probe(pkg)
    {
        Ok(found) => {
            let how = match found.link_paths.first() {
                Some(p) => p.display().to_string(),
                None => "system library path".to_string(),
            };
            let marker = found
                .link_paths
                .iter()
                .find_map(|d| lib_dir_in(lib, d).map(|(_, m)| m))
                .unwrap_or(lib.markers[0]);
            return Ok(Found {
                dirs: found.link_paths,
                marker: marker.into(),
                source: format!("pkg-config {pkg} {} ({how})", found.version),
                from_wheel: false,
            });
        }
        Err(e) => {
            let text = e.to_string();
            let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
            let why = lines
                .clone()
                .find(|l| l.starts_with("Package"))
                .or(lines.next());
            why.unwrap_or("not found").to_string()
        }
    };
    match wheel::wheel_cache(lib) {
        Ok((dir, source)) => Ok(Found {
            dirs: vec![dir],
            marker: lib.markers[0].into(),
            source,
            from_wheel: true,
        }),
        Err(wheel_err) => Err(format!(
            "  - {}: not set\n  - pkg-config {pkg}: {pkg_err}\n  - {} wheel: {wheel_err}",
            lib.dir_env, lib.wheel.0
        )),
    }
}

/// The directory under `prefix` (`lib/`, `lib64/` or itself) holding one of the library's
/// marker files, and that marker.
fn lib_dir_in(lib: &Lib, prefix: &Path) -> Option<(PathBuf, &'static str)> {
    let candidates = [prefix.join("lib"), prefix.join("lib64"), prefix.into()];
    candidates.into_iter().find_map(|d| {
        let marker = lib.markers.iter().find(|m| d.join(m).exists())?;
        Some((d, *marker))
    })
}

/// Tells cargo to rerun this script when `path` changes or disappears.
fn rerun_if_changed(path: &Path) {
    println!("cargo:rerun-if-changed={}", path.display());
}
