//! KHR_materials_pbrSpecularGlossiness (archived; still common in older Sketchfab and
//! 3ds Max exports), approximated by the metallic-roughness model with
//! KHR_materials_specular, so no new BSDF is needed:
//!
//! - base colour = `diffuseFactor` × `diffuseTexture`, metallic 0;
//! - roughness = 1 − `glossinessFactor`;
//! - specular = 1 and specular colour = `specularFactor` / 0.04 at IOR 1.5, so that the
//!   glTF-PBR f0 = min(((n−1)/(n+1))² · colour, 1) = `specularFactor` (KHR_materials_specular
//!   README, "Implementation"), with f90 = 1.
//!
//! Differences: the diffuse lobe is weighted by (1 − F) as in glTF PBR (specular-glossiness
//! adds them), and `specularGlossinessTexture` is not read (its glossiness is an inverted
//! alpha channel the metallic-roughness texture slots cannot express); a material that has
//! one is named in the loader's single warning and renders with its factors.

use crate::material::{MaterialDesc, TextureRef};
use glam::{Vec3, Vec4};

/// `desc` replaced by the approximation when the material has the extension; `diffuse` is
/// its decoded `diffuseTexture`. Returns whether a specularGlossinessTexture was dropped.
pub(super) fn apply(
    sg: Option<&gltf::material::PbrSpecularGlossiness<'_>>,
    diffuse: Option<TextureRef>,
    desc: MaterialDesc,
) -> (MaterialDesc, bool) {
    let Some(sg) = sg else {
        return (desc, false);
    };
    let f0 = Vec3::from(sg.specular_factor());
    let desc = MaterialDesc {
        base_color: Vec4::from(sg.diffuse_factor()),
        base_color_texture: diffuse,
        metallic: 0.0,
        roughness: (1.0 - sg.glossiness_factor()).clamp(0.0, 1.0),
        metallic_roughness_texture: None,
        ior: 1.5,
        specular: 1.0,
        specular_color: f0 / 0.04,
        ..desc
    };
    (desc, sg.specular_glossiness_texture().is_some())
}
