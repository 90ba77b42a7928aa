//! Render-time materials: the glTF metallic-roughness model plus the KHR extensions, with
//! textures resolved at a hit into a [`ShadingPoint`]. Colours are linear RGB.
//!
//! A material is a *dielectric interface* when `transmission > 0` and it is not fully
//! metallic: volumetric (`thickness > 0`, the mesh bounds a medium: rays bend by Snell's law
//! and are absorbed by Beer–Lambert inside) or thin-walled (`thickness == 0`: no bending,
//! the base colour tints what passes). IOR 0 is the KHR_materials_ior special mode:
//! infinite index, Fresnel = 1, no dispersion.
//!
//! Each material carries exactly one n(λ) model ([`spectrum::IorModel`], resolved by
//! [`MaterialDesc::spectral_ior`] when the material is built): RGB transport uses its n at
//! the helium d line ([`Material::ior`]), spectral transport evaluates
//! [`Material::ior_model`] at each wavelength (nm).
//!
//! A material with a measured metal (`desc.conductor`, `--metal`) is an opaque conductor
//! whose complex index n(λ) + ik(λ) comes from [`spectrum::metals`]
//! ([`Material::conductor_index`]); its base colour is not used for shading.

use crate::scene::desc::{
    effective_color, AlphaMode, ExplicitIor, ImageDesc, LayerPoint, MaterialDesc, TextureRef,
};
use crate::spectrum::{self, ior::KNOWN_NAMES};
use crate::spectrum::{Carrier, EmitterShape, Metal};
use crate::texture::{self, Encoding};
use glam::{Vec2, Vec3, Vec4};

/// One material of the render scene.
#[derive(Debug, Clone)]
pub struct Material {
    /// The validated parameters as loaded.
    pub desc: MaterialDesc,
    /// n(λ), resolved from `desc` by [`Material::new`].
    ior_model: spectrum::IorModel,
    /// Linear-sRGB colour of `desc.emission_spectrum` (Y = 1), or white without one.
    emission_tint: Vec3,
    emitter_shape: Option<EmitterShape>,
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
    /// KHR_materials_specular factor, texture applied.
    pub specular: f32,
    /// KHR_materials_specular colour (linear), texture applied.
    pub specular_color: Vec3,
    /// KHR_materials_clearcoat, _sheen and _diffuse_transmission at this point.
    pub layers: LayerPoint,
    /// KHR_materials_iridescence / KHR_materials_anisotropy, textures applied.
    pub film: crate::shading::film::FilmPoint,
}

fn lookup(images: &[ImageDesc], tex: Option<TextureRef>, uv: Vec2, enc: Encoding) -> Vec4 {
    let Some(t) = tex else { return Vec4::ONE };
    match images.get(t.image) {
        Some(img) => texture::sample(img, t.transform.transform_point2(uv), enc),
        None => Vec4::ONE,
    }
}

impl Material {
    /// Wraps a validated description and resolves its IOR model. An unknown glass name
    /// (which validation rejects) falls back to the KHR values.
    pub fn new(desc: MaterialDesc) -> Self {
        let ior_model = desc
            .spectral_ior()
            .unwrap_or_else(|_| spectrum::IorModel::from_khr(desc.ior, desc.dispersion));
        let emission_tint = effective_color(Vec3::ONE, desc.emission_spectrum);
        let emitter_shape = desc
            .emission_spectrum
            .map(|s| s.emitter_shape(desc.emissive));
        Material {
            desc,
            ior_model,
            emission_tint,
            emitter_shape,
        }
    }

    /// The exact spectral shape of the emission for spectral transport (`iris_spectrum`),
    /// or `None` (upsample the RGB emission).
    pub fn emitter_shape(&self) -> Option<&EmitterShape> {
        self.emitter_shape.as_ref()
    }

    /// Emitted radiance factor for the RGB transport (before the emissive texture):
    /// `emissive` × the `iris_spectrum` colour (normalised to luminance 1).
    pub fn emission(&self) -> Vec3 {
        self.desc.emissive * self.emission_tint
    }

    /// The emission's spectral shape (Y = 1) for the spectral transport, which multiplies it
    /// by the `emissive` filter; `None` means "upsample `emissive` as an illuminant".
    pub fn emission_spectrum(&self) -> Option<spectrum::Spectrum> {
        self.desc.emission_spectrum.map(|s| s.spectrum())
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
            emissive: self.emission() * em.truncate(),
            // KHR_materials_specular: specularTexture's A, specularColorTexture's RGB (sRGB).
            specular: d.specular * lookup(images, d.specular_texture, uv, Encoding::Linear).w,
            specular_color: d.specular_color
                * lookup(images, d.specular_color_texture, uv, Encoding::Srgb).truncate(),
            layers: d.layers.shade(uv, images),
            film: crate::shading::film::FilmPoint::shade(&d.film, uv, images),
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

    /// Index of refraction for RGB transport: the model's n_d (587.56 nm). That is the KHR
    /// `ior` itself for KHR_materials_dispersion (whose formula gives n_d only to ~1e-5),
    /// the catalogue n_d for a named glass, b + c/λ_d² for Cauchy, and `f32::INFINITY` for
    /// the `ior: 0` mode.
    pub fn ior(&self) -> f32 {
        match self.ior_model {
            spectrum::IorModel::KhrDispersion { n_d, .. } => n_d,
            model => model.n_d(),
        }
    }

    /// The measured metal of a `--metal` material, if any.
    pub fn conductor(&self) -> Option<Metal> {
        self.desc.conductor
    }

    /// The complex index (n, k) of the material's measured metal at the path's wavelengths:
    /// per wavelength in spectral transport, the metal's per-channel stand-ins
    /// ([`Metal::rgb_eta_k`]) in RGB; `None` for any other material.
    pub fn conductor_index<C: Carrier>(&self, l: &C::Lambda) -> Option<(C, C)> {
        let metal = self.desc.conductor?;
        Some(match C::lanes_nm(l) {
            Some(lanes) => {
                let nk = lanes.map(|nm| metal.eta_k(nm));
                (
                    C::from_lanes(nk.map(|p| p.0)),
                    C::from_lanes(nk.map(|p| p.1)),
                )
            }
            None => {
                let (eta, k) = metal.rgb_eta_k();
                let lanes = |v: glam::Vec3| C::from_lanes(v.extend(0.0).to_array());
                (lanes(eta), lanes(k))
            }
        })
    }

    /// The material's n(λ) model (λ in nm), for spectral transport.
    pub fn ior_model(&self) -> &spectrum::IorModel {
        &self.ior_model
    }

    /// Whether the index depends on wavelength (spectral transport then terminates the
    /// secondary wavelengths at a refraction).
    pub fn is_dispersive(&self) -> bool {
        self.ior_model.is_dispersive()
    }

    /// Beer–Lambert transmittance c^(x/d) over distance `x` inside the medium
    /// (KHR_materials_volume), for any carrier: the attenuation colour (upsampled as a
    /// reflectance at the path's wavelengths in spectral transport) raised to x/d per
    /// channel. Exactly 1 for the default infinite attenuation distance.
    pub fn transmittance_at<C: Carrier>(&self, x: f32, l: &C::Lambda) -> C {
        let d = self.desc.attenuation_distance;
        if !d.is_finite() {
            return C::ONE;
        }
        C::reflectance(self.desc.attenuation_color, l).powf(x / d)
    }

    /// The index of refraction a path at the given wavelengths sees: n(hero λ) from the IOR
    /// model in spectral transport when `dispersive` (the caller keeps only the hero), else
    /// [`Material::ior`]. `f32::INFINITY` for the `ior: 0` mode.
    pub fn ior_at(&self, hero: Option<f32>, dispersive: bool) -> f32 {
        match hero {
            Some(l) if dispersive && self.is_dispersive() => self.ior_model().ior(l),
            _ => self.ior(),
        }
    }
}

/// One line describing a material's IOR model for `iris info`, e.g.
/// `Sellmeier N-BK7 (n_d 1.5168, Abbe 64.2)` or `2.42, KHR dispersion 0.36 (Abbe 55.6)`.
pub fn describe_ior(desc: &MaterialDesc) -> String {
    let model = match desc.spectral_ior() {
        Ok(model) => model,
        Err(e) => return format!("{} ({e})", desc.ior),
    };
    if desc.ior == 0.0 {
        return "0 (infinite, no dispersion)".to_string();
    }
    let optics = format!("n_d {:.4}, Abbe {:.1}", model.n_d(), model.abbe_number());
    match (&desc.ior_model, model) {
        (Some(ExplicitIor::Glass(name)), _) => {
            // The catalogue spelling of the name as written (aliases resolve alike).
            let same = |k: &&&str| spectrum::IorModel::named(k).ok() == Some(model);
            let canonical = KNOWN_NAMES
                .iter()
                .find(same)
                .copied()
                .unwrap_or(name.as_str());
            format!("Sellmeier {canonical} ({optics})")
        }
        (Some(ExplicitIor::Sellmeier { .. }), _) => format!("Sellmeier ({optics})"),
        (_, spectrum::IorModel::Cauchy { b, c }) => format!("Cauchy b {b} c {c} ({optics})"),
        // The extension defines its Abbe number as 20/D.
        (_, spectrum::IorModel::KhrDispersion { n_d, dispersion }) => format!(
            "{n_d}, KHR dispersion {dispersion} (Abbe {:.1})",
            20.0 / dispersion
        ),
        _ => format!("{}", desc.ior),
    }
}
