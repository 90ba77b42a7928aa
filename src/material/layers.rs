//! The KHR material layer extensions of a material ([`LayerDesc`], the `layers` field of
//! [`super::MaterialDesc`]), their values at a surface point ([`LayerPoint`]) and what the
//! BSDF gets from them ([`LayerPoint::lobes`]):
//! KHR_materials_clearcoat, KHR_materials_sheen and KHR_materials_diffuse_transmission.
//! Defaults are the specs' (every layer absent). Factors are in [0, 1] and colours linear
//! RGB in [0, 1] (the loader rejects anything else); textures multiply the factors, from the
//! channel each spec names: clearcoat R, clearcoat roughness G, sheen colour RGB (sRGB),
//! sheen roughness A, diffuse transmission A, diffuse transmission colour RGB (sRGB).

use super::texture::{Encoding, TextureContext, TextureRef};
use crate::bsdf::Layers;
use crate::spectrum::Carrier;
use glam::Vec3;

/// KHR_materials_clearcoat, _sheen and _diffuse_transmission parameters as loaded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerDesc {
    /// clearcoatFactor (default 0: no coat).
    pub clearcoat: f32,
    /// clearcoatTexture (R channel, linear).
    pub clearcoat_texture: Option<TextureRef>,
    /// clearcoatRoughnessFactor (perceptual; default 0).
    pub clearcoat_roughness: f32,
    /// clearcoatRoughnessTexture (G channel, linear).
    pub clearcoat_roughness_texture: Option<TextureRef>,
    /// sheenColorFactor (linear; default black: no sheen).
    pub sheen_color: Vec3,
    /// sheenColorTexture (RGB, sRGB).
    pub sheen_color_texture: Option<TextureRef>,
    /// sheenRoughnessFactor (default 0).
    pub sheen_roughness: f32,
    /// sheenRoughnessTexture (A channel, linear).
    pub sheen_roughness_texture: Option<TextureRef>,
    /// diffuseTransmissionFactor (default 0: no transmission).
    pub diffuse_transmission: f32,
    /// diffuseTransmissionTexture (A channel, linear).
    pub diffuse_transmission_texture: Option<TextureRef>,
    /// diffuseTransmissionColorFactor (linear; default white).
    pub diffuse_transmission_color: Vec3,
    /// diffuseTransmissionColorTexture (RGB, sRGB).
    pub diffuse_transmission_color_texture: Option<TextureRef>,
}

impl Default for LayerDesc {
    fn default() -> Self {
        LayerDesc {
            clearcoat: 0.0,
            clearcoat_texture: None,
            clearcoat_roughness: 0.0,
            clearcoat_roughness_texture: None,
            sheen_color: Vec3::ZERO,
            sheen_color_texture: None,
            sheen_roughness: 0.0,
            sheen_roughness_texture: None,
            diffuse_transmission: 0.0,
            diffuse_transmission_texture: None,
            diffuse_transmission_color: Vec3::ONE,
            diffuse_transmission_color_texture: None,
        }
    }
}

/// The layer parameters at one surface point, textures applied.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerPoint {
    /// Clearcoat intensity in [0, 1].
    pub clearcoat: f32,
    /// Clearcoat perceptual roughness in [0, 1].
    pub clearcoat_roughness: f32,
    /// Sheen colour (linear).
    pub sheen_color: Vec3,
    /// Sheen roughness in [0, 1].
    pub sheen_roughness: f32,
    /// Diffuse transmission factor in [0, 1].
    pub diffuse_transmission: f32,
    /// Diffuse transmission colour (linear).
    pub diffuse_transmission_color: Vec3,
}

impl LayerDesc {
    /// Whether any layer is present (a non-zero factor or colour).
    pub fn any(&self) -> bool {
        self.clearcoat > 0.0
            || self.sheen_color.max_element() > 0.0
            || self.diffuse_transmission > 0.0
    }

    /// The texture slots with their glTF property names.
    pub fn textures(&self) -> [(&'static str, Option<TextureRef>); 6] {
        [
            ("clearcoatTexture", self.clearcoat_texture),
            (
                "clearcoatRoughnessTexture",
                self.clearcoat_roughness_texture,
            ),
            ("sheenColorTexture", self.sheen_color_texture),
            ("sheenRoughnessTexture", self.sheen_roughness_texture),
            (
                "diffuseTransmissionTexture",
                self.diffuse_transmission_texture,
            ),
            (
                "diffuseTransmissionColorTexture",
                self.diffuse_transmission_color_texture,
            ),
        ]
    }

    /// The layers where textures are evaluated by `tex` (untextured materials skip the
    /// lookups).
    pub fn at(&self, tex: &TextureContext) -> LayerPoint {
        let unit = |v: f32| v.clamp(0.0, 1.0);
        let colour = |v: Vec3| v.clamp(Vec3::ZERO, Vec3::ONE);
        let lin = |t| tex.lookup(t, Encoding::Linear);
        let srgb = |t| tex.lookup(t, Encoding::Srgb);
        let mut p = LayerPoint {
            clearcoat: unit(self.clearcoat),
            clearcoat_roughness: unit(self.clearcoat_roughness),
            sheen_color: colour(self.sheen_color),
            sheen_roughness: unit(self.sheen_roughness),
            diffuse_transmission: unit(self.diffuse_transmission),
            diffuse_transmission_color: colour(self.diffuse_transmission_color),
        };
        if !self.any() {
            return p;
        }
        p.clearcoat = unit(p.clearcoat * lin(self.clearcoat_texture).x);
        p.clearcoat_roughness =
            unit(p.clearcoat_roughness * lin(self.clearcoat_roughness_texture).y);
        p.sheen_color = colour(p.sheen_color * srgb(self.sheen_color_texture).truncate());
        p.sheen_roughness = unit(p.sheen_roughness * lin(self.sheen_roughness_texture).w);
        p.diffuse_transmission =
            unit(p.diffuse_transmission * lin(self.diffuse_transmission_texture).w);
        p.diffuse_transmission_color = colour(
            p.diffuse_transmission_color * srgb(self.diffuse_transmission_color_texture).truncate(),
        );
        p
    }
}

impl LayerPoint {
    /// The layers for the BSDF at the path's wavelengths `l` (colours upsampled as
    /// reflectances; α = clearcoat roughness², sheen α = sheen roughness as the sheen spec
    /// writes it).
    pub fn lobes<C: Carrier>(&self, l: &C::Lambda) -> Layers<C> {
        if self.clearcoat <= 0.0
            && self.sheen_color.max_element() <= 0.0
            && self.diffuse_transmission <= 0.0
        {
            return Layers::none();
        }
        Layers {
            clearcoat: self.clearcoat,
            clearcoat_alpha: self.clearcoat_roughness * self.clearcoat_roughness,
            sheen_color: C::reflectance(self.sheen_color, l),
            sheen_alpha: self.sheen_roughness,
            diffuse_transmission: self.diffuse_transmission,
            diffuse_transmission_color: C::reflectance(self.diffuse_transmission_color, l),
        }
    }
}
