//! Wavefront OBJ/MTL loader → [`SceneDesc`] (not yet validated).
//!
//! Units and frames: OBJ positions are taken as **metres, +Y up, right-handed** and copied
//! as given (no transform); faces are assumed counter-clockwise seen from outside, as the
//! OBJ convention says. Polygons are fan-triangulated by tobj (`triangulate` +
//! `single_index`: one index per corner for positions, normals and UVs).
//!
//! Pipeline: read bytes (missing file → `Io`; invalid UTF-8 is replaced with a warning) →
//! `scan` (line-numbered errors, canonical text) → tobj on the canonical text, with an
//! MTL loader closure that parses each `mtllib` through `mtl` (a missing library is a
//! warning: its materials fall back to the default) → one [`MeshDesc`] per tobj model,
//! named `object "name"` / `group "name"` (`… part k` when tobj splits one name over
//! several materials) → materials via `material`.
//!
//! Per-vertex data: normals and UVs are kept only when every vertex of the model has one
//! (otherwise dropped with a warning). UVs are converted to glTF's convention (origin at
//! the top-left of the image): `v_gltf = 1 − v_obj`.
//!
//! Meshes without a known material get an explicit grey diffuse double-sided material
//! (glTF's default material is a rough metal, which is not what an OBJ without MTL means).

mod material;
mod mtl;
mod scan;

use super::files::Files;
use crate::error::{LoadError, LoadErrorKind};
use crate::material::MaterialDesc;
use crate::scene::desc::{MeshDesc, SceneDesc};
use glam::{Vec2, Vec3};
use mtl::RawMtl;
use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

/// What the MTL loader closure collects while tobj runs.
#[derive(Default)]
struct Libraries {
    /// Every material of every library, in tobj's material-id order, with its library path.
    materials: Vec<(PathBuf, RawMtl)>,
    warnings: Vec<String>,
    /// The first MTL error (tobj only sees a generic failure).
    error: Option<LoadError>,
    /// Libraries already parsed: a repeated `mtllib` adds nothing (and costs nothing, so
    /// a file repeating one line 10⁵ times cannot make loading quadratic).
    loaded: std::collections::HashSet<PathBuf>,
}

/// Loads an OBJ file (and its MTL libraries) into a world-space scene description.
pub fn load_obj(path: &Path) -> Result<SceneDesc, LoadError> {
    let bytes = Files::Disk
        .read(path, crate::fileio::Input::Scene)
        .map_err(|e| e.at(path, ""))?;
    load_obj_bytes(path, bytes, Files::Disk)
}

/// Loads OBJ `bytes` that were read from `path`; `mtllib` libraries and their texture
/// maps are looked up next to `path` through `files`.
pub fn load_obj_bytes(
    path: &Path,
    bytes: Vec<u8>,
    files: Files<'_>,
) -> Result<SceneDesc, LoadError> {
    let mut warnings = Vec::new();
    let text = utf8_lossy(path, bytes, &mut warnings);
    let scanned = scan::scan(path, &text)?;
    drop(text);

    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let libs = RefCell::new(Libraries::default());
    // triangulate + single_index, points and 2-vertex lines ignored.
    let options = tobj::GPU_LOAD_OPTIONS;
    let result = tobj::load_obj_buf(&mut scanned.text.as_bytes(), &options, |lib| {
        load_library(&dir, lib, &libs, files)
    });
    let libs = libs.into_inner();
    if let Some(e) = libs.error {
        return Err(e);
    }
    let (models, _) = result.map_err(|e| {
        LoadError::new(
            path,
            "",
            LoadErrorKind::Parse,
            format!("OBJ rejected by tobj: {e}"),
        )
    })?;
    warnings.extend(libs.warnings);
    ignored_statements(&scanned.ignored, &mut warnings);

    let mut desc = SceneDesc {
        source: path.to_path_buf(),
        ..SceneDesc::default()
    };
    let mut images = material::Images::default();
    let mut unsupported = Vec::new();
    // Only materials some face uses get their textures decoded (the render plan's
    // "textures" stage).
    let used: std::collections::BTreeSet<usize> = models
        .iter()
        .filter(|m| !m.mesh.indices.is_empty())
        .filter_map(|m| m.mesh.material_id)
        .collect();
    for (index, (lib, raw)) in libs.materials.iter().enumerate() {
        let textures = if used.contains(&index) {
            Some(&mut images)
        } else {
            desc.skipped_textures += usize::from(raw.map_kd.is_some());
            None
        };
        let m = material::to_material(index, raw, lib, files, textures, &mut unsupported)?;
        desc.materials.push(m);
    }
    desc.images = images.images;
    warnings.extend(images.warnings);
    unsupported_mtl(&unsupported, &mut warnings);
    unknown_materials(&scanned.used_materials, &libs.materials, &mut warnings);

    let mtl_count = desc.materials.len();
    desc.meshes = to_meshes(
        &models,
        &scanned.names,
        mtl_count,
        &mut desc.materials,
        &mut warnings,
    );
    desc.warnings = warnings;
    Ok(desc)
}

/// One mesh per non-empty tobj model. `materials` holds the `mtl_count` MTL materials; the
/// default material is appended to it when a model has none (or an unknown one).
fn to_meshes(
    models: &[tobj::Model],
    names_kind: &HashMap<String, scan::NameKind>,
    mtl_count: usize,
    materials: &mut Vec<MaterialDesc>,
    warnings: &mut Vec<String>,
) -> Vec<MeshDesc> {
    let mut meshes = Vec::new();
    let mut names: HashMap<&str, usize> = HashMap::new();
    for model in models.iter().filter(|m| !m.mesh.indices.is_empty()) {
        *names.entry(model.name.as_str()).or_default() += 1;
    }
    let mut seen: HashMap<&str, usize> = HashMap::new();
    let (mut partial_normals, mut partial_uvs) = (Vec::new(), Vec::new());
    let mut default_material = None;
    for model in models.iter().filter(|m| !m.mesh.indices.is_empty()) {
        let kind = names_kind.get(&model.name).map_or("object", |k| k.word());
        let part = seen.entry(model.name.as_str()).or_default();
        *part += 1;
        let mut name = format!("{kind} \"{}\"", model.name);
        if names.get(model.name.as_str()).copied().unwrap_or(0) > 1 {
            name = format!("{name} part {part}");
        }
        let mesh = &model.mesh;
        let vertex_count = mesh.positions.len() / 3;
        let mut normals = vec3s(&mesh.normals);
        if normals.len() != vertex_count && !normals.is_empty() {
            partial_normals.push(name.clone());
            normals.clear();
        }
        let mut uvs: Vec<Vec2> = mesh
            .texcoords
            .chunks_exact(2)
            .filter_map(|c| match c {
                [u, v] => Some(Vec2::new(*u, 1.0 - *v)),
                _ => None,
            })
            .collect();
        if uvs.len() != vertex_count && !uvs.is_empty() {
            partial_uvs.push(name.clone());
            uvs.clear();
        }
        let material = match mesh.material_id.filter(|&i| i < mtl_count) {
            Some(i) => i,
            None => *default_material.get_or_insert_with(|| {
                materials.push(material::default_material(materials.len()));
                materials.len() - 1
            }),
        };
        meshes.push(MeshDesc {
            name,
            positions: vec3s(&mesh.positions),
            normals,
            uvs,
            uvs1: Vec::new(),
            tangents: Vec::new(),
            orientation: glam::Mat3::IDENTITY,
            indices: mesh
                .indices
                .chunks_exact(3)
                .filter_map(|c| match c {
                    [a, b, c] => Some([*a, *b, *c]),
                    _ => None,
                })
                .collect(),
            material: Some(material),
        });
    }
    for (list, what) in [
        (partial_normals, "normals"),
        (partial_uvs, "texture coordinates"),
    ] {
        if !list.is_empty() {
            warnings.push(format!(
                "{what} ignored where only some faces have them: {}",
                list.join(", ")
            ));
        }
    }
    meshes
}

/// Decodes UTF-8, replacing invalid bytes (e.g. Latin-1 comments) with a warning.
fn utf8_lossy(path: &Path, bytes: Vec<u8>, warnings: &mut Vec<String>) -> String {
    match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => {
            warnings.push(format!(
                "{}: not valid UTF-8; invalid bytes replaced",
                path.display()
            ));
            String::from_utf8_lossy(e.as_bytes()).into_owned()
        }
    }
}

fn vec3s(flat: &[f32]) -> Vec<Vec3> {
    flat.chunks_exact(3)
        .filter_map(|c| match c {
            [x, y, z] => Some(Vec3::new(*x, *y, *z)),
            _ => None,
        })
        .collect()
}

/// tobj's material loader: parses `lib` (relative to the OBJ's folder) with `mtl`.
/// `mtllib a.mtl b.mtl` (several files on one line) is split when no file has the whole name.
fn load_library(
    dir: &Path,
    lib: &Path,
    state: &RefCell<Libraries>,
    files: Files<'_>,
) -> tobj::MTLLoadResult {
    let mut state = state.borrow_mut();
    if state.error.is_some() {
        return Err(tobj::LoadError::GenericFailure);
    }
    let whole = dir.join(lib);
    let spelled = lib.to_string_lossy().into_owned();
    let paths: Vec<PathBuf> = if files.is_file(&whole) || !spelled.contains(' ') {
        vec![whole]
    } else {
        spelled.split_whitespace().map(|f| dir.join(f)).collect()
    };
    let mut names = Vec::new();
    let mut repeated = false;
    for file in paths {
        if !state.loaded.insert(file.clone()) {
            repeated = true;
            continue;
        }
        let text = match files.read(&file, crate::fileio::Input::Scene) {
            Ok(bytes) => utf8_lossy(&file, bytes, &mut state.warnings),
            Err(e) => {
                state.warnings.push(format!(
                    "material library {} not read ({e}); its materials use the default material",
                    file.display()
                ));
                continue;
            }
        };
        match mtl::parse_mtl(&file, &text) {
            Ok(parsed) => {
                state.warnings.extend(parsed.warnings);
                for raw in parsed.materials {
                    names.push(raw.name.clone());
                    state.materials.push((file.clone(), raw));
                }
            }
            Err(e) => {
                state.error = Some(e);
                return Err(tobj::LoadError::MaterialParseError);
            }
        }
    }
    if names.is_empty() {
        if repeated {
            // Its materials are already in tobj's table.
            return Ok((Vec::new(), Default::default()));
        }
        return Err(tobj::LoadError::OpenFileFailed);
    }
    // tobj offsets these ids by the materials of earlier libraries, like `state.materials`.
    let map = names
        .iter()
        .enumerate()
        .map(|(i, n)| (n.clone(), i))
        .collect();
    let materials = names
        .into_iter()
        .map(|name| tobj::Material {
            name,
            ..Default::default()
        })
        .collect();
    Ok((materials, map))
}

fn ignored_statements(ignored: &BTreeMap<String, (usize, usize)>, warnings: &mut Vec<String>) {
    if ignored.is_empty() {
        return;
    }
    let list: Vec<String> = ignored
        .iter()
        .map(|(key, (count, line))| format!("`{key}` ×{count} (first at line {line})"))
        .collect();
    warnings.push(format!("OBJ statements ignored: {}", list.join(", ")));
}

/// One warning for every unsupported MTL key / illum value, each listed once.
fn unsupported_mtl(entries: &[(String, String)], warnings: &mut Vec<String>) {
    let mut by_key: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (key, material) in entries {
        let list = by_key.entry(key).or_default();
        if !list.contains(&material.as_str()) {
            list.push(material);
        }
    }
    if by_key.is_empty() {
        return;
    }
    let list: Vec<String> = by_key
        .iter()
        .map(|(key, mats)| format!("`{key}` (in \"{}\")", mats.join("\", \"")))
        .collect();
    warnings.push(format!(
        "MTL statements not supported, ignored: {}",
        list.join(", ")
    ));
}

fn unknown_materials(
    used: &std::collections::HashSet<String>,
    defined: &[(PathBuf, RawMtl)],
    warnings: &mut Vec<String>,
) {
    let defined: std::collections::HashSet<&str> =
        defined.iter().map(|(_, m)| m.name.as_str()).collect();
    let mut unknown: Vec<&str> = used
        .iter()
        .filter(|u| !defined.contains(u.as_str()))
        .map(String::as_str)
        .collect();
    if !unknown.is_empty() {
        unknown.sort_unstable();
        warnings.push(format!(
            "usemtl names not found in any material library (default material used): \"{}\"",
            unknown.join("\", \"")
        ));
    }
}
