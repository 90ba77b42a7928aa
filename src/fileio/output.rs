//! Checking where Iris will write, before the work that makes the output (a render, a
//! merge, a gallery): every command calls these on its outputs first, so a bad path fails
//! at once with an error naming it instead of after the render.
//!
//! - An output file ([`check_file`]): its directory exists and is a directory in which a
//!   file can be created (proved by creating and removing a probe named like
//!   `output::atomic`'s temporary files, `.NAME.tmp-PID-probeN`); if the output
//!   exists, it is a regular file with write permission. Outputs are written to a
//!   temporary file renamed over the old one, which would replace a device or FIFO itself
//!   (`-o /dev/null` as root would turn `/dev/null` into a file), so those are refused.
//!   A read-only file is refused too, as `cp` refuses it, although the rename could
//!   replace it.
//! - An output directory ([`check_dir`]): it is a directory in which a file can be
//!   created, or it does not exist yet and its nearest existing ancestor is one (the
//!   command creates it when it writes).
//! - Files named twice ([`check_distinct`]): two outputs naming one file, or an output
//!   naming one of the command's inputs (which the write would replace).

use super::input::describe;
use crate::error::{Error, Result};
use std::ffi::OsString;
use std::fs;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes the probes of one process.
static PROBES: AtomicU64 = AtomicU64::new(0);

/// The directory `path` is in ("." for a bare name).
fn parent_or_dot(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Checks that the output file `path` can be written (module docs); the error
/// ([`Error::Output`]) names the path and says why not.
pub fn check_file(path: &Path) -> Result<()> {
    let fail = |reason: String| Error::Output {
        path: path.to_path_buf(),
        reason,
    };
    let Some(name) = path.file_name() else {
        return Err(fail("the path does not name a file".into()));
    };
    if let Ok(meta) = fs::metadata(path) {
        if meta.is_dir() {
            return Err(fail(format!("it is {}", describe(path, &meta))));
        }
        if !meta.is_file() {
            return Err(fail(format!(
                "it is {}: Iris writes a temporary file and renames it over the output, \
                 which would replace it; name a regular file",
                describe(path, &meta)
            )));
        }
        if meta.permissions().readonly() {
            return Err(fail(
                "the file is read-only (no write permission), so Iris does not replace it".into(),
            ));
        }
    }
    writable_dir(&parent_or_dot(path), name).map_err(fail)
}

/// Checks that the output directory `dir` can be written into, or created (module docs);
/// the error ([`Error::Output`]) names it.
pub fn check_dir(dir: &Path) -> Result<()> {
    let fail = |reason: String| Error::Output {
        path: dir.to_path_buf(),
        reason,
    };
    let name = OsString::from("iris-dir");
    match fs::metadata(dir) {
        Ok(meta) if meta.is_dir() => writable_dir(dir, &name).map_err(fail),
        Ok(meta) => Err(fail(format!(
            "it is {}, not a directory",
            describe(dir, &meta)
        ))),
        Err(_) => {
            // Missing (or under a file): the nearest ancestor that exists must be a
            // directory the command can create `dir` in.
            let ancestor = dir
                .ancestors()
                .skip(1)
                .map(|a| {
                    if a.as_os_str().is_empty() {
                        Path::new(".")
                    } else {
                        a
                    }
                })
                .find(|a| fs::symlink_metadata(a).is_ok())
                .unwrap_or(Path::new("."));
            writable_dir(ancestor, &name).map_err(|why| fail(format!("cannot be created: {why}")))
        }
    }
}

/// Whether a file can be created in `dir`: it is a directory, and a probe file (named after
/// the output `name`) can be created there and removed.
fn writable_dir(dir: &Path, name: &std::ffi::OsStr) -> std::result::Result<(), String> {
    match fs::metadata(dir) {
        Err(e) if e.kind() == ErrorKind::NotFound => {
            return Err(format!("the directory {} does not exist", dir.display()))
        }
        Err(e) => return Err(format!("{}: {e}", dir.display())),
        Ok(meta) if !meta.is_dir() => {
            return Err(format!(
                "{} is {}, not a directory",
                dir.display(),
                describe(dir, &meta)
            ))
        }
        Ok(_) => {}
    }
    let mut probe_name = OsString::from(".");
    probe_name.push(name);
    probe_name.push(format!(
        ".tmp-{}-probe{}",
        std::process::id(),
        PROBES.fetch_add(1, Ordering::Relaxed)
    ));
    let probe = dir.join(probe_name);
    let created = fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe);
    match created {
        Ok(file) => {
            drop(file);
            let _ = fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => Err(format!("cannot create a file in {}: {e}", dir.display())),
    }
}

/// Whether `a` and `b` name the same file: the same file system object when both exist,
/// else the same name in the same (canonical) directory.
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    if let (Ok(x), Ok(y)) = (fs::metadata(a), fs::metadata(b)) {
        use std::os::unix::fs::MetadataExt;
        return x.dev() == y.dev() && x.ino() == y.ino();
    }
    let resolved = |p: &Path| {
        let name = p.file_name()?;
        Some(fs::canonicalize(parent_or_dot(p)).ok()?.join(name))
    };
    match (resolved(a), resolved(b)) {
        (Some(x), Some(y)) => x == y,
        _ => a == b,
    }
}

/// Refuses two of `outputs` naming one file, and an output naming one of `inputs` (which
/// writing it would replace). Each entry is (the flag that named it, the path).
pub fn check_distinct(outputs: &[(&str, &Path)], inputs: &[(&str, &Path)]) -> Result<()> {
    for (i, (flag, path)) in outputs.iter().enumerate() {
        for (other, earlier) in &outputs[..i] {
            if same_file(path, earlier) {
                return Err(Error::Usage(format!(
                    "{other} {} and {flag} {} name the same file: each output needs its own",
                    earlier.display(),
                    path.display()
                )));
            }
        }
        for (input, read) in inputs {
            if same_file(path, read) {
                return Err(Error::Usage(format!(
                    "{flag} {} is the {input} {}: writing it would replace a file this \
                     command reads; name another output",
                    path.display(),
                    read.display()
                )));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("iris-outcheck-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("scratch dir");
        dir
    }

    fn reason(e: Error) -> String {
        match e {
            Error::Output { reason, .. } => reason,
            other => panic!("not an output error: {other}"),
        }
    }

    #[test]
    fn output_files_are_checked_without_leaving_files() {
        let dir = scratch("files");
        check_file(&dir.join("new.png")).unwrap();
        assert_eq!(
            fs::read_dir(&dir).unwrap().count(),
            0,
            "the probe was removed"
        );
        let missing = reason(check_file(&dir.join("no/out.png")).unwrap_err());
        assert!(missing.starts_with("the directory "), "{missing}");
        assert!(missing.ends_with("/no does not exist"), "{missing}");
        assert_eq!(reason(check_file(&dir).unwrap_err()), "it is a directory");
        let file = dir.join("f.txt");
        fs::write(&file, b"").unwrap();
        let under = reason(check_file(&file.join("out.png")).unwrap_err());
        assert!(
            under.ends_with("f.txt is a regular file, not a directory"),
            "{under}"
        );
        let mut perms = fs::metadata(&file).unwrap().permissions();
        perms.set_readonly(true);
        fs::set_permissions(&file, perms).unwrap();
        let read_only = reason(check_file(&file).unwrap_err());
        assert!(
            read_only.starts_with("the file is read-only"),
            "{read_only}"
        );
        #[cfg(unix)]
        {
            let null = reason(check_file(Path::new("/dev/null")).unwrap_err());
            assert!(null.starts_with("it is a character device: "), "{null}");
        }
    }

    #[test]
    fn output_dirs_may_be_created_under_a_directory_only() {
        let dir = scratch("dirs");
        check_dir(&dir).unwrap();
        check_dir(&dir.join("a/b/c")).unwrap();
        assert!(!dir.join("a").exists(), "nothing is created");
        let file = dir.join("f");
        fs::write(&file, b"").unwrap();
        assert_eq!(
            reason(check_dir(&file).unwrap_err()),
            "it is a regular file, not a directory"
        );
        let under = reason(check_dir(&file.join("sub")).unwrap_err());
        assert!(under.starts_with("cannot be created: "), "{under}");
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 1);
    }

    #[test]
    fn files_named_twice_are_refused() {
        let dir = scratch("twice");
        let a = dir.join("a.exr");
        fs::write(&a, b"x").unwrap();
        let spelled = dir.join(".").join("a.exr");
        let e = check_distinct(&[("-o", &spelled)], &[("part", &a)]).unwrap_err();
        assert!(e.to_string().contains("is the part"), "{e}");
        let e = check_distinct(
            &[("-o", &dir.join("n.png")), ("--plot", &dir.join("n.png"))],
            &[],
        )
        .unwrap_err();
        assert!(e.to_string().contains("name the same file"), "{e}");
        check_distinct(
            &[("-o", &dir.join("n.png")), ("--plot", &dir.join("m.png"))],
            &[("part", &a)],
        )
        .unwrap();
    }
}
