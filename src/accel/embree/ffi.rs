//! The Embree 4.4 ABI as Iris uses it: `RTCRay`, `RTCHit`, `RTCRayHit`, the packets'
//! `valid` argument and the query argument structs declared with the library's layout (see
//! the ABI note in [`super`]; the 8- and 16-lane `RTCRayHitN` is
//! [`crate::accel::packet::RayPacket`] itself, its layout asserted in `packet`), the
//! `all_hits` argument filter, and the device error callback with integer error codes.
//! Units: `t` along the unnormalised ray direction; barycentrics as Embree's.

use super::super::{HitList, RawHit};
use embree4_sys as sys;
use glam::Vec3;
use std::ffi::{c_char, c_void, CStr};
use std::ptr;
use std::sync::Mutex;

/// Embree's invalid geometry/primitive/instance id.
pub(super) const INVALID_ID: u32 = u32::MAX;

/// `RTCRay` (48 bytes, unchanged 4.0–4.4).
#[repr(C, align(16))]
#[derive(Clone, Copy)]
pub(super) struct Ray {
    pub(super) org: [f32; 3],
    pub(super) tnear: f32,
    pub(super) dir: [f32; 3],
    pub(super) time: f32,
    pub(super) tfar: f32,
    pub(super) mask: u32,
    pub(super) id: u32,
    pub(super) flags: u32,
}

/// `RTCHit` as in Embree 4.3+/4.4 with `RTC_MAX_INSTANCE_LEVEL_COUNT = 1` and instance
/// arrays: `inst[0]` is `instID[0]`, `inst[1]` is `instPrimID[0]`. With a level count of 2
/// and no instance arrays the struct also fits; we never read the instance fields.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
pub(super) struct Hit {
    pub(super) ng: [f32; 3],
    pub(super) u: f32,
    pub(super) v: f32,
    pub(super) prim_id: u32,
    pub(super) geom_id: u32,
    pub(super) inst: [u32; 2],
}

/// `RTCRayHit`: 96 bytes, 16-byte aligned.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
pub(super) struct RayHit {
    pub(super) ray: Ray,
    pub(super) hit: Hit,
}

/// The `valid` argument of `rtcIntersect8/16` and `rtcOccluded8/16`: one `int` per lane,
/// `-1` active and `0` inactive, aligned like the packet (Embree loads it as one vector).
#[repr(C, align(64))]
#[derive(Clone, Copy)]
pub(super) struct ValidN<const N: usize>(pub(super) [i32; N]);

/// `RTCIntersectArguments` / `RTCOccludedArguments` (identical layouts): flags,
/// feature mask, context, filter, user-geometry callback, and `minWidthDistanceFactor`
/// which exists only in `RTC_MIN_WIDTH` builds (zero is its default there).
#[repr(C)]
pub(super) struct QueryArgs {
    pub(super) flags: u32,
    pub(super) feature_mask: u32,
    pub(super) context: *mut c_void,
    pub(super) filter: *const c_void,
    pub(super) callback: *const c_void,
    pub(super) min_width_distance_factor: f32,
}

impl QueryArgs {
    /// What `rtcInitIntersectArguments` (an inline C function bindgen skips) sets.
    #[inline(always)]
    pub(super) fn incoherent() -> Self {
        Self::with_flags(sys::RTCRayQueryFlags::INCOHERENT)
    }

    /// The default arguments with the ray-query flags `flags`.
    #[inline(always)]
    pub(super) fn with_flags(flags: sys::RTCRayQueryFlags) -> Self {
        QueryArgs {
            flags: flags.0,
            feature_mask: sys::RTCFeatureFlags::RTC_FEATURE_FLAG_ALL.0,
            context: ptr::null_mut(),
            filter: ptr::null(),
            callback: ptr::null(),
            min_width_distance_factor: 0.0,
        }
    }
}

impl Ray {
    #[inline(always)]
    pub(super) fn new(o: Vec3, d: Vec3, t_max: f32) -> Self {
        Ray {
            org: o.to_array(),
            tnear: 0.0,
            dir: d.to_array(),
            time: 0.0,
            tfar: t_max,
            mask: u32::MAX,
            id: 0,
            flags: 0,
        }
    }
}

impl RayHit {
    #[inline(always)]
    pub(super) fn new(o: Vec3, d: Vec3, t_max: f32) -> Self {
        RayHit {
            ray: Ray::new(o, d, t_max),
            hit: Hit {
                ng: [0.0; 3],
                u: 0.0,
                v: 0.0,
                prim_id: INVALID_ID,
                geom_id: INVALID_ID,
                inst: [INVALID_ID; 2],
            },
        }
    }
}

/// The query context of [`EmbreeAccel::all_hits`]: Embree's `RTCRayQueryContext` first
/// (room for `instID`/`instPrimID` of any level count this build may have), then ours.
#[repr(C)]
pub(super) struct CollectContext {
    pub(super) base: [u32; 4],
    pub(super) hits: HitList,
}

/// Argument filter of [`EmbreeAccel::all_hits`]: records every valid candidate of the
/// ray packet (SOA layout `RTCRayN`/`RTCHitN`, field k of lane i at `k·N + i`) and rejects
/// it. Lane layout: ray field 8 is `tfar` (the candidate's t); hit fields 3, 4 are u, v
/// and 5 is `primID`.
pub(super) unsafe extern "C" fn collect_filter(args: *const sys::RTCFilterFunctionNArguments) {
    let args = &*args;
    let n = args.N as usize;
    let ctx = &mut *(args.context as *mut CollectContext);
    let ray = args.ray as *const f32;
    let hit = args.hit as *const f32;
    for i in 0..n {
        let valid = args.valid.add(i);
        if *valid == 0 {
            continue;
        }
        ctx.hits.push(RawHit {
            t: *ray.add(8 * n + i),
            prim: *(hit.add(5 * n + i) as *const u32),
            u: *hit.add(3 * n + i),
            v: *hit.add(4 * n + i),
        });
        *valid = 0;
    }
}

pub(super) type ErrorFn = unsafe extern "C" fn(user: *mut c_void, code: u32, msg: *const c_char);

// Declared here with integer error codes (see the ABI note in the module docs).
extern "C" {
    pub(super) fn rtcGetDeviceError(device: sys::RTCDevice) -> u32;
    pub(super) fn rtcSetDeviceErrorFunction(
        device: sys::RTCDevice,
        f: Option<ErrorFn>,
        user: *mut c_void,
    );
}

pub(super) fn error_name(code: u32) -> &'static str {
    match code {
        0 => "no error",
        1 => "unknown error",
        2 => "invalid argument",
        3 => "invalid operation",
        4 => "out of memory",
        5 => "unsupported CPU",
        6 => "cancelled",
        7 => "Level Zero ray tracing support missing",
        _ => "unrecognised error code",
    }
}

/// Error callback: keeps the first message Embree reports on the device.
pub(super) unsafe extern "C" fn record_error(user: *mut c_void, code: u32, msg: *const c_char) {
    // SAFETY: `user` is the `Mutex` boxed in `EmbreeAccel::errors` (or in `embree_version`),
    // which outlives the device; `msg` is null or a NUL-terminated string.
    let slot = unsafe { &*(user as *const Mutex<Option<String>>) };
    let text = if msg.is_null() {
        String::new()
    } else {
        unsafe { CStr::from_ptr(msg) }
            .to_string_lossy()
            .into_owned()
    };
    if let Ok(mut first) = slot.lock() {
        first.get_or_insert_with(|| format!("{}: {text}", error_name(code)));
    }
}
