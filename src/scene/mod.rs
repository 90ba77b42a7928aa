//! Scenes: the plain description loaders produce ([`desc`]), its validation
//! ([`validate`]), and the immutable render [`Scene`] that integrators read.
//!
//! A `Scene` holds every triangle of every mesh as one record in one world-space array
//! ([`Triangle`]: corners, material, vertex indices, mesh; so a triangle id from a backend
//! indexes it directly), sorted by the Morton code of the centroids so that nearby hits read
//! nearby memory ([`geometry`]); the per-vertex shading data; materials; lights (the punctual
//! ones with their spectral shapes, the emissive triangles, the environment and the one
//! light choice, [`LightSampler`]); cameras and the acceleration structure. It is built once,
//! from a description that already holds everything Iris adds (environment light, studio or
//! default lights, floor: [`desc::AddedLights`], [`lighting`]), and never mutated: its fields
//! are private and read through methods. Rays reach it only through [`crate::interaction`].

pub mod contact;
mod content;
mod crystal_axes;
pub mod desc;
pub mod geometry;
pub mod lighting;
mod thin;
pub mod triangle;
pub mod validate;
pub mod weld;
pub mod winding;

pub use geometry::Vertices;
pub use triangle::Triangle;

use crate::accel::{Accel, Backend, HitList};
use crate::error::Result;
use crate::light::area::AreaLights;
use crate::light::env::Environment;
use crate::light::{Light, LightId, LightSampler, PunctualLight};
use crate::material::{ImageDesc, Material, MaterialDesc, TexCoords, TextureContext};
use crate::math::Ray;
use crate::volume::fog::Fog;
use desc::{AddedLights, CameraDesc, SceneDesc};
use geometry::Geometry;
use glam::Vec3;
use std::path::{Path, PathBuf};
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

/// The immutable render scene (see the module docs).
pub struct Scene {
    source: PathBuf,
    vertices: Vertices,
    triangles: Vec<Triangle>,
    meshes: Vec<MeshInfo>,
    /// The last one is the default material.
    materials: Vec<Material>,
    images: Vec<ImageDesc>,
    skipped_textures: usize,
    lights: Vec<PunctualLight>,
    area_lights: AreaLights,
    environment: Option<Environment>,
    fog: Option<Fog>,
    /// Some material holds a scattering medium, or there is fog.
    has_media: bool,
    light_sampler: LightSampler,
    default_lights: bool,
    cameras: Vec<CameraDesc>,
    bounds: (Vec3, Vec3),
    subject_bounds: (Vec3, Vec3),
    warnings: Vec<String>,
    touching_triangles: usize,
    has_cutouts: bool,
    accel_build_time: Duration,
    accel: Accel,
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
        let lights = lights
            .into_iter()
            .map(|light| PunctualLight { light, shape: None })
            .collect();
        Scene::build_lit(desc, backend, lights)
    }

    /// [`Scene::build`] with the punctual lights already decided.
    fn build_lit(
        mut desc: SceneDesc,
        backend: Backend,
        lights: Vec<PunctualLight>,
    ) -> Result<Scene> {
        crystal_axes::orient(&mut desc);
        let g = Geometry::gather(&desc);
        let mut materials: Vec<Material> = std::mem::take(&mut desc.materials)
            .into_iter()
            .map(Material::new)
            .collect();
        materials.push(Material::new(MaterialDesc::default()));
        let bounds = g.bounds();
        let area_lights = AreaLights::build(
            g.triangles
                .iter()
                .enumerate()
                .map(|(i, t)| (i as u32, t.p, t.material())),
            |m| {
                let mat = &materials[m as usize];
                (mat.emission(), mat.desc.double_sided)
            },
        );
        let mut warnings = desc.warnings;
        if let Some(Environment::Map(m)) = &desc.environment_light {
            warnings.extend(m.warnings().iter().cloned());
        }
        warnings.extend(geometry::scale_warning(&desc.source, bounds));
        let has_cutouts = materials.iter().any(Material::may_cut_out);
        let fog = desc.fog.map(|medium| Fog { medium, bounds });
        let has_media = fog.is_some() || materials.iter().any(|m| m.medium().is_some());
        let light_sampler = nee_sampler(lights.len(), &area_lights, &desc.environment_light);
        let start = Instant::now();
        let indices: Vec<[u32; 3]> = g.triangles.iter().map(|t| t.vertices).collect();
        let accel = Accel::build(backend, &g.vertices.positions, &indices)?;
        let accel_build_time = start.elapsed();
        let mut scene = Scene {
            source: desc.source,
            vertices: g.vertices,
            triangles: g.triangles,
            meshes: g.meshes,
            materials,
            images: desc.images,
            skipped_textures: desc.skipped_textures,
            lights,
            area_lights,
            environment: desc.environment_light,
            fog,
            has_media,
            light_sampler,
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
        scene.touching_triangles = contact::mark_touching(&mut scene);
        Ok(scene)
    }

    /// The scene-wide medium and the box it fills ([`crate::volume::fog`]).
    pub fn fog(&self) -> Option<&Fog> {
        self.fog.as_ref()
    }

    /// Whether light scatters in a medium somewhere: a material holds a scattering medium
    /// or the air is fogged. Only the path tracer renders such scenes.
    pub fn has_media(&self) -> bool {
        self.has_media
    }

    /// The file the scene came from.
    pub fn source(&self) -> &Path {
        &self.source
    }

    /// The per-vertex attributes, indexed by [`Triangle::vertices`].
    pub fn vertices(&self) -> &Vertices {
        &self.vertices
    }

    /// World-space vertex positions of all meshes.
    pub fn positions(&self) -> &[Vec3] {
        &self.vertices.positions
    }

    /// Every triangle, in the order backends number them.
    pub fn triangles(&self) -> &[Triangle] {
        &self.triangles
    }

    /// Triangle `prim` (an id a backend returned).
    #[inline]
    pub fn triangle(&self, prim: u32) -> &Triangle {
        &self.triangles[prim as usize]
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The meshes.
    pub fn meshes(&self) -> &[MeshInfo] {
        &self.meshes
    }

    /// The materials; the last one is the default material.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// Material `id` (a [`Triangle::material`]).
    #[inline]
    pub fn material(&self, id: u32) -> &Material {
        &self.materials[id as usize]
    }

    /// The decoded texture images.
    pub fn images(&self) -> &[ImageDesc] {
        &self.images
    }

    /// Texture slots the loader did not decode: their material is on no mesh.
    pub fn skipped_textures(&self) -> usize {
        self.skipped_textures
    }

    /// The punctual lights: the file's, then those Iris added ([`desc::AddedLights`]: the
    /// default key/fill lights when nothing else lights the scene, or a studio's keys).
    pub fn lights(&self) -> &[PunctualLight] {
        &self.lights
    }

    /// The emissive triangles, sampled for direct light.
    pub fn area_lights(&self) -> &AreaLights {
        &self.area_lights
    }

    /// Light from infinitely far away (`--env`, the file's, or a studio's), if any.
    pub fn environment(&self) -> Option<&Environment> {
        self.environment.as_ref()
    }

    /// The choice of one light for next-event estimation and its MIS weights: the punctual
    /// lights, the emissive triangles as one group and the environment
    /// ([`crate::light::sampler`]).
    pub fn light_sampler(&self) -> &LightSampler {
        &self.light_sampler
    }

    /// Whether the default key/fill lights were added (nothing else lit the scene).
    pub fn default_lights(&self) -> bool {
        self.default_lights
    }

    /// Cameras from the file.
    pub fn cameras(&self) -> &[CameraDesc] {
        &self.cameras
    }

    /// World bounding box (min, max).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.bounds
    }

    /// The scene's scale in scene units ([`geometry::scale`]).
    pub fn scale(&self) -> f32 {
        geometry::scale(self.bounds)
    }

    /// Bounds of the file's own geometry, which cameras frame and the studio lights: equal
    /// to [`Scene::bounds`] unless a floor was added ([`crate::studio::ground`]).
    pub fn subject_bounds(&self) -> (Vec3, Vec3) {
        self.subject_bounds
    }

    /// Loader, validation and environment-map warnings.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Triangles on which another object's face lies ([`Triangle::TOUCHES`]: touching
    /// volumes are crossed as one interface there).
    pub fn touching_triangles(&self) -> usize {
        self.touching_triangles
    }

    /// Whether any material can cut holes (alpha MASK).
    pub fn has_cutouts(&self) -> bool {
        self.has_cutouts
    }

    /// Time spent building the acceleration structure.
    pub fn accel_build_time(&self) -> Duration {
        self.accel_build_time
    }

    /// The acceleration structure (read by the intersection layer).
    pub(crate) fn accel(&self) -> &Accel {
        &self.accel
    }

    /// Name of the acceleration backend in use.
    pub fn backend_name(&self) -> &'static str {
        self.accel.name()
    }

    /// The texture coordinates on triangle `prim` at barycentric weights `b` of its
    /// vertices 0, 1, 2 (zero on a mesh without TEXCOORD_0; set 1 is set 0 on a mesh
    /// without TEXCOORD_1).
    pub fn tex_coords(&self, prim: u32, [b0, b1, b2]: [f32; 3]) -> TexCoords {
        let Some(t) = self.triangles.get(prim as usize) else {
            return TexCoords::default();
        };
        if !t.has(Triangle::HAS_UVS) {
            return TexCoords::default();
        }
        let [i0, i1, i2] = t.vertices.map(|i| i as usize);
        let lerp = |set: &[glam::Vec2]| set[i0] * b0 + set[i1] * b1 + set[i2] * b2;
        let uv0 = lerp(&self.vertices.uvs);
        let uv1 = if self.vertices.uvs1.is_empty() {
            uv0
        } else {
            lerp(&self.vertices.uvs1)
        };
        TexCoords([uv0, uv1])
    }

    /// The texture context at `uv`: the scene's images, for every texture lookup.
    pub fn textures_at(&self, uv: TexCoords) -> TextureContext<'_> {
        TextureContext::new(&self.images, uv)
    }

    /// The emitted radiance (linear RGB) at barycentric weights `b` of triangle `prim`:
    /// its material's emission with the emissive texture applied there.
    pub fn emission_at(&self, prim: u32, b: [f32; 3]) -> Vec3 {
        let mat = self.material(self.triangle(prim).material());
        mat.emitted(&self.textures_at(self.tex_coords(prim, b)))
    }

    /// Every surface crossing the segment `p ± half·ng` (the coincidence probe of the
    /// intersection layer and of [`contact`]), with the probe ray (from `p + half·ng` along
    /// `−ng`).
    pub(crate) fn probe(&self, p: Vec3, ng: Vec3, half: f32) -> (Ray, HitList) {
        let probe = Ray {
            origin: p + ng * half,
            dir: -ng,
            t_max: 2.0 * half,
            skipped: 0.0,
        };
        if half.is_nan() || half <= 0.0 {
            return (probe, HitList::default());
        }
        let hits = self.accel.all_hits(probe.origin, probe.dir, probe.t_max);
        (probe, hits)
    }
}

/// The light choice of next-event estimation: `punctual` point, spot and directional
/// lights, then the emissive triangles and the environment where the scene has them, each
/// with the same probability ([`crate::light::sampler`] says why uniform).
fn nee_sampler(
    punctual: usize,
    area: &AreaLights,
    environment: &Option<Environment>,
) -> LightSampler {
    let mut ids: Vec<LightId> = (0..punctual as u32).map(LightId::Punctual).collect();
    if !area.is_empty() {
        ids.push(LightId::Area);
    }
    if environment.is_some() {
        ids.push(LightId::Environment);
    }
    LightSampler::uniform(ids)
}
