//! Entry points that run the real loaders on bytes in memory, for the cargo-fuzz targets
//! in `fuzz/` and the replay test `tests/heap/fuzz_replay/mod.rs`.
//!
//! Each function goes through the same code as loading a file from disk (the loaders'
//! `*_bytes` functions, then [`crate::scene::validate`]), except that referenced files come
//! from [`Files::Memory`]: a glTF's external buffers, images and environment maps resolve
//! to nothing (a `MissingBuffer`/`Io` error), and an OBJ's `mtllib` resolves to the given
//! MTL bytes, whatever its name. No input can make these functions read the file system.
//! Environment maps (HDR/EXR), which Iris only reads from files, are written to a scratch
//! file in the system temp dir and loaded with [`crate::light::env::load`].
//!
//! Contract (checked by the fuzzers): every input returns `Ok` or an `Err` naming the
//! file and, where there is one, the element; never a panic, a hang, or an allocation
//! out of proportion with the limits in [`crate::load::decode`], [`crate::light::env::MAX_TEXELS`]
//! and [`crate::scene::validate::MAX_ELEMENTS`].

use super::files::Files;
use crate::error::{Error, LoadError};
use crate::scene::desc::SceneDesc;
use std::path::{Path, PathBuf};

/// Separates the OBJ part from the MTL part in an `obj` fuzz input.
pub const OBJ_MTL_SEPARATOR: &[u8] = b"\n#%%MTL%%\n";

/// Loads and validates a `.glb` or `.gltf` (recognised by the `glTF` magic) from memory.
pub fn load_gltf_bytes(bytes: &[u8]) -> Result<SceneDesc, LoadError> {
    let name = if bytes.starts_with(b"glTF") {
        "fuzz-input.glb"
    } else {
        "fuzz-input.gltf"
    };
    let none = |_: &Path| None;
    let desc = super::gltf::load_gltf_bytes(Path::new(name), bytes, Files::Memory(&none))?;
    crate::scene::validate::validate(desc)
}

/// Loads and validates an OBJ whose `mtllib` statements all resolve to `mtl`.
pub fn load_obj_bytes(obj: &[u8], mtl: &[u8]) -> Result<SceneDesc, LoadError> {
    // Only the first `.mtl` path asked for exists: with every name resolving to the same
    // bytes, `mtllib a.mtl b.mtl …` would parse one MTL once per name, a quadratic cost
    // that real files (one MTL file per name) do not have.
    let first = std::cell::RefCell::new(None::<PathBuf>);
    let lookup = |p: &Path| {
        let is_mtl = p.extension().is_some_and(|e| e.eq_ignore_ascii_case("mtl"));
        if !is_mtl {
            return None;
        }
        let mut first = first.borrow_mut();
        let first = first.get_or_insert_with(|| p.to_path_buf());
        (first == p).then(|| mtl.to_vec())
    };
    let path = Path::new("fuzz-input.obj");
    let desc = super::obj::load_obj_bytes(path, obj.to_vec(), Files::Memory(&lookup))?;
    crate::scene::validate::validate(desc)
}

/// [`load_obj_bytes`] on `data` split at the first [`OBJ_MTL_SEPARATOR`] (no separator:
/// the whole input is the OBJ and the MTL is empty).
pub fn load_obj_mtl_bytes(data: &[u8]) -> Result<SceneDesc, LoadError> {
    let (obj, mtl) = split_obj_mtl(data);
    load_obj_bytes(obj, mtl)
}

/// The OBJ and MTL parts of an `obj` fuzz input.
pub fn split_obj_mtl(data: &[u8]) -> (&[u8], &[u8]) {
    let sep = OBJ_MTL_SEPARATOR;
    match data.windows(sep.len()).position(|w| w == sep) {
        Some(at) => (&data[..at], &data[at + sep.len()..]),
        None => (data, &[]),
    }
}

/// What [`decode_image_bytes`] made of an input.
#[derive(Debug)]
pub struct ImageOutcome {
    /// The texture decoder's result: the size, or the error kind and message.
    pub texture: Result<(u32, u32), (crate::error::LoadErrorKind, String)>,
    /// The environment-map loader's result, when the input starts like EXR or HDR.
    pub environment: Option<Result<(u32, u32), Error>>,
}

/// Decodes `bytes` as a texture (as the glTF and MTL loaders do) and, when they start like
/// an OpenEXR or Radiance HDR file, also as an environment map (as `--env` does).
pub fn decode_image_bytes(bytes: &[u8]) -> ImageOutcome {
    let texture =
        super::decode::decode_rgba8(bytes, "fuzz-input".into()).map(|img| (img.width, img.height));
    let env_ext = if bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        Some("exr")
    } else if bytes.starts_with(b"#?") {
        Some("hdr")
    } else {
        None
    };
    ImageOutcome {
        texture,
        environment: env_ext.map(|ext| load_env_bytes(bytes, ext)),
    }
}

/// Writes `bytes` to a scratch `.ext` file and loads it as an environment map.
fn load_env_bytes(bytes: &[u8], ext: &str) -> Result<(u32, u32), Error> {
    let path = scratch_file(ext);
    std::fs::write(&path, bytes).map_err(|e| Error::Output {
        path: path.clone(),
        reason: e.to_string(),
    })?;
    let map = crate::light::env::load(&path);
    let _ = std::fs::remove_file(&path);
    map.map(|m| (m.width(), m.height()))
}

/// A scratch path private to this process and thread.
fn scratch_file(ext: &str) -> PathBuf {
    let thread = format!("{:?}", std::thread::current().id());
    let thread: String = thread.chars().filter(char::is_ascii_digit).collect();
    std::env::temp_dir().join(format!(
        "iris-fuzz-env-{}-{thread}.{ext}",
        std::process::id()
    ))
}
