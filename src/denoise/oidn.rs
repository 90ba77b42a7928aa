//! The FFI layer to Intel Open Image Denoise 2 (linked by `build.rs`, feature `denoise`): the
//! few C calls Iris makes, declared here by hand from OIDN 2.x `include/OpenImageDenoise/oidn.h`
//! (2.1 renamed `oidnSetFilter1b`/`1i` to `oidnSetFilterBool`/`Int`; the 2.5.1 library exports
//! only the new names), and one safe function ([`rt_filter`]) running the `RT` filter on
//! packed f32 RGB buffers.
//!
//! - The device is the CPU device (`OIDN_DEVICE_TYPE_CPU`), asked for explicitly, so OIDN
//!   never looks for its CUDA, HIP or SYCL modules. It is created once per process and kept
//!   ([`device`]), as OIDN's docs advise (one device per physical device). Creating it is
//!   cheap here, so this is for tidiness more than speed: the first 8×8 denoise of a
//!   process took 9 ms (module load and device creation included), later ones 1.5 ms;
//!   an 800×600 RT filter 1.4–3.4 s (2 loaded cores).
//!   Calls on it are serialised by a mutex; OIDN keeps errors per thread and device, and the
//!   error is read on the thread that made the calls, under the lock.
//! - Images are shared (`oidnSetSharedFilterImage`): OIDN reads and writes the caller's
//!   buffers in place, `FLOAT3` pixels 12 bytes apart, rows `12 × width` bytes apart
//!   (strides given explicitly). They must outlive `oidnExecuteFilter`, which blocks.
//!
//! Units: `color` is HDR linear RGB (OIDN reads 1.0 as 100 cd/m² after its automatic input
//! scale), albedo in [0, 1], normals world-space in [−1, 1]. The caller guards the values
//! ([`super::denoise`]).

use glam::Vec3;
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::ptr;
use std::sync::{Mutex, OnceLock};

/// `OIDNDeviceImpl` (opaque).
#[repr(C)]
struct DeviceImpl {
    _opaque: [u8; 0],
}

/// `OIDNFilterImpl` (opaque).
#[repr(C)]
struct FilterImpl {
    _opaque: [u8; 0],
}

type OidnDevice = *mut DeviceImpl;
type OidnFilter = *mut FilterImpl;

/// `OIDN_DEVICE_TYPE_CPU` (`OIDNDeviceType`, a C enum: `int`).
const DEVICE_TYPE_CPU: c_int = 1;
/// `OIDN_FORMAT_FLOAT3` (`OIDN_FORMAT_FLOAT = 1`, then FLOAT2, FLOAT3).
const FORMAT_FLOAT3: c_int = 3;
/// `OIDN_ERROR_NONE`.
const ERROR_NONE: c_int = 0;
/// `OIDN_QUALITY_HIGH` (`OIDNQuality`: DEFAULT 0, FAST 4, BALANCED 5, HIGH 6); the default
/// for the RT filter, set explicitly so the output does not depend on a changed default.
const QUALITY_HIGH: c_int = 6;

#[allow(non_snake_case)]
extern "C" {
    fn oidnNewDevice(device_type: c_int) -> OidnDevice;
    fn oidnCommitDevice(device: OidnDevice);
    fn oidnGetDeviceError(device: OidnDevice, out_message: *mut *const c_char) -> c_int;
    fn oidnReleaseDevice(device: OidnDevice);
    fn oidnNewFilter(device: OidnDevice, filter_type: *const c_char) -> OidnFilter;
    fn oidnSetSharedFilterImage(
        filter: OidnFilter,
        name: *const c_char,
        dev_ptr: *mut c_void,
        format: c_int,
        width: usize,
        height: usize,
        byte_offset: usize,
        pixel_byte_stride: usize,
        row_byte_stride: usize,
    );
    fn oidnSetFilterBool(filter: OidnFilter, name: *const c_char, value: bool);
    fn oidnSetFilterInt(filter: OidnFilter, name: *const c_char, value: c_int);
    fn oidnCommitFilter(filter: OidnFilter);
    fn oidnExecuteFilter(filter: OidnFilter);
    fn oidnReleaseFilter(filter: OidnFilter);
}

// `Vec3` is `#[repr(C)]` with three f32 (glam's SIMD type is `Vec3A`): a slice of them is a
// packed FLOAT3 image.
const _: () = assert!(std::mem::size_of::<Vec3>() == 12);

/// The process-wide CPU device.
struct Device(OidnDevice);

// SAFETY: an OIDN device may be used from any thread (the API is thread-safe); every use
// goes through the mutex in `device()`, so calls are also serialised.
unsafe impl Send for Device {}

/// The first error stored for `device` on this thread (clearing it), with OIDN's message.
///
/// # Safety
/// `device` is a live device or null (then: why device creation failed).
unsafe fn take_error(device: OidnDevice) -> Option<String> {
    let mut msg: *const c_char = ptr::null();
    let code = oidnGetDeviceError(device, &mut msg);
    if code == ERROR_NONE {
        return None;
    }
    let text = if msg.is_null() {
        String::new()
    } else {
        // SAFETY: OIDN returns a NUL-terminated string valid until its next error query.
        CStr::from_ptr(msg).to_string_lossy().into_owned()
    };
    Some(format!("OIDN error {code}: {text}"))
}

/// The process-wide device, created on first use; an error (kept for later calls too) if
/// OIDN cannot create a CPU device (e.g. a CPU without SSE4.1).
fn device() -> Result<&'static Mutex<Device>, String> {
    static DEVICE: OnceLock<Result<Mutex<Device>, String>> = OnceLock::new();
    DEVICE
        .get_or_init(|| {
            // SAFETY: plain constructor calls; the handle is checked before use and released
            // on failure.
            unsafe {
                let d = oidnNewDevice(DEVICE_TYPE_CPU);
                if d.is_null() {
                    let why = take_error(ptr::null_mut()).unwrap_or_default();
                    return Err(format!("cannot create the OIDN CPU device: {why}"));
                }
                oidnCommitDevice(d);
                if let Some(e) = take_error(d) {
                    oidnReleaseDevice(d);
                    return Err(format!("cannot create the OIDN CPU device: {e}"));
                }
                Ok(Mutex::new(Device(d)))
            }
        })
        .as_ref()
        .map_err(Clone::clone)
}

/// The inputs of one RT filter run: packed RGB images of `width × height` pixels.
pub(super) struct RtInputs<'a> {
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
    /// HDR colour (non-negative, finite).
    pub color: &'a [Vec3],
    /// Albedo and normal, both or neither.
    pub aux: Option<(&'a [Vec3], &'a [Vec3])>,
    /// The auxiliary images are noise-free (`cleanAux`).
    pub clean_aux: bool,
}

/// Runs OIDN's `RT` filter (`hdr` = true, quality high) and returns the denoised colour, or
/// OIDN's error message. Every slice must hold `width × height` pixels (checked: a
/// mismatch is an error, never an out-of-bounds read).
pub(super) fn rt_filter(inputs: &RtInputs) -> Result<Vec<Vec3>, String> {
    let n = inputs.width * inputs.height;
    let aux_ok = inputs
        .aux
        .is_none_or(|(a, nrm)| a.len() == n && nrm.len() == n);
    if n == 0 || inputs.color.len() != n || !aux_ok {
        return Err(format!(
            "buffers do not hold {}x{} pixels",
            inputs.width, inputs.height
        ));
    }
    let mut output = vec![Vec3::ZERO; n];
    let device = device()?;
    let guard = device.lock().unwrap_or_else(|e| e.into_inner());
    let d = guard.0;
    let name = |s: &str| CString::new(s).expect("no NUL in a literal");
    let (rt, color, albedo, normal, out) = (
        name("RT"),
        name("color"),
        name("albedo"),
        name("normal"),
        name("output"),
    );
    let (hdr, clean_aux, quality) = (name("hdr"), name("cleanAux"), name("quality"));
    let (w, h) = (inputs.width, inputs.height);
    let (px, row) = (12usize, 12 * w);
    // SAFETY: the device is live (kept for the process) and used under its lock; every
    // image pointer is valid for `n` FLOAT3 pixels (lengths checked above) and outlives
    // `oidnExecuteFilter`, which blocks until the filter is done, after which the filter
    // is released; OIDN writes only `output`, which we own mutably. Names are
    // NUL-terminated and live across the calls.
    unsafe {
        let filter = oidnNewFilter(d, rt.as_ptr());
        if filter.is_null() {
            return Err(take_error(d).unwrap_or_else(|| "oidnNewFilter failed".into()));
        }
        let set = |name: &CString, data: *mut c_void| {
            oidnSetSharedFilterImage(filter, name.as_ptr(), data, FORMAT_FLOAT3, w, h, 0, px, row)
        };
        set(&color, inputs.color.as_ptr() as *mut c_void);
        if let Some((a, nrm)) = inputs.aux {
            set(&albedo, a.as_ptr() as *mut c_void);
            set(&normal, nrm.as_ptr() as *mut c_void);
            oidnSetFilterBool(filter, clean_aux.as_ptr(), inputs.clean_aux);
        }
        set(&out, output.as_mut_ptr() as *mut c_void);
        oidnSetFilterBool(filter, hdr.as_ptr(), true);
        oidnSetFilterInt(filter, quality.as_ptr(), QUALITY_HIGH);
        oidnCommitFilter(filter);
        let mut error = take_error(d);
        if error.is_none() {
            oidnExecuteFilter(filter);
            error = take_error(d);
        }
        oidnReleaseFilter(filter);
        match error {
            Some(e) => Err(e),
            None => Ok(output),
        }
    }
}
