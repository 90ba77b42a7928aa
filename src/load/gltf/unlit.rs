//! KHR_materials_unlit, approximated for a physically based renderer: an unlit surface
//! shows its base colour whatever the lighting (KHR_materials_unlit README, "Overview"),
//! so Iris makes it an emitter of radiance = base colour (factor × texture, linear RGB, the
//! same units as `emissiveFactor`) that reflects and transmits nothing: base colour black
//! (its alpha kept for MASK/BLEND), no metal, no specular layer, no transmission.
//!
//! What differs from a rasterizer's unlit: the surface lights its surroundings (it is an
//! area light in Iris), and the picture's exposure scales it like any emitter.

use crate::material::MaterialDesc;
use glam::Vec3;

/// `desc` turned into the unlit approximation when `m` has KHR_materials_unlit.
pub(super) fn apply(m: &gltf::Material<'_>, desc: MaterialDesc) -> MaterialDesc {
    if m.extension_value("KHR_materials_unlit").is_none() {
        return desc;
    }
    MaterialDesc {
        emissive: desc.base_color.truncate(),
        emissive_texture: desc.base_color_texture,
        base_color: desc.base_color * glam::Vec4::new(0.0, 0.0, 0.0, 1.0),
        metallic: 0.0,
        specular: 0.0,
        specular_color: Vec3::ZERO,
        transmission: 0.0,
        transmission_texture: None,
        ..desc
    }
}
