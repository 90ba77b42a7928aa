//! Render-time materials: the glTF metallic-roughness model plus the KHR extensions, with
//! textures resolved at a hit into a [`ShadingPoint`]. Colours are linear RGB.
//!
//! A material is a *dielectric interface* when `transmission > 0` and it is not fully
//! metallic: volumetric (`thickness > 0`, the mesh bounds a medium: rays bend by Snell's law
//! and are absorbed by Beer–Lambert inside) or thin-walled (`thickness == 0`: no bending,
//! the base colour tints what passes). IOR 0 is the KHR_materials_ior special mode:
//! infinite index, Fresnel = 1.

use crate::scene::desc::{AlphaMode, ImageDesc, IorModel, MaterialDesc, TextureRef};
use crate::texture::{self, Encoding};
use glam::{Vec2, Vec3, Vec4};

/// One material of the render scene.
#[derive(Debug, Clone)]
pub struct Material {
    /// The validated parameters as loaded.
    pub desc: MaterialDesc,
}

/// Material parameters at one surface point, textures applied.
#[derive(Debug, Clone, Copy)]
pub struct ShadingPoint {
    /// Linear base colour.
    pub base_color: Vec3,
    /// Coverage (base colour alpha), used by MASK and BLEND.
    pub alpha: f32,
    /// Metallic in [0,1].
    pub metallic: f32,
    /// Perceptual roughness in [0,1].
    pub roughness: f32,
    /// Transmission weight in [0,1] (0 for metals).
    pub transmission: f32,
    /// Emitted radiance, linear RGB.
    pub emissive: Vec3,
}

fn lookup(images: &[ImageDesc], tex: Option<TextureRef>, uv: Vec2, enc: Encoding) -> Vec4 {
    match tex.and_then(|t| images.get(t.image)) {
        Some(img) => texture::sample(img, uv, enc),
        None => Vec4::ONE,
    }
}

impl Material {
    /// Wraps a validated description.
    pub fn new(desc: MaterialDesc) -> Self {
        Material { desc }
    }

    /// Resolves textures at texture coordinate `uv`.
    pub fn shade(&self, uv: Vec2, images: &[ImageDesc]) -> ShadingPoint {
        let d = &self.desc;
        let bc = d.base_color * lookup(images, d.base_color_texture, uv, Encoding::Srgb);
        // glTF: metallic in B, roughness in G of the metallic-roughness texture.
        let mr = lookup(images, d.metallic_roughness_texture, uv, Encoding::Linear);
        let em = lookup(images, d.emissive_texture, uv, Encoding::Srgb);
        let tr = lookup(images, d.transmission_texture, uv, Encoding::Linear);
        let metallic = (d.metallic * mr.z).clamp(0.0, 1.0);
        ShadingPoint {
            base_color: bc.truncate().clamp(Vec3::ZERO, Vec3::ONE),
            alpha: bc.w.clamp(0.0, 1.0),
            metallic,
            roughness: (d.roughness * mr.y).clamp(0.0, 1.0),
            transmission: (d.transmission * tr.x).clamp(0.0, 1.0) * (1.0 - metallic),
            emissive: d.emissive * em.truncate(),
        }
    }

    /// Whether a hit at `uv` is cut away by alpha masking (glTF `MASK`).
    pub fn is_cut_out(&self, uv: Vec2, images: &[ImageDesc]) -> bool {
        match self.desc.alpha_mode {
            AlphaMode::Mask(cutoff) => {
                let a = self.desc.base_color.w
                    * lookup(images, self.desc.base_color_texture, uv, Encoding::Srgb).w;
                a < cutoff
            }
            _ => false,
        }
    }

    /// Whether any hit can be cut away (so shadow rays must look at each hit).
    pub fn may_cut_out(&self) -> bool {
        matches!(self.desc.alpha_mode, AlphaMode::Mask(_))
    }

    /// Whether the surface transmits light at all.
    pub fn is_transmissive(&self) -> bool {
        self.desc.transmission > 0.0 && self.desc.metallic < 1.0
    }

    /// Whether the mesh bounds a refracting medium (KHR_materials_volume thickness > 0).
    pub fn is_volume(&self) -> bool {
        self.desc.thickness > 0.0
    }

    /// Index of refraction for RGB transport: the KHR `ior` (n_d), or the Cauchy model
    /// evaluated at the helium d line, 587.56 nm. `f32::INFINITY` for the `ior: 0` mode.
    pub fn ior(&self) -> f32 {
        match self.desc.ior_model {
            Some(IorModel::Cauchy { b, c }) => {
                let l = 0.587_56f32;
                b + c / (l * l)
            }
            None if self.desc.ior == 0.0 => f32::INFINITY,
            None => self.desc.ior,
        }
    }

    /// Beer–Lambert transmittance c^(x/d) over distance `x` inside the medium
    /// (KHR_materials_volume). Exactly 1 for the default infinite attenuation distance.
    pub fn transmittance(&self, x: f32) -> Vec3 {
        let d = self.desc.attenuation_distance;
        if !d.is_finite() {
            return Vec3::ONE;
        }
        let c = self.desc.attenuation_color;
        let e = x / d;
        Vec3::new(c.x.powf(e), c.y.powf(e), c.z.powf(e))
    }
}
