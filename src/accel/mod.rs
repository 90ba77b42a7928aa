//! Ray–triangle acceleration backends: Embree 4 (feature `embree`) and a pure-Rust BVH
//! (obvhs CWBVH). Backends know nothing of materials or offsets: they take a ray with
//! `t_min = 0` and return only `t`, the triangle index and Embree-style barycentrics
//! (`p = (1-u-v)·p0 + u·p1 + v·p2`). The intersection layer (`interaction`) builds the hit.

pub mod brute;
pub mod bvh;
// The Embree FFI layer: with `denoise::oidn`, the one module allowed `unsafe` (lib.rs).
#[cfg(feature = "embree")]
#[allow(unsafe_code)]
pub mod embree;
pub mod triangle;

#[cfg(not(feature = "embree"))]
use crate::error::Error;
use crate::error::Result;
use glam::Vec3;

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

    /// Backend name for summaries.
    pub fn name(&self) -> &'static str {
        match self {
            Accel::Bvh(_) => "bvh (obvhs)",
            #[cfg(feature = "embree")]
            Accel::Embree(_) => "embree 4",
        }
    }
}
