//! Opening a file for reading: regular files only, within a size bound per kind of file.
//!
//! - The path is examined (`stat`, following symbolic links) **before** it is opened: a
//!   directory, FIFO, character or block device or socket is refused with an error naming
//!   what it is (and, for a symbolic link, its target). Opening a FIFO would wait for a
//!   writer and a device such as `/dev/zero` never ends, so neither is ever opened.
//! - The size is checked against the kind's bound ([`Input::bound`]) before a byte is read.
//! - The file is opened non-blocking (Unix) and the open handle examined again (`fstat`),
//!   so a path swapped for a FIFO between the two looks is refused, not waited on.
//! - Reads stop at the bound ([`Reader`]): a file that grows while it is read is refused
//!   at its bound, not read on.
//!
//! Sizes are in bytes; the bounds are listed in docs/command-line.md ("Bounds").

use crate::error::{LoadError, LoadErrorKind};
use std::fs::{File, Metadata};
use std::io::{self, Read, Seek, SeekFrom};
use std::path::Path;

/// Largest scene file (glTF JSON, GLB, OBJ, MTL) or external glTF buffer: 4 GiB, the most
/// a GLB can hold (its header stores the length in 32 bits).
pub const SCENE_BYTES: u64 = 4 << 30;

/// Largest compressed image (PNG, JPEG or WebP texture, Radiance `.hdr` map, PNG frame):
/// 1 GiB, twice the texture decoder's allocation limit (`load::decode::MAX_DECODE_BYTES`,
/// 512 MiB; an image's file is smaller than its pixels unless stored uncompressed).
pub const IMAGE_BYTES: u64 = 1 << 30;

/// Largest OpenEXR file (a shard's partial image, a reference, an environment map): 8 GiB,
/// a partial image of the largest render (2²⁶ pixels, 29 four-byte channels, 7.25 GiB)
/// stored uncompressed.
pub const EXR_BYTES: u64 = 8 << 30;

/// Largest text file Iris reads back (a gallery's page and manifest): 64 MiB.
pub const TEXT_BYTES: u64 = 64 << 20;

/// What a file is read as, which sets its size bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Input {
    /// A scene file or a glTF buffer: at most [`SCENE_BYTES`].
    Scene,
    /// A compressed image: at most [`IMAGE_BYTES`].
    Image,
    /// An OpenEXR image: at most [`EXR_BYTES`].
    Exr,
    /// A text file: at most [`TEXT_BYTES`].
    Text,
}

impl Input {
    /// The most bytes a file of this kind may hold.
    pub const fn bound(self) -> u64 {
        match self {
            Input::Scene => SCENE_BYTES,
            Input::Image => IMAGE_BYTES,
            Input::Exr => EXR_BYTES,
            Input::Text => TEXT_BYTES,
        }
    }

    /// The kind in words, for errors ("scene files").
    pub const fn name(self) -> &'static str {
        match self {
            Input::Scene => "scene files and glTF buffers",
            Input::Image => "PNG, JPEG, WebP and HDR images",
            Input::Exr => "EXR images",
            Input::Text => "text files",
        }
    }
}

/// Why a file was not read: the class of problem and a sentence that does not repeat the
/// path (the caller names it, [`ReadError::at`]).
#[derive(Debug, Clone)]
pub struct ReadError {
    /// [`LoadErrorKind::Io`] (missing, not a regular file, permission) or
    /// [`LoadErrorKind::TooLarge`] (over the bound).
    pub kind: LoadErrorKind,
    /// What is wrong, e.g. "a FIFO (named pipe), not a regular file".
    pub detail: String,
}

impl ReadError {
    /// The error as a [`LoadError`] naming `path` and `element`.
    pub fn at(self, path: &Path, element: impl Into<String>) -> LoadError {
        LoadError::new(path, element, self.kind, self.detail)
    }

    fn io(e: &io::Error) -> ReadError {
        ReadError {
            kind: LoadErrorKind::Io,
            detail: e.to_string(),
        }
    }

    fn too_large(len: u64, kind: Input) -> ReadError {
        ReadError {
            kind: LoadErrorKind::TooLarge,
            detail: format!(
                "{len} bytes, over the bound of {} for {}",
                size_text(kind.bound()),
                kind.name()
            ),
        }
    }
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.detail)
    }
}

impl std::error::Error for ReadError {}

/// `n` bytes in words: "8 GiB", "1.50 MiB", "17 bytes".
pub fn size_text(n: u64) -> String {
    const UNITS: [(&str, u64); 3] = [("GiB", 1 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)];
    for (unit, size) in UNITS {
        if n >= size {
            return if n.is_multiple_of(size) {
                format!("{} {unit}", n / size)
            } else {
                format!("{:.2} {unit}", n as f64 / size as f64)
            };
        }
    }
    format!("{n} bytes")
}

/// What a file system object other than a regular file is, in words ("a directory").
pub fn special_kind(meta: &Metadata) -> &'static str {
    let t = meta.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a directory"
    } else if t.is_file() {
        "a regular file"
    } else {
        "a special file"
    }
}

/// `path` (whose target's metadata is `meta`) described for an error: "a directory",
/// "a symbolic link to /dev/zero, a character device".
pub fn describe(path: &Path, meta: &Metadata) -> String {
    let what = special_kind(meta);
    let linked = std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink());
    match std::fs::canonicalize(path) {
        Ok(target) if linked => format!("a symbolic link to {}, {what}", target.display()),
        _ => what.to_string(),
    }
}

/// The error for a path that is not a regular file.
fn not_regular(path: &Path, meta: &Metadata) -> ReadError {
    let what = describe(path, meta);
    let detail = if meta.is_dir() {
        format!("{what}, not a file")
    } else {
        format!("{what}, not a regular file (Iris reads regular files only)")
    };
    ReadError {
        kind: LoadErrorKind::Io,
        detail,
    }
}

/// Refuses a path that exists but is not a regular file (a directory, FIFO, device,
/// socket), naming what it is; a missing path or a regular file passes (the caller's own
/// checks judge those).
pub fn refuse_special(path: &Path) -> Result<(), ReadError> {
    match std::fs::metadata(path) {
        Ok(meta) if !meta.is_file() => Err(not_regular(path, &meta)),
        _ => Ok(()),
    }
}

/// Checks `path` without opening it: it exists, is a regular file (after following
/// symbolic links) and holds at most `kind`'s bound; returns its size.
pub fn check(path: &Path, kind: Input) -> Result<u64, ReadError> {
    let meta = std::fs::metadata(path).map_err(|e| ReadError::io(&e))?;
    check_metadata(path, &meta, kind)
}

fn check_metadata(path: &Path, meta: &Metadata, kind: Input) -> Result<u64, ReadError> {
    if !meta.is_file() {
        return Err(not_regular(path, meta));
    }
    if meta.len() > kind.bound() {
        return Err(ReadError::too_large(meta.len(), kind));
    }
    Ok(meta.len())
}

/// Opens `path` for reading as a file of `kind`, after [`check`]; the reader stops at the
/// bound.
pub fn open(path: &Path, kind: Input) -> Result<Reader, ReadError> {
    check(path, kind)?;
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // A FIFO put in the path's place after `check` opens at once instead of waiting
        // for a writer; the handle's own metadata then refuses it. Regular files ignore
        // the flag.
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(|e| ReadError::io(&e))?;
    let meta = file.metadata().map_err(|e| ReadError::io(&e))?;
    let len = check_metadata(path, &meta, kind)?;
    Ok(Reader {
        file,
        pos: 0,
        len,
        kind,
    })
}

/// The whole content of `path` read as a file of `kind` ([`open`]).
pub fn read(path: &Path, kind: Input) -> Result<Vec<u8>, ReadError> {
    let mut reader = open(path, kind)?;
    let mut bytes = Vec::with_capacity(usize::try_from(reader.len).unwrap_or(0));
    reader.read_to_end(&mut bytes).map_err(|e| {
        match e
            .get_ref()
            .and_then(|inner| inner.downcast_ref::<ReadError>())
        {
            Some(grew) => grew.clone(),
            None => ReadError::io(&e),
        }
    })?;
    Ok(bytes)
}

/// A file opened by [`open`]: reads and seeks as the file does, but never past its kind's
/// bound (reading there fails when the file has grown beyond it).
#[derive(Debug)]
pub struct Reader {
    file: File,
    pos: u64,
    len: u64,
    kind: Input,
}

impl Reader {
    /// The file's size when it was opened.
    pub fn len(&self) -> u64 {
        self.len
    }

    /// True for an empty file.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl Read for Reader {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let left = self.kind.bound().saturating_sub(self.pos);
        if left == 0 {
            // At the bound: one more byte means the file grew past it.
            let mut probe = [0u8; 1];
            return match self.file.read(&mut probe)? {
                0 => Ok(0),
                _ => Err(io::Error::other(ReadError {
                    kind: LoadErrorKind::TooLarge,
                    detail: format!(
                        "grew past the bound of {} for {} while it was read",
                        size_text(self.kind.bound()),
                        self.kind.name()
                    ),
                })),
            };
        }
        let n = buf.len().min(usize::try_from(left).unwrap_or(usize::MAX));
        let got = self.file.read(&mut buf[..n])?;
        self.pos += got as u64;
        Ok(got)
    }
}

impl Seek for Reader {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        self.pos = self.file.seek(to)?;
        Ok(self.pos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("iris-input-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("scratch dir");
        dir
    }

    #[test]
    fn sizes_read_in_words() {
        assert_eq!(size_text(17), "17 bytes");
        assert_eq!(size_text(8 << 30), "8 GiB");
        assert_eq!(size_text(3 << 19), "1.50 MiB");
    }

    #[test]
    fn regular_files_are_read_and_others_refused_by_name() {
        let dir = scratch("kinds");
        let file = dir.join("a.bin");
        std::fs::write(&file, b"abc").unwrap();
        assert_eq!(read(&file, Input::Text).unwrap(), b"abc");
        let e = read(&dir, Input::Text).unwrap_err();
        assert_eq!(e.kind, LoadErrorKind::Io);
        assert!(e.detail.starts_with("a directory, not a file"), "{e}");
        #[cfg(unix)]
        {
            let link = dir.join("zero.exr");
            std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
            let e = read(&link, Input::Exr).unwrap_err();
            assert!(
                e.detail
                    .starts_with("a symbolic link to /dev/zero, a character device, not a"),
                "{e}"
            );
        }
        let missing = read(&dir.join("none"), Input::Scene).unwrap_err();
        assert_eq!(missing.kind, LoadErrorKind::Io);
    }

    #[test]
    fn a_file_over_its_bound_is_refused_before_reading() {
        let dir = scratch("bound");
        let file = dir.join("big.txt");
        let f = File::create(&file).unwrap();
        // Sparse: no data is written.
        f.set_len(TEXT_BYTES + 1).unwrap();
        let e = read(&file, Input::Text).unwrap_err();
        assert_eq!(e.kind, LoadErrorKind::TooLarge);
        assert_eq!(
            e.detail,
            "67108865 bytes, over the bound of 64 MiB for text files"
        );
    }

    #[test]
    fn a_file_growing_past_its_bound_while_read_is_refused() {
        let dir = scratch("grow");
        let file = dir.join("grow.txt");
        std::fs::write(&file, b"x").unwrap();
        let mut reader = open(&file, Input::Text).unwrap();
        std::fs::OpenOptions::new()
            .write(true)
            .open(&file)
            .unwrap()
            .set_len(TEXT_BYTES + 10)
            .unwrap();
        let e = std::io::copy(&mut reader, &mut std::io::sink()).unwrap_err();
        assert!(e.to_string().starts_with("grew past the bound"), "{e}");
    }
}
