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

pub use added::{AddedLights, SpotKey};

use crate::light::env::Environment;
use crate::material::{ImageDesc, MaterialDesc};
use crate::spectrum::EmissionSpectrum;
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};
use std::path::PathBuf;

/// A whole scene as read from a file.
#[derive(Debug, Clone, Default)]
pub struct SceneDesc {
    /// The file it came from (used in error messages).
    pub source: PathBuf,
    /// The scene's own name (glTF: the chosen scene's `name`); empty when the file gives none.
    pub name: String,
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
    /// The scene-wide medium filling the air ([`crate::volume::fog`]): the file's
    /// `extras.iris_fog`, replaced by `--fog` in preparation; `None`: clear air.
    pub fog: Option<crate::volume::Medium>,
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
    /// A computed sky (`"sky:elevation=…"`, as `--env sky:…`).
    Sky(crate::light::sky::SkyParams),
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
    /// Per-vertex second texture coordinates (TEXCOORD_1), or empty; read only where a
    /// material on the mesh samples set 1.
    pub uvs1: Vec<Vec2>,
    /// Per-vertex tangents (glTF TANGENT: xyz unit, w = ±1 the bitangent sign), world
    /// space, or empty.
    pub tangents: Vec<Vec4>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub indices: Vec<[u32; 3]>,
    /// Index into `SceneDesc::materials`; `None` uses the default material.
    pub material: Option<usize>,
    /// The linear part of the transform from the mesh's own frame (its glTF node's) to
    /// world space: where a crystal material's axes, given in that frame, point
    /// ([`crate::material::CrystalDesc`]). The identity for meshes given in world space.
    pub orientation: Mat3,
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
        crate::spectrum::effective_color(self.color(), self.spectrum())
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
