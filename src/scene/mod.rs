//! Scenes: the plain description loaders produce ([`desc`]), its validation
//! ([`validate`]), and the immutable render [`Scene`] that integrators read.
//!
//! A `Scene` holds every triangle of every mesh in one world-space array (so a triangle id
//! from a backend indexes it directly), sorted by the Morton code of the centroids so that
//! nearby hits read nearby memory (`triangle_mesh` says which mesh each came from), per-vertex shading data, materials, lights,
//! cameras and the acceleration structure. It is built once and never mutated; rays reach
//! it only through [`crate::interaction`].

pub mod contact;
pub mod desc;
mod thin;
pub mod triangle;
pub mod validate;
pub mod winding;

pub use triangle::TriangleData;

use crate::accel::{Accel, Backend};
use crate::error::Result;
use crate::light::area::AreaLights;
use crate::light::env::Environment;
use crate::light::{self, Light};
use crate::material::Material;
use crate::spectrum::EmitterShape;
use desc::{CameraDesc, ImageDesc, MaterialDesc, SceneDesc};
use glam::{Vec2, Vec3};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Per-mesh bookkeeping.
#[derive(Debug, Clone)]
pub struct MeshInfo {
    /// Name from the description (used in messages).
    pub name: String,
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
    /// Positions and material per triangle, for building hits.
    pub triangle_data: Vec<TriangleData>,
    /// Mesh index per triangle.
    pub triangle_mesh: Vec<u32>,
    /// Meshes.
    pub meshes: Vec<MeshInfo>,
    /// Materials; the last one is the default material.
    pub materials: Vec<Material>,
    /// Texture images.
    pub images: Vec<ImageDesc>,
    /// Texture slots the loader did not decode: their material is on no mesh.
    pub skipped_textures: usize,
    /// Lights (the default key/fill lights when the file has no light and no emitter).
    pub lights: Vec<Light>,
    /// The exact spectral shape of each light that names one (`iris_spectrum`), for
    /// spectral transport; parallel to `lights`.
    pub light_shapes: Vec<Option<EmitterShape>>,
    /// Emissive triangles, sampled for direct light.
    pub area_lights: AreaLights,
    /// Light from infinitely far away (`--env`), if any.
    pub environment: Option<Environment>,
    /// Whether `lights` are the default key/fill lights (the file had none).
    pub default_lights: bool,
    /// Cameras from the file.
    pub cameras: Vec<CameraDesc>,
    /// World bounding box (min, max).
    pub bounds: (Vec3, Vec3),
    /// Bounds of the file's own geometry, which cameras frame and the studio lights: equal
    /// to `bounds` unless a floor was added ([`crate::studio::ground`]).
    pub subject_bounds: (Vec3, Vec3),
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
        let mut triangle_data = Vec::with_capacity(total_t);
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
                triangle_count: m.indices.len() as u32,
                has_normals,
            });
            let mat = m.material.map_or(default_material, |i| i as u32);
            let mut flags = 0;
            if has_normals {
                flags |= TriangleData::HAS_NORMALS;
            }
            if m.uvs.len() == m.positions.len() && !m.uvs.is_empty() {
                flags |= TriangleData::HAS_UVS;
            }
            for t in &m.indices {
                triangles.push(t.map(|i| i + base));
                triangle_data.push(TriangleData {
                    p: t.map(|i| m.positions[i as usize]),
                    info: (mat & TriangleData::MATERIAL_MASK) | flags,
                });
                triangle_material.push(mat);
                triangle_mesh.push(mi as u32);
            }
        }
        // Spatial order: hits of neighbouring rays then touch neighbouring memory.
        let order = morton_order(&triangle_data);
        let triangles: Vec<[u32; 3]> = order.iter().map(|&i| triangles[i]).collect();
        let triangle_material: Vec<u32> = order.iter().map(|&i| triangle_material[i]).collect();
        let triangle_mesh: Vec<u32> = order.iter().map(|&i| triangle_mesh[i]).collect();
        let triangle_data: Vec<TriangleData> = order.iter().map(|&i| triangle_data[i]).collect();
        let mut materials: Vec<Material> = desc.materials.into_iter().map(Material::new).collect();
        materials.push(Material::new(MaterialDesc::default()));
        let bounds = positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let mut notes = Vec::new();
        let area_lights = AreaLights::build(&triangle_data, |m| {
            let mat = &materials[m as usize];
            (mat.emission(), mat.desc.double_sided)
        });
        let mut lights: Vec<Light> = desc.lights.iter().map(Light::from_desc).collect();
        let mut light_shapes: Vec<Option<EmitterShape>> = desc
            .lights
            .iter()
            .map(|l| {
                l.spectrum()
                    .map(|s| s.emitter_shape(l.color() * l.intensity()))
            })
            .collect();
        let default_lights = lights.is_empty() && area_lights.is_empty();
        if default_lights {
            lights = light::default_lights();
            light_shapes = vec![None; lights.len()];
            notes.push("no light in the file: using the default key and fill lights".into());
        }
        let has_cutouts = materials.iter().any(Material::may_cut_out);
        let start = Instant::now();
        let accel = Accel::build(backend, &positions, &triangles)?;
        let accel_build_time = start.elapsed();
        let mut scene = Scene {
            source: desc.source,
            positions,
            normals,
            uvs,
            triangles,
            triangle_material,
            triangle_data,
            triangle_mesh,
            meshes,
            materials,
            images: desc.images,
            skipped_textures: desc.skipped_textures,
            lights,
            light_shapes,
            area_lights,
            environment: None,
            default_lights,
            cameras: desc.cameras,
            bounds,
            subject_bounds: bounds,
            warnings: desc.warnings,
            notes,
            has_cutouts,
            accel_build_time,
            accel,
        };
        contact::mark_touching(&mut scene);
        Ok(scene)
    }

    /// Adds an environment light. It replaces the default key/fill lights (which are only
    /// there because the file has no light of its own).
    pub fn with_environment(mut self, env: Option<Environment>) -> Scene {
        if env.is_some() && self.default_lights {
            self.lights.clear();
            self.default_lights = false;
            self.notes.retain(|n| !n.contains("default key"));
        }
        if let Some(Environment::Map(m)) = &env {
            self.warnings.extend(m.warnings().iter().cloned());
        }
        self.environment = env;
        self
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

/// Spreads the low 10 bits of `v` to every third bit (for a 30-bit 3D Morton code).
fn spread_bits(v: u32) -> u32 {
    let mut x = v & 0x3ff;
    x = (x | (x << 16)) & 0x0300_00ff;
    x = (x | (x << 8)) & 0x0300_f00f;
    x = (x | (x << 4)) & 0x030c_30c3;
    x = (x | (x << 2)) & 0x0924_9249;
    x
}

/// Triangle indices sorted by the Morton code of their centroids (ties by index, so the
/// order is deterministic). Both backends are built over this order.
fn morton_order(tris: &[TriangleData]) -> Vec<usize> {
    let (lo, hi) = tris.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), t| {
            let c = (t.p[0] + t.p[1] + t.p[2]) / 3.0;
            (lo.min(c), hi.max(c))
        },
    );
    let ext = (hi - lo).max(Vec3::splat(f32::MIN_POSITIVE));
    let mut keyed: Vec<(u32, usize)> = tris
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let c = ((t.p[0] + t.p[1] + t.p[2]) / 3.0 - lo) / ext * 1023.0;
            let q = c.clamp(Vec3::ZERO, Vec3::splat(1023.0)).as_uvec3();
            let code = spread_bits(q.x) | (spread_bits(q.y) << 1) | (spread_bits(q.z) << 2);
            (code, i)
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}
