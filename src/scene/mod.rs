//! Scenes: the plain description loaders produce ([`desc`]), its validation
//! ([`validate`]), and the immutable render [`Scene`] that integrators read.
//!
//! A `Scene` holds every triangle of every mesh in one world-space array (so a triangle id
//! from a backend indexes it directly), per-vertex shading data, materials, lights,
//! cameras and the acceleration structure. It is built once and never mutated; rays reach
//! it only through [`crate::interaction`].

pub mod desc;
pub mod validate;

use crate::accel::{Accel, Backend};
use crate::error::Result;
use crate::light::{self, Light};
use crate::material::Material;
use desc::{CameraDesc, ImageDesc, MaterialDesc, SceneDesc};
use glam::{Vec2, Vec3};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Per-mesh bookkeeping.
#[derive(Debug, Clone)]
pub struct MeshInfo {
    /// Name from the description (used in messages).
    pub name: String,
    /// First triangle index in the scene arrays.
    pub first_triangle: u32,
    /// Number of triangles.
    pub triangle_count: u32,
    /// Whether the mesh has per-vertex shading normals.
    pub has_normals: bool,
}

/// The immutable render scene.
pub struct Scene {
    /// The file the scene came from.
    pub source: PathBuf,
    /// World-space vertex positions of all meshes.
    pub positions: Vec<Vec3>,
    /// Per-vertex unit shading normals (zero where the mesh has none).
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates (zero where the mesh has none).
    pub uvs: Vec<Vec2>,
    /// Triangles (global vertex indices), CCW seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Material index per triangle.
    pub triangle_material: Vec<u32>,
    /// Mesh index per triangle.
    pub triangle_mesh: Vec<u32>,
    /// Meshes.
    pub meshes: Vec<MeshInfo>,
    /// Materials; the last one is the default material.
    pub materials: Vec<Material>,
    /// Texture images.
    pub images: Vec<ImageDesc>,
    /// Lights (the default key/fill lights when the file has none).
    pub lights: Vec<Light>,
    /// Cameras from the file.
    pub cameras: Vec<CameraDesc>,
    /// World bounding box (min, max).
    pub bounds: (Vec3, Vec3),
    /// Loader and validation warnings.
    pub warnings: Vec<String>,
    /// Decisions taken for the user (e.g. "no light in the file: default key light").
    pub notes: Vec<String>,
    /// Whether any material can cut holes (alpha MASK).
    pub has_cutouts: bool,
    /// Time spent building the acceleration structure.
    pub accel_build_time: Duration,
    /// The acceleration structure (read only by `interaction`).
    pub(crate) accel: Accel,
}

impl Scene {
    /// Builds the render scene from a **validated** description.
    pub fn build(desc: SceneDesc, backend: Backend) -> Result<Scene> {
        let total_v: usize = desc.meshes.iter().map(|m| m.positions.len()).sum();
        let total_t: usize = desc.meshes.iter().map(|m| m.indices.len()).sum();
        let mut positions = Vec::with_capacity(total_v);
        let mut normals = Vec::with_capacity(total_v);
        let mut uvs = Vec::with_capacity(total_v);
        let mut triangles = Vec::with_capacity(total_t);
        let mut triangle_material = Vec::with_capacity(total_t);
        let mut triangle_mesh = Vec::with_capacity(total_t);
        let mut meshes = Vec::with_capacity(desc.meshes.len());
        let default_material = desc.materials.len() as u32;
        for (mi, m) in desc.meshes.iter().enumerate() {
            let base = positions.len() as u32;
            positions.extend_from_slice(&m.positions);
            let has_normals = m.normals.len() == m.positions.len() && !m.normals.is_empty();
            if has_normals {
                normals.extend(m.normals.iter().map(|n| n.normalize_or_zero()));
            } else {
                normals.extend(std::iter::repeat_n(Vec3::ZERO, m.positions.len()));
            }
            if m.uvs.len() == m.positions.len() {
                uvs.extend_from_slice(&m.uvs);
            } else {
                uvs.extend(std::iter::repeat_n(Vec2::ZERO, m.positions.len()));
            }
            meshes.push(MeshInfo {
                name: m.name.clone(),
                first_triangle: triangles.len() as u32,
                triangle_count: m.indices.len() as u32,
                has_normals,
            });
            let mat = m.material.map_or(default_material, |i| i as u32);
            for t in &m.indices {
                triangles.push(t.map(|i| i + base));
                triangle_material.push(mat);
                triangle_mesh.push(mi as u32);
            }
        }
        let mut materials: Vec<Material> = desc.materials.into_iter().map(Material::new).collect();
        materials.push(Material::new(MaterialDesc::default()));
        let bounds = positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let mut notes = Vec::new();
        let mut lights: Vec<Light> = desc.lights.iter().map(Light::from_desc).collect();
        if lights.is_empty() {
            lights = light::default_lights();
            notes.push("no light in the file: using the default key and fill lights".into());
        }
        let has_cutouts = materials.iter().any(Material::may_cut_out);
        let start = Instant::now();
        let accel = Accel::build(backend, &positions, &triangles)?;
        let accel_build_time = start.elapsed();
        Ok(Scene {
            source: desc.source,
            positions,
            normals,
            uvs,
            triangles,
            triangle_material,
            triangle_mesh,
            meshes,
            materials,
            images: desc.images,
            lights,
            cameras: desc.cameras,
            bounds,
            warnings: desc.warnings,
            notes,
            has_cutouts,
            accel_build_time,
            accel,
        })
    }

    /// Name of the acceleration backend in use.
    pub fn backend_name(&self) -> &'static str {
        self.accel.name()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
}
