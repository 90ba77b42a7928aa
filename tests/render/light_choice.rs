//! The one light choice ([`iris::light::LightSampler`]) in a scene with many lights of every
//! kind: three point lights, six emissive quads of different power (two double-sided), and
//! an environment map with one bright texel, above a diffuse floor.
//!
//! Multiple importance sampling is right only while its two sides agree on the probability
//! of reaching a light: next-event estimation weighs a light sample by `pmf(light) · pdf`
//! (the sampler's probability of choosing the light times the light's own density), and the
//! MIS weight of a BSDF-sampled hit on the same light asks
//! [`iris::shading::lights::area_pdf`] or [`iris::shading::lights::environment_pdf`]. For
//! every light and many receivers and samples, the two must give the same number (up to
//! the f32 error of recomputing the hit point by tracing the sampled direction: 1e-3
//! relative). The scene's sampler itself must pick each light as often as its `pmf` says.

use glam::{Vec2, Vec3};
use iris::accel::Backend;
use iris::light::env::{EnvMap, Environment};
use iris::light::{Light, LightId};
use iris::material::MaterialDesc;
use iris::math::{Ray, Rng};
use iris::scene::desc::{MeshDesc, SceneDesc};
use iris::scene::Scene;
use iris::shading::lights;

/// A quad of half-size `h` centred at `c`, normal along −Y (facing down) or +Y.
fn quad(name: &str, c: Vec3, h: f32, down: bool, material: usize) -> MeshDesc {
    let p = [
        c + Vec3::new(-h, 0.0, -h),
        c + Vec3::new(h, 0.0, -h),
        c + Vec3::new(h, 0.0, h),
        c + Vec3::new(-h, 0.0, h),
    ];
    // Counter-clockwise seen from the side the normal points to.
    let indices = if down {
        vec![[0, 1, 2], [0, 2, 3]]
    } else {
        vec![[0, 2, 1], [0, 3, 2]]
    };
    MeshDesc {
        name: name.into(),
        positions: p.to_vec(),
        indices,
        material: Some(material),
        ..Default::default()
    }
}

fn emitter(le: f32, double_sided: bool) -> MaterialDesc {
    MaterialDesc {
        name: format!("emitter {le}"),
        base_color: glam::Vec4::new(0.0, 0.0, 0.0, 1.0),
        metallic: 0.0,
        emissive: Vec3::new(le, 0.8 * le, 0.6 * le),
        double_sided,
        ..Default::default()
    }
}

/// An 8 × 4 environment map with one bright texel.
fn sky() -> Environment {
    let data = (0..32)
        .map(|i| {
            if i == 10 {
                Vec3::new(30.0, 20.0, 10.0)
            } else {
                Vec3::splat(0.05 + 0.01 * i as f32)
            }
        })
        .collect();
    let img = iris::image::ImageRgb {
        width: 8,
        height: 4,
        data,
    };
    Environment::Map(EnvMap::from_image(img, std::path::Path::new("sky.exr")).unwrap())
}

fn many_lights(backend: Backend) -> Scene {
    let floor = MaterialDesc {
        name: "floor".into(),
        base_color: glam::Vec4::new(0.7, 0.7, 0.7, 1.0),
        metallic: 0.0,
        ..Default::default()
    };
    let mut materials = vec![floor];
    let mut meshes = vec![quad("floor", Vec3::ZERO, 4.0, false, 0)];
    let lamps = [
        (Vec3::new(-2.0, 2.0, -1.0), 0.3, 2.0, false),
        (Vec3::new(0.0, 1.5, 0.0), 0.2, 20.0, false),
        (Vec3::new(2.0, 2.5, 1.0), 0.6, 1.0, true),
        (Vec3::new(-1.0, 3.0, 2.0), 0.1, 200.0, false),
        (Vec3::new(1.5, 1.0, -2.0), 0.4, 5.0, true),
        (Vec3::new(3.0, 2.0, -3.0), 0.25, 0.5, false),
    ];
    for (i, (c, h, le, two)) in lamps.into_iter().enumerate() {
        materials.push(emitter(le, two));
        meshes.push(quad(&format!("lamp {i}"), c, h, true, i + 1));
    }
    let desc = SceneDesc {
        source: "many lights".into(),
        meshes,
        materials,
        environment_light: Some(sky()),
        ..Default::default()
    };
    let desc = iris::scene::validate::validate(desc).expect("valid");
    let points = vec![
        Light::Point {
            position: Vec3::new(0.5, 2.0, 0.5),
            intensity: Vec3::splat(3.0),
            range: None,
        },
        Light::Point {
            position: Vec3::new(-3.0, 1.0, 0.0),
            intensity: Vec3::new(10.0, 1.0, 1.0),
            range: Some(8.0),
        },
        Light::Directional {
            direction: Vec3::new(0.3, -1.0, 0.2).normalize(),
            illuminance: Vec3::splat(0.5),
        },
    ];
    Scene::build_with_lights(desc, backend, points).expect("build")
}

#[test]
fn both_sides_of_mis_use_the_same_light_probability() {
    for backend in [Backend::Bvh, Backend::Auto] {
        let scene = many_lights(backend);
        let sampler = scene.light_sampler();
        // 3 punctual lights, the emissive group and the environment.
        assert_eq!(sampler.lights().len(), 5);
        let mut rng = Rng::new(&[29]);
        let (mut area_checked, mut env_checked) = (0, 0);
        for _ in 0..300 {
            let x = Vec2::new(rng.next_f32(), rng.next_f32()) * 7.0 - Vec2::splat(3.5);
            let down = Ray::new(Vec3::new(x.x, 5.0, x.y), Vec3::NEG_Y);
            // Receivers on the floor (rays that hit a lamp from above are skipped).
            let Some(hit) = scene.intersect(&down).filter(|h| h.material == 0) else {
                continue;
            };
            for &id in sampler.lights() {
                let (uc, u) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
                let Some(ls) = lights::sample(&scene, &hit, id, uc, u) else {
                    continue;
                };
                let Some(pdf) = ls.pdf else {
                    assert!(matches!(id, LightId::Punctual(_)), "{id:?} is not delta");
                    continue;
                };
                let nee = sampler.pmf(id) * pdf;
                let bsdf_side = match id {
                    LightId::Area => {
                        // Trace the sampled direction: the BSDF side meets the emitter there.
                        let Some(at) = scene.intersect(&hit.spawn_ray(ls.wi)) else {
                            continue;
                        };
                        if scene.material(at.material).emission() == Vec3::ZERO {
                            continue; // blocked by another surface
                        }
                        area_checked += 1;
                        lights::area_pdf(&scene, at.prim, hit.p, at.p)
                    }
                    LightId::Environment => {
                        env_checked += 1;
                        lights::environment_pdf(&scene, ls.wi)
                    }
                    LightId::Punctual(_) => unreachable!("punctual lights are delta"),
                };
                assert!(
                    (nee - bsdf_side).abs() <= 1e-3 * nee.max(bsdf_side),
                    "{id:?} at {}: next-event {nee} vs BSDF side {bsdf_side}",
                    hit.p
                );
            }
        }
        assert!(
            area_checked > 100 && env_checked > 100,
            "{area_checked} {env_checked}"
        );
    }
}

#[test]
fn the_scene_sampler_picks_each_light_as_often_as_its_pmf() {
    let scene = many_lights(Backend::Bvh);
    let sampler = scene.light_sampler();
    let n = 50_000;
    let mut count = vec![0usize; sampler.lights().len()];
    for i in 0..n {
        let c = sampler
            .sample((i as f32 + 0.5) / n as f32)
            .expect("a light");
        assert_eq!(c.pmf, sampler.pmf(c.light));
        count[c.index] += 1;
    }
    for (k, &id) in sampler.lights().iter().enumerate() {
        let want = sampler.pmf(id) as f64 * n as f64;
        assert!(
            (count[k] as f64 - want).abs() <= 1.5,
            "{id:?}: {} vs {want}",
            count[k]
        );
    }
    // A light the scene does not have is never chosen.
    assert_eq!(sampler.pmf(LightId::Punctual(7)), 0.0);
}

#[test]
fn photon_emission_chooses_lights_by_power() {
    let scene = many_lights(Backend::Bvh);
    let emitter = iris::photon::emit::PhotonEmitter::new(&scene);
    let s = emitter.sampler();
    assert_eq!(s.rule(), iris::light::sampler::Rule::Power);
    // The first point light (3 cd white) emits 4π·3 lm·sr; the second's luminance is
    // 4π·(0.2126·10 + 0.7152 + 0.0722): their probabilities are in that ratio.
    let y = |c: Vec3| 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    let ratio = s.pmf(LightId::Punctual(0)) / s.pmf(LightId::Punctual(1));
    let want = y(Vec3::splat(3.0)) / y(Vec3::new(10.0, 1.0, 1.0));
    assert!((ratio - want).abs() < 1e-5 * want, "{ratio} vs {want}");
    let sum: f32 = s.lights().iter().map(|&l| s.pmf(l)).sum();
    assert!((sum - 1.0).abs() < 1e-5);
}
