//! Which image a texture shows, with the texture-format extensions: EXT_texture_webp
//! (its `source` is a WebP image, decoded by the `image` crate) and KHR_texture_basisu
//! (KTX2 + Basis Universal, which Iris does not decode: its fallback `source`, a PNG or
//! JPEG, is used when the file has one).
//!
//! Order (EXT_texture_webp README, "Best practices"): the WebP image when the extension is
//! present, else the texture's own `source`. A texture whose only image is KTX2 has no
//! image Iris can show: the material is then rendered without that texture and the
//! loader's single warning names it. Both extensions allow `source` to be omitted, so the
//! structural validation tolerates a missing `source` on such textures
//! ([`tolerates_missing_source`]); every index is still range-checked by the image cache.

use serde_json::Value;

/// The glTF image index `texture` shows, or `None` when it has none Iris can decode.
pub(super) fn image_of(doc: &gltf::Document, texture: &gltf::Texture<'_>) -> Option<usize> {
    if let Some(i) = extension_source(texture.extension_value("EXT_texture_webp")) {
        return Some(i);
    }
    let own = doc.as_json().textures.get(texture.index())?.source.value();
    (own < doc.as_json().images.len()).then_some(own)
}

/// Whether validation may accept texture `index` without a valid `source`: it names its
/// image through EXT_texture_webp or KHR_texture_basisu.
pub(super) fn tolerates_missing_source(doc: &gltf::Document, index: usize) -> bool {
    doc.textures().nth(index).is_some_and(|t| {
        ["EXT_texture_webp", "KHR_texture_basisu"]
            .iter()
            .any(|ext| extension_source(t.extension_value(ext)).is_some())
    })
}

fn extension_source(ext: Option<&Value>) -> Option<usize> {
    ext?.get("source")?
        .as_u64()
        .and_then(|i| usize::try_from(i).ok())
}
