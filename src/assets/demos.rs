//! Iris's demonstration scenes, generated and shipped (CC0) in `assets/scenes/`.
//!
//! Units are metres, +Y up, linear RGB; real-world sizes. Diffuse surfaces are
//! `metallic 0, roughness 1`; glass, water and gem are smooth (`roughness 0`),
//! fully transmissive (`transmission 1`) solids (`KHR_materials_volume` thickness > 0).
//! Emitters are black diffuse quads with `emissiveFactor` × `KHR_materials_emissive_strength`
//! = the radiance given below; they emit from their front face.
//!
//! | file | objects | materials | light | camera |
//! |---|---|---|---|---|
//! | `glass_of_water.glb` | a tapered tumbler (Ø 60→72 mm, 110 mm tall, 2.5 mm wall, 8 mm base, 96 segments, rounded rim) holding water up to 75 mm; the water's side and bottom are the glass's inner wall and floor with reversed winding (same vertices); 0.5 mm above a checker table (24×16 tiles of 25 mm) before a checker backdrop at z = −0.2 | glass IOR 1.5; water IOR 1.33, faint blue-green absorption (attenuation colour (0.8, 0.93, 0.96) over 0.25 m) | key panel 16×16 cm facing down at (−0.12, 0.4, 0.12), radiance 60; fill panel 60×30 cm facing −Z at z = 0.6, radiance 3 | eye (0, 0.12, 0.38) → (0, 0.055, 0), yfov 28°, 1:1 |
//! | `ruby.glb` | round brilliant ([`Brilliant::ideal`], Ø 20 mm, 73 facets) lying on a pavilion main, table tilted 40.75° towards the camera, 0.2 mm above a plain floor | ruby: IOR 1.77, dispersion 0.28 (Abbe ≈ 72), attenuation colour (0.9, 0.1, 0.18) over 20 mm; floor 0.85 grey | panels 5×5 cm radiance 40 (front-left) and 4×4 cm radiance 30 (back-right), facing down; scene extras `iris_environment: 0.15` (uniform grey) | eye (0.015, 0.038, 0.075) → (0, 0.006, 0), yfov 30°, 1:1 |
//! | `sunset_sphere.glb` | a glass sphere (r 0.1 m, 4 subdivisions) 1 mm above a 3×3 m checker floor (0.15 m tiles) framed by plain floor out to ±60 m | glass IOR 1.5; checker 0.8 / 0.55 grey, plain floor 0.7 | scene extras `iris_environment: "sky:elevation=4,azimuth=20"` ([`crate::light::sky`]: a computed sky whose sun, 4° up, 20° right of −Z, lights the sphere from behind; its caustic and shadow stretch towards the camera) | eye (0.15, 0.22, 0.75) → (0, 0.1, 0), yfov 40°, 16:9 |
//! | `prism_sky.glb` + `sky.hdr` | an upright 60° prism (side 0.25, height 0.4, apex towards +Z) 1 mm above a 3×3 m checker floor (0.15 m tiles) framed by plain floor out to ±60 m | prism glass IOR 1.5, dispersion 1.0 (Abbe 20); checker 0.8 / 0.55 grey, plain floor 0.7 | scene extras `iris_environment: "sky.hdr"` ([`super::sky`]: sky, ground, four coloured panels, sun at elevation 30° whose light crosses the prism near minimum deviation and lands on the floor on the +Z side) | eye (0.55, 0.3, 0.8) → (−0.05, 0.12, 0.1), yfov 45°, 1:1 |//!
//! `fig5_3_1_prism_beam.glb` (a white beam through an N-BK7 prism at minimum deviation
//! onto a screen) and `diamond.glb` (IOR 2.42, dispersion 0.36) are built in
//! [`super::spectral`], which documents them. `fig5_3_1_rainbow.glb` (sunlight
//! through a slit and an N-BK7 prism, the rainbow as a caustic on a screen) is built in
//! [`super::rainbow`], `gem_caustics.glb` (a diamond under a narrow spot light) in
//! [`super::caustic`], and the scattering-media scenes `milky_tank.glb`, `hazy_prism.glb`
//! and `opal.glb` in [`super::media`], and the birefringence scenes `calcite_rhomb.glb`,
//! `moissanite_and_diamond.glb` and `pleochroic_tourmaline.glb` in
//! [`super::birefringence`].

use super::birefringence::{calcite_rhomb, moissanite_and_diamond, pleochroic_tourmaline};
use super::caustic::gem_caustics;
use super::media::{hazy_prism, milky_tank, opal};
use super::paper::{add_checker, grey_pair, SceneBuilder};
use super::parts::{add_mesh, add_panel, camera};
use super::rainbow::fig5_3_1_rainbow;
use super::sky::sky_hdr;
use super::spectral::{diamond, fig5_3_1_prism_beam};
use crate::authoring::gem::Brilliant;
use crate::authoring::glb::write_glb;
use crate::authoring::lathe::{append, Tumbler};
use crate::authoring::shapes::{checkerboard, ground_plane, prism, quarter_turn_x, TriMesh};
use crate::error::{Error, Result};
use crate::light::sky::SkyParams;
use crate::material::MaterialDesc;
use crate::scene::desc::{EnvironmentDesc, SceneDesc};
use glam::{Mat3, Vec3};
use std::path::{Path, PathBuf};

/// File name of the sky map next to the scenes.
pub const SKY_FILE: &str = "sky.hdr";

/// File names and builders of the scenes, in the order [`write_scene_assets`] writes them
/// (the sky map [`SKY_FILE`] comes last).
pub const SCENES: [(&str, SceneBuilder); 14] = [
    ("glass_of_water.glb", glass_of_water),
    ("ruby.glb", ruby),
    ("prism_sky.glb", prism_sky),
    ("fig5_3_1_prism_beam.glb", fig5_3_1_prism_beam),
    ("diamond.glb", diamond),
    ("fig5_3_1_rainbow.glb", fig5_3_1_rainbow),
    ("gem_caustics.glb", gem_caustics),
    ("sunset_sphere.glb", sunset_sphere),
    ("milky_tank.glb", milky_tank),
    ("hazy_prism.glb", hazy_prism),
    ("opal.glb", opal),
    ("calcite_rhomb.glb", calcite_rhomb),
    ("moissanite_and_diamond.glb", moissanite_and_diamond),
    ("pleochroic_tourmaline.glb", pleochroic_tourmaline),
];

/// The drinking glass of [`glass_of_water`].
pub const TUMBLER: Tumbler = Tumbler {
    bottom_radius: 0.03,
    top_radius: 0.036,
    height: 0.11,
    wall: 0.0025,
    base: 0.008,
    water_level: 0.075,
    segments: 96,
    rim_segments: 6,
};

/// Writes the scenes and the sky map into `dir` (created if missing), each atomically;
/// returns their paths.
pub fn write_scene_assets(dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::Output {
        path: dir.to_path_buf(),
        reason: format!("cannot create directory: {e}"),
    })?;
    let mut written = Vec::with_capacity(SCENES.len() + 1);
    for (name, build) in SCENES {
        let path = dir.join(name);
        write_glb(&path, &build())?;
        written.push(path);
    }
    let sky = dir.join(SKY_FILE);
    crate::output::atomic::write_file_atomic(&sky, &sky_hdr())?;
    written.push(sky);
    Ok(written)
}

/// A glass of water on a checker table.
pub fn glass_of_water() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Glass of water".into(),
        ..SceneDesc::default()
    };
    add_checker(
        &mut s,
        "Table",
        checkerboard(24, 16, 0.025),
        grey_pair(),
        Mat3::IDENTITY,
        Vec3::ZERO,
    );
    let backdrop = (Vec3::new(0.85, 0.8, 0.65), Vec3::new(0.03, 0.06, 0.25));
    add_checker(
        &mut s,
        "Backdrop",
        checkerboard(24, 12, 0.025),
        backdrop,
        quarter_turn_x(),
        Vec3::new(0.0, 0.15, -0.2),
    );
    let parts = TUMBLER.build();
    let lift = Some(Vec3::new(0.0, 0.0005, 0.0));
    let glass = MaterialDesc::clear_glass("Glass IOR 1.5", 1.5, TUMBLER.wall as f32);
    let mut water = MaterialDesc::clear_glass("Water IOR 1.33", 1.33, 0.06);
    water.attenuation_color = Vec3::new(0.8, 0.93, 0.96);
    water.attenuation_distance = 0.25;
    for (name, geometry, material) in [("Glass", parts.glass, glass), ("Water", parts.water, water)]
    {
        add_mesh(&mut s, name, geometry, material, lift);
    }
    let down = Mat3::from_cols(Vec3::X, Vec3::NEG_Y, Vec3::NEG_Z);
    let towards_minus_z = Mat3::from_cols(Vec3::X, Vec3::NEG_Z, Vec3::Y);
    add_panel(
        &mut s,
        "Key panel",
        60.0,
        (0.08, 0.08),
        down,
        Vec3::new(-0.12, 0.4, 0.12),
    );
    add_panel(
        &mut s,
        "Fill panel",
        3.0,
        (0.3, 0.15),
        towards_minus_z,
        Vec3::new(0.0, 0.2, 0.6),
    );
    s.cameras.push(camera(
        Vec3::new(0.0, 0.12, 0.38),
        Vec3::new(0.0, 0.055, 0.0),
        28.0,
        1.0,
    ));
    s
}

/// A ruby brilliant lying on a light floor.
pub fn ruby() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Ruby, round brilliant".into(),
        environment: Some(EnvironmentDesc::Uniform(Vec3::splat(0.15))),
        ..SceneDesc::default()
    };
    let floor = MaterialDesc::diffuse("Floor", Vec3::splat(0.85));
    add_mesh(&mut s, "Floor", ground_plane(0.3, 0.3), floor, None);
    let mut ruby = MaterialDesc::clear_glass("Ruby IOR 1.77", 1.77, 0.012);
    ruby.dispersion = 0.28;
    ruby.attenuation_color = Vec3::new(0.9, 0.1, 0.18);
    ruby.attenuation_distance = 0.02;
    let stone = Brilliant::ideal(0.02).resting(0.0002);
    add_mesh(&mut s, "Ruby", stone, ruby, None);
    let down = Mat3::from_cols(Vec3::X, Vec3::NEG_Y, Vec3::NEG_Z);
    add_panel(
        &mut s,
        "Key panel",
        40.0,
        (0.025, 0.025),
        down,
        Vec3::new(-0.04, 0.12, 0.03),
    );
    add_panel(
        &mut s,
        "Back panel",
        30.0,
        (0.02, 0.02),
        down,
        Vec3::new(0.05, 0.1, -0.05),
    );
    s.cameras.push(camera(
        Vec3::new(0.015, 0.038, 0.075),
        Vec3::new(0.0, 0.006, 0.0),
        30.0,
        1.0,
    ));
    s
}

/// A glass sphere on a checker floor at sunset (a computed sky, [`crate::light::sky`]).
pub fn sunset_sphere() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Glass sphere at sunset".into(),
        environment: Some(EnvironmentDesc::Sky(SkyParams {
            elevation: 4.0,
            azimuth: 20.0,
            turbidity: 2.0,
        })),
        ..SceneDesc::default()
    };
    add_floor_to_the_horizon(&mut s);
    let glass = MaterialDesc::clear_glass("Glass IOR 1.5", 1.5, 0.2);
    let sphere = crate::authoring::shapes::icosphere(0.1, 4);
    add_mesh(
        &mut s,
        "Sphere",
        sphere,
        glass,
        Some(Vec3::new(0.0, 0.101, 0.0)),
    );
    s.cameras.push(camera(
        Vec3::new(0.15, 0.22, 0.75),
        Vec3::new(0.0, 0.1, 0.0),
        40.0,
        16.0 / 9.0,
    ));
    s
}

/// A 3×3 m checker of 0.15 m tiles around the origin, framed by plain floor out to ±60 m
/// (four quads that meet the checker's edges, no overlap).
fn add_floor_to_the_horizon(s: &mut SceneDesc) {
    add_checker(
        s,
        "Floor",
        checkerboard(20, 20, 0.15),
        (Vec3::splat(0.8), Vec3::splat(0.55)),
        Mat3::IDENTITY,
        Vec3::ZERO,
    );
    let mut frame = TriMesh::default();
    let (inner, outer) = (1.5f32, 60.0f32);
    let mid = (inner + outer) / 2.0;
    let half = (outer - inner) / 2.0;
    for (hx, hz, x, z) in [
        (outer, half, 0.0, -mid),
        (outer, half, 0.0, mid),
        (half, inner, -mid, 0.0),
        (half, inner, mid, 0.0),
    ] {
        let quad = ground_plane(hx, hz).transformed(Mat3::IDENTITY, Vec3::new(x, 0.0, z));
        append(&mut frame, &quad);
    }
    let floor = MaterialDesc::diffuse("Floor plain", Vec3::splat(0.7));
    add_mesh(s, "Floor plain", frame, floor, None);
}

/// A dispersive prism standing on a floor under the generated sky.
pub fn prism_sky() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Prism under the sky".into(),
        environment: Some(EnvironmentDesc::Map(SKY_FILE.into())),
        ..SceneDesc::default()
    };
    add_floor_to_the_horizon(&mut s);
    let mut glass = MaterialDesc::clear_glass("Prism glass IOR 1.5", 1.5, 0.25);
    glass.dispersion = 1.0;
    // Axis vertical: the prism's Z axis turns to −Y, its apex (+Y) to +Z.
    let upright = prism(0.25, 0.4).transformed(quarter_turn_x(), Vec3::ZERO);
    let at = Some(Vec3::new(0.0, 0.201, 0.0));
    add_mesh(&mut s, "Prism", upright, glass, at);
    s.cameras.push(camera(
        Vec3::new(0.55, 0.3, 0.8),
        Vec3::new(-0.05, 0.12, 0.1),
        45.0,
        1.0,
    ));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scenes_encode_deterministically_and_small() {
        for (name, build) in SCENES {
            let a = crate::authoring::glb::encode_glb(&build()).expect(name);
            let b = crate::authoring::glb::encode_glb(&build()).expect(name);
            assert_eq!(a, b, "{name} not deterministic");
            assert!(a.len() < 300_000, "{name} is {} bytes", a.len());
        }
        let sky = sky_hdr();
        assert_eq!(sky, sky_hdr());
        assert!(sky.len() < 300_000, "sky is {} bytes", sky.len());
    }
}
