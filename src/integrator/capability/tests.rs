//! Each method's declaration agrees with what its render does: a "no" is refused by the
//! render (and the plan) with the declared reason, a "yes" renders.

use super::*;
use crate::accel::Backend;
use crate::integrator::PhotonSettings;
use crate::render::RenderSettings;
use crate::scene::desc::{CameraDesc, Projection};
use glam::Vec3;

/// The scene `assets/scenes/NAME`, built.
fn scene(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes")
        .join(name);
    let desc = crate::load::load_scene(&path).expect("asset loads");
    Scene::build(desc, Backend::Auto).expect("scene builds")
}

/// A camera 4 m up the z axis looking at the origin, perspective or orthographic.
fn camera(projection: Projection) -> Camera {
    let desc = CameraDesc {
        name: "test".into(),
        projection,
        world_from_camera: crate::camera::look_at(Vec3::new(0.0, 0.5, 4.0), Vec3::ZERO, Vec3::Y),
    };
    Camera::new(&desc, 8, 6)
}

fn pinhole() -> Camera {
    camera(Projection::Perspective {
        yfov: 0.8,
        aspect: None,
    })
}

/// 8×6 pixels, one unit (sample or pass), few photons, two threads.
fn tiny(spectral: bool) -> (RenderSettings, PhotonSettings) {
    let settings = RenderSettings {
        width: 8,
        height: 6,
        spp: 1,
        seed: 3,
        threads: 2,
        quiet: true,
        spectral,
        time_limit: None,
        sampler: Default::default(),
        adaptive: None,
        cancel: Default::default(),
        kernel: Default::default(),
    };
    let photon = PhotonSettings {
        photons: 500,
        passes: 1,
        ..PhotonSettings::default()
    };
    (settings, photon)
}

/// Every method but `auto`.
fn methods() -> impl Iterator<Item = Method> {
    Method::ALL.into_iter().filter(|m| *m != Method::Auto)
}

#[test]
fn media_are_refused_with_the_declared_reason_or_rendered() {
    let scene = scene("milky_tank.glb");
    assert!(scene.has_media());
    let cam = pinhole();
    let (settings, photon) = tiny(false);
    for m in methods() {
        let integrator = Integrator::new(m, 8, &photon).unwrap();
        let rendered = integrator.render(&scene, &cam, &settings);
        match m.caps().media {
            Support::No(why) => {
                let e = rendered.unwrap_err().to_string();
                assert!(e.contains(why) && e.contains(m.name()), "{}: {e}", m.name());
                assert!(e.contains("use --method path, hybrid or auto"), "{e}");
            }
            Support::Yes => {
                let (image, _) = rendered.unwrap_or_else(|e| panic!("{}: {e}", m.name()));
                assert_eq!(image.data.len(), 8 * 6, "{}", m.name());
            }
        }
    }
}

#[test]
fn an_orthographic_camera_is_refused_with_the_declared_reason_or_accepted() {
    let scene = scene("ruby.glb");
    let ortho = camera(Projection::Orthographic {
        xmag: 1.0,
        ymag: 0.75,
    });
    let photon = PhotonSettings::default();
    for m in methods() {
        let checked = Integrator::new(m, 8, &photon)
            .unwrap()
            .check_scene(&scene, &ortho, false);
        match m.caps().orthographic {
            Support::No(why) => {
                let e = checked.unwrap_err().to_string();
                assert!(e.contains(why) && e.contains("orthographic"), "{e}");
            }
            Support::Yes => checked.unwrap_or_else(|e| panic!("{}: {e}", m.name())),
        }
    }
}

/// Polarized transport is a setting only the methods that declare it keep; with it on
/// they render spectrally, and refuse RGB transport and scattering media.
#[test]
fn polarization_is_kept_where_declared_and_refused_in_rgb_and_media() {
    let (ruby, tank, cam) = (scene("ruby.glb"), scene("milky_tank.glb"), pinhole());
    let p = Some(crate::integrator::path::polarized::Polarization { polarizer: None });
    let (settings, photon) = tiny(true);
    for m in methods() {
        let integrator = Integrator::new(m, 8, &photon).unwrap().with_polarization(p);
        assert_eq!(
            integrator.polarization().is_some(),
            m.caps().polarization.is_yes(),
            "{}",
            m.name()
        );
        let refused = check_polarization(m, &ruby, true);
        match m.caps().polarization {
            Support::No(why) => assert!(refused.unwrap_err().to_string().contains(why)),
            Support::Yes => {
                refused.unwrap();
                integrator.render(&ruby, &cam, &settings).unwrap();
                let rgb = integrator.check_scene(&ruby, &cam, false).unwrap_err();
                assert!(rgb.to_string().contains("spectral"), "{rgb}");
                let media = integrator.check_scene(&tank, &cam, true).unwrap_err();
                let why = crate::integrator::path::polarized::WHY_NO_MEDIA;
                assert!(
                    media.to_string().contains("scattering media")
                        && media.to_string().contains(why),
                    "{media}"
                );
            }
        }
    }
}

/// A render counts the units its declaration names, and takes a shard of them.
#[test]
fn units_and_shards_are_the_declared_ones() {
    let (scene, cam) = (scene("ruby.glb"), pinhole());
    let (mut settings, mut photon) = tiny(false);
    (settings.spp, photon.passes) = (3, 2);
    for m in methods() {
        let integrator = Integrator::new(m, 8, &photon).unwrap();
        let total = integrator.total_units(&settings);
        let want = match m.caps().units {
            Units::Samples => 3,
            Units::Passes => 2,
        };
        assert_eq!(total, want, "{}", m.name());
        let shard = integrator.render_units(&scene, &cam, &settings, Some(1..total), None);
        match m.caps().shards {
            Support::No(why) => {
                let e = shard.err().map(|e| e.to_string()).unwrap_or_default();
                assert!(e.contains(why), "{}: {e}", m.name());
            }
            Support::Yes => {
                let (_, stats) = shard.unwrap_or_else(|e| panic!("{}: {e}", m.name()));
                let pixels = u64::from(settings.width * settings.height);
                assert_eq!(stats.samples, (total - 1) * pixels, "{}", m.name());
            }
        }
    }
}

#[test]
fn alternatives_list_the_methods_that_say_yes() {
    assert_eq!(alternatives(|_| NO_MEDIA), "");
    assert_eq!(
        alternatives(|c| if c.name == "path" {
            Support::Yes
        } else {
            NO_MEDIA
        }),
        "path"
    );
    assert_eq!(alternatives(|c| c.media), "path, hybrid or auto");
    assert_eq!(alternatives(|c| c.polarization), "path, hybrid or auto");
}
