//! Error types. Every failure caused by user input (a scene file, a flag, an output path)
//! ends here, naming the file and the element (glTF node/mesh/material/accessor, OBJ line)
//! so the user can find it. Library code never panics on user data.

use std::fmt;
use std::path::{Path, PathBuf};

/// What went wrong while loading a scene; tests match on this.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadErrorKind {
    /// The file could not be read (missing, permission, …).
    Io,
    /// The file is not valid glTF/GLB/OBJ/MTL (truncated GLB, bad JSON, bad OBJ syntax).
    Parse,
    /// A buffer or image referenced by the file is missing or too short.
    MissingBuffer,
    /// An index (vertex index, accessor, material, texture) points outside its array.
    IndexOutOfRange,
    /// A vertex position, normal or texture coordinate is NaN or infinite.
    NonFinite,
    /// An index of refraction is negative, NaN, infinite or between 0 and 1 where not allowed.
    InvalidIor,
    /// A material, light or camera value is outside its valid range.
    InvalidValue,
    /// The scene contains no triangles at all.
    NoTriangles,
    /// The file declares more data than Iris will allocate.
    TooLarge,
    /// The file format or a required extension is not supported.
    Unsupported,
}

impl fmt::Display for LoadErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self {
            LoadErrorKind::Io => "cannot read",
            LoadErrorKind::Parse => "malformed file",
            LoadErrorKind::MissingBuffer => "missing data",
            LoadErrorKind::IndexOutOfRange => "index out of range",
            LoadErrorKind::NonFinite => "non-finite value",
            LoadErrorKind::InvalidIor => "invalid index of refraction",
            LoadErrorKind::InvalidValue => "invalid value",
            LoadErrorKind::NoTriangles => "no triangles",
            LoadErrorKind::TooLarge => "too large",
            LoadErrorKind::Unsupported => "unsupported",
        };
        f.write_str(s)
    }
}

/// A scene-loading error: the file, the element inside it, what kind of problem, and details.
#[derive(Debug, Clone)]
pub struct LoadError {
    /// The scene file (or the buffer/MTL file it references).
    pub file: PathBuf,
    /// The element, e.g. `mesh 2 "Prism" primitive 0`, `material 3 "Glass"`, `line 17`.
    pub element: String,
    /// The class of problem.
    pub kind: LoadErrorKind,
    /// Human-readable details.
    pub detail: String,
}

impl LoadError {
    /// Builds a load error.
    pub fn new(
        file: &Path,
        element: impl Into<String>,
        kind: LoadErrorKind,
        detail: impl Into<String>,
    ) -> Self {
        LoadError {
            file: file.to_path_buf(),
            element: element.into(),
            kind,
            detail: detail.into(),
        }
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.element.is_empty() {
            write!(f, "{}: {}: {}", self.file.display(), self.kind, self.detail)
        } else {
            write!(
                f,
                "{}: {}: {}: {}",
                self.file.display(),
                self.element,
                self.kind,
                self.detail
            )
        }
    }
}

impl std::error::Error for LoadError {}

/// Any error Iris reports.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The scene could not be loaded.
    #[error("{0}")]
    Load(#[from] LoadError),
    /// A command-line value is invalid.
    #[error("invalid argument: {0}")]
    Usage(String),
    /// The requested acceleration backend is unavailable or failed.
    #[error("acceleration structure: {0}")]
    Accel(String),
    /// The denoiser is unavailable, was given inconsistent buffers, or failed.
    #[error("denoiser: {0}")]
    Denoise(String),
    /// An output file could not be written.
    #[error("{path}: cannot write output: {reason}")]
    Output {
        /// The output path.
        path: PathBuf,
        /// Why.
        reason: String,
    },
}

/// Result alias used throughout the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Parses a command-line name among `names` (case-insensitive, surrounding blanks
/// ignored): the one rule by which every enum the CLI reads is parsed. The error names
/// `flag`, the value and the accepted names.
pub fn parse_name<T: Copy>(flag: &str, s: &str, names: &[(&str, T)]) -> Result<T> {
    names
        .iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(s.trim()))
        .map(|&(_, v)| v)
        .ok_or_else(|| {
            let accepted: Vec<&str> = names.iter().map(|(n, _)| *n).collect();
            Error::Usage(format!(
                "{flag} {s:?}: unknown value (accepted: {})",
                accepted.join(", ")
            ))
        })
}
