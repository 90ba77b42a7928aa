//! KHR_materials_anisotropy: a brushed surface whose specular lobe stretches along one
//! direction of the tangent plane. The extension as loaded ([`AnisotropyDesc`]), its value
//! rules and its value at a surface point ([`AnisotropyPoint`]); the shading frame that
//! turns the tangent-space direction into world space is [`crate::shading::frame`]'s.
//!
//! Units: the rotation in radians, counter-clockwise from the tangent toward the
//! bitangent; the strength dimensionless. Texture channels (linear): strength × B of
//! `anisotropyTexture`, direction 2·RG − 1 (normalised; (1, 0) without a texture) rotated
//! by `anisotropyRotation`.

use super::check::{finite, unit};
use super::texture::{Encoding, TextureContext, TextureRef};
use glam::Vec2;

/// KHR_materials_anisotropy as loaded.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AnisotropyDesc {
    /// `anisotropyStrength` in [0, 1].
    pub strength: f32,
    /// `anisotropyRotation` (radians).
    pub rotation: f32,
    /// `anisotropyTexture`: RG the direction in tangent space (mapped from [0, 1] to
    /// [−1, 1]), B multiplies the strength.
    pub texture: Option<TextureRef>,
}

/// The anisotropy at one surface point, textures applied.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnisotropyPoint {
    /// Strength in [0, 1] (0 = isotropic).
    pub strength: f32,
    /// Unit direction in tangent space (x along the tangent T, y along the bitangent B).
    pub direction: Vec2,
}

impl AnisotropyPoint {
    /// Isotropic.
    pub const NONE: AnisotropyPoint = AnisotropyPoint {
        strength: 0.0,
        direction: Vec2::X,
    };
}

impl AnisotropyDesc {
    /// Whether the surface can be anisotropic anywhere (a strength or a texture), so it
    /// needs a tangent frame.
    pub fn is_on(&self) -> bool {
        self.strength > 0.0 || self.texture.is_some()
    }

    /// The texture slot with its glTF property name.
    pub fn textures(&self) -> [(&'static str, Option<TextureRef>); 1] {
        [("anisotropyTexture", self.texture)]
    }

    /// The value rules, as a message naming the property: the strength in [0, 1], the
    /// rotation finite.
    pub fn check(&self) -> Result<(), String> {
        unit("KHR_materials_anisotropy.anisotropyStrength", self.strength)?;
        finite("KHR_materials_anisotropy.anisotropyRotation", self.rotation)
    }

    /// A few words for `iris info`.
    pub fn describe(&self) -> String {
        let tex = if self.texture.is_some() {
            ", textured"
        } else {
            ""
        };
        format!(
            "anisotropy {} (rotation {} rad{tex})",
            self.strength, self.rotation
        )
    }

    /// The anisotropy where textures are evaluated by `tex`.
    pub fn at(&self, tex: &TextureContext) -> AnisotropyPoint {
        let t = tex.get(self.texture, Encoding::Linear);
        let strength = (self.strength * t.map_or(1.0, |t| t.z)).clamp(0.0, 1.0);
        let d = t.map_or(Vec2::X, |t| Vec2::new(t.x, t.y) * 2.0 - Vec2::ONE);
        let d = d.try_normalize().unwrap_or(Vec2::X);
        let (s, c) = self.rotation.sin_cos();
        let rotated = Vec2::new(c * d.x - s * d.y, s * d.x + c * d.y);
        AnisotropyPoint {
            strength,
            direction: rotated.try_normalize().unwrap_or(Vec2::X),
        }
    }
}
