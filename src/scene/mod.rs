//! Scenes: the plain description loaders produce ([`desc`]), its validation
//! ([`validate`]), and the immutable render [`Scene`] that integrators read.
//!
//! A `Scene` holds every triangle of every mesh in one world-space array (so a triangle id
//! from a backend indexes it directly), sorted by the Morton code of the centroids so that
//! nearby hits read nearby memory (`triangle_mesh` says which mesh each came from), per-vertex shading data, materials, lights,
//! cameras and the acceleration structure. It is built once, from a description that
//! already holds everything Iris adds (environment light, studio or default lights, floor:
//! [`desc::AddedLights`], [`lighting`]), and never mutated; rays reach it only through
//! [`crate::interaction`].

pub mod contact;
pub mod desc;
pub mod lighting;
mod thin;
pub mod triangle;
pub mod validate;
pub mod winding;

pub use triangle::TriangleData;

use crate::accel::{Accel, Backend};
use crate::error::Result;
use crate::light::area::AreaLights;
use crate::light::env::Environment;
use crate::light::Light;
use crate::material::Material;
use crate::spectrum::EmitterShape;
use desc::{AddedLights, CameraDesc, ImageDesc, MaterialDesc, SceneDesc};
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
    /// Per-vertex glTF tangents (xyz, w = bitangent sign ±1; zero where the mesh has
    /// none), or empty when no mesh has any. Read only for anisotropic materials
    /// ([`crate::shading::film`]).
    pub tangents: Vec<glam::Vec4>,
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
    /// Lights: the file's, then those Iris added ([`desc::AddedLights`]: the default
    /// key/fill lights when nothing else lights the scene, or a studio's keys).
    pub lights: Vec<Light>,
    /// The exact spectral shape of each light that names one (`iris_spectrum`), for
    /// spectral transport; parallel to `lights`.
    pub light_shapes: Vec<Option<EmitterShape>>,
    /// Emissive triangles, sampled for direct light.
    pub area_lights: AreaLights,
    /// Light from infinitely far away (`--env`, the file's, or a studio's), if any.
    pub environment: Option<Environment>,
    /// Whether the default key/fill lights were added (nothing else lit the scene).
    pub default_lights: bool,
    /// Cameras from the file.
    pub cameras: Vec<CameraDesc>,
    /// World bounding box (min, max).
    pub bounds: (Vec3, Vec3),
    /// Bounds of the file's own geometry, which cameras frame and the studio lights: equal
    /// to `bounds` unless a floor was added ([`crate::studio::ground`]).
    pub subject_bounds: (Vec3, Vec3),
    /// Loader, validation and environment-map warnings.
    pub warnings: Vec<String>,
    /// Triangles on which another object's face lies ([`TriangleData::TOUCHES`]: touching
    /// volumes are crossed as one interface there).
    pub touching_triangles: usize,
    /// Whether any material can cut holes (alpha MASK).
    pub has_cutouts: bool,
    /// Time spent building the acceleration structure.
    pub accel_build_time: Duration,
    /// The acceleration structure (read only by `interaction`).
    pub(crate) accel: Accel,
}

impl Scene {
    /// Builds the render scene from a **validated** description, lit as it says; a
    /// description that nothing lights gets the default key and fill lights
    /// ([`lighting::light_if_unlit`]).
    pub fn build(mut desc: SceneDesc, backend: Backend) -> Result<Scene> {
        lighting::light_if_unlit(&mut desc);
        let lights = lighting::render_lights(&desc);
        Scene::build_lit(desc, backend, lights)
    }

    /// Builds the render scene from a **validated** description with exactly these
    /// punctual lights in render terms (and no spectral shapes), instead of the ones the
    /// description implies, and no default lights: for tests and tools that place lights
    /// by their render values (candela, lux, unit directions), which
    /// [`crate::scene::desc::LightDesc`]'s unit conversions would round.
    pub fn build_with_lights(
        desc: SceneDesc,
        backend: Backend,
        lights: Vec<Light>,
    ) -> Result<Scene> {
        let shapes = vec![None; lights.len()];
        Scene::build_lit(desc, backend, (lights, shapes))
    }

    /// [`Scene::build`] with the punctual lights already decided.
    fn build_lit(
        mut desc: SceneDesc,
        backend: Backend,
        (lights, light_shapes): (Vec<Light>, Vec<Option<EmitterShape>>),
    ) -> Result<Scene> {
        let g = Geometry::gather(&desc);
        let mut materials: Vec<Material> = std::mem::take(&mut desc.materials)
            .into_iter()
            .map(Material::new)
            .collect();
        materials.push(Material::new(MaterialDesc::default()));
        let bounds = g.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let area_lights = AreaLights::build(&g.triangle_data, |m| {
            let mat = &materials[m as usize];
            (mat.emission(), mat.desc.double_sided)
        });
        let mut warnings = desc.warnings;
        if let Some(Environment::Map(m)) = &desc.environment_light {
            warnings.extend(m.warnings().iter().cloned());
        }
        let has_cutouts = materials.iter().any(Material::may_cut_out);
        let start = Instant::now();
        let accel = Accel::build(backend, &g.positions, &g.triangles)?;
        let accel_build_time = start.elapsed();
        let mut scene = Scene {
            source: desc.source,
            positions: g.positions,
            normals: g.normals,
            uvs: g.uvs,
            tangents: g.tangents,
            triangles: g.triangles,
            triangle_material: g.triangle_material,
            triangle_data: g.triangle_data,
            triangle_mesh: g.triangle_mesh,
            meshes: g.meshes,
            materials,
            images: desc.images,
            skipped_textures: desc.skipped_textures,
            lights,
            light_shapes,
            area_lights,
            environment: desc.environment_light,
            default_lights: desc.added_lights == AddedLights::KeyFill,
            cameras: desc.cameras,
            bounds,
            subject_bounds: desc.subject_bounds.unwrap_or(bounds),
            warnings,
            touching_triangles: 0,
            has_cutouts,
            accel_build_time,
            accel,
        };
        // The last step of the build: it probes the finished acceleration structure.
        let touching_triangles = contact::mark_touching(&mut scene);
        Ok(Scene {
            touching_triangles,
            ..scene
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

/// The meshes of a description gathered into the scene's arrays, triangles in Morton
/// order ([`morton_order`]).
struct Geometry {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    tangents: Vec<glam::Vec4>,
    triangles: Vec<[u32; 3]>,
    triangle_material: Vec<u32>,
    triangle_data: Vec<TriangleData>,
    triangle_mesh: Vec<u32>,
    meshes: Vec<MeshInfo>,
}

impl Geometry {
    /// Concatenates the meshes of `desc` (a mesh without a material gets the default one,
    /// index `desc.materials.len()`), then sorts the triangles spatially.
    fn gather(desc: &SceneDesc) -> Geometry {
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
        let any_tangents = desc
            .meshes
            .iter()
            .any(|m| !m.tangents.is_empty() && m.tangents.len() == m.positions.len());
        let mut tangents = Vec::with_capacity(if any_tangents { total_v } else { 0 });
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
            if any_tangents {
                if m.tangents.len() == m.positions.len() {
                    tangents.extend_from_slice(&m.tangents);
                } else {
                    tangents.extend(std::iter::repeat_n(glam::Vec4::ZERO, m.positions.len()));
                }
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
        Geometry {
            positions,
            normals,
            uvs,
            tangents,
            triangles: order.iter().map(|&i| triangles[i]).collect(),
            triangle_material: order.iter().map(|&i| triangle_material[i]).collect(),
            triangle_data: order.iter().map(|&i| triangle_data[i]).collect(),
            triangle_mesh: order.iter().map(|&i| triangle_mesh[i]).collect(),
            meshes,
        }
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
