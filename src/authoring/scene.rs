//! The generator's in-memory scene model: what [`super::glb`] writes as a GLB file.
//!
//! Same conventions as the rest of Iris: world space is metres, right-handed, +Y up;
//! meshes wind counter-clockwise seen from outside; colours are **linear** RGB; point and
//! spot intensities are in candela, directional ones in lux (KHR_lights_punctual).
//! A mesh is placed by an optional node translation (no rotation or scale), so its
//! world-space geometry is its local geometry shifted.
//!
//! [`GenScene::validate`] rejects anything that would give an invalid or lossy file
//! (non-finite numbers, out-of-range indices, degenerate cameras) with [`Error::Usage`].

use super::layers::GenLayers;
use super::shapes::TriMesh;
use crate::error::{Error, Result};
use crate::material::{AnisotropyDesc, IridescenceDesc};
use glam::{Vec2, Vec3, Vec4};

/// A whole generated scene.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GenScene {
    /// Scene name (glTF `scenes[0].name`).
    pub name: String,
    /// Meshes, one glTF node each.
    pub meshes: Vec<GenMesh>,
    /// Materials referenced by `GenMesh::material`.
    pub materials: Vec<GenMaterial>,
    /// Punctual lights.
    pub lights: Vec<GenLight>,
    /// The camera, if any.
    pub camera: Option<GenCamera>,
    /// Scene `extras` (glTF `scenes[0].extras`), e.g. `{"iris_environment": "sky.hdr"}`.
    pub extras: Option<serde_json::Value>,
    /// `extras` of `lights[i]` (e.g. `{"iris_spectrum": "sun"}`); missing entries = none.
    /// Must not be longer than `lights`.
    pub light_extras: Vec<Option<serde_json::Value>>,
    /// TEXCOORD_0 of `meshes[i]` (one per position; glTF's v-down convention); missing
    /// entries = none. Must not be longer than `meshes`.
    pub mesh_uvs: Vec<Option<Vec<Vec2>>>,
}

/// A mesh instance: geometry, material and placement.
#[derive(Debug, Clone, PartialEq)]
pub struct GenMesh {
    /// Name of the mesh and its node.
    pub name: String,
    /// Geometry in the node's frame.
    pub geometry: TriMesh,
    /// Index into `GenScene::materials`.
    pub material: usize,
    /// Node translation (metres), if any.
    pub translation: Option<Vec3>,
}

/// KHR_materials_volume parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenVolume {
    /// `thicknessFactor` (metres, > 0 for a solid volume).
    pub thickness: f32,
    /// `attenuationColor`, linear RGB.
    pub attenuation_color: Vec3,
    /// `attenuationDistance` (metres); `None` = no absorption (+∞).
    pub attenuation_distance: Option<f32>,
    /// Scattering in the volume, written as the draft KHR_materials_volume_scatter
    /// (`multiscatterColor`, `scatterAnisotropy`); `None` = it only absorbs.
    pub scatter: Option<GenScatter>,
}

/// KHR_materials_volume_scatter (draft, glTF PR #2453) values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenScatter {
    /// `multiscatterColor`: the multiple-scattering albedo, linear RGB in [0, 1].
    pub multiscatter: Vec3,
    /// `scatterAnisotropy`: Henyey–Greenstein g in (−1, 1).
    pub anisotropy: f32,
}

/// A glTF metallic-roughness material with the optional KHR extensions Iris reads.
#[derive(Debug, Clone, PartialEq)]
pub struct GenMaterial {
    /// Material name.
    pub name: String,
    /// Linear RGBA `baseColorFactor`.
    pub base_color: Vec4,
    /// `metallicFactor` in [0, 1].
    pub metallic: f32,
    /// `roughnessFactor` in [0, 1].
    pub roughness: f32,
    /// KHR_materials_ior `ior` (≥ 0; values in (0, 1) are allowed on purpose, e.g. a bubble).
    pub ior: Option<f32>,
    /// KHR_materials_transmission `transmissionFactor` in [0, 1].
    pub transmission: Option<f32>,
    /// KHR_materials_volume.
    pub volume: Option<GenVolume>,
    /// KHR_materials_dispersion `dispersion` (20 / Abbe number, ≥ 0).
    pub dispersion: Option<f32>,
    /// Material `extras` (any JSON, e.g. `{"cauchy": {"b": 1.5, "c": 0.0042}}`).
    pub extras: Option<serde_json::Value>,
    /// Emitted radiance, linear RGB (may exceed 1): written as `emissiveFactor` = colour /
    /// max component and `KHR_materials_emissive_strength` = max component.
    pub emissive: Option<Vec3>,
    /// KHR_materials_iridescence (factors only: the writer writes no textures).
    pub iridescence: Option<IridescenceDesc>,
    /// KHR_materials_anisotropy (factors only: the writer writes no textures).
    pub anisotropy: Option<AnisotropyDesc>,
    /// KHR_materials_clearcoat, _sheen and _diffuse_transmission (none by default).
    pub layers: GenLayers,
    /// glTF `doubleSided` (written only when true), e.g. a thin sheet seen from both sides.
    pub double_sided: bool,
}

impl GenMaterial {
    /// An opaque dielectric diffuse-looking material (metallic 0, roughness 1).
    pub fn diffuse(name: &str, color: Vec3) -> Self {
        GenMaterial {
            name: name.into(),
            base_color: color.extend(1.0),
            metallic: 0.0,
            roughness: 1.0,
            ior: None,
            transmission: None,
            volume: None,
            dispersion: None,
            extras: None,
            emissive: None,
            iridescence: None,
            anisotropy: None,
            layers: GenLayers::default(),
            double_sided: false,
        }
    }

    /// A black diffuse surface emitting `radiance` (linear RGB) from its front face: an
    /// area light.
    pub fn emitter(name: &str, radiance: Vec3) -> Self {
        GenMaterial {
            emissive: Some(radiance),
            ..GenMaterial::diffuse(name, Vec3::ZERO)
        }
    }

    /// Clear, smooth, fully transmissive glass bounding a solid volume of typical
    /// `thickness` (metres), with index of refraction `ior` and no absorption.
    pub fn clear_glass(name: &str, ior: f32, thickness: f32) -> Self {
        GenMaterial {
            name: name.into(),
            base_color: Vec4::ONE,
            metallic: 0.0,
            roughness: 0.0,
            ior: Some(ior),
            transmission: Some(1.0),
            volume: Some(GenVolume {
                thickness,
                attenuation_color: Vec3::ONE,
                attenuation_distance: None,
                scatter: None,
            }),
            dispersion: None,
            extras: None,
            emissive: None,
            iridescence: None,
            anisotropy: None,
            layers: GenLayers::default(),
            double_sided: false,
        }
    }
}

/// A punctual light (KHR_lights_punctual). Directions are where the light travels.
#[derive(Debug, Clone, PartialEq)]
pub enum GenLight {
    /// Point light, intensity in candela.
    Point {
        /// Name.
        name: String,
        /// Position, metres.
        position: Vec3,
        /// Linear RGB colour.
        color: Vec3,
        /// Candela.
        intensity: f32,
    },
    /// Spot light, intensity in candela.
    Spot {
        /// Name.
        name: String,
        /// Position, metres.
        position: Vec3,
        /// Direction the cone points to (need not be unit).
        direction: Vec3,
        /// Linear RGB colour.
        color: Vec3,
        /// Candela.
        intensity: f32,
        /// Inner cone half-angle, radians.
        inner_cone: f32,
        /// Outer cone half-angle, radians, in (inner, π/2].
        outer_cone: f32,
    },
    /// Directional light, illuminance in lux.
    Directional {
        /// Name.
        name: String,
        /// Direction the light travels (need not be unit).
        direction: Vec3,
        /// Linear RGB colour.
        color: Vec3,
        /// Lux.
        intensity: f32,
    },
}

/// A perspective camera given by a look-at frame.
#[derive(Debug, Clone, PartialEq)]
pub struct GenCamera {
    /// Name.
    pub name: String,
    /// Eye position, metres.
    pub eye: Vec3,
    /// The point looked at.
    pub target: Vec3,
    /// Approximate up direction (not parallel to `target − eye`).
    pub up: Vec3,
    /// Vertical field of view, radians, in (0, π).
    pub yfov: f32,
    /// Width / height, if fixed.
    pub aspect: Option<f32>,
}

fn bad(element: &str, what: impl std::fmt::Display) -> Error {
    Error::Usage(format!("scene generator: {element}: {what}"))
}

fn finite3(v: Vec3) -> bool {
    v.is_finite()
}

fn in_unit(x: f32) -> bool {
    (0.0..=1.0).contains(&x)
}

impl GenScene {
    /// Checks every value the GLB writer relies on; the error names the element. Elements
    /// are checked in file order: meshes, materials, lights, light extras, camera.
    pub fn validate(&self) -> Result<()> {
        for (i, m) in self.meshes.iter().enumerate() {
            check_mesh(i, m, self.materials.len())?;
        }
        for (i, m) in self.materials.iter().enumerate() {
            check_material(i, m)?;
        }
        for (i, l) in self.lights.iter().enumerate() {
            check_light(i, l)?;
        }
        if self.light_extras.len() > self.lights.len() {
            return Err(bad("light extras", "more entries than lights"));
        }
        if self.mesh_uvs.len() > self.meshes.len() {
            return Err(bad("mesh uvs", "more entries than meshes"));
        }
        for (i, uvs) in self.mesh_uvs.iter().enumerate() {
            let Some(uvs) = uvs else { continue };
            let el = format!("mesh {i} uvs");
            if uvs.len() != self.meshes[i].geometry.positions.len() {
                return Err(bad(&el, "not one per position"));
            }
            if !uvs.iter().all(|uv| uv.is_finite()) {
                return Err(bad(&el, "non-finite texture coordinate"));
            }
        }
        if let Some(c) = &self.camera {
            check_camera(c)?;
        }
        Ok(())
    }
}

/// Mesh `i`: triangles present and within u32 counts, normals matching positions, finite
/// values, indices in range, material `< materials`, finite translation.
fn check_mesh(i: usize, m: &GenMesh, materials: usize) -> Result<()> {
    let el = format!("mesh {i} \"{}\"", m.name);
    let g = &m.geometry;
    if g.positions.is_empty() || g.indices.is_empty() {
        return Err(bad(&el, "no triangles"));
    }
    if u32::try_from(g.positions.len()).is_err() || g.indices.len() > (u32::MAX / 3) as usize {
        return Err(bad(&el, "too many vertices or triangles"));
    }
    if !g.normals.is_empty() && g.normals.len() != g.positions.len() {
        return Err(bad(&el, "normals and positions differ in length"));
    }
    if !g.positions.iter().chain(&g.normals).all(|&p| finite3(p)) {
        return Err(bad(&el, "non-finite position or normal"));
    }
    let n = g.positions.len() as u64;
    if g.indices.iter().flatten().any(|&k| u64::from(k) >= n) {
        return Err(bad(&el, "vertex index out of range"));
    }
    if m.material >= materials {
        return Err(bad(&el, format!("material {} out of range", m.material)));
    }
    if m.translation.is_some_and(|t| !finite3(t)) {
        return Err(bad(&el, "non-finite translation"));
    }
    Ok(())
}

/// Material `i`: factors in their glTF ranges, finite non-negative ior, dispersion and
/// emission, valid volume and layer parameters.
fn check_material(i: usize, m: &GenMaterial) -> Result<()> {
    let el = format!("material {i} \"{}\"", m.name);
    let c = m.base_color;
    if !(c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0) {
        return Err(bad(&el, "base colour outside [0, 1]"));
    }
    if !in_unit(m.metallic) || !in_unit(m.roughness) || !m.transmission.is_none_or(in_unit) {
        return Err(bad(
            &el,
            "metallic, roughness or transmission outside [0, 1]",
        ));
    }
    if !m.ior.is_none_or(|n| n.is_finite() && n >= 0.0) {
        return Err(bad(&el, "ior must be finite and ≥ 0"));
    }
    if !m.dispersion.is_none_or(|d| d.is_finite() && d >= 0.0) {
        return Err(bad(&el, "dispersion must be finite and ≥ 0"));
    }
    if let Some(i) = &m.iridescence {
        i.check().map_err(|e| bad(&el, e))?;
        if i.textures().iter().any(|(_, t)| t.is_some()) {
            return Err(bad(&el, "the writer writes no textures"));
        }
    }
    if let Some(a) = &m.anisotropy {
        a.check().map_err(|e| bad(&el, e))?;
        if a.texture.is_some() {
            return Err(bad(&el, "the writer writes no textures"));
        }
    }
    if !m
        .emissive
        .is_none_or(|e| e.is_finite() && e.min_element() >= 0.0)
    {
        return Err(bad(&el, "emissive radiance must be finite and ≥ 0"));
    }
    if let Some(v) = m.volume {
        let ok = v.thickness.is_finite()
            && v.thickness >= 0.0
            && v.attenuation_color.is_finite()
            && v.attenuation_color.min_element() >= 0.0
            && v.attenuation_color.max_element() <= 1.0
            && v.attenuation_distance
                .is_none_or(|d| d.is_finite() && d > 0.0);
        if !ok {
            return Err(bad(&el, "invalid volume parameters"));
        }
    }
    if let Err(property) = m.layers.check() {
        return Err(bad(&el, format!("{property} outside [0, 1]")));
    }
    Ok(())
}

/// Light `i`: finite non-negative colour and intensity, finite position, finite non-zero
/// direction, and for a spot `0 ≤ inner < outer ≤ π/2`.
fn check_light(i: usize, l: &GenLight) -> Result<()> {
    let (name, color, intensity, pos, dir) = match l {
        GenLight::Point {
            name,
            position,
            color,
            intensity,
        } => (name, color, intensity, Some(position), None),
        GenLight::Spot {
            name,
            position,
            direction,
            color,
            intensity,
            inner_cone,
            outer_cone,
        } => {
            let ok = inner_cone.is_finite()
                && outer_cone.is_finite()
                && *inner_cone >= 0.0
                && inner_cone < outer_cone
                && *outer_cone <= std::f32::consts::FRAC_PI_2;
            if !ok {
                return Err(bad(
                    &format!("light {i} \"{name}\""),
                    "need 0 ≤ inner < outer ≤ π/2",
                ));
            }
            (name, color, intensity, Some(position), Some(direction))
        }
        GenLight::Directional {
            name,
            direction,
            color,
            intensity,
        } => (name, color, intensity, None, Some(direction)),
    };
    let el = format!("light {i} \"{name}\"");
    if !(color.is_finite() && color.min_element() >= 0.0) {
        return Err(bad(&el, "colour must be finite and ≥ 0"));
    }
    if !(intensity.is_finite() && *intensity >= 0.0) {
        return Err(bad(&el, "intensity must be finite and ≥ 0"));
    }
    if pos.is_some_and(|p| !finite3(*p)) {
        return Err(bad(&el, "non-finite position"));
    }
    if dir.is_some_and(|d| !(finite3(*d) && d.length_squared() > 0.0)) {
        return Err(bad(&el, "direction must be finite and non-zero"));
    }
    Ok(())
}

/// The camera: finite look-at frame, `yfov` in (0, π), finite positive aspect.
fn check_camera(c: &GenCamera) -> Result<()> {
    let el = format!("camera \"{}\"", c.name);
    if !(finite3(c.eye) && finite3(c.target) && finite3(c.up)) {
        return Err(bad(&el, "non-finite eye, target or up"));
    }
    if !(c.yfov.is_finite() && c.yfov > 0.0 && c.yfov < std::f32::consts::PI) {
        return Err(bad(&el, "yfov must be in (0, π)"));
    }
    if !c.aspect.is_none_or(|a| a.is_finite() && a > 0.0) {
        return Err(bad(&el, "aspect must be finite and > 0"));
    }
    Ok(())
}
