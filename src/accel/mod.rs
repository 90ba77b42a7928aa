//! Ray–triangle acceleration backends: Embree 4 (feature `embree`) and a pure-Rust BVH
//! (obvhs CWBVH). Backends know nothing of materials or offsets: they take a ray with
//! `t_min = 0` and return only `t`, the triangle index and Embree-style barycentrics
//! (`p = (1-u-v)·p0 + u·p1 + v·p2`). The intersection layer (`interaction`) builds the hit.
//! Packets of 8 or 16 rays ([`packet`]) go to Embree's packet kernels, or lane by lane to
//! the BVH; either way each lane's result is that of the single-ray query.

pub mod brute;
pub mod bvh;
// The Embree FFI layer: with `denoise::oidn`, the one module allowed `unsafe` (lib.rs).
#[cfg(feature = "embree")]
#[allow(unsafe_code)]
pub mod embree;
pub mod packet;
pub mod triangle;

#[cfg(not(feature = "embree"))]
use crate::error::Error;
use crate::error::Result;
use glam::Vec3;
use packet::{Coherence, LaneMask, Lanes, PacketWidth, RayPacket};

/// A raw hit: ray parameter, triangle index, barycentrics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RawHit {
    /// Ray parameter (distance if the direction is unit length).
    pub t: f32,
    /// Triangle index into the scene's triangle array.
    pub prim: u32,
    /// Barycentric weight of vertex 1.
    pub u: f32,
    /// Barycentric weight of vertex 2.
    pub v: f32,
}

/// Most hits [`Accel::all_hits`] reports; further ones are counted in `overflow` only.
pub const MAX_HITS: usize = 8;

/// Every surface along a short segment, in no particular order (see [`Accel::all_hits`]).
#[derive(Debug, Clone, Copy)]
pub struct HitList {
    hits: [RawHit; MAX_HITS],
    len: usize,
    /// Hits beyond [`MAX_HITS`] that were dropped.
    pub overflow: usize,
}

impl Default for HitList {
    fn default() -> Self {
        let none = RawHit {
            t: 0.0,
            prim: 0,
            u: 0.0,
            v: 0.0,
        };
        HitList {
            hits: [none; MAX_HITS],
            len: 0,
            overflow: 0,
        }
    }
}

impl HitList {
    /// Records a hit (dropped, and counted, once the list is full).
    #[inline]
    pub fn push(&mut self, h: RawHit) {
        if self.len < MAX_HITS {
            self.hits[self.len] = h;
            self.len += 1;
        } else {
            self.overflow += 1;
        }
    }

    /// The recorded hits.
    #[inline]
    pub fn as_slice(&self) -> &[RawHit] {
        &self.hits[..self.len]
    }
}

/// Which backend to build (`--accel`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// Embree when compiled in, otherwise the BVH.
    #[default]
    Auto,
    /// Embree 4 (requires the `embree` feature).
    Embree,
    /// obvhs CWBVH, pure Rust.
    Bvh,
}

impl Backend {
    /// Parses `--accel auto|embree|bvh` ([`crate::error::parse_name`]).
    pub fn parse(s: &str) -> Result<Backend> {
        let names = [
            ("auto", Backend::Auto),
            ("embree", Backend::Embree),
            ("bvh", Backend::Bvh),
        ];
        crate::error::parse_name("--accel", s, &names)
    }
}

/// A built acceleration structure over one triangle soup.
pub enum Accel {
    /// Pure-Rust BVH.
    Bvh(bvh::BvhAccel),
    /// Embree 4.
    #[cfg(feature = "embree")]
    Embree(embree::EmbreeAccel),
}

impl Accel {
    /// Builds the requested backend over world-space triangles.
    pub fn build(backend: Backend, positions: &[Vec3], indices: &[[u32; 3]]) -> Result<Accel> {
        match backend {
            Backend::Bvh => Ok(Accel::Bvh(bvh::BvhAccel::build(positions, indices))),
            #[cfg(feature = "embree")]
            Backend::Embree | Backend::Auto => {
                Ok(Accel::Embree(embree::EmbreeAccel::build(positions, indices)?))
            }
            #[cfg(not(feature = "embree"))]
            Backend::Auto => Ok(Accel::Bvh(bvh::BvhAccel::build(positions, indices))),
            #[cfg(not(feature = "embree"))]
            Backend::Embree => Err(Error::Accel(
                "this build of iris has no Embree support (built without the `embree` feature); use --accel bvh".into(),
            )),
        }
    }

    /// Closest hit along `origin + t·dir` for `t` in `[0, t_max)`.
    #[inline]
    pub fn closest(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<RawHit> {
        match self {
            Accel::Bvh(b) => b.closest(origin, dir, t_max),
            #[cfg(feature = "embree")]
            Accel::Embree(e) => e.closest(origin, dir, t_max),
        }
    }

    /// Whether anything lies along `origin + t·dir` for `t` in `[0, t_max)`.
    #[inline]
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        match self {
            Accel::Bvh(b) => b.occluded(origin, dir, t_max),
            #[cfg(feature = "embree")]
            Accel::Embree(e) => e.occluded(origin, dir, t_max),
        }
    }

    /// Every triangle crossed by `origin + t·dir` for `t` in `[0, t_max)` (up to
    /// [`MAX_HITS`]). Meant for short probes: the intersection layer uses it to find
    /// surfaces coincident with a hit.
    #[inline]
    pub fn all_hits(&self, origin: Vec3, dir: Vec3, t_max: f32) -> HitList {
        match self {
            Accel::Bvh(b) => b.all_hits(origin, dir, t_max),
            #[cfg(feature = "embree")]
            Accel::Embree(e) => e.all_hits(origin, dir, t_max),
        }
    }

    /// The closest hit in `[0, t_max)` of every traceable lane of `rays`
    /// ([`RayPacket::traceable`]), exactly as [`Accel::closest`] finds it lane by lane,
    /// written into the packet ([`RayPacket::hits`], the `t` into `t_max`); other lanes get
    /// no hit. Embree traces the packet in place in one `rtcIntersect8/16` call
    /// (`coherence` picks its traversal), the BVH lane by lane.
    #[inline]
    pub fn closest_packet<const N: usize>(&self, rays: &mut RayPacket<N>, coherence: Coherence)
    where
        Lanes<N>: PacketWidth,
    {
        #[cfg(not(feature = "embree"))]
        let _ = coherence;
        match self {
            Accel::Bvh(b) => packet::closest_lanes(rays, |o, d, t| b.closest(o, d, t)),
            #[cfg(feature = "embree")]
            Accel::Embree(e) => e.closest_packet(rays, coherence),
        }
    }

    /// The traceable lanes of `rays` with anything in `[0, t_max)`, as [`Accel::occluded`]
    /// answers lane by lane (Embree: one `rtcOccluded8/16` call on the packet); their
    /// `t_max` becomes `-∞`.
    #[inline]
    pub fn occluded_packet<const N: usize>(
        &self,
        rays: &mut RayPacket<N>,
        coherence: Coherence,
    ) -> LaneMask
    where
        Lanes<N>: PacketWidth,
    {
        #[cfg(not(feature = "embree"))]
        let _ = coherence;
        match self {
            Accel::Bvh(b) => packet::occluded_lanes(rays, |o, d, t| b.occluded(o, d, t)),
            #[cfg(feature = "embree")]
            Accel::Embree(e) => e.occluded_packet(rays, coherence),
        }
    }

    /// The packet width to use on this machine: Embree's native width (16 with its
    /// AVX-512 kernels, 8 with AVX2, whose `rtcIntersect16` traces the lanes one by one and
    /// is slower than 8 — `benches/packets.rs`), or for the BVH, which answers lane by lane,
    /// 16 when the CPU has AVX-512F and 8 otherwise (the width of the caller's SIMD lanes).
    pub fn packet_width(&self) -> usize {
        match self {
            Accel::Bvh(_) => cpu_packet_width(),
            #[cfg(feature = "embree")]
            Accel::Embree(e) => e.native_packet_width().unwrap_or(8),
        }
    }

    /// Backend name for summaries.
    pub fn name(&self) -> &'static str {
        match self {
            Accel::Bvh(_) => "bvh (obvhs)",
            #[cfg(feature = "embree")]
            Accel::Embree(_) => "embree 4",
        }
    }
}

/// 16 when the CPU has AVX-512F, otherwise 8.
fn cpu_packet_width() -> usize {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx512f") {
        return 16;
    }
    8
}
