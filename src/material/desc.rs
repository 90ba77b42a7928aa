//! A material as loaded ([`MaterialDesc`]): glTF metallic-roughness plus the KHR material
//! extensions Iris reads, with the spec defaults, and the one list of its texture slots
//! ([`MaterialDesc::textures`]) that validation, the render plan and `iris info` read.
//!
//! Colours are linear RGB; factors dimensionless; lengths in world units (metres for glTF);
//! the IOR model's wavelengths in µm (Cauchy, Sellmeier) as the formulas write them.

use super::anisotropy::AnisotropyDesc;
use super::crystal::CrystalDesc;
use super::iridescence::IridescenceDesc;
use super::layers::LayerDesc;
use super::texture::TextureRef;
use crate::spectrum::ior::KNOWN_NAMES;
use crate::spectrum::{EmissionSpectrum, IorModel as SpectralIor, Metal, UnknownIorName};
use crate::volume::VolumeScatter;
use glam::{Vec3, Vec4};
use std::collections::BTreeSet;

/// How the base colour's alpha is used (glTF `alphaMode`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum AlphaMode {
    /// Alpha ignored.
    #[default]
    Opaque,
    /// Alpha below the cutoff makes the surface invisible.
    Mask(f32),
    /// Alpha blends (treated as stochastic coverage).
    Blend,
}

/// An IOR model given explicitly by the scene (glTF material `extras`, Iris MTL keys).
/// It takes precedence over KHR_materials_dispersion; see [`MaterialDesc::spectral_ior`].
#[derive(Debug, Clone, PartialEq)]
pub enum ExplicitIor {
    /// The Cauchy form of Cropp & Zhang, "Light Refraction with Dispersion": n(λ) = b + c/λ²,
    /// λ in micrometres (material extras `{"cauchy": {"b": 1.5, "c": 0.0042}}`, MTL
    /// `cauchy_b`/`cauchy_c`).
    Cauchy {
        /// Constant term b.
        b: f32,
        /// Coefficient c in µm².
        c: f32,
    },
    /// A named Sellmeier glass from [`crate::spectrum::ior::KNOWN_NAMES`], as written
    /// (extras `{"iris_glass": "N-BK7"}`, MTL `iris_glass N-BK7`); names are
    /// case-insensitive and validation rejects unknown ones.
    Glass(String),
    /// Sellmeier coefficients given directly (extras `{"sellmeier": {"b": [..], "c": [..]}}`,
    /// up to 4 terms, C_i in µm²); unused terms are 0. Validation rejects a resonance
    /// √C_i inside the sampled wavelength range.
    Sellmeier {
        /// Oscillator strengths B_i.
        b: [f32; 4],
        /// Resonance wavelengths squared C_i, µm².
        c: [f32; 4],
    },
}

/// A material in glTF metallic-roughness terms plus the KHR extensions Iris reads.
/// Defaults are the glTF spec defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialDesc {
    /// Name for messages, e.g. `material 4 "Glass"`.
    pub name: String,
    /// Linear RGBA base colour factor.
    pub base_color: Vec4,
    /// Base colour texture (sRGB).
    pub base_color_texture: Option<TextureRef>,
    /// Metallic factor in [0,1].
    pub metallic: f32,
    /// Perceptual roughness factor in [0,1].
    pub roughness: f32,
    /// Metallic (B) / roughness (G) texture (linear).
    pub metallic_roughness_texture: Option<TextureRef>,
    /// Linear emissive colour, already multiplied by KHR_materials_emissive_strength.
    pub emissive: Vec3,
    /// Emissive texture (sRGB).
    pub emissive_texture: Option<TextureRef>,
    /// Spectral shape of the emission (extras / MTL `iris_spectrum`); `None` upsamples the
    /// RGB `emissive` as an illuminant. See [`EmissionSpectrum`] for how the two combine.
    pub emission_spectrum: Option<EmissionSpectrum>,
    /// Nested-media priority where volumes overlap (extras / MTL `iris_priority`, default
    /// 0): inside an overlap the path is in the medium of highest priority (Schmidt & Budge
    /// 2002; see [`crate::medium_stack`]).
    pub priority: i32,
    /// Index of refraction (KHR_materials_ior, default 1.5). The value 0 is the spec's
    /// special mode: infinite IOR, Fresnel = 1, no dispersion. Otherwise unused when
    /// `ior_model` is given (it is then the fallback other renderers read).
    pub ior: f32,
    /// KHR_materials_transmission factor in [0,1].
    pub transmission: f32,
    /// Transmission texture (R channel).
    pub transmission_texture: Option<TextureRef>,
    /// KHR_materials_volume thicknessFactor: 0 = thin-walled, > 0 = the mesh bounds a volume.
    pub thickness: f32,
    /// KHR_materials_volume attenuation colour (linear RGB).
    pub attenuation_color: Vec3,
    /// KHR_materials_volume attenuation distance (world units), +∞ by default.
    pub attenuation_distance: f32,
    /// Scattering inside the volume (KHR_materials_volume_scatter / KHR_materials_scatter,
    /// or `extras.iris_medium`; [`crate::volume`]); `None`: the volume only absorbs.
    pub scatter: Option<VolumeScatter>,
    /// KHR_materials_specular specularFactor.
    pub specular: f32,
    /// KHR_materials_specular specularColorFactor (linear).
    pub specular_color: Vec3,
    /// KHR_materials_specular `specularTexture` (A channel multiplies `specular`).
    pub specular_texture: Option<TextureRef>,
    /// KHR_materials_specular `specularColorTexture` (sRGB RGB multiplies `specular_color`).
    pub specular_color_texture: Option<TextureRef>,
    /// KHR_materials_dispersion `dispersion` = 20/Abbe number.
    pub dispersion: f32,
    /// An explicit IOR model (extras / MTL keys); overrides `ior` and `dispersion`.
    pub ior_model: Option<ExplicitIor>,
    /// A measured metal (`--metal`, [`crate::prepare`]'s material override): the surface is
    /// an opaque conductor with that metal's spectral complex index n(λ) + ik(λ) and GGX
    /// roughness `roughness`; `base_color` is then only the colour other renderers and
    /// the RGB fallbacks show. Loaders leave it `None`.
    pub conductor: Option<Metal>,
    /// glTF doubleSided.
    pub double_sided: bool,
    /// glTF alphaMode / alphaCutoff.
    pub alpha_mode: AlphaMode,
    /// KHR_materials_clearcoat, _sheen and _diffuse_transmission ([`LayerDesc`]).
    pub layers: LayerDesc,
    /// KHR_materials_iridescence (`None` without the extension).
    pub iridescence: Option<IridescenceDesc>,
    /// KHR_materials_anisotropy (`None` without the extension).
    pub anisotropy: Option<AnisotropyDesc>,
    /// A birefringent crystal (extras `iris_crystal`, or `--stone` naming one): a
    /// volumetric dielectric whose light splits into two modes ([`CrystalDesc`]); `ior`
    /// is then its isotropic stand-in for transport without polarization.
    pub crystal: Option<CrystalDesc>,
    /// An ideal linear polarizer sheet (extras `iris_polarizer`): a thin-walled surface that
    /// passes the light's field component along this transmission axis (the mesh's frame
    /// as loaded, world space once built) under polarized transport, and everything
    /// without it.
    pub polarizer: Option<Vec3>,
    /// The names of the glTF material extensions the file states (`"KHR_materials_ior"`,
    /// …), so that one stated with its default values is written back
    /// ([`crate::authoring::glb`] writes the ones it knows that are stated or whose values
    /// differ from the defaults). The glTF loader fills it; other loaders leave it empty.
    pub stated: BTreeSet<String>,
    /// The material's glTF `extras` as the file gives them, written back unchanged. Iris's
    /// own keys in them (`iris_crystal`, `iris_glass`, `cauchy`, `sellmeier`,
    /// `iris_medium`, `iris_priority`, `iris_spectrum`, `iris_polarizer`) are read into
    /// the typed fields above; Iris keys live here, the typed fields are their reading.
    pub extras: Option<serde_json::Value>,
}

impl Default for MaterialDesc {
    fn default() -> Self {
        MaterialDesc {
            name: "default material".into(),
            base_color: Vec4::ONE,
            base_color_texture: None,
            metallic: 1.0,
            roughness: 1.0,
            metallic_roughness_texture: None,
            emissive: Vec3::ZERO,
            emissive_texture: None,
            emission_spectrum: None,
            priority: 0,
            ior: 1.5,
            transmission: 0.0,
            transmission_texture: None,
            thickness: 0.0,
            attenuation_color: Vec3::ONE,
            attenuation_distance: f32::INFINITY,
            scatter: None,
            specular: 1.0,
            specular_color: Vec3::ONE,
            specular_texture: None,
            specular_color_texture: None,
            dispersion: 0.0,
            ior_model: None,
            conductor: None,
            double_sided: false,
            alpha_mode: AlphaMode::Opaque,
            layers: LayerDesc::default(),
            iridescence: None,
            anisotropy: None,
            crystal: None,
            polarizer: None,
            stated: BTreeSet::new(),
            extras: None,
        }
    }
}

impl MaterialDesc {
    /// The one n(λ) model this material refracts with. Precedence: `ior == 0` (the
    /// KHR_materials_ior infinite-IOR mode: `Constant(+∞)`, no dispersion, whatever else is
    /// given) > the explicit model (`ior_model`) > KHR_materials_dispersion (`dispersion > 0`,
    /// `ior` as n_d; `ior` 1 stays constant) > `Constant(ior)`. Errs only on an unknown
    /// glass name; the value checks are [`crate::scene::validate`]'s.
    pub fn spectral_ior(&self) -> Result<SpectralIor, UnknownIorName> {
        if self.ior == 0.0 {
            return Ok(SpectralIor::Constant(f32::INFINITY));
        }
        // A crystal's isotropic stand-in: its principal y index (n_o, or n_β).
        match self.crystal.map(|c| c.optics) {
            Some(super::CrystalOptics::Table(c)) => return Ok(c.axes[1]),
            Some(super::CrystalOptics::Indices(n)) => return Ok(SpectralIor::Constant(n[1])),
            None => {}
        }
        match &self.ior_model {
            Some(ExplicitIor::Glass(name)) => SpectralIor::named(name),
            Some(ExplicitIor::Cauchy { b, c }) => Ok(SpectralIor::Cauchy { b: *b, c: *c }),
            Some(ExplicitIor::Sellmeier { b, c }) => Ok(SpectralIor::Sellmeier { b: *b, c: *c }),
            // n_d = 1 makes the KHR formula's (n_d − 1) factor vanish: n ≡ 1, not dispersive.
            None if self.ior == 1.0 => Ok(SpectralIor::Constant(1.0)),
            None => Ok(SpectralIor::from_khr(self.ior, self.dispersion)),
        }
    }

    /// Every texture slot of the material with its glTF property name, in a fixed order:
    /// the core slots, KHR_materials_specular, the layers ([`LayerDesc::textures`]),
    /// iridescence and anisotropy. Empty slots are `None`.
    pub fn textures(&self) -> Vec<(&'static str, Option<TextureRef>)> {
        let mut out = vec![
            ("baseColorTexture", self.base_color_texture),
            ("metallicRoughnessTexture", self.metallic_roughness_texture),
            ("emissiveTexture", self.emissive_texture),
            ("transmissionTexture", self.transmission_texture),
            ("specularTexture", self.specular_texture),
            ("specularColorTexture", self.specular_color_texture),
        ];
        out.extend(self.layers.textures());
        if let Some(i) = &self.iridescence {
            out.extend(i.textures());
        }
        if let Some(a) = &self.anisotropy {
            out.extend(a.textures());
        }
        out
    }

    /// Whether the material needs a tangent frame (anisotropy with a strength or texture).
    pub fn is_anisotropic(&self) -> bool {
        self.anisotropy.is_some_and(|a| a.is_on())
    }

    /// Iridescence and anisotropy in a few words for `iris info`, joined by "; " (empty
    /// without either).
    pub fn describe_extensions(&self) -> String {
        let iridescence = self.iridescence.map(|i| i.describe());
        let anisotropy = self.anisotropy.map(|a| a.describe());
        [iridescence, anisotropy]
            .into_iter()
            .flatten()
            .collect::<Vec<_>>()
            .join("; ")
    }

    /// Whether the material has a thin film (iridescence factor and thickness > 0): an
    /// interference colour that spectral transport renders per wavelength.
    pub fn is_iridescent(&self) -> bool {
        self.iridescence.is_some_and(|i| i.is_on())
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
            let same = |k: &&&str| SpectralIor::named(k).ok() == Some(model);
            let canonical = KNOWN_NAMES
                .iter()
                .find(same)
                .copied()
                .unwrap_or(name.as_str());
            format!("Sellmeier {canonical} ({optics})")
        }
        (Some(ExplicitIor::Sellmeier { .. }), _) => format!("Sellmeier ({optics})"),
        (_, SpectralIor::Cauchy { b, c }) => format!("Cauchy b {b} c {c} ({optics})"),
        // The extension defines its Abbe number as 20/D.
        (_, SpectralIor::KhrDispersion { n_d, dispersion }) => format!(
            "{n_d}, KHR dispersion {dispersion} (Abbe {:.1})",
            20.0 / dispersion
        ),
        _ => format!("{}", desc.ior),
    }
}
