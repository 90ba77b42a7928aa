//! Caustic scenes lit by delta lights (point, spot, directional) for the photon mapper,
//! shipped (CC0) in `assets/`.
//!
//! Units are metres, +Y up, linear RGB, candela (point, spot) and lux (directional).
//! Glass is [`MaterialDesc::clear_glass`] (smooth, transmission 1, clear volume). No scene
//! has an environment (black). The ball-lens test scene is [`super::focus_bench`]. The path tracer cannot carry light from a delta light
//! through glass to a diffuse floor, so it renders these scenes with black shadows where
//! the caustics belong; the photon mapper draws them. The sun-through-a-slit rainbow
//! (`scenes/fig5_3_1_rainbow.glb`) is in [`super::rainbow`].
//!
//! **`paper/fig4_5_1_caustics.glb`** (Fig. 4.5.1 of Cropp & Zhang, "Light Refraction with
//! Dispersion"):
//! - floor: white (0.8), x from −0.6 to 0.9, z from −0.6 to 0.8, at y = 0;
//! - sphere: icosphere r = [`SPHERE_RADIUS`] (subdivision 5, 20 480 triangles, radial
//!   normals), centre [`SPHERE_CENTRE`] (1 mm above the floor), glass IOR 1.5;
//! - prism: upright equilateral prism (side 0.1, height 0.12, apex towards +Z, as
//!   [`upright_prism`]) 1 mm above the floor, centroid axis at [`PRISM_AT`], glass IOR 1.5;
//! - light: one point light of [`CAUSTICS_CANDELA`] cd at [`CAUSTICS_LIGHT`], no fill; the
//!   floor gets ≈ 3.5 lx beyond the sphere, ≈ 1.5 lx where the prism's band falls (tested);
//! - sphere caustic: the light is u = 0.78 m from the sphere's centre, 40° above it. A ball
//!   lens has its focal length f = nR/(2(n−1)) = 0.15 m from the centre (Hecht, "Optics",
//!   5th ed., §6.2: a thick lens with both principal planes at the centre), so the paraxial
//!   image of the light is v = 1/(1/f − 1/u) = 0.186 m beyond the centre. The light→centre
//!   line meets the floor 0.158 m from the centre: between the sphere's back and the
//!   paraxial focus, where spherical aberration makes the caustic smallest, so a bright
//!   spot lies inside the sphere's shadow;
//! - prism caustic: the light reaches the prism descending at ≈ 28°, and seen from above
//!   along (0.908, 0, 0.418), i.e. at ≈ 55° incidence on the −X face: near minimum
//!   deviation for the index n' = √(n² − sin²γ)/cos γ ≈ 1.62 that governs the horizontal
//!   projection of a ray at elevation γ through vertical faces (Bravais' effective index;
//!   Born & Wolf, "Principles of Optics", §4.7.2). It leaves by the +X face and lands on the
//!   floor 4–24 cm from the prism's axis at x 0.42…0.65, z 0.33…0.47 (a band turned ≈ 37°
//!   towards −Z from the prism's shadow); light entering the lowest few cm is totally
//!   reflected by the bottom cap and leaves upwards. A steeper light would not do: a 60° prism passes
//!   nothing once n' sin 30° > 1, i.e. for rays steeper than ≈ 48°;
//! - camera: eye (1.25, 0.75, 0.1) → (0.3, 0, 0.05), yfov 35°, 16:9, facing the light, so
//!   the shadows and caustics fall towards it.
//!
//! **`scenes/gem_caustics.glb`**: a round brilliant ([`Brilliant::ideal`], Ø
//! [`GEM_DIAMETER`] = 15 mm, 73 facets) lying on a pavilion main (table tilted 40.75°
//! towards +Z) 0.1 mm above a white (0.8) floor 0.2 × 0.2 m; diamond `KHR_materials_ior`
//! 2.42 + `KHR_materials_dispersion` 0.36 (Abbe ≈ 55), clear volume. One spot light of
//! [`GEM_CANDELA`] cd, 0.2 m from the stone's vertex centroid, 25° off the vertical towards
//! (−0.5, 0, 0.87) (i.e. ≈ 16° off the table normal), aimed at the centroid, cone
//! 2°/3° (inner/outer): the 3° cone is 10.5 mm wide in radius at the stone (radius
//! 7.5 mm), so the direct light barely spills on the floor (≈ 500 lx there) and the
//! coloured caustics thrown by the stone land on unlit floor. Camera 0.15 m from the
//! centroid at elevation 50° from +X, yfov 35° (± 4.7 cm at the stone), 1:1.

use super::parts::{add_mesh, camera};
use super::spectral::upright_prism;
use crate::authoring::gem::Brilliant;
use crate::authoring::lathe::sin_cos;
use crate::authoring::shapes::{ground_plane, icosphere, TriMesh};
use crate::material::MaterialDesc;
use crate::scene::desc::LightDesc;
use crate::scene::desc::SceneDesc;
use glam::{DVec3, Vec3};

/// The ball-lens test scene, also reachable from here (see [`super::focus_bench`]).
pub use super::focus_bench::focus_bench;

/// Radius of the glass sphere in Fig. 4.5.1, metres.
pub const SPHERE_RADIUS: f32 = 0.1;
/// Centre of the glass sphere in Fig. 4.5.1 (1 mm above the floor): 0.6 m from the light
/// horizontally, 25° from +X towards −Z.
pub const SPHERE_CENTRE: Vec3 = Vec3::new(0.044, 0.101, -0.254);
/// Translation of Fig. 4.5.1's prism (its centroid axis): 1 m from the light horizontally.
pub const PRISM_AT: Vec3 = Vec3::new(0.408, 0.0, 0.418);
/// Position of Fig. 4.5.1's point light.
pub const CAUSTICS_LIGHT: Vec3 = Vec3::new(-0.5, 0.6, 0.0);
/// Intensity of Fig. 4.5.1's point light, candela.
pub const CAUSTICS_CANDELA: f32 = 5.0;
/// Girdle diameter of the gem in `gem_caustics.glb`, metres.
pub const GEM_DIAMETER: f64 = 0.015;
/// Intensity of the gem's spot light, candela.
pub const GEM_CANDELA: f32 = 20.0;

/// Fig. 4.5.1: a glass sphere and a glass prism on a white floor under one point light.
pub fn fig4_5_1_caustics() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Fig. 4.5.1: caustics of a glass sphere and a prism".into(),
        ..SceneDesc::default()
    };
    let floor = MaterialDesc::diffuse("Floor", Vec3::splat(0.8));
    let floor_at = Some(Vec3::new(0.15, 0.0, 0.1));
    add_mesh(&mut s, "Floor", ground_plane(0.75, 0.7), floor, floor_at);
    let r = SPHERE_RADIUS;
    let glass = MaterialDesc::clear_glass("Glass sphere IOR 1.5", 1.5, 2.0 * r);
    let sphere = icosphere(r, 5);
    add_mesh(&mut s, "Glass sphere", sphere, glass, Some(SPHERE_CENTRE));
    let glass = MaterialDesc::clear_glass("Glass prism IOR 1.5", 1.5, 0.1);
    let prism = upright_prism(0.1, 0.001, 0.12);
    add_mesh(
        &mut s,
        "Prism",
        prism,
        glass,
        Some(Vec3::new(0.05, 0.0, 0.18)),
    );
    s.lights.push(LightDesc::Point {
        name: "Light".into(),
        position: CAUSTICS_LIGHT,
        color: Vec3::ONE,
        intensity: CAUSTICS_CANDELA,
        range: None,
        spectrum: None,
    });
    s.cameras.push(camera(
        Vec3::new(1.25, 0.75, 0.1),
        Vec3::new(0.3, 0.0, 0.05),
        35.0,
        16.0 / 9.0,
    ));
    s
}

/// The gem of [`gem_caustics`] as it lies on the floor, and its vertex centroid.
pub fn gem_resting() -> (TriMesh, DVec3) {
    let stone = Brilliant::ideal(GEM_DIAMETER).resting(0.0001);
    let n = stone.positions.len() as f64;
    let centre = stone.positions.iter().map(|p| p.as_dvec3()).sum::<DVec3>() / n;
    (stone, centre)
}

/// Unit vector from the gem towards its spot light: 25° off +Y, azimuth 30° from +Z
/// towards −X.
pub fn gem_light_direction() -> DVec3 {
    let (s25, c25) = sin_cos(25f64.to_radians());
    let (s30, c30) = sin_cos(30f64.to_radians());
    DVec3::new(-s25 * s30, c25, s25 * c30)
}

/// A 15 mm round brilliant diamond on a white floor under a narrow spot light.
pub fn gem_caustics() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Diamond caustics under a spot light".into(),
        ..SceneDesc::default()
    };
    let floor = MaterialDesc::diffuse("Floor", Vec3::splat(0.8));
    add_mesh(&mut s, "Floor", ground_plane(0.1, 0.1), floor, None);
    let (stone, centre) = gem_resting();
    let mut diamond = MaterialDesc::clear_glass("Diamond IOR 2.42", 2.42, 0.01);
    diamond.dispersion = 0.36;
    add_mesh(&mut s, "Diamond", stone, diamond, None);
    let to_light = gem_light_direction();
    s.lights.push(LightDesc::Spot {
        name: "Spot".into(),
        position: (centre + 0.2 * to_light).as_vec3(),
        direction: (-to_light).as_vec3(),
        color: Vec3::ONE,
        intensity: GEM_CANDELA,
        inner_cone: 2f32.to_radians(),
        outer_cone: 3f32.to_radians(),
        range: None,
        spectrum: None,
    });
    let (s50, c50) = sin_cos(50f64.to_radians());
    let eye = centre + 0.15 * DVec3::new(c50, s50, 0.0);
    s.cameras
        .push(camera(eye.as_vec3(), centre.as_vec3(), 35.0, 1.0));
    s
}

#[cfg(test)]
mod tests {
    use super::super::focus_bench::tests::{hit_mesh, refract};
    use super::*;

    #[test]
    fn fig4_5_1_prism_throws_its_band_where_the_doc_says() {
        // Rays from the light to a 6 × 5 grid on the prism's −X face, through the mesh
        // (flat facets, n = 1.5, total internal reflection followed): at least 2/3 must leave
        // into the floor in the doc's box (x 0.42…0.65, z 0.33…0.47, with 1 cm slack) outside the
        // prism's footprint (> 3 cm from its axis; the footprint's circumradius is 5.8 cm
        // but the band lies off its +X face, whose distance from the axis is 2.9 cm).
        let n = 1.5;
        let prism = upright_prism(0.1, 0.001, 0.12).transformed(glam::Mat3::IDENTITY, PRISM_AT);
        let light = CAUSTICS_LIGHT.as_dvec3();
        let at = PRISM_AT.as_dvec3();
        let (a, c) = (
            DVec3::new(-0.05, 0.0, -0.0289),
            DVec3::new(0.0, 0.0, 0.0577),
        );
        let (mut landed, mut up) = (0, 0);
        for i in 1..=6 {
            for j in 1..=5 {
                let q = at + a + (c - a) * (f64::from(i) / 7.0) + DVec3::Y * 0.02 * f64::from(j);
                let d = (q - light).normalize();
                let (t, nrm) = hit_mesh(&prism, light, d).expect("hits the prism");
                assert!(nrm.x < -0.8, "enters by the −X face");
                let (mut o, mut d) = (light + t * d, refract(d, nrm, 1.0 / n));
                for _ in 0..4 {
                    let (t, nrm) = hit_mesh(&prism, o + 1e-7 * d, d).expect("leaves");
                    o += (t + 1e-7) * d;
                    let cos_i = d.dot(nrm);
                    if n * n * (1.0 - cos_i * cos_i) >= 1.0 {
                        d -= 2.0 * cos_i * nrm;
                        continue;
                    }
                    let out = refract(d, -nrm, n);
                    if out.y >= 0.0 {
                        // Totally reflected by the bottom cap first, then out and up.
                        up += 1;
                        break;
                    }
                    let p = o - o.y / out.y * out;
                    let axis = ((p.x - at.x).powi(2) + (p.z - at.z).powi(2)).sqrt();
                    let in_box = (0.41..0.66).contains(&p.x) && (0.32..0.48).contains(&p.z);
                    assert!(in_box && axis > 0.03, "lands at {p}");
                    landed += 1;
                    break;
                }
            }
        }
        eprintln!("fig4_5_1 prism: {landed} of 30 rays land in the band, {up} leave upwards");
        assert_eq!(landed + up, 30);
        assert!(landed >= 20, "{landed} land");
    }

    #[test]
    fn caustic_scenes_validate() {
        for s in [fig4_5_1_caustics(), gem_caustics()] {
            crate::authoring::scene::validate(&s).expect("valid");
        }
    }
}
