//! The plain scene description: what a loader (glTF, OBJ, the asset generator) produces
//! before validation. Everything is already in **world space** (metres by glTF convention;
//! OBJ files are taken as metres too), right-handed, +Y up.
//!
//! Invariants a loader must establish (validation checks them again):
//! - triangles are wound counter-clockwise seen from outside, so the geometric normal
//!   `(p1-p0)×(p2-p0)` points out of the object; a node with a negative-determinant
//!   transform has had its winding flipped by the loader;
//! - per-vertex arrays (`normals`, `uvs`) are either empty or as long as `positions`;
//! - colours are **linear** RGB (sRGB-encoded values have been decoded);
//! - light intensities keep their glTF units: candela (point, spot), lux (directional);
//! - an emission spectrum ([`EmissionSpectrum`], the Iris key `iris_spectrum`) only sets the
//!   *shape* of a light's or emissive material's spectrum, normalised to luminance Y = 1:
//!   the photometric intensity (cd, lx, emissive strength) is unchanged and the glTF
//!   `color` / `emissiveFactor` still multiplies it as a filter.
//!
//! Values are *not* trusted here: NaN, out-of-range indices and bad IORs are caught by
//! `scene::validate`, which names the element.
//!
//! What Iris adds to a file before the build is written here too, never into the built
//! scene: the resolved environment light, the studio or default lights ([`AddedLights`]),
//! the `--ground` floor (a mesh) and the bounds of the file's own geometry
//! ([`crate::prepare`] writes them; loaders leave them empty).

mod added;
mod emission;
mod film;
mod layers;

pub use added::{AddedLights, SpotKey};
pub use emission::{effective_color, EmissionSpectrum, BLACKBODY_KELVIN, SUN_KELVIN};
pub use film::{AnisotropyDesc, FilmDesc, IridescenceDesc};
pub use layers::{LayerDesc, LayerPoint};

use crate::light::env::Environment;
use crate::spectrum::{IorModel as SpectralIor, Metal, UnknownIorName};
use glam::{Mat4, Vec2, Vec3, Vec4};
use std::path::PathBuf;
use std::sync::Arc;

/// A whole scene as read from a file.
#[derive(Debug, Clone, Default)]
pub struct SceneDesc {
    /// The file it came from (used in error messages).
    pub source: PathBuf,
    /// Triangle meshes, one per glTF primitive instance / OBJ model, in world space.
    pub meshes: Vec<MeshDesc>,
    /// Materials referenced by `MeshDesc::material`.
    pub materials: Vec<MaterialDesc>,
    /// Decoded images referenced by `TextureRef::image`.
    pub images: Vec<ImageDesc>,
    /// Punctual lights (KHR_lights_punctual), in world space.
    pub lights: Vec<LightDesc>,
    /// Cameras, in world space.
    pub cameras: Vec<CameraDesc>,
    /// The environment light the file asks for (glTF scene `extras.iris_environment`);
    /// used when `--env` is not given.
    pub environment: Option<EnvironmentDesc>,
    /// Things the loader saw and did not use (unsupported extensions, MTL keys, primitive
    /// modes), each listed once.
    pub warnings: Vec<String>,
    /// Texture slots the loader left undecoded because their material is on no mesh (the
    /// render plan reports them).
    pub skipped_textures: usize,
    /// The environment light to render with, resolved (`--env`, the file's `environment`,
    /// or a studio's); `None` = no light from far away. Loaders leave it `None`.
    pub environment_light: Option<Environment>,
    /// Lights Iris adds to a file with none ([`AddedLights`]); loaders add none.
    pub added_lights: AddedLights,
    /// Bounds of the file's own geometry (min, max) when Iris added geometry to it (the
    /// `--ground` floor, [`crate::studio::ground`]); `None` = the bounds of every mesh.
    pub subject_bounds: Option<(Vec3, Vec3)>,
    /// Compressed geometry the loader decoded (glTF), shown by `iris info`.
    pub compressed: CompressedGeometry,
}

/// How much of a file's geometry was stored compressed (all zero for plain files).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CompressedGeometry {
    /// Mesh primitives with KHR_draco_mesh_compression.
    pub draco_primitives: usize,
    /// Buffer views decoded from EXT_/KHR_meshopt_compression.
    pub meshopt_views: usize,
}

/// An environment light named by the scene file (glTF scene `extras.iris_environment`).
#[derive(Debug, Clone, PartialEq)]
pub enum EnvironmentDesc {
    /// The same radiance from every direction (linear RGB, finite, ≥ 0).
    Uniform(Vec3),
    /// An equirectangular `.exr`/`.hdr` map (same convention as `--env FILE`), its path
    /// already resolved against the scene file's directory; the file exists.
    Map(PathBuf),
}

/// One triangle mesh in world space.
#[derive(Debug, Clone, Default)]
pub struct MeshDesc {
    /// Human-readable name used in errors, e.g. `node 3 "Gem" mesh 1 "Cut" primitive 0`.
    pub name: String,
    /// Vertex positions, world space.
    pub positions: Vec<Vec3>,
    /// Per-vertex shading normals, world space, or empty.
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates (TEXCOORD_0), or empty.
    pub uvs: Vec<Vec2>,
    /// Per-vertex tangents (glTF TANGENT: xyz unit, w = ±1 the bitangent sign), world
    /// space, or empty.
    pub tangents: Vec<Vec4>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub indices: Vec<[u32; 3]>,
    /// Index into `SceneDesc::materials`; `None` uses the default material.
    pub material: Option<usize>,
}

/// A reference from a material to a texture image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextureRef {
    /// Index into `SceneDesc::images`.
    pub image: usize,
    /// Which texture-coordinate set (only 0 is read; others fall back to 0 with a warning).
    pub texcoord: u32,
    /// KHR_texture_transform of this reference, applied to the texture coordinate before
    /// the lookup (identity without the extension).
    pub transform: glam::Affine2,
}

impl TextureRef {
    /// A reference to `image` through texture-coordinate set `texcoord`, untransformed.
    pub fn new(image: usize, texcoord: u32) -> Self {
        TextureRef {
            image,
            texcoord,
            transform: glam::Affine2::IDENTITY,
        }
    }
}

/// A decoded image, 8 bits per channel RGBA, **as stored in the file** (colour textures are
/// sRGB-encoded; the material decides how to decode each channel).
#[derive(Debug, Clone)]
pub struct ImageDesc {
    /// Name for messages (`image 2 "checker.png"`).
    pub name: String,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major RGBA8 texels, top row first, `width*height*4` bytes.
    pub rgba8: Arc<Vec<u8>>,
}

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
    /// The seed paper's Cauchy form n(λ) = b + c/λ², λ in micrometres (material extras
    /// `{"cauchy": {"b": 1.5, "c": 0.0042}}`, MTL `cauchy_b`/`cauchy_c`).
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
    /// 2002; see [`crate::medium`]).
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
    /// KHR_materials_iridescence and KHR_materials_anisotropy.
    pub film: FilmDesc,
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
            film: FilmDesc::default(),
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
        match &self.ior_model {
            Some(ExplicitIor::Glass(name)) => SpectralIor::named(name),
            Some(ExplicitIor::Cauchy { b, c }) => Ok(SpectralIor::Cauchy { b: *b, c: *c }),
            Some(ExplicitIor::Sellmeier { b, c }) => Ok(SpectralIor::Sellmeier { b: *b, c: *c }),
            // n_d = 1 makes the KHR formula's (n_d − 1) factor vanish: n ≡ 1, not dispersive.
            None if self.ior == 1.0 => Ok(SpectralIor::Constant(1.0)),
            None => Ok(SpectralIor::from_khr(self.ior, self.dispersion)),
        }
    }
}

/// A punctual light (KHR_lights_punctual) in world space.
#[derive(Debug, Clone, PartialEq)]
pub enum LightDesc {
    /// Point light: `intensity` in candela (lm/sr), linear RGB colour.
    Point {
        /// Name for messages.
        name: String,
        /// World position.
        position: Vec3,
        /// Linear RGB colour.
        color: Vec3,
        /// Luminous intensity in candela.
        intensity: f32,
        /// Optional range (world units).
        range: Option<f32>,
        /// Spectral shape (extras `iris_spectrum`), `color` filtering it.
        spectrum: Option<EmissionSpectrum>,
    },
    /// Spot light: candela, cone around `direction`.
    Spot {
        /// Name for messages.
        name: String,
        /// World position.
        position: Vec3,
        /// Unit direction the light points to (node −Z).
        direction: Vec3,
        /// Linear RGB colour.
        color: Vec3,
        /// Luminous intensity in candela.
        intensity: f32,
        /// Optional range (world units).
        range: Option<f32>,
        /// Inner cone angle, radians.
        inner_cone: f32,
        /// Outer cone angle, radians.
        outer_cone: f32,
        /// Spectral shape (extras `iris_spectrum`), `color` filtering it.
        spectrum: Option<EmissionSpectrum>,
    },
    /// Directional light: illuminance in lux.
    Directional {
        /// Name for messages.
        name: String,
        /// Unit direction the light travels in (node −Z).
        direction: Vec3,
        /// Linear RGB colour.
        color: Vec3,
        /// Illuminance in lux.
        intensity: f32,
        /// Spectral shape (extras `iris_spectrum`), `color` filtering it.
        spectrum: Option<EmissionSpectrum>,
    },
}

impl LightDesc {
    /// The light's name as stored by the loader.
    pub fn name(&self) -> &str {
        match self {
            LightDesc::Point { name, .. }
            | LightDesc::Spot { name, .. }
            | LightDesc::Directional { name, .. } => name,
        }
    }

    /// Intensity: candela (point, spot) or lux (directional).
    pub fn intensity(&self) -> f32 {
        match self {
            LightDesc::Point { intensity, .. }
            | LightDesc::Spot { intensity, .. }
            | LightDesc::Directional { intensity, .. } => *intensity,
        }
    }

    /// The filter colour (glTF `color`, linear RGB).
    pub fn color(&self) -> Vec3 {
        match self {
            LightDesc::Point { color, .. }
            | LightDesc::Spot { color, .. }
            | LightDesc::Directional { color, .. } => *color,
        }
    }

    /// The spectral shape named by `iris_spectrum`, if any.
    pub fn spectrum(&self) -> Option<EmissionSpectrum> {
        match self {
            LightDesc::Point { spectrum, .. }
            | LightDesc::Spot { spectrum, .. }
            | LightDesc::Directional { spectrum, .. } => *spectrum,
        }
    }

    /// The colour the RGB transport multiplies the intensity by:
    /// `color` × [`EmissionSpectrum::linear_srgb`] with a spectrum, else `color`.
    pub fn effective_color(&self) -> Vec3 {
        effective_color(self.color(), self.spectrum())
    }
}

/// Camera projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Perspective with vertical field of view (radians) and optional aspect ratio.
    Perspective {
        /// Vertical field of view, radians.
        yfov: f32,
        /// Aspect ratio width/height if the file fixes it.
        aspect: Option<f32>,
    },
    /// Orthographic with half-extents (world units).
    Orthographic {
        /// Horizontal half-width.
        xmag: f32,
        /// Vertical half-height.
        ymag: f32,
    },
}

/// A camera: looks down its local −Z with +Y up (glTF convention).
#[derive(Debug, Clone, PartialEq)]
pub struct CameraDesc {
    /// Name for `--camera NAME` and messages.
    pub name: String,
    /// Projection.
    pub projection: Projection,
    /// World-from-camera rigid transform (scale is removed by the loader).
    pub world_from_camera: Mat4,
}
