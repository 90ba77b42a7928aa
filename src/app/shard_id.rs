//! The identity of a render, as a shard's partial image records it
//! ([`crate::output::partial`]) and `iris merge` compares it ([`super::merge`]): every
//! value that changes the image, so parts of different renders are refused.
//!
//! The identity is an ordered list of `key=value` entries ([`identity`]):
//! - `iris_version`: the crate's version (another Iris may render other bits);
//! - `scene_sha256`: SHA-256 of the scene file's bytes (the file named on the command
//!   line);
//! - `content_sha256`: SHA-256 of the render scene as built
//!   ([`crate::scene::Scene::write_content`]: geometry, materials, texture images, lights,
//!   environment, fog, cameras), which also covers what the file references (glTF buffers
//!   and images, OBJ libraries, environment maps), the `--stone`/`--metal` overrides, the
//!   studio, the floor and `--fog`/`--env`;
//! - `method`, `seed`, `size`, `sampler`, `spectral`, `max_depth`, `accel` (the backend
//!   that traced: Embree and the BVH may differ in the last bits), `camera` (the camera
//!   rendered, the file's or the automatic framing), `unit` (samples or passes), `total`
//!   (the whole render's units, or `open`);
//! - `integrator`: the resolved integrator with every setting it renders with (photon
//!   settings, caustic mode, polarization and the polarizer);
//! - `options`: every `iris render` option that changes the image, as given
//!   ([`image_options`]), and `options_sha256`, its hash.
//!
//! Both lists are derived from the settings, not written by hand: [`image_options`]
//! destructures [`RenderOptions`] and [`render_entries`] destructures
//! [`RenderSettings`] exhaustively, so a new field does not compile until it is either
//! part of the identity or named as one that does not change the image, and
//! `tests/farm/shards/identity_flags.rs` fails for an `iris render` flag that is not classified.
//! Not part of it:
//! threads, `--time`, `--target-error`, `--checkpoint` (they change how many units a shard
//! takes, which its counts record), display, denoising and output flags (a partial image
//! holds the raw sums; `iris merge` has its own display flags). Hashes are lower-case hex.

use super::RenderOptions;
use crate::error::{LoadError, LoadErrorKind, Result};
use crate::integrator::Integrator;
use crate::render::RenderSettings;
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

/// SHA-256 of the render scene's content ([`Scene::write_content`]).
pub fn content_sha256(scene: &Scene) -> String {
    let mut h = Sha256::new();
    scene.write_content(&mut |bytes| h.update(bytes));
    hex(&h.finalize())
}

/// The `iris render` options that change the image, as canonical text: every field of
/// [`RenderOptions`] is either written here or named as one that does not change the
/// image (see the module docs). An environment given by `--env` is written as the
/// SHA-256 of its description (a map's texels would make the text long).
pub fn image_options(opts: &RenderOptions) -> String {
    let RenderOptions {
        // Identity entries of their own: the file's hash and the scene as built.
        scene: _,
        // Where the image goes.
        output: _,
        size,
        // The whole render's units are the `total` entry.
        spp: _,
        method,
        max_depth,
        // How many units a shard takes, which its counts record.
        time_limit: _,
        checkpoint: _,
        watch: _,
        photon,
        accel,
        seed,
        sampler,
        threads: _,
        camera,
        look_at,
        // A partial image holds raw sums; `iris merge` applies its own display flags.
        display: _,
        quiet: _,
        env,
        fog,
        spectral,
        polarization,
        polarizer,
        // `--reference`, `--report`, `--plot`, `--target-error`: measurements.
        measure: _,
        preview,
        looks,
        explain: _,
        // A shard's partial image is not denoised (`--denoise on` is refused with it).
        denoise: _,
        adaptive,
        spin,
        exr_copy: _,
        // The shard itself is recorded apart from the identity.
        shard: _,
    } = opts;
    let crate::integrator::PhotonSettings {
        photons,
        radius,
        alpha,
        // SPPM's passes are the whole render's units, the `total` entry.
        passes: _,
        roulette,
        k_caustic,
        k_global,
        caustic_mode,
    } = photon;
    let crate::prepare::drop_in::PreviewOptions {
        studio,
        ground,
        view,
        background,
    } = preview;
    let env = match env {
        None => "file".to_string(),
        Some(None) => "none".to_string(),
        Some(Some(e)) => format!("sha256:{}", sha256_text(&format!("{e:?}"))),
    };
    let entries: Vec<(&str, String)> = vec![
        ("size", format!("{size:?}")),
        ("method", format!("{method:?}")),
        ("max-depth", max_depth.to_string()),
        ("photons", photons.to_string()),
        ("radius", format!("{radius:?}")),
        ("alpha", format!("{alpha:?}")),
        ("photon-rr", format!("{roulette:?}")),
        ("k", format!("{k_caustic},{k_global}")),
        ("caustics", format!("{caustic_mode:?}")),
        ("accel", format!("{accel:?}")),
        ("seed", seed.to_string()),
        ("sampler", format!("{sampler:?}")),
        ("camera", format!("{camera:?}")),
        ("camera-look-at", format!("{look_at:?}")),
        ("env", env),
        ("fog", format!("{fog:?}")),
        ("spectral", format!("{spectral:?}")),
        ("polarization", format!("{polarization:?}")),
        ("polarizer", format!("{polarizer:?}")),
        ("studio", format!("{studio:?}")),
        ("ground", format!("{ground:?}")),
        ("view", format!("{view:?}")),
        ("background", format!("{background:?}")),
        ("stone/metal", format!("{looks:?}")),
        ("adaptive", format!("{adaptive:?}")),
        ("turn", format!("{spin:?}")),
    ];
    entries
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join("; ")
}

/// The identity entries of the render's settings: every field of [`RenderSettings`] that
/// changes the image (the others are named as not changing it).
fn render_entries(settings: &RenderSettings) -> Vec<(&'static str, String)> {
    let RenderSettings {
        width,
        height,
        // The whole render's units are the `total` entry.
        spp: _,
        seed,
        threads: _,
        quiet: _,
        spectral,
        time_limit: _,
        sampler,
        adaptive,
        cancel: _,
        kernel,
    } = settings;
    // The kernel as the environment resolves it (an error there stops the render first).
    let kernel = kernel
        .resolve()
        .map_or("invalid".to_string(), |k| format!("{k:?}"));
    vec![
        ("seed", seed.to_string()),
        ("size", format!("{width}x{height}")),
        ("sampler", format!("{sampler:?}")),
        ("spectral", spectral.to_string()),
        ("adaptive", format!("{adaptive:?}")),
        ("kernel", kernel),
    ]
}

/// The identity entries of a render (see the module docs): `opts` as given, the render
/// `scene` and its `camera`, the resolved `integrator` and `settings`, and the whole
/// render's units (`total`; `None` = an open budget).
pub fn identity(
    opts: &RenderOptions,
    (scene, camera): (&Scene, &crate::scene::desc::CameraDesc),
    (integrator, settings): (&Integrator, &RenderSettings),
    total: Option<u64>,
) -> Result<Vec<(String, String)>> {
    let method = integrator.method();
    let total = total.map_or("open".to_string(), |t| t.to_string());
    let mut e: Vec<(&str, String)> = vec![
        ("iris_version", env!("CARGO_PKG_VERSION").into()),
        ("scene_sha256", file_sha256(&opts.scene)?),
        ("content_sha256", content_sha256(scene)),
        ("method", method.name().into()),
    ];
    e.extend(render_entries(settings));
    e.extend([
        ("max_depth", integrator.max_depth().to_string()),
        ("accel", scene.backend_name().into()),
        ("camera", format!("{camera:?}")),
        ("unit", super::render_options::unit_name(method).into()),
        ("total", total),
        ("integrator", format!("{integrator:?}")),
    ]);
    let options = image_options(opts);
    e.push(("options_sha256", sha256_text(&options)));
    e.push(("options", options));
    Ok(e.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
}

/// The first option that differs between two `options` entries ([`image_options`], whose
/// keys are the flags' names): what differs ("--fog values") and its two values; `None`
/// when they agree or either is missing.
pub fn option_difference(a: Option<&str>, b: Option<&str>) -> Option<(String, String, String)> {
    let (a, b) = (a?, b?);
    let split = |s: &str| -> Vec<(String, String)> {
        s.split("; ")
            .map(|kv| match kv.split_once('=') {
                Some((k, v)) => (k.to_string(), v.to_string()),
                None => (kv.to_string(), String::new()),
            })
            .collect()
    };
    let (ea, eb) = (split(a), split(b));
    for (k, va) in &ea {
        let vb = eb.iter().find(|(kb, _)| kb == k).map(|(_, v)| v.clone());
        if vb.as_deref() != Some(va.as_str()) {
            let what = match k.as_str() {
                "stone/metal" => "--stone/--metal values".to_string(),
                "k" => "photon gather counts".to_string(),
                flag => format!("--{flag} values"),
            };
            return Some((what, va.clone(), vb.unwrap_or("none".into())));
        }
    }
    (ea.len() != eb.len()).then(|| ("options".into(), a.into(), b.into()))
}

/// Whether an identity key's value reads as a setting (seed, size, …) rather than a hash
/// or a long description (`iris merge` names those differences first).
pub fn is_readable(key: &str) -> bool {
    !matches!(
        key,
        "content_sha256" | "integrator" | "options" | "options_sha256"
    )
}

/// What each identity key means, for a refusal's message ("different seeds").
pub fn describe(key: &str) -> &str {
    match key {
        "iris_version" => "Iris versions",
        "scene_sha256" => "scene files (content)",
        "content_sha256" => {
            "scenes as built (referenced files, --stone/--metal, studio, --env, --fog)"
        }
        "method" => "methods",
        "seed" => "seeds",
        "size" => "sizes",
        "sampler" => "samplers",
        "spectral" => "transports (spectral)",
        "max_depth" => "--max-depth values",
        "adaptive" => "adaptive sampling",
        "integrator" => "integrator settings (photons, radius, caustics, polarization, polarizer)",
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
