//! Materials: what a material is as loaded ([`MaterialDesc`], [`desc`]), its KHR layers
//! ([`layers`]), thin film ([`iridescence`]) and brushed surface ([`anisotropy`]), the
//! textures it references and the **one** texture lookup ([`texture`]), and the render-time
//! [`Material`] with its parameters resolved at a surface point ([`ShadingPoint`]) and the
//! BSDF of an opaque point ([`Material::opaque_bsdf`]). Colours are linear RGB. This module
//! sits below the scene, shading and photon tracing, which all read materials through it.
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

pub mod anisotropy;
mod check;
pub mod crystal;
pub mod desc;
pub mod iridescence;
pub mod layers;
#[cfg(test)]
mod opaque_tests;
pub mod texture;

pub use anisotropy::{AnisotropyDesc, AnisotropyPoint};
pub use crystal::{CrystalDesc, CrystalOptics};
pub use desc::{describe_ior, AlphaMode, ExplicitIor, MaterialDesc};
pub use iridescence::{IridescenceDesc, IridescencePoint};
pub use layers::{LayerDesc, LayerPoint};
pub use texture::{Encoding, ImageDesc, TexCoords, TextureContext, TextureRef};

use crate::bsdf::{Bsdf, LobeExtensions};
use crate::spectrum::{self, effective_color, Carrier, EmitterShape, Metal};
use crate::volume::Medium;
use glam::Vec3;

/// Whether a material's surface, between media of equal index, changes nothing but the
/// medium: a volume (thickness > 0) of constant IOR exactly 1, fully and smoothly
/// transmissive, untinted, untextured, without emission, coverage, layers, film or metal.
/// Such a boundary (KHR_materials_ior 1.0 around a scattering medium) is crossed without
/// a bounce, by camera and shadow rays alike ([`crate::shading::media`]).
fn index_matched(d: &MaterialDesc, model: &spectrum::IorModel) -> bool {
    let l = &d.layers;
    d.thickness > 0.0
        && d.ior != 0.0
        && model.n_d() == 1.0
        && !model.is_dispersive()
        && d.transmission == 1.0
        && d.roughness == 0.0
        && d.base_color.truncate() == Vec3::ONE
        && d.emissive == Vec3::ZERO
        && matches!(d.alpha_mode, AlphaMode::Opaque)
        && d.textures().iter().all(|(_, t)| t.is_none())
        && l.clearcoat == 0.0
        && l.sheen_color == Vec3::ZERO
        && l.diffuse_transmission == 0.0
        && d.iridescence.is_none()
        && d.conductor.is_none()
}

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
    /// The shading point of a material without textures, the same at every hit: computed
    /// once here, so [`Material::shade`] only copies it.
    constant: Option<ShadingPoint>,
    /// The scattering medium the volume holds (a volume whose `scatter` scatters); its
    /// absorption is then the medium's, not [`Material::transmittance_at`]'s.
    medium: Option<Medium>,
    /// A volume boundary that changes nothing but the medium ([`Material::is_index_matched`]).
    index_matched: bool,
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
    /// KHR_materials_iridescence at this point (`None` where there is no film).
    pub iridescence: Option<IridescencePoint>,
    /// KHR_materials_anisotropy at this point.
    pub anisotropy: AnisotropyPoint,
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
        let medium = desc
            .scatter
            .filter(|_| desc.thickness > 0.0)
            .map(|s| s.medium(desc.attenuation_color, desc.attenuation_distance))
            .filter(Medium::scatters);
        let index_matched = index_matched(&desc, &ior_model);
        let mut material = Material {
            desc,
            ior_model,
            emission_tint,
            emitter_shape,
            constant: None,
            medium,
            index_matched,
        };
        if material.desc.textures().iter().all(|(_, t)| t.is_none()) {
            let untextured = TextureContext::new(&[], TexCoords::default());
            material.constant = Some(material.shade(&untextured));
        }
        material
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

    /// The emitted radiance where textures are evaluated by `tex` (linear RGB, RGB
    /// transport): [`Material::emission`] × the emissive texture. Camera paths, next-event
    /// estimation and photon emission all read emission through here.
    pub fn emitted(&self, tex: &TextureContext) -> Vec3 {
        self.emission()
            * tex
                .lookup(self.desc.emissive_texture, Encoding::Srgb)
                .truncate()
    }

    /// The material's parameters at every point of an untextured material (`None` when
    /// a texture makes them vary).
    pub fn untextured(&self) -> Option<&ShadingPoint> {
        self.constant.as_ref()
    }

    /// The material's parameters where textures are evaluated by `tex`.
    pub fn shade(&self, tex: &TextureContext) -> ShadingPoint {
        if let Some(sp) = self.constant {
            return sp;
        }
        let d = &self.desc;
        let bc = d.base_color * tex.lookup(d.base_color_texture, Encoding::Srgb);
        // glTF: metallic in B, roughness in G of the metallic-roughness texture.
        let mr = tex.lookup(d.metallic_roughness_texture, Encoding::Linear);
        let tr = tex.lookup(d.transmission_texture, Encoding::Linear);
        let metallic = (d.metallic * mr.z).clamp(0.0, 1.0);
        ShadingPoint {
            base_color: bc.truncate().clamp(Vec3::ZERO, Vec3::ONE),
            alpha: bc.w.clamp(0.0, 1.0),
            metallic,
            roughness: (d.roughness * mr.y).clamp(0.0, 1.0),
            transmission: (d.transmission * tr.x).clamp(0.0, 1.0) * (1.0 - metallic),
            emissive: self.emitted(tex),
            // KHR_materials_specular: specularTexture's A, specularColorTexture's RGB (sRGB).
            specular: d.specular * tex.lookup(d.specular_texture, Encoding::Linear).w,
            specular_color: d.specular_color
                * tex
                    .lookup(d.specular_color_texture, Encoding::Srgb)
                    .truncate(),
            layers: d.layers.at(tex),
            iridescence: d.iridescence.and_then(|i| i.at(tex)),
            anisotropy: d.anisotropy.map_or(AnisotropyPoint::NONE, |a| a.at(tex)),
        }
    }

    /// Whether a hit where textures are evaluated by `tex` is cut away by alpha masking
    /// (glTF `MASK`).
    pub fn is_cut_out(&self, tex: &TextureContext) -> bool {
        match self.desc.alpha_mode {
            AlphaMode::Mask(cutoff) => {
                let a = self.desc.base_color.w
                    * tex.lookup(self.desc.base_color_texture, Encoding::Srgb).w;
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

    /// The scattering medium inside the volume, if it scatters ([`crate::volume`]).
    pub fn medium(&self) -> Option<&Medium> {
        self.medium.as_ref()
    }

    /// Whether the surface only separates media of equal index ([`index_matched`]).
    pub fn is_index_matched(&self) -> bool {
        self.index_matched
    }

    /// Beer–Lambert transmittance c^(x/d) over distance `x` inside the medium
    /// (KHR_materials_volume), for any carrier: the attenuation colour (upsampled as a
    /// reflectance at the path's wavelengths in spectral transport) raised to x/d per
    /// channel. Exactly 1 for the default infinite attenuation distance, and for a volume
    /// holding a scattering medium, whose extinction the path's free-flight sampling takes
    /// ([`crate::volume::track`]).
    pub fn transmittance_at<C: Carrier>(&self, x: f32, l: &C::Lambda) -> C {
        if !self.absorbs() {
            return C::ONE;
        }
        let d = self.desc.attenuation_distance;
        C::reflectance(self.desc.attenuation_color, l).powf(x / d)
    }

    /// Whether [`Material::transmittance_at`] can be below 1: a finite attenuation
    /// distance, no scattering medium (whose free-flight sampling takes the extinction), and
    /// an attenuation colour other than white (white gives exactly 1 at any distance: both
    /// carriers take a grey colour as that grey, and 1^y = 1 in IEEE 754 `pow`).
    pub fn absorbs(&self) -> bool {
        self.desc.attenuation_distance.is_finite()
            && self.medium.is_none()
            && self.desc.attenuation_color != Vec3::ONE
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

    /// The BSDF of an opaque (non-transmitting) point with parameters `sp`: a measured
    /// metal's complex-index conductor ([`Material::conductor_index`], GGX α = roughness²),
    /// else glTF metallic-roughness (Appendix B of the glTF 2.0 spec) with
    /// KHR_materials_specular, the layers, iridescence and anisotropy, in its simplest form
    /// ([`Bsdf::reduced`]: without a specular part, the Lambert lobe it equals).
    pub fn opaque_bsdf<C: Carrier>(&self, sp: &ShadingPoint, l: &C::Lambda) -> Bsdf<C> {
        if let Some((eta, k)) = self.conductor_index::<C>(l) {
            return Bsdf::ComplexConductor {
                eta,
                k,
                alpha: sp.roughness * sp.roughness,
                extensions: sp.lobe::<C>(l),
            };
        }
        Bsdf::GltfPbr {
            base: C::reflectance(sp.base_color, l),
            metallic: sp.metallic,
            alpha: sp.roughness * sp.roughness,
            ior: self.ior(),
            specular: sp.specular,
            specular_color: C::reflectance(sp.specular_color, l),
            extensions: sp.lobe::<C>(l),
            layers: sp.layers.lobes::<C>(l),
        }
        .reduced()
    }

    /// The BSDF of a transmitting point with parameters `sp`, tinted by its base colour: a
    /// thin wall's straight-through slab of the material's index when `eta` is `None`, a
    /// volume boundary's smooth or rough dielectric (GGX α = roughness²) with the ratio
    /// `eta` = n_inside / n_outside the path's media give.
    pub fn transmission_bsdf<C: Carrier>(
        &self,
        sp: &ShadingPoint,
        eta: Option<f32>,
        l: &C::Lambda,
    ) -> Bsdf<C> {
        let tint = C::reflectance(sp.base_color, l);
        match eta {
            None => Bsdf::ThinDielectric {
                eta: self.ior(),
                tint,
            },
            Some(eta) => Bsdf::Dielectric {
                eta,
                alpha: sp.roughness * sp.roughness,
                tint,
            },
        }
    }
}

impl ShadingPoint {
    /// What iridescence and anisotropy add to the reflection lobe at the path's
    /// wavelengths `l`.
    pub fn lobe<C: Carrier>(&self, l: &C::Lambda) -> LobeExtensions {
        LobeExtensions {
            iridescence: self.iridescence.map(|i| i.lobe::<C>(l)),
            anisotropy: self.anisotropy.strength,
        }
    }
}
