//! The caustic pass's walk ([`Walk`]): ending photons once nothing more of them can be
//! stored keeps the map of the full walk bit for bit, with fewer rays.

use super::{emitter, CausticMap, Walk};
use crate::accel::Backend;
use crate::photon::store::Photon;
use crate::scene::{desc::SceneDesc, Scene};
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::Vec3;

fn scene(desc: SceneDesc) -> Scene {
    let desc = crate::scene::validate::validate(desc).expect("valid");
    Scene::build(desc, Backend::Auto).expect("build")
}

/// Pass `pass` of `n` photons traced into a map walked by `walk`: the surface photons, the
/// volume photons and the rays.
fn pass<C: Carrier>(
    scene: &Scene,
    walk: Walk,
    (pass, n): (u32, u64),
) -> (Vec<Photon>, Vec<Photon>, u64) {
    let mut map = CausticMap::new(None, 2.0 / 3.0);
    if walk == Walk::Full {
        map = map.full_walks();
    }
    if scene.has_media() {
        map.volume = Some(crate::integrator::volume_map::VolumeMap::new(2.0 / 3.0));
    }
    let lambda = crate::integrator::photon_pass::pass_lambda::<C>(pass, 7);
    let em = emitter(scene);
    let (rays, _) = map
        .trace_pass::<C>(scene, &em, 7, pass, n, lambda, 16, None)
        .expect("within the store budget");
    let volume = map.volume.map(|v| v.photons).unwrap_or_default();
    (map.photons, volume, rays)
}

/// Both walks give the same photons, in the same order, bit for bit; the shorter walk
/// traces fewer rays (the photons that are not caustic-origin, or that scatter in a
/// medium, end early).
fn same_map<C: Carrier>(scene: &Scene, (p, n): (u32, u64), want_volume: bool) {
    let (full, full_volume, full_rays) = pass::<C>(scene, Walk::Full, (p, n));
    let (short, short_volume, short_rays) = pass::<C>(scene, Walk::UntilStored, (p, n));
    assert!(!full.is_empty(), "no caustic photons");
    assert_eq!(want_volume, !full_volume.is_empty(), "volume photons");
    assert_eq!(full, short, "surface photons");
    assert_eq!(bits(&full), bits(&short), "surface photons' bits");
    assert_eq!(full_volume, short_volume, "volume photons");
    assert_eq!(
        bits(&full_volume),
        bits(&short_volume),
        "volume photons' bits"
    );
    assert!(
        short_rays < full_rays,
        "{short_rays} rays against {full_rays}"
    );
}

/// Each photon's position and power as bits (`==` on the photons compares their packed
/// direction and flags exactly, but takes −0 for +0).
fn bits(photons: &[Photon]) -> Vec<[u32; 7]> {
    let word = |p: &Photon| {
        let (x, w) = (p.position(), p.power());
        [x.x, x.y, x.z, w[0], w[1], w[2], w[3]].map(f32::to_bits)
    };
    photons.iter().map(word).collect()
}

#[test]
fn ending_photons_once_stored_keeps_the_caustic_map() {
    let (desc, _) = crate::assets::bench::caustic_sphere(None);
    let s = scene(desc);
    same_map::<Vec3>(&s, (0, 3000), false);
    same_map::<SampledSpectrum>(&s, (3, 3000), false);
    let (desc, _) = crate::assets::bench::caustic_sphere(Some(0.2));
    same_map::<SampledSpectrum>(&scene(desc), (1, 3000), false);
}

#[test]
fn ending_photons_once_stored_keeps_the_volume_map() {
    let s = scene(crate::assets::media::milky_tank());
    same_map::<SampledSpectrum>(&s, (0, 3000), true);
}
