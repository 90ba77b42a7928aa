//! The identity of a render, as a shard's partial image records it
//! ([`crate::output::partial`]) and `iris merge` compares it ([`super::merge`]): every
//! value that changes the image, so parts of different renders are refused.
//!
//! The identity is an ordered list of `key=value` entries ([`identity`]):
//! - `iris_version`: the crate's version (another Iris may render other bits);
//! - `scene_sha256`: SHA-256 of the scene file's bytes (the file named on the command
//!   line);
//! - `content_sha256`: SHA-256 of the render scene as built ([`content_sha256`]: geometry,
//!   materials, texture images, lights, environment), which also covers what the file
//!   references (glTF buffers and images, OBJ libraries, environment maps), the
//!   `--stone`/`--metal` overrides, the studio and the floor;
//! - `method`, `seed`, `size`, `sampler`, `spectral`, `max_depth`, `accel` (the backend
//!   that traced: Embree and the BVH may differ in the last bits), `camera` (the camera
//!   rendered, the file's or the automatic framing), `unit` (samples or passes), `total`
//!   (the whole render's units, or `open`);
//! - `options`: one canonical string of every option above plus the photon settings and
//!   the preview choices, and `options_sha256`, its hash.
//!
//! Not part of it: threads, `--time`, `--target-error` (they change how many units a
//! shard takes, which its counts record), display and output flags. Hashes are lower-case
//! hex.

use super::RenderOptions;
use crate::error::{LoadError, LoadErrorKind, Result};
use crate::scene::Scene;
use sha2::{Digest, Sha256};
use std::fmt::Write as _;
use std::path::Path;

/// Lower-case hex of a digest.
fn hex(bytes: &[u8]) -> String {
    bytes.iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    })
}

/// SHA-256 of `s`, hex.
pub fn sha256_text(s: &str) -> String {
    hex(&Sha256::digest(s.as_bytes()))
}

/// SHA-256 of the scene file at `path` (read as [`crate::fileio::Input::Scene`]), hex; an
/// error names the file.
pub fn file_sha256(path: &Path) -> Result<String> {
    let mut file = crate::fileio::input::open(path, crate::fileio::Input::Scene)
        .map_err(|e| e.at(path, ""))?;
    let mut hasher = Sha256::new();
    std::io::copy(&mut file, &mut hasher)
        .map_err(|e| LoadError::new(path, "", LoadErrorKind::Io, e.to_string()))?;
    Ok(hex(&hasher.finalize()))
}

/// A hasher that `Debug` output can be written into without building the string.
struct HashWriter(Sha256);

impl std::fmt::Write for HashWriter {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.0.update(s.as_bytes());
        Ok(())
    }
}

/// SHA-256 of the render scene's content: vertex positions, normals, both sets of texture
/// coordinates and tangents, triangles and their materials (as little-endian bits), then
/// the `Debug` text of the materials, texture images (with their texels), lights (with
/// their spectra) and environment. Deterministic for a given Iris build (no hash maps are
/// involved).
pub fn content_sha256(scene: &Scene) -> String {
    let mut h = HashWriter(Sha256::new());
    let mut bytes = Vec::new();
    let v = scene.vertices();
    let floats = |values: &[f32], bytes: &mut Vec<u8>| {
        bytes.extend(values.iter().flat_map(|c| c.to_bits().to_le_bytes()));
    };
    for p in v.positions.iter().chain(&v.normals) {
        floats(&p.to_array(), &mut bytes);
    }
    for uv in v.uvs.iter().chain(&v.uvs1) {
        floats(&uv.to_array(), &mut bytes);
    }
    for t in &v.tangents {
        floats(&t.to_array(), &mut bytes);
    }
    for t in scene.triangles() {
        let m = t.material();
        bytes.extend(t.vertices.iter().chain([&m]).flat_map(|i| i.to_le_bytes()));
    }
    h.0.update(&bytes);
    let _ = write!(
        h,
        "{:?}{:?}{:?}{:?}",
        scene.materials(),
        scene.images(),
        scene.lights(),
        scene.environment()
    );
    hex(&h.0.finalize())
}

/// The identity entries of a render (see the module docs): `opts` as given, the render
/// `scene`, its `camera` and size, the resolved `method` name, spectral transport, and the
/// whole render's units (`total`; `None` = an open budget).
pub fn identity(
    opts: &RenderOptions,
    scene: &Scene,
    camera: &crate::scene::desc::CameraDesc,
    (width, height): (u32, u32),
    (method, spectral): (crate::integrator::Method, bool),
    total: Option<u64>,
) -> Result<Vec<(String, String)>> {
    let p = &opts.photon;
    let unit = if method == crate::integrator::Method::Sppm {
        "passes"
    } else {
        "samples"
    };
    let total = total.map_or("open".to_string(), |t| t.to_string());
    let env = match &opts.env {
        None => "file",
        Some(None) => "none",
        Some(Some(_)) => "flag",
    };
    let mut e: Vec<(&str, String)> = vec![
        ("iris_version", env!("CARGO_PKG_VERSION").into()),
        ("scene_sha256", file_sha256(&opts.scene)?),
        ("content_sha256", content_sha256(scene)),
        ("method", method.name().into()),
        ("seed", opts.seed.to_string()),
        ("size", format!("{width}x{height}")),
        ("sampler", format!("{:?}", opts.sampler)),
        ("spectral", spectral.to_string()),
        ("max_depth", opts.max_depth.to_string()),
        ("accel", scene.backend_name().into()),
        ("camera", format!("{camera:?}")),
        ("unit", unit.into()),
        ("total", total),
    ];
    let mut options = e
        .iter()
        .skip(3)
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join("; ");
    let _ = write!(
        options,
        "; photons={}; radius={:?}; alpha={}; photon_rr={:?}; k={},{}; caustics={:?}; \
         env={env}; preview={:?}; looks={:?}",
        p.photons,
        p.radius,
        p.alpha,
        p.roulette,
        p.k_caustic,
        p.k_global,
        p.caustic_mode,
        opts.preview,
        opts.looks
    );
    e.push(("options_sha256", sha256_text(&options)));
    e.push(("options", options));
    Ok(e.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
}

/// What each identity key means, for a refusal's message ("different seeds").
pub fn describe(key: &str) -> &str {
    match key {
        "iris_version" => "Iris versions",
        "scene_sha256" => "scene files (content)",
        "content_sha256" => "scenes as built (referenced files, --stone/--metal, studio)",
        "method" => "methods",
        "seed" => "seeds",
        "size" => "sizes",
        "sampler" => "samplers",
        "spectral" => "transports (spectral)",
        "max_depth" => "--max-depth values",
        "accel" => "acceleration backends",
        "camera" => "cameras",
        "unit" => "units",
        "total" => "totals (--spp or --passes)",
        "options_sha256" | "options" => "options",
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hashes_are_sha256() {
        // FIPS 180-2 test vector.
        assert_eq!(
            sha256_text("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        let dir = std::env::temp_dir().join(format!("iris-shard-id-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("x.txt");
        std::fs::write(&f, "abc").unwrap();
        assert_eq!(file_sha256(&f).unwrap(), sha256_text("abc"));
        let missing = file_sha256(&dir.join("none.glb")).unwrap_err().to_string();
        assert!(missing.contains("none.glb"), "{missing}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
