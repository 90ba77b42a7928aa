//! The thin-film and brushed-surface material extensions as loaded: KHR_materials_iridescence
//! and KHR_materials_anisotropy ([`FilmDesc`], grouped in `MaterialDesc::film`), with the
//! value rules both loaders and `scene::validate` apply ([`FilmDesc::check`]).
//!
//! Units: thicknesses in nanometres, the rotation in radians (counter-clockwise from the
//! tangent toward the bitangent), factors dimensionless. Defaults are the extensions'
//! (iridescence IOR 1.3, thickness 100–400 nm; anisotropy strength 0, rotation 0).

use super::{SceneDesc, TextureRef};

/// KHR_materials_iridescence.
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

/// KHR_materials_anisotropy.
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

/// The two extensions of one material (each `None` when absent).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FilmDesc {
    /// KHR_materials_iridescence.
    pub iridescence: Option<IridescenceDesc>,
    /// KHR_materials_anisotropy.
    pub anisotropy: Option<AnisotropyDesc>,
}

impl FilmDesc {
    /// Whether the material needs a tangent frame (anisotropy with a strength or texture).
    pub fn is_anisotropic(&self) -> bool {
        self.anisotropy
            .is_some_and(|a| a.strength > 0.0 || a.texture.is_some())
    }

    /// The texture slots with their glTF property names, for index checks and `iris info`.
    pub fn textures(&self) -> Vec<(&'static str, TextureRef)> {
        let mut out = Vec::new();
        if let Some(i) = &self.iridescence {
            out.extend(i.texture.map(|t| ("iridescenceTexture", t)));
            out.extend(
                i.thickness_texture
                    .map(|t| ("iridescenceThicknessTexture", t)),
            );
        }
        if let Some(a) = &self.anisotropy {
            out.extend(a.texture.map(|t| ("anisotropyTexture", t)));
        }
        out
    }

    /// The value rules, as a message naming the property: every number finite; factor and
    /// strength in [0, 1]; film IOR ≥ 1 (a film less dense than air is not a coating);
    /// thicknesses ≥ 0 with minimum ≤ maximum.
    pub fn check(&self) -> Result<(), String> {
        let finite = |name: &str, v: f32| {
            if v.is_finite() {
                Ok(())
            } else {
                Err(format!("{name} = {v} must be a finite number"))
            }
        };
        let unit = |name: &str, v: f32| {
            finite(name, v)?;
            if (0.0..=1.0).contains(&v) {
                Ok(())
            } else {
                Err(format!("{name} = {v} must lie in [0, 1]"))
            }
        };
        if let Some(i) = &self.iridescence {
            unit("KHR_materials_iridescence.iridescenceFactor", i.factor)?;
            finite("KHR_materials_iridescence.iridescenceIor", i.ior)?;
            if i.ior < 1.0 {
                return Err(format!(
                    "KHR_materials_iridescence.iridescenceIor = {} must be >= 1",
                    i.ior
                ));
            }
            let (lo, hi) = (i.thickness_min, i.thickness_max);
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
        }
        if let Some(a) = &self.anisotropy {
            unit("KHR_materials_anisotropy.anisotropyStrength", a.strength)?;
            finite("KHR_materials_anisotropy.anisotropyRotation", a.rotation)?;
        }
        Ok(())
    }

    /// One line for `iris info` (empty when neither extension is present).
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if let Some(i) = &self.iridescence {
            let tex = if i.texture.is_some() || i.thickness_texture.is_some() {
                ", textured"
            } else {
                ""
            };
            parts.push(format!(
                "iridescence {} (film n {}, {}–{} nm{tex})",
                i.factor, i.ior, i.thickness_min, i.thickness_max
            ));
        }
        if let Some(a) = &self.anisotropy {
            let tex = if a.texture.is_some() {
                ", textured"
            } else {
                ""
            };
            parts.push(format!(
                "anisotropy {} (rotation {} rad{tex})",
                a.strength, a.rotation
            ));
        }
        parts.join("; ")
    }

    /// What the film extensions cannot do in this scene, one warning per kind: meshes
    /// whose anisotropic material has neither TANGENT nor TEXCOORD_0 (the brushing
    /// direction falls back to an arbitrary, deterministic frame), and iridescent materials
    /// that transmit (the film is applied to the opaque lobes' reflection only; the
    /// transmissive lobe keeps the plain dielectric Fresnel).
    pub fn scene_warnings(desc: &SceneDesc) -> Vec<String> {
        let mut out = Vec::new();
        let tangentless: Vec<&str> = desc
            .meshes
            .iter()
            .filter(|m| {
                m.material
                    .and_then(|i| desc.materials.get(i))
                    .is_some_and(|mat| mat.film.is_anisotropic())
                    && m.tangents.is_empty()
                    && m.uvs.is_empty()
            })
            .map(|m| m.name.as_str())
            .collect();
        if !tangentless.is_empty() {
            out.push(format!(
                "KHR_materials_anisotropy without TANGENT or TEXCOORD_0: the brushing direction is arbitrary on {}",
                short(&tangentless)
            ));
        }
        let transmissive: Vec<&str> = desc
            .materials
            .iter()
            .filter(|m| m.transmission > 0.0 && m.film.iridescence.is_some_and(|i| i.factor > 0.0))
            .map(|m| m.name.as_str())
            .collect();
        if !transmissive.is_empty() {
            out.push(format!(
                "KHR_materials_iridescence on transmissive materials is applied to their opaque reflection only (the transmission lobe keeps the plain Fresnel): {}",
                short(&transmissive)
            ));
        }
        out
    }
}

/// The first six names, then how many more.
fn short(names: &[&str]) -> String {
    let shown = names.iter().take(6).copied().collect::<Vec<_>>().join(", ");
    match names.len().saturating_sub(6) {
        0 => shown,
        more => format!("{shown} and {more} more"),
    }
}
