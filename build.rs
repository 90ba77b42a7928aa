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
//!    `python3 -m pip download`, SHA-256 checked), of which only the named shared libraries
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
//! `IRIS_OIDN_SOURCE`.
#![forbid(unsafe_code)]

use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, SystemTime};

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

/// Fixed mtime for extracted files (2025-01-01): files created during this build script run
/// would otherwise look newer than the run and make cargo rerun it (and relink) once more.
const EXTRACTED_MTIME_SECS: u64 = 1_735_689_600;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    let mut rpaths: Vec<PathBuf> = Vec::new();
    for lib in [&EMBREE, &OIDN] {
        println!("cargo:rerun-if-env-changed={}", lib.dir_env);
        println!("cargo:rerun-if-env-changed={}", lib.cache.0);
        let feature = format!("CARGO_FEATURE_{}", lib.feature.to_uppercase());
        if env::var_os(feature).is_some() {
            provide(lib, &mut rpaths);
        }
    }
    // For dependents' build scripts (DEP_IRIS_NATIVE_RPATH): python/build.rs.
    let dirs: Vec<String> = rpaths.iter().map(|d| d.display().to_string()).collect();
    println!("cargo:rpath={}", dirs.join(":"));
}

/// Finds `lib` and tells cargo how to link it (search path and RUNPATH once per directory in
/// `rpaths`), or ends the build with the ways to provide it.
fn provide(lib: &Lib, rpaths: &mut Vec<PathBuf>) {
    match locate(lib) {
        Ok(found) => {
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
                 \x20 3. the automatic download of the pinned {pin} wheel, which needs python3 with pip\n\
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
    match wheel_cache(lib) {
        Ok((dir, source)) => Ok(Found {
            dirs: vec![dir],
            marker: lib.markers[0].into(),
            source,
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

/// The cache's `lib/` directory, filled from the wheel unless already complete.
fn wheel_cache(lib: &Lib) -> Result<(PathBuf, String), String> {
    let root = match env::var_os(lib.cache.0) {
        Some(d) => PathBuf::from(d),
        None => PathBuf::from(env::var("CARGO_MANIFEST_DIR").unwrap()).join(lib.cache.1),
    };
    let dir = root.join("lib");
    // Deleting the cache must make cargo rerun this script (a missing path counts as changed).
    rerun_if_changed(&dir.join(lib.markers[0]));
    let how = format!("{} wheel, cached in {}", lib.wheel.0, dir.display());
    if cache_complete(lib, &dir) {
        return Ok((dir, how));
    }
    let out = PathBuf::from(env::var("OUT_DIR").unwrap());
    let download = out.join(format!("{}-wheel", lib.feature));
    let wheel = download_wheel(lib, &download)?;
    let parent = root.parent().ok_or("cache directory has no parent")?;
    fs::create_dir_all(parent).map_err(at(parent))?;
    let name = root
        .file_name()
        .ok_or("bad cache directory name")?
        .to_string_lossy();
    let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    let _ = fs::remove_dir_all(&tmp);
    let result = extract(lib, &wheel, &tmp.join("lib")).and_then(|()| {
        if root.exists() {
            // A leftover from an older layout, or another build finished first.
            if cache_complete(lib, &dir) {
                return Ok(());
            }
            fs::remove_dir_all(&root)
                .map_err(|e| format!("cannot replace {}: {e}", root.display()))?;
        }
        fs::rename(&tmp, &root)
            .map_err(|e| format!("cannot move cache into {}: {e}", root.display()))
    });
    let _ = fs::remove_dir_all(&tmp);
    let _ = fs::remove_dir_all(&download);
    result?;
    if !cache_complete(lib, &dir) {
        return Err(format!("{} is incomplete after extraction", dir.display()));
    }
    Ok((dir, how))
}

/// Whether `name` matches `pattern` (at most one `*`, standing for any run of characters).
fn matches(pattern: &str, name: &str) -> bool {
    match pattern.split_once('*') {
        Some((head, tail)) => {
            name.len() >= head.len() + tail.len() && name.starts_with(head) && name.ends_with(tail)
        }
        None => name == pattern,
    }
}

/// Whether `dir` holds a regular file for every extracted pattern and every link resolves
/// to a file.
fn cache_complete(lib: &Lib, dir: &Path) -> bool {
    let Ok(entries) = fs::read_dir(dir) else {
        return false;
    };
    let names: Vec<String> = entries
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    let files = lib
        .extract
        .iter()
        .all(|p| names.iter().any(|n| matches(p, n)));
    let links = lib
        .links
        .iter()
        .all(|(l, _)| fs::metadata(dir.join(l)).is_ok_and(|m| m.is_file()));
    files && links
}

/// Downloads the pinned wheel into `dir` and checks its SHA-256; returns its path.
/// A digest mismatch aborts the build outright: it never falls back to anything else.
fn download_wheel(lib: &Lib, dir: &Path) -> Result<PathBuf, String> {
    let (pin, sha256, platform) = lib.wheel;
    let _ = fs::remove_dir_all(dir);
    fs::create_dir_all(dir).map_err(at(dir))?;
    // The package is named, never a URL.
    #[rustfmt::skip]
    let args = [
        "-m", "pip", "download", "--no-deps", "--only-binary=:all:", "--platform", platform,
        "--python-version", "3.11", "--implementation", "cp", "--abi", "cp311", pin, "-d",
    ];
    let output = Command::new("python3")
        .args(args)
        .arg(dir)
        .env("PIP_DISABLE_PIP_VERSION_CHECK", "1")
        .output()
        .map_err(|e| format!("cannot run `python3 -m pip`: {e}"))?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let last = stderr.lines().rev().find(|l| !l.trim().is_empty());
        return Err(format!(
            "pip download failed: {}",
            last.unwrap_or("").trim()
        ));
    }
    let wheel = fs::read_dir(dir)
        .map_err(at(dir))?
        .flatten()
        .map(|e| e.path())
        .find(|p| p.to_string_lossy().ends_with(".whl"))
        .ok_or("pip reported success but saved no wheel")?;
    let digest = sha256_hex(&wheel)?;
    if digest != sha256 {
        eprintln!(
            "\nerror: SHA-256 MISMATCH for {}\n  expected {sha256}\n  got      {digest}\n\
             Refusing to use it. Set {} or install pkg-config {} instead.\n",
            wheel.display(),
            lib.dir_env,
            lib.pkg.0
        );
        std::process::exit(1);
    }
    Ok(wheel)
}

/// `map_err` helper: prefixes an error with the path it concerns.
fn at<E: std::fmt::Display>(path: &Path) -> impl FnOnce(E) -> String + '_ {
    move |e| format!("{}: {e}", path.display())
}

/// Tells cargo to rerun this script when `path` changes or disappears.
fn rerun_if_changed(path: &Path) {
    println!("cargo:rerun-if-changed={}", path.display());
}

fn sha256_hex(path: &Path) -> Result<String, String> {
    use sha2::{Digest, Sha256};
    let mut file = fs::File::open(path).map_err(at(path))?;
    let mut hasher = Sha256::new();
    std::io::copy(&mut file, &mut hasher).map_err(at(path))?;
    Ok(format!("{:x}", hasher.finalize()))
}

/// Extracts the files `lib.extract` names from `lib.wheel_dir` of the wheel into `dir`
/// (nothing else: no subdirectories, no other libraries), then creates `lib.links`.
fn extract(lib: &Lib, wheel: &Path, dir: &Path) -> Result<(), String> {
    let file = fs::File::open(wheel).map_err(at(wheel))?;
    let mut zip = zip::ZipArchive::new(file).map_err(at(wheel))?;
    fs::create_dir_all(dir).map_err(at(dir))?;
    let mut got: Vec<Option<String>> = vec![None; lib.extract.len()];
    for i in 0..zip.len() {
        let mut entry = zip.by_index(i).map_err(|e| e.to_string())?;
        let Some(name) = entry.name().strip_prefix(lib.wheel_dir).map(str::to_owned) else {
            continue;
        };
        let Some(k) = lib.extract.iter().position(|p| matches(p, &name)) else {
            continue;
        };
        if name.contains('/') || !entry.is_file() {
            continue;
        }
        if let Some(first) = &got[k] {
            return Err(format!(
                "the wheel has both {first} and {name} for {}{}",
                lib.wheel_dir, lib.extract[k]
            ));
        }
        let dest = dir.join(&name);
        let mut out = fs::File::create(&dest).map_err(at(&dest))?;
        std::io::copy(&mut entry, &mut out).map_err(at(&dest))?;
        out.set_modified(SystemTime::UNIX_EPOCH + Duration::from_secs(EXTRACTED_MTIME_SECS))
            .map_err(at(&dest))?;
        got[k] = Some(name);
    }
    for (k, pattern) in lib.extract.iter().enumerate() {
        if got[k].is_none() {
            return Err(format!("the wheel has no {}{pattern}", lib.wheel_dir));
        }
    }
    for (link, pattern) in lib.links {
        let k = lib.extract.iter().position(|p| p == pattern);
        let Some(Some(target)) = k.map(|k| &got[k]) else {
            return Err(format!("no extracted file for {pattern} (link {link})"));
        };
        std::os::unix::fs::symlink(target, dir.join(link))
            .map_err(|e| format!("cannot create the {link} link: {e}"))?;
    }
    Ok(())
}
