//! Where the loaders get the files a scene references (glTF buffers and images, OBJ
//! `mtllib` libraries, MTL texture maps).
//!
//! [`Files::Disk`] reads the file system, **regular files only**: a URI or `mtllib` naming
//! `/dev/zero`, a FIFO or a directory is refused instead of hanging or exhausting memory.
//! [`Files::Memory`] never touches the file system: every path is looked up in a closure
//! (the fuzz entry points in [`super::fuzz_entry`] use it, so hostile inputs cannot reach
//! files outside the test).

use std::io;
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

impl Files<'_> {
    /// The whole content of `path`.
    pub fn read(&self, path: &Path) -> io::Result<Vec<u8>> {
        match self {
            Files::Disk => {
                if !std::fs::metadata(path)?.is_file() {
                    return Err(io::Error::other("not a regular file"));
                }
                std::fs::read(path)
            }
            Files::Memory(lookup) => {
                lookup(path).ok_or_else(|| io::Error::from(io::ErrorKind::NotFound))
            }
        }
    }

    /// Whether `path` names a readable regular file.
    pub fn is_file(&self, path: &Path) -> bool {
        match self {
            Files::Disk => path.is_file(),
            Files::Memory(lookup) => lookup(path).is_some(),
        }
    }
}
