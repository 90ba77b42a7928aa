//! Tests of the Embree backend: struct layouts (single rays and packets) against Embree
//! 4.4, hits, misses, `t_max`, primitive ids, errors, the version and thread safety.

#[cfg(target_arch = "x86_64")]
use super::device::mxcsr;
use super::device::new_device;
use super::ffi::{Hit, QueryArgs, Ray, RayHit, ValidN};
use super::{embree_version, enable_flush_to_zero, sys, EmbreeAccel};
use crate::error::Error;
use glam::Vec3;
use std::sync::Mutex;

fn unit_triangle() -> EmbreeAccel {
    EmbreeAccel::build(&[Vec3::ZERO, Vec3::X, Vec3::Y], &[[0, 1, 2]]).unwrap()
}

#[test]
fn layouts_match_embree_4_4() {
    assert_eq!(std::mem::size_of::<Ray>(), 48);
    assert_eq!(std::mem::size_of::<RayHit>(), 96);
    assert_eq!(std::mem::align_of::<RayHit>(), 16);
    assert_eq!(std::mem::offset_of!(RayHit, hit), 48);
    assert_eq!(std::mem::offset_of!(Hit, geom_id), 24);
    assert!(std::mem::size_of::<QueryArgs>() >= std::mem::size_of::<sys::RTCIntersectArguments>());
}

#[test]
fn packet_layouts_match_embree_4_4() {
    use crate::accel::packet::{HitPacket, RayPacket};
    use std::mem::{align_of, offset_of, size_of};
    // RTCRay8/16: 12 fields of N lanes, then RTCHit8/16 (4.4): 9 fields of N lanes.
    assert_eq!(offset_of!(RayPacket<8>, t_max), 8 * 4 * 8);
    assert_eq!(offset_of!(RayPacket<16>, dir_x), 4 * 4 * 16);
    assert_eq!(offset_of!(RayPacket<8>, hits), 384);
    assert_eq!(offset_of!(RayPacket<16>, hits), 768);
    assert_eq!(offset_of!(HitPacket<8>, u), 3 * 4 * 8);
    assert_eq!(offset_of!(HitPacket<16>, prim), 5 * 4 * 16);
    assert_eq!(offset_of!(HitPacket<16>, geom), 6 * 4 * 16);
    // The hit lanes and the active lanes lie past what Embree 4.4 writes.
    assert!(offset_of!(HitPacket<8>, hit) >= 9 * 4 * 8);
    assert!(offset_of!(HitPacket<16>, hit) >= 9 * 4 * 16);
    // Embree's alignment: 32 bytes at N = 8, 64 at 16 (we use 64 for both).
    assert!(align_of::<RayPacket<8>>() >= 32);
    assert_eq!(align_of::<RayPacket<16>>(), 64);
    assert_eq!(align_of::<ValidN<16>>(), 64);
    assert_eq!(size_of::<ValidN<16>>(), 64);
    // The 4.2 bindings' packets (compared field by field in `packet`) have these offsets.
    assert_eq!(offset_of!(sys::RTCRayHit16, hit), 768);
}

/// Embree runs its AVX-512 kernels (native 16-ray packets) on CPUs with AVX-512
/// F/CD/BW/DQ/VL, its AVX2 ones (native 8) on CPUs with AVX2.
#[cfg(target_arch = "x86_64")]
#[test]
fn native_packet_width_follows_the_cpu() {
    use std::arch::is_x86_feature_detected as has;
    let w = unit_triangle().native_packet_width();
    let avx512 = has!("avx512f")
        && has!("avx512cd")
        && has!("avx512bw")
        && has!("avx512dq")
        && has!("avx512vl");
    let expected = if avx512 {
        Some(16)
    } else if has!("avx2") {
        Some(8)
    } else {
        w
    };
    assert_eq!(w, expected);
    if has!("avx2") {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let avx2 = EmbreeAccel::build_with_config(&p, &[[0, 1, 2]], None, "verbose=0,isa=avx2");
        assert_eq!(avx2.unwrap().native_packet_width(), Some(8));
    }
}

#[test]
fn hits_unit_triangle_with_barycentrics() {
    let a = unit_triangle();
    let h = a
        .closest(Vec3::new(0.2, 0.3, 2.0), -Vec3::Z, f32::INFINITY)
        .unwrap();
    assert_eq!(h.prim, 0);
    assert!((h.t - 2.0).abs() < 1e-6, "t = {}", h.t);
    assert!(
        (h.u - 0.2).abs() < 1e-6 && (h.v - 0.3).abs() < 1e-6,
        "{h:?}"
    );
    // Unnormalised direction: t is in units of the direction's length.
    let h = a
        .closest(Vec3::new(0.2, 0.3, 2.0), Vec3::new(0.0, 0.0, -4.0), 10.0)
        .unwrap();
    assert!((h.t - 0.5).abs() < 1e-6);
    // Two-sided, from below.
    let h = a
        .closest(Vec3::new(0.25, 0.25, -1.0), Vec3::Z, f32::INFINITY)
        .unwrap();
    assert!((h.t - 1.0).abs() < 1e-6);
}

#[test]
fn misses() {
    let a = unit_triangle();
    assert!(a
        .closest(Vec3::new(0.8, 0.8, 1.0), -Vec3::Z, f32::INFINITY)
        .is_none());
    assert!(a
        .closest(Vec3::new(0.2, 0.2, 1.0), Vec3::Z, f32::INFINITY)
        .is_none());
    assert!(!a.occluded(Vec3::new(0.8, 0.8, 1.0), -Vec3::Z, f32::INFINITY));
}

#[test]
fn t_max_is_respected() {
    let a = unit_triangle();
    let o = Vec3::new(0.2, 0.2, 1.0);
    assert!(a.closest(o, -Vec3::Z, 0.9).is_none());
    assert!(a.closest(o, -Vec3::Z, 1.1).is_some());
    assert!(a.closest(o, -Vec3::Z, 0.0).is_none());
    assert!(!a.occluded(o, -Vec3::Z, 0.9));
    assert!(a.occluded(o, -Vec3::Z, 1.1));
}

#[test]
fn occluded_agrees_with_closest() {
    let a = unit_triangle();
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut rnd = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
    };
    for _ in 0..2000 {
        let o = Vec3::new(rnd(), rnd(), rnd()) * 2.0;
        let d = Vec3::new(rnd(), rnd(), rnd());
        let t_max = 1.0 + rnd();
        assert_eq!(
            a.closest(o, d, t_max).is_some(),
            a.occluded(o, d, t_max),
            "{o} {d}"
        );
    }
}

#[test]
fn primitive_ids_index_the_triangle_list() {
    let p = [
        Vec3::ZERO,
        Vec3::X,
        Vec3::Y,
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 1.0),
    ];
    let a = EmbreeAccel::build(&p, &[[3, 4, 5], [0, 1, 2]]).unwrap();
    let h = a
        .closest(Vec3::new(0.1, 0.1, -1.0), Vec3::Z, f32::INFINITY)
        .unwrap();
    assert_eq!(h.prim, 1);
    let h = a
        .closest(Vec3::new(0.1, 0.1, 2.0), -Vec3::Z, f32::INFINITY)
        .unwrap();
    assert_eq!(h.prim, 0);
    let mut t = [0.0; 2];
    a.raw_closest_batch(
        &[
            (Vec3::new(0.1, 0.1, -1.0), Vec3::Z),
            (Vec3::splat(5.0), Vec3::X),
        ],
        &mut t,
    );
    assert!((t[0] - 1.0).abs() < 1e-6 && t[1] == f32::INFINITY);
}

#[test]
fn empty_scene_and_bad_indices() {
    let a = EmbreeAccel::build(&[], &[]).unwrap();
    assert!(a.closest(Vec3::ZERO, Vec3::X, f32::INFINITY).is_none());
    assert!(!a.occluded(Vec3::ZERO, Vec3::X, f32::INFINITY));
    let e = EmbreeAccel::build(&[Vec3::ZERO], &[[0, 1, 2]])
        .err()
        .unwrap();
    assert!(e.to_string().contains("triangle 0"), "{e}");
}

#[test]
fn invalid_device_config_is_an_accel_error() {
    let errors = Mutex::new(None);
    let e = new_device("verbose=not-a-number", &errors).err().unwrap();
    assert!(matches!(e, Error::Accel(_)), "{e}");
    assert!(e.to_string().contains("Embree device"), "{e}");
}

#[test]
fn version_is_4x() {
    let v = embree_version();
    assert!(v.starts_with("4."), "{v}");
}

#[test]
fn is_send_sync_and_queries_in_parallel() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<EmbreeAccel>();
    let a = unit_triangle();
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                for _ in 0..1000 {
                    assert!(a.closest(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z, 5.0).is_some());
                }
            });
        }
    });
}

#[cfg(target_arch = "x86_64")]
#[test]
fn flush_to_zero_sets_mxcsr_bits() {
    std::thread::spawn(|| {
        enable_flush_to_zero();
        assert_eq!(mxcsr() & 0x8040, 0x8040);
    })
    .join()
    .unwrap();
}
