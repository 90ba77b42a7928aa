//! Embree 4 backend, called through `embree4-sys` directly (this module and its files are,
//! with `denoise::oidn`, the only place with `unsafe`: its declaration allows it).
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
//! writes past the end of a 4.2-sized struct (likewise `RTCHit8/16` end with
//! `instPrimID[1][N]`). We therefore declare the ray/hit structs, their packet forms and the
//! argument structs in `ffi` with the 4.4 layout (plus room for `RTC_MIN_WIDTH` builds), and
//! read error codes as plain integers because 4.3 added `RTCError` values unknown to the
//! 4.2 enum.
//!
//! Files: `ffi`, the ray/hit/argument structs and declarations with the 4.4 layout and the
//! filter and error callbacks; `device`, the device, the library version and the
//! thread's floating-point mode; `build`, the scene build; `query`, the ray queries;
//! `packet`, the 8- and 16-ray packet queries.

mod build;
mod device;
mod ffi;
mod packet;
mod query;
#[cfg(test)]
mod tests;

pub use device::{embree_version, enable_flush_to_zero};

use embree4_sys as sys;
use std::sync::Mutex;

/// Above this many triangles the scene is built with MEDIUM instead of HIGH quality.
pub const HIGH_QUALITY_MAX_TRIANGLES: usize = 4_000_000;

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
