//! KHR_materials_iridescence: a thin dielectric film on the surface whose interference
//! colours the specular reflection. The extension as loaded ([`IridescenceDesc`]), its value
//! rules ([`IridescenceDesc::check`], applied by both loaders and `scene::validate`) and its
//! value at a surface point ([`IridescencePoint`], which the BSDF's thin-film Fresnel reads
//! as [`crate::bsdf::Iridescence`]).
//!
//! Units: thicknesses in nanometres, the film index relative to the outside, the factor
//! dimensionless. Defaults are the extension's (film IOR 1.3, thickness 100–400 nm).
//! Texture channels (linear): the factor × R of `iridescenceTexture`; thickness =
//! mix(min, max, G of `iridescenceThicknessTexture`), or the maximum without it.

use super::check::{finite, unit};
use super::texture::{Encoding, TextureContext, TextureRef};
use crate::bsdf::Iridescence;
use crate::spectrum::Carrier;

/// KHR_materials_iridescence as loaded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IridescenceDesc {
    /// `iridescenceFactor` in [0, 1].
    pub factor: f32,
    /// `iridescenceTexture` (R multiplies the factor).
    pub texture: Option<TextureRef>,
    /// `iridescenceIor`, the film's index (default 1.3).
    pub ior: f32,
    /// `iridescenceThicknessMinimum` (nm, default 100).
    pub thickness_min: f32,
    /// `iridescenceThicknessMaximum` (nm, default 400).
    pub thickness_max: f32,
    /// `iridescenceThicknessTexture` (G mixes min → max); without it the thickness is the
    /// maximum.
    pub thickness_texture: Option<TextureRef>,
}

impl Default for IridescenceDesc {
    fn default() -> Self {
        IridescenceDesc {
            factor: 0.0,
            texture: None,
            ior: 1.3,
            thickness_min: 100.0,
            thickness_max: 400.0,
            thickness_texture: None,
        }
    }
}

/// The film at one surface point, textures applied: present only where both the factor
/// and the thickness are > 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IridescencePoint {
    /// Mix weight of the film's Fresnel, in (0, 1].
    pub factor: f32,
    /// Film index of refraction (relative to the outside).
    pub ior: f32,
    /// Film thickness in nm (> 0).
    pub thickness: f32,
}

impl IridescenceDesc {
    /// Whether the film can show anywhere (factor and maximum thickness > 0).
    pub fn is_on(&self) -> bool {
        self.factor > 0.0 && self.thickness_max > 0.0
    }

    /// The texture slots with their glTF property names.
    pub fn textures(&self) -> [(&'static str, Option<TextureRef>); 2] {
        [
            ("iridescenceTexture", self.texture),
            ("iridescenceThicknessTexture", self.thickness_texture),
        ]
    }

    /// The value rules, as a message naming the property: every number finite; the factor
    /// in [0, 1]; film IOR ≥ 1 (a film less dense than air is not a coating); thicknesses
    /// ≥ 0 with minimum ≤ maximum.
    pub fn check(&self) -> Result<(), String> {
        unit("KHR_materials_iridescence.iridescenceFactor", self.factor)?;
        finite("KHR_materials_iridescence.iridescenceIor", self.ior)?;
        if self.ior < 1.0 {
            return Err(format!(
                "KHR_materials_iridescence.iridescenceIor = {} must be >= 1",
                self.ior
            ));
        }
        let (lo, hi) = (self.thickness_min, self.thickness_max);
        for (name, v) in [
            ("iridescenceThicknessMinimum", lo),
            ("iridescenceThicknessMaximum", hi),
        ] {
            finite(&format!("KHR_materials_iridescence.{name}"), v)?;
            if v < 0.0 {
                return Err(format!(
                    "KHR_materials_iridescence.{name} = {v} nm must not be negative"
                ));
            }
        }
        if lo > hi {
            return Err(format!(
                "KHR_materials_iridescence.iridescenceThicknessMinimum ({lo} nm) exceeds iridescenceThicknessMaximum ({hi} nm)"
            ));
        }
        Ok(())
    }

    /// A few words for `iris info`.
    pub fn describe(&self) -> String {
        let tex = if self.texture.is_some() || self.thickness_texture.is_some() {
            ", textured"
        } else {
            ""
        };
        format!(
            "iridescence {} (film n {}, {}–{} nm{tex})",
            self.factor, self.ior, self.thickness_min, self.thickness_max
        )
    }

    /// The film where textures are evaluated by `tex`; `None` where it is off.
    pub fn at(&self, tex: &TextureContext) -> Option<IridescencePoint> {
        let factor = self.factor * tex.get(self.texture, Encoding::Linear).map_or(1.0, |t| t.x);
        let thickness = match tex.get(self.thickness_texture, Encoding::Linear) {
            Some(t) => self.thickness_min + (self.thickness_max - self.thickness_min) * t.y,
            None => self.thickness_max,
        };
        let factor = factor.clamp(0.0, 1.0);
        (factor > 0.0 && thickness > 0.0).then_some(IridescencePoint {
            factor,
            ior: self.ior,
            thickness,
        })
    }
}

impl IridescencePoint {
    /// What the BSDF's Fresnel needs at the path's wavelengths `l`.
    pub fn lobe<C: Carrier>(&self, l: &C::Lambda) -> Iridescence {
        Iridescence {
            factor: self.factor,
            ior: self.ior,
            thickness: self.thickness,
            lanes: C::lanes_nm(l),
        }
    }
}
