//! A raw `textureInfo` JSON object (glTF 2.0 §5.22: `{"index": i, "texCoord": t}`, plus a
//! KHR_texture_transform) of a material extension the `gltf` crate does not type, resolved
//! to the material's texture through the material reader's one resolver ([`TextureFn`]:
//! WebP/KTX2 sources, the transform, the texCoord warning, no decoding for unused
//! materials). Errors name the material and the property (`slot`, e.g.
//! `KHR_materials_sheen.sheenColorTexture`).

use super::{texture_transform, Ctx};
use crate::error::{LoadError, LoadErrorKind};
use crate::material::TextureRef;
use serde_json::Value;

/// Resolves a texture reference: (slot name, glTF texture, texCoord, KHR_texture_transform)
/// → the material's
/// texture (or `None` when the material's textures are not decoded).
pub(super) type TextureFn<'a> = dyn FnMut(&str, &gltf::Texture<'_>, u32, glam::Affine2) -> Result<Option<TextureRef>, LoadError>
    + 'a;

/// Resolves the textureInfo `v` of property `slot` of material `element`.
pub(super) fn texture_info(
    ctx: &Ctx<'_>,
    element: &str,
    slot: &str,
    v: &Value,
    texture: &mut TextureFn<'_>,
) -> Result<Option<TextureRef>, LoadError> {
    let invalid = |detail: String| ctx.error(element, LoadErrorKind::InvalidValue, detail);
    let info = v.as_object().ok_or_else(|| {
        invalid(format!(
            "{slot} = {v} must be a textureInfo {{\"index\": i, …}}"
        ))
    })?;
    let index = match info.get("index") {
        Some(i) => i
            .as_u64()
            .ok_or_else(|| invalid(format!("{slot}.index = {i} must be a texture index")))?,
        None => return Err(invalid(format!("{slot}.index is missing ({v})"))),
    };
    let count = ctx.doc.textures().len();
    let tex = usize::try_from(index)
        .ok()
        .and_then(|i| ctx.doc.textures().nth(i))
        .ok_or_else(|| {
            ctx.error(
                element,
                LoadErrorKind::IndexOutOfRange,
                format!("{slot}.index {index} refers to texture {index}, but the file has {count}"),
            )
        })?;
    let texcoord = match info.get("texCoord") {
        None => 0,
        Some(t) => t
            .as_u64()
            .and_then(|t| u32::try_from(t).ok())
            .ok_or_else(|| invalid(format!("{slot}.texCoord = {t} must be an integer ≥ 0")))?,
    };
    let (transform, texcoord_override) =
        texture_transform::of_json(v).map_err(|e| invalid(format!("{slot}: {e}")))?;
    texture(slot, &tex, texcoord_override.unwrap_or(texcoord), transform)
}
