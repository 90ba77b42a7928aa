//! The intersection layer: Embree, the BVH and brute force agree, packets, self-intersection,
//! rays it refuses, the front-face choice of η, and stiff geometry.

#[path = "../common/mod.rs"]
mod common;

mod accel_packets;
mod accel_parity;
mod interface_scene;
mod invalid_rays;
mod reintersect;
mod stiff_geometry;
