//! Where the loaders get the files a scene references (glTF buffers and images, OBJ
//! `mtllib` libraries, MTL texture maps).
//!
//! [`Files::Disk`] reads the file system through [`crate::fileio::input`]: regular files
//! only, each within its kind's size bound, so a URI or `mtllib` naming `/dev/zero`, a FIFO
//! or a directory is refused instead of hanging or exhausting memory.
//! [`Files::Memory`] never touches the file system: every path is looked up in a closure
//! (the fuzz entry points in [`super::fuzz_entry`] use it, so hostile inputs cannot reach
//! files outside the test).

use crate::error::LoadErrorKind;
use crate::fileio::{input, Input, ReadError};
use std::path::Path;

/// A source of referenced files.
#[derive(Clone, Copy)]
pub enum Files<'a> {
    /// The file system (regular files only).
    Disk,
    /// An in-memory lookup: `Some(bytes)` for a file that exists, `None` otherwise.
    Memory(&'a dyn Fn(&Path) -> Option<Vec<u8>>),
}

impl std::fmt::Debug for Files<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Files::Disk => f.write_str("Files::Disk"),
            Files::Memory(_) => f.write_str("Files::Memory"),
        }
    }
}

/// The error of a file the in-memory lookup does not hold.
fn not_found() -> ReadError {
    ReadError {
        kind: LoadErrorKind::Io,
        detail: std::io::Error::from(std::io::ErrorKind::NotFound).to_string(),
    }
}

impl Files<'_> {
    /// The whole content of `path`, read as a file of `kind` (its size bound).
    pub fn read(&self, path: &Path, kind: Input) -> Result<Vec<u8>, ReadError> {
        match self {
            Files::Disk => input::read(path, kind),
            Files::Memory(lookup) => lookup(path).ok_or_else(not_found),
        }
    }

    /// Whether `path` could be read as a file of `kind`, without reading it: why not
    /// otherwise (missing, a directory, a FIFO, over the bound).
    pub fn check(&self, path: &Path, kind: Input) -> Result<(), ReadError> {
        match self {
            Files::Disk => input::check(path, kind).map(|_| ()),
            Files::Memory(lookup) => lookup(path).map(|_| ()).ok_or_else(not_found),
        }
    }

    /// Whether `path` names a regular file.
    pub fn is_file(&self, path: &Path) -> bool {
        match self {
            Files::Disk => path.is_file(),
            Files::Memory(lookup) => lookup(path).is_some(),
        }
    }
}
