//! Embree 4 backend. STUB: being written.
#![allow(unsafe_code)]
use super::RawHit;
use crate::error::Result;
use glam::Vec3;

/// Embree 4 scene over one triangle mesh.
pub struct EmbreeAccel {}

impl EmbreeAccel {
    /// Builds the Embree scene.
    pub fn build(_positions: &[Vec3], _indices: &[[u32; 3]]) -> Result<Self> {
        Err(crate::Error::Accel("embree backend not built yet".into()))
    }
    /// Closest hit in `[0, t_max)`.
    pub fn closest(&self, _o: Vec3, _d: Vec3, _t_max: f32) -> Option<RawHit> {
        None
    }
    /// Any hit in `[0, t_max)`.
    pub fn occluded(&self, _o: Vec3, _d: Vec3, _t_max: f32) -> bool {
        false
    }
}
