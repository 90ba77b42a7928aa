//! The scattering-media scenes ([`crate::volume`], `docs/media.md`), generated and shipped
//! (CC0) in `assets/scenes/`. Units are metres, +Y up, linear RGB.
//!
//! | file | objects | materials | light | camera |
//! |---|---|---|---|---|
//! | `milky_tank.glb` | a 40 × 16 × 16 cm block of milky water 1 mm above a dark table, a grey card 25 cm beyond its far end | water IOR 1.33 with Rayleigh scattering `iris_medium: {rayleigh: 1.2}` (σ_s = 1.2 m⁻¹ at 550 nm, 2.7 m⁻¹ at 450 nm); table 0.12 grey, card 0.2 | a white spot (inner 1°, outer 1.6°, 12 cd) 40 cm before the near end, shining along the tank's axis; scene extras `iris_environment: 0.05` | eye (0.12, 0.32, 0.95) → (0.04, 0.07, 0), yfov 32°, 16:9 |
//! | `hazy_prism.glb` | `fig5_3_1_prism_beam.glb` ([`super::spectral`]) in haze | as there, the floor dark (0.03); scene extras `iris_fog: "density=0.3,g=0.3"` (the scene's bounding box: the floor and up to the screen's top) | the beam through the slit only (the fill light removed) | as there |
//! | `opal.glb` | an ellipsoidal cabochon (semi-axes 9 × 6 × 7 mm) resting on black velvet | opal: IOR 1.45, Rayleigh scattering `iris_medium: {rayleigh: 40}`; velvet 0.02 | a panel 6 × 6 cm of radiance 2 above and in front, a panel 8 × 8 mm of radiance 8 hidden behind the stone, facing the camera | eye (0, 0.015, 0.06) → (0, 0.006, 0), yfov 30°, 1:1 |
//!
//! The tank shows the Tyndall effect: the beam blue seen from the side (Rayleigh's λ⁻⁴
//! scatters blue out of it), the spot it leaves on the card orange. The haze makes the
//! prism's fan of colours visible in the air; the opal is blue where light scattered back
//! out of it and orange where the back light came through.

use super::parts::{add_mesh, add_panel, camera};
use super::spectral::fig5_3_1_prism_beam;
use crate::authoring::shapes::{cuboid, ground_plane, icosphere, TriMesh};
use crate::material::MaterialDesc;
use crate::scene::desc::LightDesc;
use crate::scene::desc::{EnvironmentDesc, SceneDesc};
use crate::volume::{Phase, Scattering, VolumeScatter};
use glam::{Mat3, Vec3};

/// A smooth, fully transmissive volume of index `ior` holding Rayleigh scattering of
/// σ_s(550 nm) = `rayleigh` per metre (`extras.iris_medium`; other viewers see clear
/// glass).
fn rayleigh_medium(name: &str, ior: f32, thickness: f32, rayleigh: f32) -> MaterialDesc {
    let mut m = MaterialDesc::clear_glass(name, ior, thickness);
    m.extras = Some(serde_json::json!({"iris_medium": {"rayleigh": rayleigh}}));
    // The key's reading (load::gltf::scatter).
    m.scatter = Some(VolumeScatter {
        scattering: Scattering::Rayleigh { at_550: rayleigh },
        phase: Phase::Rayleigh,
    });
    m
}

/// A block of milky water lit along its axis by a narrow white spot.
pub fn milky_tank() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Milky water in a white beam (Tyndall effect)".into(),
        environment: Some(EnvironmentDesc::Uniform(Vec3::splat(0.05))),
        ..SceneDesc::default()
    };
    let table = MaterialDesc::diffuse("Table", Vec3::splat(0.12));
    add_mesh(&mut s, "Table", ground_plane(0.9, 0.5), table, None);
    let water = rayleigh_medium("Milky water", 1.33, 0.16, 1.2);
    let tank = cuboid(Vec3::new(0.2, 0.08, 0.08));
    add_mesh(
        &mut s,
        "Milky water",
        tank,
        water,
        Some(Vec3::new(0.0, 0.081, 0.0)),
    );
    // The card beyond the far end, facing −X (ground_plane's +Y turned to −X).
    let card =
        ground_plane(0.15, 0.12).transformed(Mat3::from_rotation_z(90f32.to_radians()), Vec3::ZERO);
    let white = MaterialDesc::diffuse("Card", Vec3::splat(0.2));
    add_mesh(
        &mut s,
        "Card",
        card,
        white,
        Some(Vec3::new(0.45, 0.12, 0.0)),
    );
    s.lights.push(LightDesc::Spot {
        name: "Beam".into(),
        position: Vec3::new(-0.6, 0.081, 0.0),
        direction: Vec3::X,
        color: Vec3::ONE,
        intensity: 12.0,
        inner_cone: 1f32.to_radians(),
        outer_cone: 1.6f32.to_radians(),
        range: None,
        spectrum: None,
    });
    s.cameras.push(camera(
        Vec3::new(0.12, 0.32, 0.95),
        Vec3::new(0.04, 0.07, 0.0),
        32.0,
        16.0 / 9.0,
    ));
    s
}

/// The paper's prism beam in haze: the dispersed fan visible in the air.
pub fn hazy_prism() -> SceneDesc {
    let mut s = fig5_3_1_prism_beam();
    s.name = "A white beam through a prism in haze".into();
    // In a dark room: the fill light would light the whole haze, and a light floor would
    // show the glow the haze sends down, which only many passes make smooth.
    s.lights.clear();
    for m in s.materials.iter_mut().filter(|m| m.name == "Floor") {
        m.base_color = glam::Vec4::new(0.03, 0.03, 0.03, 1.0);
    }
    s.fog = crate::volume::fog::parse("density=0.3,g=0.3").ok();
    s
}

/// An ellipsoid of semi-axes `a` (metres) around the origin: a unit icosphere scaled, with
/// the normals of the scaled surface (the inverse transpose of the scaling).
fn ellipsoid(a: Vec3) -> TriMesh {
    let unit = icosphere(1.0, 4);
    TriMesh {
        positions: unit.positions.iter().map(|&p| p * a).collect(),
        normals: unit
            .positions
            .iter()
            .map(|&p| (p / a).normalize())
            .collect(),
        indices: unit.indices,
    }
}

/// An opalescent cabochon on black velvet, lit from the front and from behind.
pub fn opal() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Opal: Rayleigh scattering in a stone".into(),
        ..SceneDesc::default()
    };
    let velvet = MaterialDesc::diffuse("Velvet", Vec3::splat(0.02));
    add_mesh(&mut s, "Velvet", ground_plane(0.1, 0.1), velvet, None);
    let semi = Vec3::new(0.009, 0.006, 0.007);
    let stone = rayleigh_medium("Opal", 1.45, 0.012, 40.0);
    add_mesh(
        &mut s,
        "Opal",
        ellipsoid(semi),
        stone,
        Some(Vec3::new(0.0, 0.0061, 0.0)),
    );
    // Key: above and in front, facing down and back; rim: behind, facing the camera.
    let key_turn = Mat3::from_rotation_x(-142f32.to_radians());
    add_panel(
        &mut s,
        "Key",
        2.0,
        (0.03, 0.03),
        key_turn,
        Vec3::new(0.0, 0.07, 0.05),
    );
    let back_turn = Mat3::from_rotation_x(90f32.to_radians());
    let back_at = Vec3::new(0.0, 0.0042, -0.04);
    add_panel(
        &mut s,
        "Back light",
        8.0,
        (0.004, 0.004),
        back_turn,
        back_at,
    );
    s.cameras.push(camera(
        Vec3::new(0.0, 0.015, 0.06),
        Vec3::new(0.0, 0.006, 0.0),
        30.0,
        1.0,
    ));
    s
}
