//! KHR_materials_iridescence and KHR_materials_anisotropy, read from the material's raw
//! extension JSON (the `gltf` crate does not type them) into [`IridescenceDesc`] and
//! [`AnisotropyDesc`].
//!
//! Properties read (spec defaults when absent): `iridescenceFactor` (0),
//! `iridescenceTexture` (R), `iridescenceIor` (1.3), `iridescenceThicknessMinimum` (100 nm),
//! `iridescenceThicknessMaximum` (400 nm), `iridescenceThicknessTexture` (G);
//! `anisotropyStrength` (0), `anisotropyRotation` (0 rad), `anisotropyTexture` (RG
//! direction, B strength). A texture is `{"index": i, "texCoord": t}`; `index` must name an
//! existing texture with an image (`IndexOutOfRange` otherwise). Non-numbers, non-objects
//! and out-of-range values (NaN, negative thickness, minimum > maximum, factors outside
//! [0, 1]: [`IridescenceDesc::check`], [`AnisotropyDesc::check`]) are `InvalidValue` errors naming the material and the
//! property. Textures go through the material reader's one texture resolver (WebP/KTX2
//! sources, `KHR_texture_transform`, texCoord warnings).

use super::texture_info::texture_info;
use super::texture_info::TextureFn;
use super::{Ctx, Warnings};
use crate::error::{LoadError, LoadErrorKind};
use crate::material::{AnisotropyDesc, IridescenceDesc, TextureRef};
use serde_json::{Map, Value};

/// Extension names this module reads.
pub(super) const IRIDESCENCE: &str = "KHR_materials_iridescence";
/// See [`IRIDESCENCE`].
pub(super) const ANISOTROPY: &str = "KHR_materials_anisotropy";

/// Reads both extensions of material `m` (`element` names it); textures are resolved by
/// `texture` (which does not decode them for an unused material).
pub(super) fn read_iridescence_anisotropy(
    ctx: &Ctx<'_>,
    m: &gltf::Material<'_>,
    element: &str,
    texture: &mut TextureFn<'_>,
    warnings: &mut Warnings,
) -> Result<(Option<IridescenceDesc>, Option<AnisotropyDesc>), LoadError> {
    let mut reader = Reader {
        ctx,
        element,
        texture,
        warnings,
    };
    let invalid = |d| ctx.error(element, LoadErrorKind::InvalidValue, d);
    let iridescence = match m.extension_value(IRIDESCENCE) {
        Some(v) => Some(reader.iridescence(v)?),
        None => None,
    };
    let anisotropy = match m.extension_value(ANISOTROPY) {
        Some(v) => Some(reader.anisotropy(v)?),
        None => None,
    };
    if let Some(i) = &iridescence {
        i.check().map_err(invalid)?;
    }
    if let Some(a) = &anisotropy {
        a.check().map_err(invalid)?;
    }
    Ok((iridescence, anisotropy))
}

struct Reader<'a, 'c, 't> {
    ctx: &'a Ctx<'c>,
    element: &'a str,
    texture: &'a mut TextureFn<'t>,
    #[allow(dead_code)]
    warnings: &'a mut Warnings,
}

impl Reader<'_, '_, '_> {
    fn invalid(&self, detail: String) -> LoadError {
        self.ctx
            .error(self.element, LoadErrorKind::InvalidValue, detail)
    }

    fn object<'v>(&self, ext: &str, v: &'v Value) -> Result<&'v Map<String, Value>, LoadError> {
        v.as_object()
            .ok_or_else(|| self.invalid(format!("{ext} must be a JSON object, found {v}")))
    }

    /// A number property, `default` when absent.
    fn number(
        &self,
        ext: &str,
        obj: &Map<String, Value>,
        key: &str,
        default: f32,
    ) -> Result<f32, LoadError> {
        match obj.get(key) {
            None => Ok(default),
            Some(v) => v
                .as_f64()
                .map(|x| x as f32)
                .ok_or_else(|| self.invalid(format!("{ext}.{key} must be a number, found {v}"))),
        }
    }

    /// A textureInfo property (`None` when absent, or when the material is unused).
    fn texture(
        &mut self,
        ext: &str,
        obj: &Map<String, Value>,
        key: &str,
    ) -> Result<Option<TextureRef>, LoadError> {
        let Some(info) = obj.get(key) else {
            return Ok(None);
        };
        texture_info(
            self.ctx,
            self.element,
            &format!("{ext}.{key}"),
            info,
            self.texture,
        )
    }

    fn iridescence(&mut self, v: &Value) -> Result<IridescenceDesc, LoadError> {
        let ext = IRIDESCENCE;
        let obj = self.object(ext, v)?;
        let d = IridescenceDesc::default();
        Ok(IridescenceDesc {
            factor: self.number(ext, obj, "iridescenceFactor", d.factor)?,
            texture: self.texture(ext, obj, "iridescenceTexture")?,
            ior: self.number(ext, obj, "iridescenceIor", d.ior)?,
            thickness_min: self.number(ext, obj, "iridescenceThicknessMinimum", d.thickness_min)?,
            thickness_max: self.number(ext, obj, "iridescenceThicknessMaximum", d.thickness_max)?,
            thickness_texture: self.texture(ext, obj, "iridescenceThicknessTexture")?,
        })
    }

    fn anisotropy(&mut self, v: &Value) -> Result<AnisotropyDesc, LoadError> {
        let ext = ANISOTROPY;
        let obj = self.object(ext, v)?;
        Ok(AnisotropyDesc {
            strength: self.number(ext, obj, "anisotropyStrength", 0.0)?,
            rotation: self.number(ext, obj, "anisotropyRotation", 0.0)?,
            texture: self.texture(ext, obj, "anisotropyTexture")?,
        })
    }
}
