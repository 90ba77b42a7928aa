//! Packet queries on a committed [`EmbreeAccel`]: the closest hits and the occluded lanes
//! of a [`RayPacket`] of 8 or 16 rays through `rtcIntersect8/16` and `rtcOccluded8/16`, and
//! the widest packet the library's kernels trace natively on this CPU.
//!
//! Each traceable lane (see [`crate::accel::packet`]) becomes an Embree ray with
//! `tnear = 0`, `tfar = t_max`, time 0, mask `0xFFFF_FFFF` and id = its lane, as the
//! single-ray queries make it; every other lane is invalid (`valid = 0`) and holds a
//! harmless finite ray, so NaN or infinite input never reaches Embree's vector code.

use super::ffi::{HitN, QueryArgs, RayHitN, RayN, ValidN, INVALID_ID};
use super::EmbreeAccel;
use crate::accel::packet::{
    closest_lanes, lanes, occluded_lanes, Coherence, HitPacket, LaneMask, Lanes, PacketWidth,
    RayPacket,
};
use embree4_sys as sys;

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
    /// `rtcIntersect8/16` call); other lanes get no hit.
    pub fn closest_packet<const N: usize>(
        &self,
        rays: &RayPacket<N>,
        coherence: Coherence,
        out: &mut HitPacket<N>,
    ) where
        Lanes<N>: PacketWidth,
    {
        let live = rays.traceable();
        out.hit = 0;
        if live == 0 {
            return;
        }
        let (valid, ray) = embree_rays(rays, live);
        let mut rh = RayHitN {
            ray,
            hit: HitN {
                ng_x: [0.0; N],
                ng_y: [0.0; N],
                ng_z: [0.0; N],
                u: [0.0; N],
                v: [0.0; N],
                prim_id: [INVALID_ID; N],
                geom_id: [INVALID_ID; N],
                inst: [[INVALID_ID; N]; 2],
            },
        };
        let mut args = query_args(coherence);
        let v = valid.0.as_ptr();
        let rh_ptr = &mut rh as *mut RayHitN<N>;
        let args_ptr = &mut args as *mut QueryArgs;
        // SAFETY: the scene is committed; `rh` has the library's `RTCRayHit8/16` layout for
        // this `N` and `valid` one `int` per lane, both 64-byte aligned (Embree asks for 32
        // at N = 8, 64 at 16); `args` has the `RTCIntersectArguments` layout. All three
        // outlive the call.
        unsafe {
            match N {
                8 => sys::rtcIntersect8(v, self.scene, rh_ptr.cast(), args_ptr.cast()),
                16 => sys::rtcIntersect16(v, self.scene, rh_ptr.cast(), args_ptr.cast()),
                // `PacketWidth` admits only 8 and 16.
                _ => return closest_lanes(rays, out, |o, d, t| self.closest(o, d, t)),
            }
        }
        for lane in lanes(live) {
            if rh.hit.geom_id[lane] != INVALID_ID {
                out.t[lane] = rh.ray.tfar[lane];
                out.prim[lane] = rh.hit.prim_id[lane];
                out.u[lane] = rh.hit.u[lane];
                out.v[lane] = rh.hit.v[lane];
                out.hit |= 1 << lane;
            }
        }
    }

    /// The traceable lanes of `rays` with anything in `[0, t_max)` (one
    /// `rtcOccluded8/16` call).
    pub fn occluded_packet<const N: usize>(
        &self,
        rays: &RayPacket<N>,
        coherence: Coherence,
    ) -> LaneMask
    where
        Lanes<N>: PacketWidth,
    {
        let live = rays.traceable();
        if live == 0 {
            return 0;
        }
        let (valid, mut ray) = embree_rays(rays, live);
        let mut args = query_args(coherence);
        let v = valid.0.as_ptr();
        let ray_ptr = &mut ray as *mut RayN<N>;
        let args_ptr = &mut args as *mut QueryArgs;
        // SAFETY: as in `closest_packet`, with the `RTCRay8/16` and `RTCOccludedArguments`
        // layouts.
        unsafe {
            match N {
                8 => sys::rtcOccluded8(v, self.scene, ray_ptr.cast(), args_ptr.cast()),
                16 => sys::rtcOccluded16(v, self.scene, ray_ptr.cast(), args_ptr.cast()),
                // `PacketWidth` admits only 8 and 16.
                _ => return occluded_lanes(rays, |o, d, t| self.occluded(o, d, t)),
            }
        }
        lanes(live)
            .filter(|&lane| ray.tfar[lane] == f32::NEG_INFINITY)
            .fold(0, |m, lane| m | 1 << lane)
    }
}

/// The query arguments for `coherence` (otherwise `rtcInitIntersectArguments`' defaults).
fn query_args(coherence: Coherence) -> QueryArgs {
    QueryArgs::with_flags(match coherence {
        Coherence::Coherent => sys::RTCRayQueryFlags::COHERENT,
        Coherence::Incoherent => sys::RTCRayQueryFlags::INCOHERENT,
    })
}

/// Embree's valid mask and ray packet for the `live` lanes of `rays`; the other lanes get
/// `valid = 0` and the finite ray from the origin along (1, 1, 1) with `tfar = 0`.
#[inline]
fn embree_rays<const N: usize>(rays: &RayPacket<N>, live: LaneMask) -> (ValidN<N>, RayN<N>)
where
    Lanes<N>: PacketWidth,
{
    let mut valid = ValidN([0; N]);
    let mut ray = RayN {
        org_x: [0.0; N],
        org_y: [0.0; N],
        org_z: [0.0; N],
        tnear: [0.0; N],
        dir_x: [1.0; N],
        dir_y: [1.0; N],
        dir_z: [1.0; N],
        time: [0.0; N],
        tfar: [0.0; N],
        mask: [u32::MAX; N],
        id: std::array::from_fn(|lane| lane as u32),
        flags: [0; N],
    };
    for lane in lanes(live) {
        valid.0[lane] = -1;
        ray.org_x[lane] = rays.org_x[lane];
        ray.org_y[lane] = rays.org_y[lane];
        ray.org_z[lane] = rays.org_z[lane];
        ray.dir_x[lane] = rays.dir_x[lane];
        ray.dir_y[lane] = rays.dir_y[lane];
        ray.dir_z[lane] = rays.dir_z[lane];
        ray.tfar[lane] = rays.t_max[lane];
    }
    (valid, ray)
}
