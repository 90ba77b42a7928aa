//! Ray packets: `N` rays (8 or 16, see [`PacketWidth`]) in structure-of-arrays layout for
//! the SIMD-lane integrators, and their closest hits. Backend-independent: Embree traces a
//! packet with `rtcIntersect8/16` / `rtcOccluded8/16`, the BVH lane by lane with its
//! single-ray queries ([`closest_lanes`], [`occluded_lanes`]): obvhs 0.4 traverses one ray
//! at a time (`ray_traverse*`, or `ray_traverse_dynamic` with a per-ray state), with no
//! packet traversal.
//!
//! Units and conventions are those of the single-ray queries ([`super::Accel::closest`]):
//! world units, `t` along the unnormalised direction in `[0, t_max)`, Embree-style
//! barycentrics. Lane `i` is bit `i` of a [`LaneMask`].
//!
//! Invariants:
//! - Only *traceable* lanes ([`RayPacket::traceable`]) reach a backend: active, finite
//!   origin, finite non-zero direction, and `t_max > 0` (so not NaN). `t_max` NaN or ≤ 0
//!   finds nothing, as in the single-ray queries. A non-finite origin or direction or a zero
//!   direction — what [`crate::math::Ray::is_valid`] refuses, and what Embree leaves
//!   undefined — reports no hit and no occlusion; [`RayPacket::untraceable`] lists those
//!   lanes so a caller can treat them as `Scene::occluded` does (blocked).
//! - Lanes that are not traceable never carry a hit: their [`HitPacket`] lane is cleared.
//! - The data of inactive lanes is ignored (it may hold anything, NaN included).

use super::RawHit;
use glam::Vec3;

/// One bit per lane, lane `i` in bit `i` (bits at and above `N` are always clear).
pub type LaneMask = u32;

/// The packet widths with a native Embree query: 8 (`rtcIntersect8`, AVX2) and 16
/// (`rtcIntersect16`, AVX-512). Implemented for `Lanes<8>` and `Lanes<16>` only.
pub trait PacketWidth: sealed::Sealed {}

/// The type that names a packet width `N` for [`PacketWidth`] bounds.
pub struct Lanes<const N: usize>;

impl PacketWidth for Lanes<8> {}
impl PacketWidth for Lanes<16> {}

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::Lanes<8> {}
    impl Sealed for super::Lanes<16> {}
}

/// Whether a packet's rays travel together (Embree's `RTC_RAY_QUERY_FLAG_COHERENT`, which
/// selects its frustum traversal) or not (`INCOHERENT`). A hint only: the hits are the same.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coherence {
    /// Neighbouring camera rays (one pixel block, or samples of one pixel).
    Coherent,
    /// Bounce and shadow rays.
    Incoherent,
}

/// `N` rays in structure-of-arrays layout, 64-byte aligned so each field loads as one
/// AVX-512 vector (or two AVX2 ones). `t_max` bounds `t` as in [`super::Accel::closest`].
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct RayPacket<const N: usize> {
    /// Origin x per lane.
    pub org_x: [f32; N],
    /// Origin y per lane.
    pub org_y: [f32; N],
    /// Origin z per lane.
    pub org_z: [f32; N],
    /// Direction x per lane (need not be unit length).
    pub dir_x: [f32; N],
    /// Direction y per lane.
    pub dir_y: [f32; N],
    /// Direction z per lane.
    pub dir_z: [f32; N],
    /// Upper bound of `t` per lane (`+∞` for none).
    pub t_max: [f32; N],
    active: LaneMask,
}

impl<const N: usize> Default for RayPacket<N>
where
    Lanes<N>: PacketWidth,
{
    fn default() -> Self {
        RayPacket {
            org_x: [0.0; N],
            org_y: [0.0; N],
            org_z: [0.0; N],
            dir_x: [0.0; N],
            dir_y: [0.0; N],
            dir_z: [0.0; N],
            t_max: [0.0; N],
            active: 0,
        }
    }
}

impl<const N: usize> RayPacket<N>
where
    Lanes<N>: PacketWidth,
{
    /// Every lane set: `N` bits.
    pub const FULL: LaneMask = ((1u64 << N) - 1) as LaneMask;

    /// A packet with no active lane.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets lane `lane` to `origin + t·dir`, `t < t_max`, and activates it.
    ///
    /// # Panics
    /// If `lane >= N`.
    #[inline]
    pub fn set(&mut self, lane: usize, origin: Vec3, dir: Vec3, t_max: f32) {
        self.org_x[lane] = origin.x;
        self.org_y[lane] = origin.y;
        self.org_z[lane] = origin.z;
        self.dir_x[lane] = dir.x;
        self.dir_y[lane] = dir.y;
        self.dir_z[lane] = dir.z;
        self.t_max[lane] = t_max;
        self.active |= 1 << lane;
    }

    /// Lane `lane`'s origin.
    #[inline]
    pub fn origin(&self, lane: usize) -> Vec3 {
        Vec3::new(self.org_x[lane], self.org_y[lane], self.org_z[lane])
    }

    /// Lane `lane`'s direction.
    #[inline]
    pub fn dir(&self, lane: usize) -> Vec3 {
        Vec3::new(self.dir_x[lane], self.dir_y[lane], self.dir_z[lane])
    }

    /// The active lanes.
    #[inline]
    pub fn active(&self) -> LaneMask {
        self.active
    }

    /// Makes exactly the lanes of `mask` active (bits at and above `N` are dropped).
    #[inline]
    pub fn set_active(&mut self, mask: LaneMask) {
        self.active = mask & Self::FULL;
    }

    /// The active lanes a backend can trace (see the module docs).
    pub fn traceable(&self) -> LaneMask {
        self.active_where(|p, lane| p.has_line(lane) && p.t_max[lane] > 0.0)
    }

    /// The active lanes with a non-finite origin or direction, a zero direction or a NaN
    /// `t_max` (the rays [`crate::math::Ray::is_valid`] refuses).
    pub fn untraceable(&self) -> LaneMask {
        self.active_where(|p, lane| !p.has_line(lane) || p.t_max[lane].is_nan())
    }

    /// Whether lane `lane` has a finite origin and a finite non-zero direction.
    #[inline]
    fn has_line(&self, lane: usize) -> bool {
        let (o, d) = (self.origin(lane), self.dir(lane));
        o.is_finite() && d.is_finite() && d != Vec3::ZERO
    }

    /// The active lanes for which `test` holds.
    #[inline]
    fn active_where(&self, test: impl Fn(&Self, usize) -> bool) -> LaneMask {
        lanes(self.active)
            .filter(|&lane| test(self, lane))
            .fold(0, |m, lane| m | 1 << lane)
    }
}

/// The closest hits of a [`RayPacket`], structure of arrays: lane `i` holds a hit when bit
/// `i` of [`HitPacket::hit`] is set; the other lanes' values are unspecified.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct HitPacket<const N: usize> {
    /// Ray parameter of the hit.
    pub t: [f32; N],
    /// Triangle index into the scene's triangle array.
    pub prim: [u32; N],
    /// Barycentric weight of vertex 1.
    pub u: [f32; N],
    /// Barycentric weight of vertex 2.
    pub v: [f32; N],
    /// The lanes that hit something.
    pub hit: LaneMask,
}

impl<const N: usize> Default for HitPacket<N>
where
    Lanes<N>: PacketWidth,
{
    fn default() -> Self {
        HitPacket {
            t: [f32::INFINITY; N],
            prim: [u32::MAX; N],
            u: [0.0; N],
            v: [0.0; N],
            hit: 0,
        }
    }
}

impl<const N: usize> HitPacket<N>
where
    Lanes<N>: PacketWidth,
{
    /// Lane `lane`'s hit, if any.
    #[inline]
    pub fn get(&self, lane: usize) -> Option<RawHit> {
        (self.hit & (1 << lane) != 0).then(|| RawHit {
            t: self.t[lane],
            prim: self.prim[lane],
            u: self.u[lane],
            v: self.v[lane],
        })
    }

    /// Records lane `lane`'s result (a hit, or none).
    #[inline]
    pub fn set(&mut self, lane: usize, hit: Option<RawHit>) {
        match hit {
            Some(h) => {
                self.t[lane] = h.t;
                self.prim[lane] = h.prim;
                self.u[lane] = h.u;
                self.v[lane] = h.v;
                self.hit |= 1 << lane;
            }
            None => self.hit &= !(1 << lane),
        }
    }
}

/// The set lanes of `mask`, lowest first.
#[inline]
pub fn lanes(mut mask: LaneMask) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            lane
        })
    })
}

/// A packet's closest hits found lane by lane with a single-ray query (`origin, dir, t_max`
/// → hit): the traceable lanes' results, every other lane cleared.
#[inline]
pub fn closest_lanes<const N: usize>(
    rays: &RayPacket<N>,
    out: &mut HitPacket<N>,
    closest: impl Fn(Vec3, Vec3, f32) -> Option<RawHit>,
) where
    Lanes<N>: PacketWidth,
{
    out.hit = 0;
    for lane in lanes(rays.traceable()) {
        out.set(
            lane,
            closest(rays.origin(lane), rays.dir(lane), rays.t_max[lane]),
        );
    }
}

/// A packet's occluded lanes found lane by lane with a single-ray query.
#[inline]
pub fn occluded_lanes<const N: usize>(
    rays: &RayPacket<N>,
    occluded: impl Fn(Vec3, Vec3, f32) -> bool,
) -> LaneMask
where
    Lanes<N>: PacketWidth,
{
    lanes(rays.traceable())
        .filter(|&lane| occluded(rays.origin(lane), rays.dir(lane), rays.t_max[lane]))
        .fold(0, |m, lane| m | 1 << lane)
}
