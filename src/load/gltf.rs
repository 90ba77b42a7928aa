//! glTF 2.0 loader (`.gltf` with external or `data:` buffers, and `.glb`).
//!
//! Produces a [`SceneDesc`] in world space: metres, right-handed, +Y up (glTF 2.0 §3.4).
//! Node hierarchies are flattened; each triangle-mode primitive instance becomes one
//! [`MeshDesc`](crate::scene::desc::MeshDesc) named like `node 3 "Gem" mesh 1 "Cut" primitive 0`.
//! Nodes whose world transform mirrors space (negative determinant) get their triangle
//! winding flipped so that `(p1-p0)×(p2-p0)` still points out of the object.
//!
//! The loader never panics on file content. The document is parsed without the `gltf`
//! crate's built-in validation (which rejects required extensions it does not know), then
//! validated here so that the crate's accessors, which `unwrap` checked values, are safe.
//! Buffers, accessors, images and cameras are read by this module's own bounds-checked code
//! instead of `gltf`'s importers and readers. Every failure is a [`LoadError`] naming the
//! file and the element (`buffer 0 "geo"`, `material 2 "Glass"`, …).
//!
//! Extension policy: the KHR material extensions listed in `READ_EXTENSIONS`,
//! KHR_lights_punctual, KHR_mesh_quantization (any accessor component type is read),
//! and compressed geometry (KHR_draco_mesh_compression, EXT_/KHR_meshopt_compression)
//! are honoured; other used extensions are listed in one warning, and unknown required
//! extensions only warn.
//!
//! Submodules: `uri` (data/relative URIs), `source` (buffers and images), `meshopt`
//! (compressed buffer views, decoded before anything reads a view), `accessor` (typed
//! accessor reads), `draco` (Draco-compressed primitives), `mesh` (primitives),
//! `material`, `scene` (node graph, lights, cameras).

mod accessor;
pub(crate) mod crystal;
mod draco;
mod draco_header;
mod extras;
mod instancing;
mod iridescence_anisotropy;
mod material;
mod material_layers;
mod mesh;
mod meshopt;
mod scatter;
mod scene;
mod source;
mod spec_gloss;
mod texture_info;
mod texture_source;
mod texture_transform;
mod unlit;
mod uri;

use super::files::Files;
use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::{CompressedGeometry, SceneDesc};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Extensions whose data Iris reads (or, for `KHR_mesh_quantization`, honours by reading
/// every accessor component type).
const READ_EXTENSIONS: &[&str] = &[
    "KHR_materials_ior",
    "KHR_materials_transmission",
    "KHR_materials_volume",
    "KHR_materials_specular",
    "KHR_materials_emissive_strength",
    "KHR_materials_dispersion",
    "KHR_materials_volume_scatter",
    "KHR_materials_scatter",
    "KHR_materials_iridescence",
    "KHR_materials_anisotropy",
    "KHR_lights_punctual",
    "KHR_mesh_quantization",
    "KHR_texture_transform",
    "EXT_mesh_gpu_instancing",
    "KHR_materials_unlit",
    "EXT_texture_webp",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_meshopt_compression",
];

/// Upper bound on triangles (and on vertices) over the whole flattened scene.
const MAX_TRIANGLES: usize = 1 << 27;

/// Loads a glTF/GLB file into a world-space scene description (not yet validated).
pub fn load_gltf(path: &Path) -> Result<SceneDesc, LoadError> {
    let bytes = Files::Disk
        .read(path, crate::fileio::Input::Scene)
        .map_err(|e| e.at(path, ""))?;
    load_gltf_bytes(path, &bytes, Files::Disk)
}

/// Loads glTF/GLB `bytes` that were read from `path`; buffers, images and environment
/// maps referenced by relative URIs are looked up next to `path` through `files`.
pub fn load_gltf_bytes(
    path: &Path,
    bytes: &[u8],
    files: Files<'_>,
) -> Result<SceneDesc, LoadError> {
    let parsed = parse(path, bytes)?;
    let mut warnings = Warnings::default();
    check_extensions(&parsed.document, &mut warnings);
    validate_document(path, &parsed.document)?;

    let base_dir = path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."));
    let mut decoded = meshopt::DecodedViews::default();
    let buffers = source::load_buffers(
        path,
        &base_dir,
        files,
        &parsed.document,
        parsed.blob,
        &mut decoded.fallback,
    )?;
    meshopt::decode_views(path, &parsed.document, &buffers, &mut decoded)?;
    let ctx = Ctx {
        path,
        base_dir,
        files,
        doc: &parsed.document,
        buffers,
        decoded,
    };

    let mut desc = SceneDesc {
        source: path.to_path_buf(),
        compressed: CompressedGeometry {
            draco_primitives: draco::compressed_primitives(parsed.document.as_json()),
            meshopt_views: ctx.decoded.views.len(),
        },
        ..SceneDesc::default()
    };
    // The scene graph first: only materials some mesh instance uses get their textures
    // decoded (the render plan's "textures" stage).
    scene::read_scene_graph(&ctx, &mut desc, &mut warnings)?;
    let used: std::collections::BTreeSet<usize> =
        desc.meshes.iter().filter_map(|m| m.material).collect();
    let (materials, images, skipped) = material::read_materials(&ctx, &used, &mut warnings)?;
    desc.materials = materials;
    desc.images = images;
    desc.skipped_textures = skipped;
    warnings.texcoord1_missing = missing_texcoord1(&desc);
    desc.warnings = warnings.finish();
    Ok(desc)
}

/// What every reader needs: the file (for errors), where relative URIs start, where
/// referenced files are read from, the document, the loaded buffer bytes (index =
/// glTF buffer index) and the meshopt-decoded buffer views.
struct Ctx<'a> {
    path: &'a Path,
    base_dir: PathBuf,
    files: Files<'a>,
    doc: &'a gltf::Document,
    buffers: Vec<Vec<u8>>,
    decoded: meshopt::DecodedViews,
}

impl Ctx<'_> {
    /// An error about `element` of this file.
    fn error(
        &self,
        element: impl Into<String>,
        kind: LoadErrorKind,
        detail: impl Into<String>,
    ) -> LoadError {
        LoadError::new(self.path, element, kind, detail)
    }
}

/// `kind index "name"`, or `kind index` when the element has no name.
fn label(kind: &str, index: usize, name: Option<&str>) -> String {
    match name {
        Some(name) => format!("{kind} {index} {name:?}"),
        None => format!("{kind} {index}"),
    }
}

/// Things the loader saw and did not use, collected so each kind becomes one warning.
#[derive(Default)]
struct Warnings {
    unsupported_extensions: BTreeSet<String>,
    unhonoured_required: BTreeSet<String>,
    skipped_primitives: Vec<String>,
    no_position: Vec<String>,
    texcoord_sets: Vec<String>,
    /// Texture slots reading TEXCOORD_1 on a mesh that has none.
    texcoord1_missing: Vec<String>,
    undecodable_textures: Vec<String>,
    spec_gloss_textures: Vec<String>,
    /// Material properties read but not rendered (e.g. a clearcoat normal map).
    ignored_properties: Vec<String>,
    draco_points: Vec<String>,
}

impl Warnings {
    fn finish(self) -> Vec<String> {
        let mut out = Vec::new();
        if !self.unsupported_extensions.is_empty() {
            let names: Vec<_> = self.unsupported_extensions.into_iter().collect();
            out.push(format!(
                "glTF extensions not supported by Iris, ignored: {}",
                names.join(", ")
            ));
        }
        if !self.unhonoured_required.is_empty() {
            let names: Vec<_> = self.unhonoured_required.into_iter().collect();
            out.push(format!(
                "extensionsRequired lists extensions Iris cannot honour; rendering without them: {}",
                names.join(", ")
            ));
        }
        if !self.undecodable_textures.is_empty() {
            out.push(format!(
                "textures with only a KTX2/Basis image (KHR_texture_basisu, not decoded) are left out: {}",
                short_list(&self.undecodable_textures)
            ));
        }
        if !self.spec_gloss_textures.is_empty() {
            out.push(format!(
                "KHR_materials_pbrSpecularGlossiness is approximated without its specularGlossinessTexture (factors only): {}",
                short_list(&self.spec_gloss_textures)
            ));
        }
        if !self.skipped_primitives.is_empty() {
            out.push(format!(
                "skipped primitives that are points or lines (only triangles are rendered): {}",
                short_list(&self.skipped_primitives)
            ));
        }
        if !self.no_position.is_empty() {
            out.push(format!(
                "skipped primitives without a POSITION attribute: {}",
                short_list(&self.no_position)
            ));
        }
        if !self.draco_points.is_empty() {
            out.push(format!(
                "Draco decoding produced more points than the accessors declare; the decoded meshes are used: {}",
                short_list(&self.draco_points)
            ));
        }
        if !self.texcoord_sets.is_empty() {
            out.push(format!(
                "textures using texCoord 2 or higher are sampled with TEXCOORD_0 (Iris reads TEXCOORD_0 and TEXCOORD_1): {}",
                short_list(&self.texcoord_sets)
            ));
        }
        if !self.texcoord1_missing.is_empty() {
            out.push(format!(
                "textures using texCoord 1 on meshes without TEXCOORD_1 are sampled with TEXCOORD_0: {}",
                short_list(&self.texcoord1_missing)
            ));
        }
        if !self.ignored_properties.is_empty() {
            out.push(format!(
                "material properties Iris does not render, ignored: {}",
                short_list(&self.ignored_properties)
            ));
        }
        out
    }
}

/// The texture slots that read texture-coordinate set 1 on a mesh without TEXCOORD_1 (the
/// scene then repeats TEXCOORD_0 there), one entry per material (named as the loader labels
/// it) and slot, naming the meshes.
fn missing_texcoord1(desc: &SceneDesc) -> Vec<String> {
    let mut out = Vec::new();
    for (index, m) in desc.materials.iter().enumerate() {
        let meshes: Vec<String> = desc
            .meshes
            .iter()
            .filter(|mesh| mesh.material == Some(index) && mesh.uvs1.is_empty())
            .map(|mesh| mesh.name.clone())
            .collect();
        if meshes.is_empty() {
            continue;
        }
        for (slot, texture) in m.textures() {
            if texture.is_some_and(|t| t.texcoord == 1) {
                out.push(format!("{} {slot} ({})", m.name, short_list(&meshes)));
            }
        }
    }
    out
}

/// The first few items of a list, then how many more.
fn short_list(items: &[String]) -> String {
    const SHOWN: usize = 6;
    let head = items
        .iter()
        .take(SHOWN)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    match items.len().checked_sub(SHOWN) {
        Some(more) if more > 0 => format!("{head} and {more} more"),
        _ => head,
    }
}

/// Parses JSON or GLB bytes (glTF 2.0 §4.4 "Binary glTF Layout") without the crate's
/// validation. GLB headers are checked here first so a truncated file is reported plainly.
/// The element of a parse error is `GLB header`, `GLB container`, `GLB JSON chunk` or `JSON`.
fn parse(path: &Path, bytes: &[u8]) -> Result<gltf::Gltf, LoadError> {
    let is_glb = bytes.starts_with(b"glTF");
    if is_glb {
        let header_error =
            |detail: String| LoadError::new(path, "GLB header", LoadErrorKind::Parse, detail);
        // Header: magic, version, total length, all u32 little-endian (§4.4.2).
        let declared = bytes
            .get(8..12)
            .and_then(|b| <[u8; 4]>::try_from(b).ok())
            .map(u32::from_le_bytes)
            .ok_or_else(|| header_error("truncated GLB: incomplete 12-byte header".into()))?;
        let declared = declared as usize;
        if declared < 20 {
            return Err(header_error(format!(
                "declares a length of {declared} bytes, too short for a JSON chunk"
            )));
        }
        if declared > bytes.len() {
            return Err(header_error(format!(
                "truncated GLB: the header declares {declared} bytes but the file has {}",
                bytes.len()
            )));
        }
    }
    gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| {
        let element = match (&e, is_glb) {
            (gltf::Error::Deserialize(_), true) => "GLB JSON chunk",
            (_, true) => "GLB container",
            (_, false) => "JSON",
        };
        LoadError::new(
            path,
            element,
            LoadErrorKind::Parse,
            format!("not valid glTF: {e}"),
        )
    })
}

/// Applies the extension policy: required or used extensions that Iris does not read
/// become (one) warning each.
fn check_extensions(doc: &gltf::Document, warnings: &mut Warnings) {
    let required: BTreeSet<&str> = doc.extensions_required().collect();
    for ext in &required {
        if !READ_EXTENSIONS.contains(ext) && !material_layers::LAYER_EXTENSIONS.contains(ext) {
            warnings.unhonoured_required.insert((*ext).to_string());
        }
    }
    for ext in doc.extensions_used() {
        let read =
            READ_EXTENSIONS.contains(&ext) || material_layers::LAYER_EXTENSIONS.contains(&ext);
        if !read && !required.contains(ext) {
            warnings.unsupported_extensions.insert(ext.to_string());
        }
    }
}

/// Runs the `gltf-json` structural validation (index ranges, enum values, required
/// fields). Ignored: its objection to required extensions (handled above), accessor
/// `min`/`max` or a missing POSITION (Iris reads neither bound and skips such primitives),
/// and the missing `bufferView` of accessors that a Draco-compressed primitive fills.
fn validate_document(path: &Path, doc: &gltf::Document) -> Result<(), LoadError> {
    use gltf::json::validation::{Error, Validate};
    let root = doc.as_json();
    precheck_attributes(path, root)?;
    let draco_accessors: BTreeSet<String> = draco::accessors_without_views(root)
        .into_iter()
        .map(|i| format!("accessors[{i}].bufferView"))
        .collect();
    let mut problems: Vec<(String, Error)> = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |where_, error| {
        let where_ = where_().to_string();
        let texture_source = where_
            .strip_prefix("textures[")
            .and_then(|rest| rest.strip_suffix("].source"))
            .and_then(|i| i.parse::<usize>().ok());
        let tolerated = (error == Error::Unsupported && where_.starts_with("extensionsRequired"))
            || texture_source.is_some_and(|i| texture_source::tolerates_missing_source(doc, i))
            || (error == Error::Missing && draco_accessors.contains(&where_))
            || (where_.contains("attributes[\"POSITION\"]")
                && (where_.ends_with(".min")
                    || where_.ends_with(".max")
                    || error == Error::Missing));
        if !tolerated {
            problems.push((where_, error));
        }
    });
    match problems.first() {
        None => Ok(()),
        Some((where_, error)) => {
            let kind = match error {
                Error::IndexOutOfBounds => LoadErrorKind::IndexOutOfRange,
                _ => LoadErrorKind::Parse,
            };
            let more = match problems.len() {
                1 => String::new(),
                n => format!(" (and {} more problems)", n - 1),
            };
            Err(LoadError::new(
                path,
                where_.clone(),
                kind,
                format!("invalid glTF: {error}{more}"),
            ))
        }
    }
}

/// Attribute accessor indices must exist before `gltf-json` validation runs: its
/// primitive hook indexes `accessors[POSITION]` without a bounds check.
fn precheck_attributes(path: &Path, root: &gltf::json::Root) -> Result<(), LoadError> {
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            for (semantic, accessor) in &prim.attributes {
                if accessor.value() >= root.accessors.len() {
                    let name = semantic.to_string();
                    return Err(LoadError::new(
                        path,
                        format!("{} primitive {p}", label("mesh", m, mesh.name.as_deref())),
                        LoadErrorKind::IndexOutOfRange,
                        format!(
                            "{name} refers to accessor {} but the file has {} accessors",
                            accessor.value(),
                            root.accessors.len()
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}
