//! KHR_materials_clearcoat, KHR_materials_sheen and KHR_materials_diffuse_transmission
//! into [`LayerDesc`], read from the raw extension JSON (the `gltf` crate does not type
//! them). Absent properties take the specs' defaults.
//!
//! Parameters read (names as in the specs):
//! - KHR_materials_clearcoat: `clearcoatFactor`, `clearcoatTexture`,
//!   `clearcoatRoughnessFactor`, `clearcoatRoughnessTexture`; `clearcoatNormalTexture` is
//!   noted once per file and ignored (Iris has no normal maps).
//! - KHR_materials_sheen: `sheenColorFactor`, `sheenColorTexture`, `sheenRoughnessFactor`,
//!   `sheenRoughnessTexture`.
//! - KHR_materials_diffuse_transmission: `diffuseTransmissionFactor`,
//!   `diffuseTransmissionTexture`, `diffuseTransmissionColorFactor`,
//!   `diffuseTransmissionColorTexture`.
//!
//! Errors (`InvalidValue`, naming the material and `extension.property`): an extension that
//! is not a JSON object, a factor that is not a number in [0, 1] (negative, NaN, > 1), a
//! colour that is not 3 numbers in [0, 1], a texture that is not `{"index": i}` with a
//! texture `i` of the file (`IndexOutOfRange` when there is no such texture).

use super::texture_info::{texture_info, TextureFn};
use super::{Ctx, Warnings};
use crate::error::{LoadError, LoadErrorKind};
use crate::material::{LayerDesc, TextureRef};
use glam::Vec3;
use serde_json::{Map, Value};

/// The extensions this module reads (for the loader's extension policy).
pub(super) const LAYER_EXTENSIONS: &[&str] = &[
    "KHR_materials_clearcoat",
    "KHR_materials_sheen",
    "KHR_materials_diffuse_transmission",
];

/// One extension's JSON object, with the material's name for errors.
struct Ext<'a, 'c> {
    ctx: &'a Ctx<'c>,
    element: &'a str,
    name: &'static str,
    obj: &'a Map<String, Value>,
}

impl Ext<'_, '_> {
    fn invalid(&self, key: &str, detail: String) -> LoadError {
        self.ctx.error(
            self.element,
            LoadErrorKind::InvalidValue,
            format!("{}.{key} {detail}", self.name),
        )
    }

    /// A factor in [0, 1] (`default` when absent).
    fn factor(&self, key: &str, default: f32) -> Result<f32, LoadError> {
        let Some(v) = self.obj.get(key) else {
            return Ok(default);
        };
        match v.as_f64() {
            Some(x) if (0.0..=1.0).contains(&x) => Ok(x as f32),
            _ => Err(self.invalid(key, format!("= {v} must be a number in [0, 1]"))),
        }
    }

    /// An RGB colour with components in [0, 1] (`default` when absent).
    fn colour(&self, key: &str, default: Vec3) -> Result<Vec3, LoadError> {
        let Some(v) = self.obj.get(key) else {
            return Ok(default);
        };
        let bad = || self.invalid(key, format!("= {v} must be 3 numbers in [0, 1]"));
        let list = v.as_array().filter(|l| l.len() == 3).ok_or_else(bad)?;
        let mut c = [0.0f32; 3];
        for (out, x) in c.iter_mut().zip(list) {
            match x.as_f64() {
                Some(x) if (0.0..=1.0).contains(&x) => *out = x as f32,
                _ => return Err(bad()),
            }
        }
        Ok(Vec3::from(c))
    }

    /// A `textureInfo` (`{"index": i, "texCoord": k}`) resolved through `texture`.
    fn texture(
        &self,
        key: &str,
        texture: &mut TextureFn<'_>,
    ) -> Result<Option<TextureRef>, LoadError> {
        let Some(v) = self.obj.get(key) else {
            return Ok(None);
        };
        texture_info(
            self.ctx,
            self.element,
            &format!("{}.{key}", self.name),
            v,
            texture,
        )
    }
}

/// The extension `name` of material `m` as a JSON object (`None` when absent).
fn extension<'a, 'c>(
    ctx: &'a Ctx<'c>,
    m: &'a gltf::Material<'_>,
    element: &'a str,
    name: &'static str,
) -> Result<Option<Ext<'a, 'c>>, LoadError>
where
    'c: 'a,
{
    let Some(v) = m.extension_value(name) else {
        return Ok(None);
    };
    let obj = v.as_object().ok_or_else(|| {
        ctx.error(
            element,
            LoadErrorKind::InvalidValue,
            format!("{name} must be a JSON object"),
        )
    })?;
    Ok(Some(Ext {
        ctx,
        element,
        name,
        obj,
    }))
}

/// Reads the three layer extensions of material `m` (`element` names it for errors);
/// unsupported properties are noted in `warnings`.
pub(super) fn read_layers(
    ctx: &Ctx<'_>,
    m: &gltf::Material<'_>,
    element: &str,
    texture: &mut TextureFn<'_>,
    warnings: &mut Warnings,
) -> Result<LayerDesc, LoadError> {
    let mut d = LayerDesc::default();
    if let Some(e) = extension(ctx, m, element, "KHR_materials_clearcoat")? {
        d.clearcoat = e.factor("clearcoatFactor", 0.0)?;
        d.clearcoat_texture = e.texture("clearcoatTexture", texture)?;
        d.clearcoat_roughness = e.factor("clearcoatRoughnessFactor", 0.0)?;
        d.clearcoat_roughness_texture = e.texture("clearcoatRoughnessTexture", texture)?;
        if e.obj.contains_key("clearcoatNormalTexture") {
            warnings.ignored_properties.push(format!(
                "{element} KHR_materials_clearcoat.clearcoatNormalTexture (no normal maps)"
            ));
        }
    }
    if let Some(e) = extension(ctx, m, element, "KHR_materials_sheen")? {
        d.sheen_color = e.colour("sheenColorFactor", Vec3::ZERO)?;
        d.sheen_color_texture = e.texture("sheenColorTexture", texture)?;
        d.sheen_roughness = e.factor("sheenRoughnessFactor", 0.0)?;
        d.sheen_roughness_texture = e.texture("sheenRoughnessTexture", texture)?;
    }
    if let Some(e) = extension(ctx, m, element, "KHR_materials_diffuse_transmission")? {
        d.diffuse_transmission = e.factor("diffuseTransmissionFactor", 0.0)?;
        d.diffuse_transmission_texture = e.texture("diffuseTransmissionTexture", texture)?;
        d.diffuse_transmission_color = e.colour("diffuseTransmissionColorFactor", Vec3::ONE)?;
        d.diffuse_transmission_color_texture =
            e.texture("diffuseTransmissionColorTexture", texture)?;
    }
    Ok(d)
}
