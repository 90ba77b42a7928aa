//! Locates (or provisions) Embree 4 for the `embree` feature; does nothing without it.
//!
//! Search order, first hit wins:
//! 1. `EMBREE_DIR`: a prefix holding `lib/libembree4.so` (or `lib64/`, or the directory itself).
//!    If set but unusable, the build fails instead of silently trying something else.
//! 2. pkg-config `embree4` (distribution packages, e.g. Debian 13 `libembree-dev`).
//! 3. A project-local copy of Embree 4.4.0 taken from the pinned Python wheel
//!    `embreex==4.4.0.post1` (fetched by name with `python3 -m pip download`, SHA-256
//!    checked), extracted into `.cache/embree4-4.4.0/lib/` (override the directory that
//!    holds `lib/` with `IRIS_EMBREE_CACHE`). The cache is written to a temporary sibling
//!    and renamed into place, so an interrupted build never leaves half a cache.
//!
//! The chosen library directory is added to the link search path and baked into the
//! binaries' RUNPATH, so `target/release/iris`, tests and benches need no LD_LIBRARY_PATH.
//! `embree4-sys` itself emits `rustc-link-lib=embree4`. How Embree was found is exported to
//! the crate as `IRIS_EMBREE_SOURCE`.

use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, SystemTime};

const WHEEL_PIN: &str = "embreex==4.4.0.post1";
/// `python3` arguments before the destination directory (the package is named, never a URL).
#[rustfmt::skip]
const PIP_DOWNLOAD: &[&str] = &[
    "-m", "pip", "download", "--no-deps", "--only-binary=:all:", "--platform",
    "manylinux_2_28_x86_64", "--python-version", "3.11", "--implementation", "cp", "--abi",
    "cp311", WHEEL_PIN, "-d",
];
const WHEEL_SHA256: &str = "2cd0f7d5c6342e6247e31f700761689cae7829454d8c6de0c41e62124a023e1f";
/// Fixed mtime for extracted files (2025-01-01): files created during this build script run
/// would otherwise look newer than the run and make cargo rerun it (and relink) once more.
const EXTRACTED_MTIME_SECS: u64 = 1_735_689_600;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=EMBREE_DIR");
    println!("cargo:rerun-if-env-changed=IRIS_EMBREE_CACHE");
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    if env::var_os("CARGO_FEATURE_EMBREE").is_none() {
        return;
    }
    match locate() {
        Ok((dirs, source)) => {
            for dir in dirs {
                println!("cargo:rustc-link-search=native={}", dir.display());
                println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
            }
            println!("cargo:rustc-env=IRIS_EMBREE_SOURCE={source}");
        }
        Err(reasons) => {
            eprintln!(
                "\nerror: the `embree` feature needs Embree 4, which was not found:\n{reasons}\n\
                 Provide it one of three ways:\n\
                 \x20 1. EMBREE_DIR=<prefix containing lib/libembree4.so>\n\
                 \x20 2. a system package visible to `pkg-config embree4` (e.g. Debian 13 libembree-dev)\n\
                 \x20 3. the automatic download of the pinned {WHEEL_PIN} wheel, which needs python3 with pip\n\
                 or build without Embree: cargo build --no-default-features\n"
            );
            std::process::exit(1);
        }
    }
}

/// Library directories to link from and a description of the source, or why every way failed.
fn locate() -> Result<(Vec<PathBuf>, String), String> {
    if let Some(dir) = env::var_os("EMBREE_DIR") {
        let dir = PathBuf::from(dir);
        return match lib_dir_in(&dir) {
            Some(lib) => {
                rerun_if_changed(&lib.join("libembree4.so"));
                Ok((vec![lib.clone()], format!("EMBREE_DIR ({})", lib.display())))
            }
            None => Err(format!(
                "  - EMBREE_DIR={} has no lib/libembree4.so, lib64/libembree4.so or libembree4.so",
                dir.display()
            )),
        };
    }
    let pkg_err = match pkg_config::Config::new()
        .atleast_version("4.0")
        .cargo_metadata(false)
        .probe("embree4")
    {
        Ok(lib) => {
            let how = match lib.link_paths.first() {
                Some(p) => p.display().to_string(),
                None => "system library path".to_string(),
            };
            return Ok((
                lib.link_paths,
                format!("pkg-config embree4 {} ({how})", lib.version),
            ));
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
    match wheel_cache() {
        Ok((lib, how)) => Ok((vec![lib], how)),
        Err(wheel_err) => Err(format!(
            "  - EMBREE_DIR: not set\n  - pkg-config embree4: {pkg_err}\n  - {WHEEL_PIN} wheel: {wheel_err}"
        )),
    }
}

/// The directory under `prefix` that contains `libembree4.so`, if any.
fn lib_dir_in(prefix: &Path) -> Option<PathBuf> {
    let candidates = [prefix.join("lib"), prefix.join("lib64"), prefix.into()];
    candidates
        .into_iter()
        .find(|d| d.join("libembree4.so").exists())
}

/// The cache's `lib/` directory, filled from the wheel unless already complete.
fn wheel_cache() -> Result<(PathBuf, String), String> {
    let root = match env::var_os("IRIS_EMBREE_CACHE") {
        Some(d) => PathBuf::from(d),
        None => PathBuf::from(env::var("CARGO_MANIFEST_DIR").unwrap()).join(".cache/embree4-4.4.0"),
    };
    let lib = root.join("lib");
    // Deleting the cache must make cargo rerun this script (a missing path counts as changed).
    rerun_if_changed(&lib.join("libembree4.so"));
    let how = format!("{WHEEL_PIN} wheel, cached in {}", lib.display());
    if cache_complete(&lib) {
        return Ok((lib, how));
    }
    let out = PathBuf::from(env::var("OUT_DIR").unwrap());
    let wheel = download_wheel(&out.join("embreex-wheel"))?;
    let parent = root.parent().ok_or("cache directory has no parent")?;
    fs::create_dir_all(parent).map_err(at(parent))?;
    let name = root
        .file_name()
        .ok_or("bad cache directory name")?
        .to_string_lossy();
    let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    let _ = fs::remove_dir_all(&tmp);
    let result = extract(&wheel, &tmp.join("lib")).and_then(|()| {
        if root.exists() {
            // A leftover from an older layout, or another build finished first.
            if cache_complete(&lib) {
                return Ok(());
            }
            fs::remove_dir_all(&root)
                .map_err(|e| format!("cannot replace {}: {e}", root.display()))?;
        }
        fs::rename(&tmp, &root)
            .map_err(|e| format!("cannot move cache into {}: {e}", root.display()))
    });
    let _ = fs::remove_dir_all(&tmp);
    let _ = fs::remove_dir_all(out.join("embreex-wheel"));
    result?;
    if !cache_complete(&lib) {
        return Err(format!("{} is incomplete after extraction", lib.display()));
    }
    Ok((lib, how))
}

/// Whether `lib` has the `libembree4.so` link resolving to a real file, and the TBB beside it.
fn cache_complete(lib: &Path) -> bool {
    let tbb = fs::read_dir(lib).ok().is_some_and(|rd| {
        rd.flatten()
            .any(|e| e.file_name().to_string_lossy().starts_with("libtbb-"))
    });
    tbb && fs::metadata(lib.join("libembree4.so")).is_ok_and(|m| m.is_file())
}

/// Downloads the pinned wheel into `dir` and checks its SHA-256; returns its path.
/// A digest mismatch aborts the build outright: it never falls back to anything else.
fn download_wheel(dir: &Path) -> Result<PathBuf, String> {
    let _ = fs::remove_dir_all(dir);
    fs::create_dir_all(dir).map_err(at(dir))?;
    let output = Command::new("python3")
        .args(PIP_DOWNLOAD)
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
    if digest != WHEEL_SHA256 {
        eprintln!(
            "\nerror: SHA-256 MISMATCH for {}\n  expected {WHEEL_SHA256}\n  got      {digest}\n\
             Refusing to use it. Set EMBREE_DIR or install pkg-config embree4 instead.\n",
            wheel.display()
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

/// Extracts `embreex.libs/libembree4-*.so.4` and `libtbb-*.so.*` into `lib` and adds the
/// `libembree4.so` link the linker looks for. Embree's DT_NEEDED names the hashed TBB file
/// and its RPATH is `$ORIGIN`, so both must sit side by side.
fn extract(wheel: &Path, lib: &Path) -> Result<(), String> {
    let file = fs::File::open(wheel).map_err(at(wheel))?;
    let mut zip = zip::ZipArchive::new(file).map_err(at(wheel))?;
    fs::create_dir_all(lib).map_err(at(lib))?;
    let mut embree = None;
    let mut tbb = false;
    for i in 0..zip.len() {
        let mut entry = zip.by_index(i).map_err(|e| e.to_string())?;
        let Some(name) = entry
            .name()
            .strip_prefix("embreex.libs/")
            .map(str::to_owned)
        else {
            continue;
        };
        let is_embree = name.starts_with("libembree4-") && name.ends_with(".so.4");
        let is_tbb = name.starts_with("libtbb-") && name.contains(".so.");
        if !(is_embree || is_tbb) || name.contains('/') {
            continue;
        }
        let dest = lib.join(&name);
        let mut out = fs::File::create(&dest).map_err(at(&dest))?;
        std::io::copy(&mut entry, &mut out).map_err(at(&dest))?;
        out.set_modified(SystemTime::UNIX_EPOCH + Duration::from_secs(EXTRACTED_MTIME_SECS))
            .map_err(at(&dest))?;
        tbb |= is_tbb;
        if is_embree {
            embree = Some(name);
        }
    }
    let embree = embree.ok_or("the wheel has no embreex.libs/libembree4-*.so.4")?;
    if !tbb {
        return Err("the wheel has no embreex.libs/libtbb-*.so.*".into());
    }
    std::os::unix::fs::symlink(&embree, lib.join("libembree4.so"))
        .map_err(|e| format!("cannot create the libembree4.so link: {e}"))
}
