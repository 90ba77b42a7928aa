//! The pinned-wheel provisioning of build.rs: download (pip, or Python's standard library
//! where pip is missing), SHA-256 check, and extraction of the named shared libraries into
//! the cache.

use super::{rerun_if_changed, Lib};
use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, SystemTime};

/// Fixed mtime for extracted files (2025-01-01): files created during this build script run
/// would otherwise look newer than the run and make cargo rerun it (and relink) once more.
const EXTRACTED_MTIME_SECS: u64 = 1_735_689_600;

/// The cache's `lib/` directory, filled from the wheel unless already complete.
pub(super) fn wheel_cache(lib: &Lib) -> Result<(PathBuf, String), String> {
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

/// The standard-library fetcher (`python3 -c`, so nothing of it is written anywhere).
const FETCH_WHEEL: &str = include_str!("fetch_wheel.py");

/// Downloads the pinned wheel into `dir` and checks its SHA-256; returns its path.
/// `python3 -m pip download` first (it follows the user's pip configuration: index, proxy,
/// certificates); where that fails, as where python3 has no pip (pip's build isolation), the
/// standard-library fetcher takes the file with the pinned digest from the index. Either
/// way the package is named (or picked by its digest), never given as a URL, and a digest
/// mismatch aborts the build outright: it never falls back to anything else.
fn download_wheel(lib: &Lib, dir: &Path) -> Result<PathBuf, String> {
    let (pin, sha256, platform) = lib.wheel;
    let empty = || {
        let _ = fs::remove_dir_all(dir);
        fs::create_dir_all(dir).map_err(at(dir))
    };
    empty()?;
    #[rustfmt::skip]
    let pip = [
        "-m", "pip", "download", "--no-deps", "--only-binary=:all:", "--platform", platform,
        "--python-version", "3.11", "--implementation", "cp", "--abi", "cp311", pin, "-d",
    ];
    if let Err(pip_err) = python3(&pip, dir) {
        empty()?;
        python3(&["-c", FETCH_WHEEL, pin, sha256], dir).map_err(|e| {
            format!("pip download failed ({pip_err}), and so did the download without pip ({e})")
        })?;
        println!("cargo:warning=pip download failed ({pip_err}); fetched {pin} without pip");
    }
    let wheel = fs::read_dir(dir)
        .map_err(at(dir))?
        .flatten()
        .map(|e| e.path())
        .find(|p| p.to_string_lossy().ends_with(".whl"))
        .ok_or("the download reported success but saved no wheel")?;
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

/// Runs `python3 ARGS... DIR`; the error is the last line it printed to stderr.
fn python3(args: &[&str], dir: &Path) -> Result<(), String> {
    let output = Command::new("python3")
        .args(args)
        .arg(dir)
        .env("PIP_DISABLE_PIP_VERSION_CHECK", "1")
        .output()
        .map_err(|e| format!("cannot run python3: {e}"))?;
    if output.status.success() {
        return Ok(());
    }
    let stderr = String::from_utf8_lossy(&output.stderr);
    let last = stderr.lines().rev().find(|l| !l.trim().is_empty());
    Err(last.unwrap_or("no message").trim().to_string())
}

/// `map_err` helper: prefixes an error with the path it concerns.
fn at<E: std::fmt::Display>(path: &Path) -> impl FnOnce(E) -> String + '_ {
    move |e| format!("{}: {e}", path.display())
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
