//! Packet queries on a committed [`EmbreeAccel`]: the closest hits and the occluded lanes
//! of a [`RayPacket`] of 8 or 16 rays through `rtcIntersect8/16` and `rtcOccluded8/16`, and
//! the widest packet the library's kernels trace natively on this CPU.
//!
//! The packet's memory is Embree's `RTCRayHit8/16` (checked below, at compile time), so
//! Embree reads the caller's rays and writes the hits in place: `tnear = 0`, time 0, mask
//! `0xFFFF_FFFF` and id = lane as the single-ray queries make a ray, `tfar = t_max`. The
//! traceable lanes are valid (`-1`); every other lane is invalid (`0`) and, when there is
//! one, the query overwrites its ray with a harmless finite one (origin 0, direction
//! (1, 1, 1), `tfar = 0`), so NaN or infinite input never reaches Embree's vector code.

use super::ffi::{QueryArgs, ValidN};
use super::EmbreeAccel;
use crate::accel::packet::{
    closest_lanes, mask_where, occluded_lanes, Coherence, HitPacket, LaneMask, Lanes, PacketWidth,
    RayPacket, NO_GEOMETRY,
};
use embree4_sys as sys;
use std::mem::{align_of, offset_of, size_of};

/// `RayPacket<N>` is `RTCRayHitN` (the 4.2 bindings agree with 4.4 on everything before the
/// instance fields): the ray fields where `RTCRayN` has them, the hit packet at byte `48·N`
/// with `RTCHitN`'s fields, 9·4·`N` bytes of which Embree 4.4 writes, and Embree's
/// alignment (32 bytes at `N` = 8, 64 at 16).
const _: () = {
    assert!(offset_of!(RayPacket<8>, org_x) == offset_of!(sys::RTCRay8, org_x));
    assert!(offset_of!(RayPacket<8>, dir_x) == offset_of!(sys::RTCRay8, dir_x));
    assert!(offset_of!(RayPacket<8>, t_max) == offset_of!(sys::RTCRay8, tfar));
    assert!(offset_of!(RayPacket<8>, hits) == offset_of!(sys::RTCRayHit8, hit));
    assert!(offset_of!(RayPacket<16>, org_x) == offset_of!(sys::RTCRay16, org_x));
    assert!(offset_of!(RayPacket<16>, dir_x) == offset_of!(sys::RTCRay16, dir_x));
    assert!(offset_of!(RayPacket<16>, t_max) == offset_of!(sys::RTCRay16, tfar));
    assert!(offset_of!(RayPacket<16>, hits) == offset_of!(sys::RTCRayHit16, hit));
    assert!(offset_of!(HitPacket<8>, u) == offset_of!(sys::RTCHit8, u));
    assert!(offset_of!(HitPacket<8>, prim) == offset_of!(sys::RTCHit8, primID));
    assert!(offset_of!(HitPacket<8>, geom) == offset_of!(sys::RTCHit8, geomID));
    assert!(offset_of!(HitPacket<16>, u) == offset_of!(sys::RTCHit16, u));
    assert!(offset_of!(HitPacket<16>, v) == offset_of!(sys::RTCHit16, v));
    assert!(offset_of!(HitPacket<16>, prim) == offset_of!(sys::RTCHit16, primID));
    assert!(offset_of!(HitPacket<16>, geom) == offset_of!(sys::RTCHit16, geomID));
    assert!(offset_of!(HitPacket<8>, hit) >= 9 * 4 * 8);
    assert!(offset_of!(HitPacket<16>, hit) >= 9 * 4 * 16);
    assert!(align_of::<RayPacket<8>>() >= 32 && align_of::<RayPacket<16>>() >= 64);
    assert!(size_of::<ValidN<16>>() == 4 * 16 && align_of::<ValidN<16>>() >= 64);
};

impl EmbreeAccel {
    /// The widest packet Embree's kernels trace natively here: 16 when it reports
    /// `NATIVE_RAY16_SUPPORTED` (its AVX-512 kernels), 8 when `NATIVE_RAY8_SUPPORTED`
    /// (AVX/AVX2), otherwise `None` (the packet calls then trace their rays one by one
    /// inside Embree).
    pub fn native_packet_width(&self) -> Option<usize> {
        let native = |p: sys::RTCDeviceProperty| {
            // SAFETY: the device is live; querying a property has no other effect.
            unsafe { sys::rtcGetDeviceProperty(self.device, p) != 0 }
        };
        if native(sys::RTCDeviceProperty::NATIVE_RAY16_SUPPORTED) {
            Some(16)
        } else if native(sys::RTCDeviceProperty::NATIVE_RAY8_SUPPORTED) {
            Some(8)
        } else {
            None
        }
    }

    /// The closest hit in `[0, t_max)` of every traceable lane of `rays` (one
    /// `rtcIntersect8/16` call on the packet itself): `rays.hits` and the hit lanes'
    /// `t_max` hold them afterwards; other lanes get no hit.
    pub fn closest_packet<const N: usize>(&self, rays: &mut RayPacket<N>, coherence: Coherence)
    where
        Lanes<N>: PacketWidth,
    {
        let live = rays.traceable();
        rays.hits.hit = 0;
        if live == 0 {
            return;
        }
        if N != 8 && N != 16 {
            // `PacketWidth` admits only 8 and 16.
            return closest_lanes(rays, |o, d, t| self.closest(o, d, t));
        }
        let valid = valid_lanes(rays, live);
        rays.hits.geom = [NO_GEOMETRY; N];
        let mut args = query_args(coherence);
        let rh_ptr = rays as *mut RayPacket<N>;
        let args_ptr = &mut args as *mut QueryArgs;
        // SAFETY: the scene is committed; `*rays` has the library's `RTCRayHit8/16` layout
        // for this `N` and Embree's alignment (the assertions above), `valid` one `int` per
        // lane, 64-byte aligned, `args` the `RTCIntersectArguments` layout. The pointer comes
        // from the exclusive borrow `rays`, unused until the call returns; all three outlive
        // the call. Embree writes only `tfar` and the hit fields.
        unsafe {
            match N {
                8 => {
                    sys::rtcIntersect8(valid.0.as_ptr(), self.scene, rh_ptr.cast(), args_ptr.cast())
                }
                _ => sys::rtcIntersect16(
                    valid.0.as_ptr(),
                    self.scene,
                    rh_ptr.cast(),
                    args_ptr.cast(),
                ),
            }
        }
        rays.hits.hit = mask_where::<N>(|i| rays.hits.geom[i] != NO_GEOMETRY);
    }

    /// The traceable lanes of `rays` with anything in `[0, t_max)` (one `rtcOccluded8/16`
    /// call on the packet itself, which sets an occluded lane's `t_max` to `-∞`).
    pub fn occluded_packet<const N: usize>(
        &self,
        rays: &mut RayPacket<N>,
        coherence: Coherence,
    ) -> LaneMask
    where
        Lanes<N>: PacketWidth,
    {
        let live = rays.traceable();
        if live == 0 {
            return 0;
        }
        if N != 8 && N != 16 {
            // `PacketWidth` admits only 8 and 16.
            return occluded_lanes(rays, |o, d, t| self.occluded(o, d, t));
        }
        let valid = valid_lanes(rays, live);
        let mut args = query_args(coherence);
        let ray_ptr = rays as *mut RayPacket<N>;
        let args_ptr = &mut args as *mut QueryArgs;
        // SAFETY: as in `closest_packet`: `*rays` begins with the `RTCRay8/16` layout, and
        // `args` has the `RTCOccludedArguments` layout. Embree writes only `tfar`.
        unsafe {
            match N {
                8 => sys::rtcOccluded8(
                    valid.0.as_ptr(),
                    self.scene,
                    ray_ptr.cast(),
                    args_ptr.cast(),
                ),
                _ => sys::rtcOccluded16(
                    valid.0.as_ptr(),
                    self.scene,
                    ray_ptr.cast(),
                    args_ptr.cast(),
                ),
            }
        }
        live & mask_where::<N>(|i| rays.t_max[i] == f32::NEG_INFINITY)
    }
}

/// The query arguments for `coherence` (otherwise `rtcInitIntersectArguments`' defaults).
fn query_args(coherence: Coherence) -> QueryArgs {
    QueryArgs::with_flags(match coherence {
        Coherence::Coherent => sys::RTCRayQueryFlags::COHERENT,
        Coherence::Incoherent => sys::RTCRayQueryFlags::INCOHERENT,
    })
}

/// Embree's valid mask for the `live` lanes of `rays`, as loops over all lanes; when some
/// lane is not live, its ray becomes the finite ray from the origin along (1, 1, 1) with
/// `tfar = 0`.
#[inline]
fn valid_lanes<const N: usize>(rays: &mut RayPacket<N>, live: LaneMask) -> ValidN<N>
where
    Lanes<N>: PacketWidth,
{
    let mut valid = ValidN([0; N]);
    for (i, v) in valid.0.iter_mut().enumerate() {
        *v = -(((live >> i) & 1) as i32);
    }
    if live != RayPacket::<N>::FULL {
        let keep = |x: &mut [f32; N], off: f32| {
            for (x, &v) in x.iter_mut().zip(&valid.0) {
                *x = if v != 0 { *x } else { off };
            }
        };
        keep(&mut rays.org_x, 0.0);
        keep(&mut rays.org_y, 0.0);
        keep(&mut rays.org_z, 0.0);
        keep(&mut rays.dir_x, 1.0);
        keep(&mut rays.dir_y, 1.0);
        keep(&mut rays.dir_z, 1.0);
        keep(&mut rays.t_max, 0.0);
    }
    valid
}
