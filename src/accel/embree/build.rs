//! Building an [`EmbreeAccel`]: a `ROBUST` scene with one triangle geometry (mask 1),
//! HIGH quality up to [`HIGH_QUALITY_MAX_TRIANGLES`] triangles, MEDIUM above; indices are
//! checked against the positions first. Embree copies the data at build time.

use super::device::{new_device, DEVICE_CONFIG};
use super::ffi::{error_name, rtcGetDeviceError};
use super::{EmbreeAccel, HIGH_QUALITY_MAX_TRIANGLES};
use crate::error::{Error, Result};
use embree4_sys as sys;
use glam::Vec3;
use std::ptr;
use std::sync::Mutex;

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
        Self::build_with_config(positions, indices, high, DEVICE_CONFIG)
    }

    /// As [`EmbreeAccel::build_with_quality`], on a device made with Embree's configuration
    /// string `config` (benchmarks: `"verbose=0,isa=avx2"` runs the AVX2 kernels on an
    /// AVX-512 CPU).
    pub fn build_with_config(
        positions: &[Vec3],
        indices: &[[u32; 3]],
        high: Option<bool>,
        config: &str,
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
        let device = new_device(config, &errors)?;
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
}
