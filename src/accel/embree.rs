//! Embree 4 backend, called through `embree4-sys` directly (the only module with `unsafe`).
//!
//! Invariants and units:
//! - One device and one committed scene per [`EmbreeAccel`], holding a single
//!   `RTC_GEOMETRY_TYPE_TRIANGLE` geometry; `primID` of a hit is the index into the
//!   `indices` slice given to [`EmbreeAccel::build`]. Embree copies the data at build time.
//! - Rays use `tnear = 0`, `tfar = t_max` (world units of `t` along the unnormalised
//!   direction), mask `0xFFFF_FFFF` against geometry mask 1 (Embree 4's default mask is 1).
//! - Barycentrics follow Embree: `p = (1-u-v)·p0 + u·p1 + v·p2`.
//! - The scene is `ROBUST` (no holes at shared edges); build quality HIGH (spatial splits)
//!   up to [`HIGH_QUALITY_MAX_TRIANGLES`], MEDIUM above (HIGH's build time and memory grow).
//! - After commit the scene is only read; Embree allows concurrent queries on a committed
//!   scene, which is what makes the type `Send + Sync`.
//!
//! ABI note: `embree4-sys` 0.0.10 generates bindings from Embree **4.2** headers, while the
//! library we link is 4.4 (or whatever 4.x the system has). Since 4.3, `RTCHit` ends with
//! `instPrimID[RTC_MAX_INSTANCE_LEVEL_COUNT]` (instance arrays), so the library's
//! `RTCRayHit` is 96 bytes, not the 80 bytes of the 4.2 binding, and `rtcIntersect1`
//! writes past the end of a 4.2-sized struct. We therefore declare the ray/hit and
//! argument structs here with the 4.4 layout (plus room for `RTC_MIN_WIDTH` builds), and
//! read error codes as plain integers because 4.3 added `RTCError` values unknown to the
//! 4.2 enum.

#![allow(unsafe_code)]

use super::{HitList, RawHit};
use crate::error::{Error, Result};
use embree4_sys as sys;
use glam::Vec3;
use std::ffi::{c_char, c_void, CStr, CString};
use std::ptr;
use std::sync::Mutex;

/// Above this many triangles the scene is built with MEDIUM instead of HIGH quality.
pub const HIGH_QUALITY_MAX_TRIANGLES: usize = 4_000_000;

/// Device configuration string (made NUL-terminated with `CString`).
const DEVICE_CONFIG: &str = "verbose=0";

const INVALID_ID: u32 = u32::MAX;

/// `RTCRay` (48 bytes, unchanged 4.0–4.4).
#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct Ray {
    org: [f32; 3],
    tnear: f32,
    dir: [f32; 3],
    time: f32,
    tfar: f32,
    mask: u32,
    id: u32,
    flags: u32,
}

/// `RTCHit` as in Embree 4.3+/4.4 with `RTC_MAX_INSTANCE_LEVEL_COUNT = 1` and instance
/// arrays: `inst[0]` is `instID[0]`, `inst[1]` is `instPrimID[0]`. With a level count of 2
/// and no instance arrays the struct also fits; we never read the instance fields.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct Hit {
    ng: [f32; 3],
    u: f32,
    v: f32,
    prim_id: u32,
    geom_id: u32,
    inst: [u32; 2],
}

/// `RTCRayHit`: 96 bytes, 16-byte aligned.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct RayHit {
    ray: Ray,
    hit: Hit,
}

/// `RTCIntersectArguments` / `RTCOccludedArguments` (identical layouts): flags,
/// feature mask, context, filter, user-geometry callback, and `minWidthDistanceFactor`
/// which exists only in `RTC_MIN_WIDTH` builds (zero is its default there).
#[repr(C)]
struct QueryArgs {
    flags: u32,
    feature_mask: u32,
    context: *mut c_void,
    filter: *const c_void,
    callback: *const c_void,
    min_width_distance_factor: f32,
}

impl QueryArgs {
    /// What `rtcInitIntersectArguments` (an inline C function bindgen skips) sets.
    #[inline(always)]
    fn incoherent() -> Self {
        QueryArgs {
            flags: sys::RTCRayQueryFlags::INCOHERENT.0,
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
    fn new(o: Vec3, d: Vec3, t_max: f32) -> Self {
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
    fn new(o: Vec3, d: Vec3, t_max: f32) -> Self {
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
struct CollectContext {
    base: [u32; 4],
    hits: HitList,
}

/// Argument filter of [`EmbreeAccel::all_hits`]: records every valid candidate of the
/// ray packet (SOA layout `RTCRayN`/`RTCHitN`, field k of lane i at `k·N + i`) and rejects
/// it. Lane layout: ray field 8 is `tfar` (the candidate's t); hit fields 3, 4 are u, v
/// and 5 is `primID`.
unsafe extern "C" fn collect_filter(args: *const sys::RTCFilterFunctionNArguments) {
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

type ErrorFn = unsafe extern "C" fn(user: *mut c_void, code: u32, msg: *const c_char);

// Declared here with integer error codes (see the ABI note in the module docs).
extern "C" {
    fn rtcGetDeviceError(device: sys::RTCDevice) -> u32;
    fn rtcSetDeviceErrorFunction(device: sys::RTCDevice, f: Option<ErrorFn>, user: *mut c_void);
}

fn error_name(code: u32) -> &'static str {
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
unsafe extern "C" fn record_error(user: *mut c_void, code: u32, msg: *const c_char) {
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

/// Embree 4 scene over one triangle mesh.
pub struct EmbreeAccel {
    device: sys::RTCDevice,
    scene: sys::RTCScene,
    /// First error message reported by the device (its callback's user pointer).
    errors: Box<Mutex<Option<String>>>,
}

// SAFETY: the handles are reference-counted Embree objects owned by this value. After
// `build` returns, the scene is committed and only queried; Embree documents ray queries on
// a committed scene as thread-safe, and the device is only touched again in `Drop`.
unsafe impl Send for EmbreeAccel {}
unsafe impl Sync for EmbreeAccel {}

impl Drop for EmbreeAccel {
    fn drop(&mut self) {
        // SAFETY: handles were created in `build`, are non-null and released exactly once;
        // the scene goes first because it references the device.
        unsafe {
            if !self.scene.is_null() {
                sys::rtcReleaseScene(self.scene);
            }
            sys::rtcReleaseDevice(self.device);
        }
    }
}

/// Creates a device with the given configuration whose errors go to `errors`.
fn new_device(config: &str, errors: &Mutex<Option<String>>) -> Result<sys::RTCDevice> {
    let config = CString::new(config)
        .map_err(|_| Error::Accel("Embree device config contains a NUL byte".into()))?;
    // SAFETY: `config` is NUL-terminated and lives across the call; `errors` outlives the
    // device (callers release the device before dropping it).
    unsafe {
        let device = sys::rtcNewDevice(config.as_ptr());
        if device.is_null() {
            let code = rtcGetDeviceError(ptr::null_mut());
            return Err(Error::Accel(format!(
                "cannot create the Embree device ({config:?}): {}",
                error_name(code)
            )));
        }
        let user = errors as *const Mutex<Option<String>> as *mut c_void;
        rtcSetDeviceErrorFunction(device, Some(record_error), user);
        Ok(device)
    }
}

impl EmbreeAccel {
    /// Builds and commits the Embree scene over world-space triangles.
    ///
    /// Fails with [`Error::Accel`] if an index is out of range or Embree reports an error
    /// (unsupported CPU, out of memory, …).
    pub fn build(positions: &[Vec3], indices: &[[u32; 3]]) -> Result<Self> {
        Self::build_with_quality(positions, indices, None)
    }

    /// As [`EmbreeAccel::build`], with the build quality forced: `Some(true)` HIGH,
    /// `Some(false)` MEDIUM, `None` the default rule (benchmarks compare the two).
    pub fn build_with_quality(
        positions: &[Vec3],
        indices: &[[u32; 3]],
        high: Option<bool>,
    ) -> Result<Self> {
        if let Some((i, t)) = indices
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&k| k as usize >= positions.len()))
        {
            return Err(Error::Accel(format!(
                "triangle {i} has vertex index {t:?} but there are {} positions",
                positions.len()
            )));
        }
        let errors = Box::new(Mutex::new(None));
        let device = new_device(DEVICE_CONFIG, &errors)?;
        let mut accel = EmbreeAccel {
            device,
            scene: ptr::null_mut(),
            errors,
        };
        // SAFETY: every handle is checked for null before use; buffer pointers returned by
        // `rtcSetNewGeometryBuffer` hold `count` items of the requested stride (Embree pads
        // vertex buffers itself for its 16-byte loads); the geometry reference is handed to
        // the scene before we release ours.
        unsafe {
            accel.scene = sys::rtcNewScene(device);
            if accel.scene.is_null() {
                return Err(accel.error("cannot create the Embree scene"));
            }
            // FILTER_FUNCTION_IN_ARGUMENTS lets `all_hits` pass its collecting filter per
            // query; queries without a filter (all others) are unaffected.
            sys::rtcSetSceneFlags(
                accel.scene,
                sys::RTCSceneFlags::ROBUST | sys::RTCSceneFlags::FILTER_FUNCTION_IN_ARGUMENTS,
            );
            let high = high.unwrap_or(indices.len() <= HIGH_QUALITY_MAX_TRIANGLES);
            let quality = if high {
                sys::RTCBuildQuality::HIGH
            } else {
                sys::RTCBuildQuality::MEDIUM
            };
            sys::rtcSetSceneBuildQuality(accel.scene, quality);
            if !indices.is_empty() {
                accel.attach_mesh(positions, indices)?;
            }
            sys::rtcCommitScene(accel.scene);
        }
        accel.check("building the Embree scene")?;
        Ok(accel)
    }

    /// Creates, fills, commits and attaches the triangle geometry.
    ///
    /// # Safety
    /// `self.scene` must be a live, uncommitted scene and all indices in range.
    unsafe fn attach_mesh(&self, positions: &[Vec3], indices: &[[u32; 3]]) -> Result<()> {
        let geom = sys::rtcNewGeometry(self.device, sys::RTCGeometryType::TRIANGLE);
        if geom.is_null() {
            return Err(self.error("cannot create the Embree triangle geometry"));
        }
        let verts = sys::rtcSetNewGeometryBuffer(
            geom,
            sys::RTCBufferType::VERTEX,
            0,
            sys::RTCFormat::FLOAT3,
            12,
            positions.len(),
        ) as *mut [f32; 3];
        let tris = sys::rtcSetNewGeometryBuffer(
            geom,
            sys::RTCBufferType::INDEX,
            0,
            sys::RTCFormat::UINT3,
            12,
            indices.len(),
        ) as *mut [u32; 3];
        if verts.is_null() || tris.is_null() {
            sys::rtcReleaseGeometry(geom);
            return Err(self.error("cannot allocate the Embree geometry buffers"));
        }
        for (i, p) in positions.iter().enumerate() {
            verts.add(i).write(p.to_array());
        }
        ptr::copy_nonoverlapping(indices.as_ptr(), tris, indices.len());
        sys::rtcSetGeometryMask(geom, 1);
        sys::rtcCommitGeometry(geom);
        sys::rtcAttachGeometry(self.scene, geom);
        sys::rtcReleaseGeometry(geom);
        Ok(())
    }

    /// The device's pending error (and first recorded message) as an [`Error`].
    fn error(&self, context: &str) -> Error {
        self.check(context)
            .err()
            .unwrap_or_else(|| Error::Accel(format!("{context}: Embree returned null")))
    }

    /// `Err` if the device reported an error since the last check.
    fn check(&self, context: &str) -> Result<()> {
        // SAFETY: the device is live.
        let code = unsafe { rtcGetDeviceError(self.device) };
        let message = self.errors.lock().ok().and_then(|mut m| m.take());
        match (code, message) {
            (0, None) => Ok(()),
            (_, Some(m)) => Err(Error::Accel(format!("{context}: {m}"))),
            (c, None) => Err(Error::Accel(format!("{context}: {}", error_name(c)))),
        }
    }

    /// Closest hit in `[0, t_max)`.
    #[inline]
    pub fn closest(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<RawHit> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        let mut rh = RayHit::new(origin, dir, t_max);
        let mut args = QueryArgs::incoherent();
        // SAFETY: the scene is committed; `rh` has the library's 16-byte-aligned `RTCRayHit`
        // layout and `args` its `RTCIntersectArguments` layout (see the module docs).
        unsafe {
            sys::rtcIntersect1(
                self.scene,
                (&mut rh as *mut RayHit).cast(),
                (&mut args as *mut QueryArgs).cast(),
            );
        }
        (rh.hit.geom_id != INVALID_ID).then_some(RawHit {
            t: rh.ray.tfar,
            prim: rh.hit.prim_id,
            u: rh.hit.u,
            v: rh.hit.v,
        })
    }

    /// Any hit in `[0, t_max)`.
    #[inline]
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        if t_max.is_nan() || t_max <= 0.0 {
            return false;
        }
        let mut ray = Ray::new(origin, dir, t_max);
        let mut args = QueryArgs::incoherent();
        // SAFETY: as in `closest`, with the `RTCRay` and `RTCOccludedArguments` layouts.
        unsafe {
            sys::rtcOccluded1(
                self.scene,
                (&mut ray as *mut Ray).cast(),
                (&mut args as *mut QueryArgs).cast(),
            );
        }
        ray.tfar == f32::NEG_INFINITY
    }

    /// Every hit in `[0, t_max)` (up to [`super::MAX_HITS`]): an argument filter records
    /// each candidate and rejects it, so Embree keeps traversing until none is left.
    pub fn all_hits(&self, origin: Vec3, dir: Vec3, t_max: f32) -> HitList {
        let mut ctx = CollectContext {
            base: [INVALID_ID; 4],
            hits: HitList::default(),
        };
        if t_max.is_nan() || t_max <= 0.0 {
            return ctx.hits;
        }
        let mut rh = RayHit::new(origin, dir, t_max);
        let mut args = QueryArgs::incoherent();
        args.flags |= sys::RTCRayQueryFlags::INVOKE_ARGUMENT_FILTER.0;
        args.context = (&mut ctx as *mut CollectContext).cast();
        args.filter = collect_filter as *const c_void;
        // SAFETY: as in `closest`; `args.context` points at `ctx`, whose first field stands
        // in for the `RTCRayQueryContext` (instance ids, set invalid as
        // `rtcInitRayQueryContext` does) and which outlives the call; `collect_filter` only
        // reads through the pointers Embree passes it.
        unsafe {
            sys::rtcIntersect1(
                self.scene,
                (&mut rh as *mut RayHit).cast(),
                (&mut args as *mut QueryArgs).cast(),
            );
        }
        ctx.hits
    }

    /// Benchmark baseline: a bare `rtcIntersect1` loop over `(origin, dir)` rays with
    /// `t_max = ∞`, writing the hit `t` (or `+∞` on a miss) to `out_t`.
    ///
    /// # Panics
    /// If `out_t` is shorter than `rays`.
    pub fn raw_closest_batch(&self, rays: &[(Vec3, Vec3)], out_t: &mut [f32]) {
        assert!(out_t.len() >= rays.len(), "out_t shorter than rays");
        let mut args = QueryArgs::incoherent();
        for (&(o, d), t) in rays.iter().zip(out_t) {
            let mut rh = RayHit::new(o, d, f32::INFINITY);
            // SAFETY: as in `closest`.
            unsafe {
                sys::rtcIntersect1(
                    self.scene,
                    (&mut rh as *mut RayHit).cast(),
                    (&mut args as *mut QueryArgs).cast(),
                );
            }
            *t = if rh.hit.geom_id == INVALID_ID {
                f32::INFINITY
            } else {
                rh.ray.tfar
            };
        }
    }
}

/// The linked Embree library's version, e.g. `"4.4.0"` (from `RTC_DEVICE_PROPERTY_VERSION`),
/// or a description of why no device could be created.
pub fn embree_version() -> String {
    let errors = Mutex::new(None);
    match new_device(DEVICE_CONFIG, &errors) {
        Ok(device) => {
            // SAFETY: the device is live and released right after the query.
            let v = unsafe {
                let v = sys::rtcGetDeviceProperty(device, sys::RTCDeviceProperty::VERSION);
                sys::rtcReleaseDevice(device);
                v
            };
            format!("{}.{}.{}", v / 10000, (v / 100) % 100, v % 100)
        }
        Err(e) => format!("unavailable ({e})"),
    }
}

/// Turns on flush-to-zero and denormals-are-zero in MXCSR for the calling thread, as
/// Embree recommends for every thread that traces rays. No-op off x86.
///
/// Rust/LLVM assume the default floating-point environment, so subnormal results in this
/// thread may differ from compile-time evaluation; no pixel-relevant value is subnormal.
pub fn enable_flush_to_zero() {
    #[cfg(any(
        target_arch = "x86_64",
        all(target_arch = "x86", target_feature = "sse")
    ))]
    {
        const FTZ: u32 = 1 << 15;
        const DAZ: u32 = 1 << 6;
        let mut csr: u32 = 0;
        // SAFETY: stmxcsr/ldmxcsr read and write a 4-byte local; only the FTZ/DAZ bits of
        // this thread's MXCSR change (DAZ exists on every x86_64 and SSE2 CPU).
        unsafe {
            std::arch::asm!("stmxcsr [{}]", in(reg) &mut csr, options(nostack, preserves_flags));
            csr |= FTZ | DAZ;
            std::arch::asm!("ldmxcsr [{}]", in(reg) &csr, options(nostack, preserves_flags, readonly));
        }
    }
}

/// MXCSR of the calling thread (tests only).
#[cfg(all(test, target_arch = "x86_64"))]
fn mxcsr() -> u32 {
    let mut csr: u32 = 0;
    // SAFETY: stores MXCSR into a local.
    unsafe { std::arch::asm!("stmxcsr [{}]", in(reg) &mut csr, options(nostack, preserves_flags)) };
    csr
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert!(
            std::mem::size_of::<QueryArgs>() >= std::mem::size_of::<sys::RTCIntersectArguments>()
        );
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
}
