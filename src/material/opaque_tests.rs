//! [`super::Material::opaque_bsdf`] leaves out what a point does not need: a glTF BRDF
//! without a specular part is the Lambert lobe, and that lobe answers exactly as the glTF
//! mix it replaces; Beer–Lambert only where it absorbs.

use super::{Material, MaterialDesc, TextureContext};
use crate::bsdf::{Bsdf, TransportMode};
use glam::{Vec2, Vec3};

fn opaque(desc: MaterialDesc) -> Bsdf<Vec3> {
    let ctx = TextureContext::new(&[], crate::material::TexCoords::default());
    let m = Material::new(desc);
    m.opaque_bsdf::<Vec3>(&m.shade(&ctx), &())
}

fn no_specular() -> MaterialDesc {
    let mut d = MaterialDesc::diffuse("Floor", Vec3::new(0.8, 0.5, 0.2));
    d.specular = 0.0;
    d
}

#[test]
fn a_brdf_without_specular_is_the_lambert_lobe() {
    assert!(matches!(opaque(no_specular()), Bsdf::Lambert { .. }));
    // Any specular part keeps the glTF mix: a specular factor, metal, a layer.
    let mut spec = no_specular();
    spec.specular = 0.5;
    let mut metal = no_specular();
    metal.metallic = 0.25;
    let mut coat = no_specular();
    coat.layers.clearcoat = 0.5;
    for d in [
        MaterialDesc::diffuse("Default", Vec3::ONE),
        spec,
        metal,
        coat,
    ] {
        assert!(matches!(opaque(d), Bsdf::GltfPbr { .. }));
    }
}

/// The Lambert lobe against the glTF BRDF with `specular` 0 (F0 = F90 = 0, the GGX term
/// weighed by zero): equal f and pdf for directions on both sides, and equal samples, bit
/// for bit, over a grid of numbers.
#[test]
fn the_lambert_lobe_answers_as_the_zero_specular_mix() {
    let lambert = opaque(no_specular());
    let Bsdf::Lambert { albedo } = lambert else {
        panic!("expected the Lambert lobe, got {lambert:?}");
    };
    let mix: Bsdf<Vec3> = Bsdf::GltfPbr {
        base: albedo,
        metallic: 0.0,
        alpha: 0.25,
        ior: 1.5,
        specular: 0.0,
        specular_color: Vec3::ONE,
        layers: crate::bsdf::Layers::none(),
        extensions: crate::bsdf::LobeExtensions::NONE,
    };
    let mode = TransportMode::Radiance;
    let dirs = [
        Vec3::new(0.3, -0.2, 0.93),
        Vec3::new(-0.8, 0.1, 0.59),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.6, 0.6, -0.53),
        Vec3::new(0.05, -0.99, 0.13),
    ]
    .map(Vec3::normalize);
    for wo in dirs {
        for wi in dirs {
            assert_eq!(
                lambert.eval(wo, wi, mode),
                mix.eval(wo, wi, mode),
                "{wo} {wi}"
            );
            assert_eq!(
                lambert.pdf(wo, wi, mode),
                mix.pdf(wo, wi, mode),
                "{wo} {wi}"
            );
        }
        for i in 0..16 {
            let u = Vec2::new((i as f32 + 0.5) / 16.0, ((i * 7) % 16) as f32 / 16.0);
            let (a, b) = (
                lambert.sample(wo, 0.3, u, mode),
                mix.sample(wo, 0.3, u, mode),
            );
            let key = |s: Option<crate::bsdf::BsdfSample<Vec3>>| s.map(|s| (s.wi, s.f, s.pdf));
            assert_eq!(key(a), key(b), "{wo} {u}");
        }
    }
}

/// Beer–Lambert is computed only where it can take light away: a white attenuation colour
/// transmits exactly 1 at any distance, as does an infinite distance.
#[test]
fn only_a_coloured_finite_attenuation_absorbs() {
    let glass = |color: Vec3, distance: f32| {
        let mut d = MaterialDesc::clear_glass("Glass", 1.5, 0.01);
        d.attenuation_color = color;
        d.attenuation_distance = distance;
        Material::new(d)
    };
    let white = glass(Vec3::ONE, 1.0);
    assert!(!white.absorbs());
    assert_eq!(white.transmittance_at::<Vec3>(3.0, &()), Vec3::ONE);
    assert!(!glass(Vec3::new(0.5, 0.8, 0.9), f32::INFINITY).absorbs());
    let tinted = glass(Vec3::new(0.5, 0.8, 0.9), 2.0);
    assert!(tinted.absorbs());
    // c^(x/d) at x = d is c.
    assert_eq!(
        tinted.transmittance_at::<Vec3>(2.0, &()),
        Vec3::new(0.5, 0.8, 0.9)
    );
    // The same through the carrier's own pow: 1^y is exactly 1 for the white glass.
    assert_eq!(Vec3::ONE.powf(1.7), Vec3::ONE);
}
