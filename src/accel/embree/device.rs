//! The Embree device: creation with Iris's error callback, the linked library's version,
//! and the per-thread floating-point mode Embree asks for (flush-to-zero).

use super::ffi::{error_name, record_error, rtcGetDeviceError, rtcSetDeviceErrorFunction};
use crate::error::{Error, Result};
use embree4_sys as sys;
use std::ffi::{c_void, CString};
use std::ptr;
use std::sync::Mutex;

/// Device configuration string (made NUL-terminated with `CString`).
pub(super) const DEVICE_CONFIG: &str = "verbose=0";

/// Creates a device with the given configuration whose errors go to `errors`.
pub(super) fn new_device(config: &str, errors: &Mutex<Option<String>>) -> Result<sys::RTCDevice> {
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
pub(super) fn mxcsr() -> u32 {
    let mut csr: u32 = 0;
    // SAFETY: stores MXCSR into a local.
    unsafe { std::arch::asm!("stmxcsr [{}]", in(reg) &mut csr, options(nostack, preserves_flags)) };
    csr
}
