//! Atomic file replacement: the bytes go to a temporary file in the target's directory
//! (`.<name>.tmp-<pid>-<n>`), are flushed to disk with `fsync`, and only then renamed over
//! the target. A reader therefore sees either the old file or the complete new one, never a
//! half-written output. On any failure the temporary file is removed. A Ctrl-C or SIGTERM
//! that ends the process waits for a write in flight ([`crate::interrupt::Writing`]), and a
//! write does not start once the process is ending, so no temporary file outlives it.
//!
//! Invariant: the temporary file lives in the same directory as the target, so the final
//! `rename` never crosses a file system (POSIX `rename(2)` is atomic only within one).

use crate::error::{Error, Result};
use std::fs::{self, File};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes temporary files of concurrent writes from the same process.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Writes `bytes` to `path` atomically (temporary file, fsync, rename).
///
/// Errors are [`Error::Output`] naming `path`; no temporary file is left behind.
pub fn write_file_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let output_err = |reason: String| Error::Output {
        path: path.to_path_buf(),
        reason,
    };
    let name = path
        .file_name()
        .ok_or_else(|| output_err("the path does not name a file".into()))?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    // The rename would replace a directory, device or FIFO itself (`/dev/null` as root).
    if let Ok(meta) = fs::metadata(path) {
        if !meta.is_file() {
            let what = crate::fileio::input::describe(path, &meta);
            return Err(output_err(format!("it is {what}, not a regular file")));
        }
    }
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".tmp-{}-{n}", std::process::id()));
    let tmp = dir.join(tmp_name);

    let Some(_writing) = crate::interrupt::Writing::begin() else {
        return Err(output_err(
            "not written: the process is ending on a signal".into(),
        ));
    };
    let result = write_and_sync(&tmp, bytes).and_then(|()| fs::rename(&tmp, path));
    match result {
        Ok(()) => {
            sync_dir(&dir);
            Ok(())
        }
        Err(e) => {
            // The temp file may not exist (e.g. the directory is missing); ignore that.
            let _ = fs::remove_file(&tmp);
            Err(output_err(e.to_string()))
        }
    }
}

/// Creates `tmp`, writes all bytes and flushes them to the storage device.
fn write_and_sync(tmp: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut f = File::create(tmp)?;
    f.write_all(bytes)?;
    f.sync_all()
}

/// Best effort: makes the rename itself durable by syncing the directory entry. Failure is
/// harmless for correctness (the file is complete either way), so it is ignored.
fn sync_dir(dir: &Path) {
    #[cfg(unix)]
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
    #[cfg(not(unix))]
    let _ = dir;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("iris-atomic-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("scratch dir");
        dir
    }

    #[test]
    fn replaces_existing_file_and_leaves_no_temp() {
        let dir = scratch("replace");
        let target = dir.join("out.bin");
        fs::write(&target, b"old").expect("seed");
        write_file_atomic(&target, b"new contents").expect("write");
        assert_eq!(fs::read(&target).expect("read"), b"new contents");
        let entries: Vec<_> = fs::read_dir(&dir).expect("ls").collect();
        assert_eq!(entries.len(), 1, "only the target remains");
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn target_is_a_directory_fails_cleanly() {
        let dir = scratch("isdir");
        let target = dir.join("sub");
        fs::create_dir(&target).expect("mkdir");
        fs::write(target.join("x"), b"x").expect("fill");
        let err = write_file_atomic(&target, b"data").expect_err("rename over a directory");
        assert!(matches!(err, Error::Output { .. }));
        let names: Vec<_> = fs::read_dir(&dir)
            .expect("ls")
            .map(|e| e.expect("entry").file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("sub")]);
        let _ = fs::remove_dir_all(&dir);
    }
}
