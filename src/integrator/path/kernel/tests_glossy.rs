//! The kernel's glossy lanes ([`super::glossy`]: the glTF BRDF with its specular or metal
//! part, rough glass) against the scalar path tracer: glossy floors of three kinds under
//! the point light, and under a glossy emissive quad and an environment (next-event
//! estimation and the light paths meet, both weighted against the lobe's own density);
//! rough glass spheres, clear and absorbing, under both.

use super::features::Shade;
use super::tests::{assert_agrees, assert_near_same_seed, build, desc, rough_sphere};
use super::tests_lights::{lamp_scene_with, three_images};
use crate::accel::Backend;
use crate::light::env::Environment;
use crate::material::MaterialDesc;
use crate::scene::Scene;
use glam::Vec3;

/// Three glossy floors: a dielectric coat (the glTF default specular, ior 1.5) at
/// roughness 0.35; a gold-coloured metal at roughness 0.25; a mix (metallic 0.3) with a
/// tinted specular colour and factor 0.7 at roughness 0.6.
fn floors() -> [(&'static str, MaterialDesc); 3] {
    let base = |rgb: Vec3| MaterialDesc::diffuse("floor", rgb);
    [
        (
            "plastic",
            MaterialDesc {
                roughness: 0.35,
                ..base(Vec3::new(0.8, 0.6, 0.4))
            },
        ),
        (
            "metal",
            MaterialDesc {
                metallic: 1.0,
                roughness: 0.25,
                ..base(Vec3::new(0.9, 0.7, 0.3))
            },
        ),
        (
            "mixed",
            MaterialDesc {
                metallic: 0.3,
                roughness: 0.6,
                specular: 0.7,
                specular_color: Vec3::new(0.4, 0.8, 1.0),
                ..base(Vec3::new(0.5, 0.7, 0.6))
            },
        ),
    ]
}

/// The kernel's image of `scene` (whose glossy material is its material `glossy`) and the
/// scalar path tracer's agree as in [`super::tests::assert_agrees`] (every 4×4 block within
/// 5 σ, the image means within 4 standard errors; at the same seed at most 7 pixels
/// further apart than 1e-4), in RGB and in spectral transport; the floor is the kernel's.
fn agrees(what: &str, scene: &Scene, glossy: usize) {
    agrees_as(what, scene, (glossy, Shade::Glossy));
}

/// [`agrees`] where material `m` is shaded as `shade`; at the same seed within
/// [`assert_near_same_seed`]'s bounds for rough glass, whose many microfacet bounces
/// magnify the hit records' rounding.
fn agrees_as(what: &str, scene: &Scene, (m, shade): (usize, Shade)) {
    let tables = super::qualify(scene, true, false).expect("qualifies");
    assert_eq!(tables.shades[m], shade, "{what}");
    assert!(tables.scalar.is_empty(), "{what}: {:?}", tables.scalar);
    for spectral in [false, true] {
        let (k, s, same_seed) = three_images(scene, spectral, 31);
        let what = format!("{what}{}", if spectral { ", spectral" } else { "" });
        if shade == Shade::Glossy {
            assert_agrees(&what, (&k, &s, 4), Some(&same_seed));
        } else {
            assert_agrees(&what, (&k, &s, 4), None);
            assert_near_same_seed(&what, (&k.0, &same_seed), spectral);
        }
    }
}

/// Glossy floors under the point light: the lobe sampled (its lobe number read, the GGX
/// visible normal or the cosine), evaluated toward the light, and the bounces after it.
#[test]
fn glossy_floors_under_a_point_light_agree_with_the_scalar_path_tracer() {
    for (what, floor) in floors() {
        agrees(what, &build(desc(floor), Backend::Auto), 0);
    }
}

/// Glossy floors under a glossy emissive quad (the glTF default specular on a black
/// emitter, as a studio lamp) and a uniform environment: the light sample's MIS weight
/// against the lobe's density, and the emission a glossy bounce meets against the light
/// sampler's.
#[test]
fn glossy_floors_under_area_light_agree_with_the_scalar_path_tracer() {
    let env = Environment::Uniform {
        radiance: Vec3::new(0.2, 0.25, 0.3),
    };
    for (what, floor) in floors() {
        let lamp = MaterialDesc::emitter("lamp", Vec3::new(6.0, 5.0, 4.0));
        let scene = lamp_scene_with((desc(floor), lamp), Some(env.clone()));
        agrees(what, &scene, 0);
        let tables = super::qualify(&scene, true, false).expect("qualifies");
        assert_eq!(tables.shades[2], Shade::Glossy, "the lamp");
    }
}

/// Rough glass (roughness 0.2, α 0.04, index 1.5) under the point light, clear, then
/// absorbing (Beer–Lambert inside, so a lane must know it entered the volume) under the
/// emissive quad and the environment: reflection and refraction sampled from the
/// microfacet lobe, the η scale roulette reads, next-event estimation through the surface.
#[test]
fn rough_glass_agrees_with_the_scalar_path_tracer() {
    let rough = Shade::RoughGlass { eta: 1.5 };
    let scene = build(rough_sphere(), Backend::Auto);
    agrees_as("rough sphere", &scene, (1, rough));
    let mut d = rough_sphere();
    d.materials[1].attenuation_color = Vec3::new(0.4, 0.7, 0.9);
    d.materials[1].attenuation_distance = 0.5;
    let lamp = MaterialDesc {
        specular: 0.0,
        ..MaterialDesc::emitter("lamp", Vec3::new(6.0, 5.0, 4.0))
    };
    let env = Environment::Uniform {
        radiance: Vec3::new(0.2, 0.25, 0.3),
    };
    let scene = lamp_scene_with((d, lamp), Some(env));
    assert!(scene.materials()[1].absorbs());
    agrees_as("absorbing rough sphere", &scene, (1, rough));
}
