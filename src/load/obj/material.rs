//! MTL → [`MaterialDesc`] mapping (colours are linear RGB, taken as written).
//!
//! | MTL | Iris |
//! |---|---|
//! | `Kd` (+ `map_Kd`) | base colour (+ sRGB texture; a missing/unreadable file is a warning) |
//! | `Ks`, `Ns` | specular weight = max(Ks), specular colour = Ks / max(Ks); roughness below |
//! | `Ke` | emissive |
//! | `iris_spectrum D65\|sun\|blackbody K` | emission spectrum, `Ke` as its filter (Iris key) |
//! | `Ni` | ior (absent: 1.5, or n(589.3 nm) of the Cauchy model, or the glass's n_d) |
//! | `d`, else `1 − Tr` | alpha; alpha < 1 → [`AlphaMode::Blend`] |
//! | `Pr`, `Pm` | roughness, metallic (PBR extension; override the values below) |
//! | `cauchy_b`, `cauchy_c` | [`ExplicitIor::Cauchy`] (Iris keys) |
//! | `iris_glass NAME` (or `# iris_glass NAME`) | [`ExplicitIor::Glass`] (Iris key) |
//!
//! An Iris IOR model (either key) overrides `Ni` for refraction (`Ni` stays the value other
//! renderers use) and counts as `Ni` for the illum rules below.
//!
//! **Roughness.** Walter et al. 2007 match a Blinn–Phong exponent `Ns` to a microfacet
//! width `α = sqrt(2 / (Ns + 2))`. `MaterialDesc::roughness` is glTF's *perceptual*
//! roughness (`α = roughness²`), so `roughness = α^½ = (2 / (Ns + 2))^¼`. No `Ns` → 1;
//! negative `Ns` counts as 0.
//!
//! **illum.** 0–2: opaque dielectric (metallic 0; 0 and 1 have no specular lobe, `illum 0`
//! "constant colour" is reported unsupported). 3 and 5: mirror (metallic 1, roughness 0,
//! base colour `Ks`). 6 and 7 *with* `Ni` (or an Iris IOR model): a refracting **dielectric** — transmission 1,
//! thickness 1 (volumetric: the mesh bounds a medium), metallic 0, roughness 0, specular 1,
//! base colour white, opaque. `illum 4` ("glass", dissolve-based transparency in the MTL
//! spec) is a dielectric only with `Ni` *and* a dissolve below 1 (`d < 1` or `Tr > 0`);
//! otherwise it is opaque (the Cornell-box light: `illum 4`, `Ni 1.5`, `d 1`, `Ke 10`).
//! `Tf` never makes a dielectric and is not used: the Cornell files write `Tf 0.10` on the
//! glass and `Tf 1 1 1` on the light, so it carries no reliable absorption colour; glass
//! stays white (no attenuation). Other illum values and 6/7 without `Ni` are reported.
//!
//! OBJ has no back-face culling, so every OBJ material is double-sided.

use super::mtl::RawMtl;
use crate::error::{LoadError, LoadErrorKind};
use crate::load::decode::decode_rgba8;
use crate::load::files::Files;
use crate::material::{AlphaMode, ExplicitIor, ImageDesc, MaterialDesc, TextureRef};
use glam::{Vec3, Vec4};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Sodium D line in µm: where a Cauchy model is evaluated for `ior` when `Ni` is absent.
const SODIUM_D_UM: f32 = 0.5893;

/// Images decoded so far, shared between materials by resolved path.
#[derive(Debug, Default)]
pub(super) struct Images {
    /// Decoded images in `SceneDesc::images` order.
    pub images: Vec<ImageDesc>,
    by_path: HashMap<PathBuf, Option<usize>>,
    /// One note per texture that could not be used.
    pub warnings: Vec<String>,
}

impl Images {
    /// Index of the decoded image at `path`, or `None` (with a warning, once) if unreadable.
    fn get(&mut self, path: &Path, files: Files<'_>, material: &str) -> Option<usize> {
        if let Some(found) = self.by_path.get(path) {
            return *found;
        }
        let name = format!(
            "image {} \"{}\"",
            self.images.len(),
            path.file_name().unwrap_or_default().to_string_lossy()
        );
        let decoded = files
            .read(path, crate::fileio::Input::Image)
            .map_err(|e| e.to_string())
            .and_then(|bytes| decode_rgba8(&bytes, name).map_err(|(_, e)| e));
        let index = match decoded {
            Ok(image) => {
                self.images.push(image);
                Some(self.images.len() - 1)
            }
            Err(e) => {
                self.warnings.push(format!(
                    "{material}: texture {} not used: {e}",
                    path.display()
                ));
                None
            }
        };
        self.by_path.insert(path.to_path_buf(), index);
        index
    }
}

/// The material given to OBJ meshes without a (known) material: grey diffuse, double-sided.
pub(super) fn default_material(index: usize) -> MaterialDesc {
    MaterialDesc {
        name: format!("material {index} \"default\" (OBJ mesh without a known material)"),
        base_color: Vec4::new(0.8, 0.8, 0.8, 1.0),
        metallic: 0.0,
        specular: 0.0,
        double_sided: true,
        ..MaterialDesc::default()
    }
}

/// Maps one MTL material (from library `lib`) to material number `index`. Unused keys and
/// unsupported illum values are appended to `unsupported` as `key` → material names. With
/// `images` `None` (no face uses the material) its texture is not decoded.
pub(super) fn to_material(
    index: usize,
    raw: &RawMtl,
    lib: &Path,
    files: Files<'_>,
    images: Option<&mut Images>,
    unsupported: &mut Vec<(String, String)>,
) -> Result<MaterialDesc, LoadError> {
    let lib_name = lib.file_name().unwrap_or_default().to_string_lossy();
    let name = format!(
        "material {index} \"{}\" ({lib_name} line {})",
        raw.name, raw.line
    );
    for key in &raw.unsupported {
        unsupported.push((key.clone(), raw.name.clone()));
    }
    if let Some(ns) = raw.ns.filter(|n| n.is_nan()) {
        return Err(LoadError::new(
            lib,
            &name,
            LoadErrorKind::InvalidValue,
            format!("Ns = {ns} is not a number"),
        ));
    }
    let mut m = MaterialDesc {
        name,
        metallic: 0.0,
        double_sided: true,
        ..MaterialDesc::default()
    };
    if let Some((b, c)) = raw.cauchy {
        m.ior_model = Some(ExplicitIor::Cauchy { b, c });
        m.ior = b + c / (SODIUM_D_UM * SODIUM_D_UM);
    }
    if let Some(glass) = &raw.glass {
        // The parser checked the name; `named` cannot fail here.
        if let Ok(model) = crate::spectrum::IorModel::named(glass) {
            m.ior = model.n_d();
        }
        m.ior_model = Some(ExplicitIor::Glass(glass.clone()));
    }
    if let Some(ni) = raw.ni {
        m.ior = ni;
    }
    let alpha = raw.d.or(raw.tr.map(|t| 1.0 - t)).unwrap_or(1.0);
    let illum = raw.illum.unwrap_or(2);
    let has_ior = raw.ni.is_some() || m.ior_model.is_some();
    let dielectric = has_ior && (matches!(illum, 6 | 7) || (illum == 4 && alpha < 1.0));
    if matches!(illum, 6 | 7) && !has_ior {
        unsupported.push((format!("illum {illum} without Ni"), raw.name.clone()));
    } else if !matches!(illum, 1..=7) {
        unsupported.push((format!("illum {illum}"), raw.name.clone()));
    }

    m.emissive = raw.ke.unwrap_or(Vec3::ZERO);
    m.emission_spectrum = raw.spectrum;
    m.priority = raw.priority.unwrap_or(0);
    if dielectric {
        m.base_color = Vec4::ONE;
        m.transmission = 1.0;
        m.thickness = 1.0;
        m.roughness = 0.0;
        m.specular = 1.0;
        return Ok(m);
    }
    if matches!(illum, 3 | 5) {
        m.base_color = raw.ks.unwrap_or(Vec3::ONE).extend(alpha);
        m.metallic = 1.0;
        m.roughness = 0.0;
    } else {
        m.base_color = raw.kd.unwrap_or(Vec3::ONE).extend(alpha);
        m.roughness = raw
            .ns
            .map_or(1.0, |ns| (2.0 / (ns.max(0.0) + 2.0)).sqrt().sqrt());
        match raw.ks {
            _ if illum <= 1 => m.specular = 0.0,
            Some(ks) => {
                let peak = ks.max_element();
                m.specular = peak;
                if peak > 0.0 {
                    m.specular_color = ks / peak;
                }
            }
            None => {}
        }
    }
    if let Some(pr) = raw.pr {
        m.roughness = pr;
    }
    if let Some(pm) = raw.pm {
        m.metallic = pm;
    }
    if alpha < 1.0 {
        m.alpha_mode = AlphaMode::Blend;
    }
    if let (Some(file), Some(images)) = (&raw.map_kd, images) {
        let path = lib.parent().unwrap_or(Path::new("")).join(file);
        m.base_color_texture = images
            .get(&path, files, &m.name)
            .map(|image| TextureRef::new(image, 0));
    }
    Ok(m)
}
