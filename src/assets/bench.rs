//! Scenes for tests and benchmarks of caustics (not shipped as assets): a glass sphere on
//! a white floor lit by a point light or a small area light. Units: metres, candela,
//! nits; +Y up.

use crate::authoring::shapes;
use crate::material::MaterialDesc;
use crate::scene::desc::{CameraDesc, LightDesc, Projection, SceneDesc};
use glam::{Mat3, Vec3};

/// A white Lambertian (no specular layer).
fn white() -> MaterialDesc {
    MaterialDesc {
        name: "white".into(),
        metallic: 0.0,
        specular: 0.0,
        ..Default::default()
    }
}
/// The caustic test scene: a glass sphere (n 1.5, radius 0.25, centre (0, 0.25, 0)) on a
/// white (0.8) floor 2 × 2 m, lit from the side either by a point light of 1 cd at
/// (1, 0.8, 0) or, with `area = Some(h)`, by a 2h × 2h emitter facing down at the same
/// place with radiance 100·(0.05/h)² (the power of a 10 cm square at radiance 100, π W
/// in the lights' units, whatever its size). Camera above, looking down at
/// the sphere's shadow and caustic. Backend auto.
pub fn caustic_sphere(area: Option<f32>) -> (SceneDesc, CameraDesc) {
    let mesh = |name: &str, m: shapes::TriMesh, material: usize| m.into_mesh_desc(name, material);
    let sphere = shapes::icosphere(0.25, 5).transformed(Mat3::IDENTITY, Vec3::new(0.0, 0.25, 0.0));
    let floor = shapes::ground_plane(1.0, 1.0);
    let mut meshes = vec![mesh("sphere", sphere, 0), mesh("floor", floor, 1)];
    let mut materials = vec![
        MaterialDesc {
            name: "glass".into(),
            metallic: 0.0,
            roughness: 0.0,
            transmission: 1.0,
            thickness: 1.0,
            ior: 1.5,
            ..Default::default()
        },
        MaterialDesc {
            base_color: glam::Vec4::new(0.8, 0.8, 0.8, 1.0),
            ..white()
        },
    ];
    let mut lights = Vec::new();
    let light_pos = Vec3::new(1.0, 0.8, 0.0);
    if let Some(half) = area {
        // A horizontal quad facing down (−Y): the ground plane flipped over.
        let flip = Mat3::from_cols(Vec3::X, -Vec3::Y, -Vec3::Z);
        let quad = shapes::ground_plane(half, half).transformed(flip, light_pos);
        meshes.push(mesh("lamp", quad, 2));
        materials.push(MaterialDesc {
            name: "lamp".into(),
            base_color: glam::Vec4::new(0.0, 0.0, 0.0, 1.0),
            emissive: Vec3::splat(100.0 * (0.05 / half) * (0.05 / half)),
            ..white()
        });
    } else {
        lights.push(LightDesc::Point {
            name: "bulb".into(),
            position: light_pos,
            color: Vec3::ONE,
            intensity: 1.0,
            range: None,
            spectrum: None,
        });
    }
    let desc = SceneDesc {
        source: "caustic sphere".into(),
        meshes,
        materials,
        lights,
        ..Default::default()
    };
    let cam = CameraDesc {
        name: "above".into(),
        projection: Projection::Perspective {
            yfov: 0.9,
            aspect: None,
        },
        world_from_camera: crate::camera::look_at(
            Vec3::new(0.0, 1.3, 1.1),
            Vec3::new(-0.15, 0.05, 0.0),
            Vec3::Y,
        ),
    };
    (desc, cam)
}
