//! Ray packets: `N` rays (8 or 16, see [`PacketWidth`]) in structure-of-arrays layout for
//! the SIMD-lane integrators, with room for their closest hits. The memory of a
//! [`RayPacket`] is Embree's `RTCRayHit8/16` (the rays as `RTCRayN`, then the hits as
//! `RTCHitN` at byte `48·N`, 64-byte aligned): callers fill its arrays, Embree traces it in
//! place with `rtcIntersect8/16` / `rtcOccluded8/16` and writes the hits where the caller
//! reads them. The BVH answers lane by lane with its single-ray queries
//! ([`closest_lanes`], [`occluded_lanes`]): obvhs 0.4 traverses one ray at a time
//! (`ray_traverse*`, or `ray_traverse_dynamic` with a per-ray state), with no packet
//! traversal.
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
//! - A query writes into the packet, as Embree does: after a closest-hit query a hit lane's
//!   `t_max` is its hit's `t` and [`RayPacket::hits`] holds the hits (lanes that are not
//!   traceable never carry one); after an occlusion query an occluded lane's `t_max` is
//!   `-∞`. Embree's backend may also overwrite the rays of lanes that are not traceable
//!   (with a finite ray), so [`RayPacket::untraceable`] is asked before a query.
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

/// Embree's invalid geometry id (`RTC_INVALID_GEOMETRY_ID`): a lane without a hit.
pub(super) const NO_GEOMETRY: u32 = u32::MAX;

/// `N` rays in Embree's `RTCRayN` layout (`RTCRay`'s fields in order, each an array of `N`
/// lanes: 48·`N` bytes), their closest hits ([`HitPacket`], Embree's `RTCHitN`) right after
/// them, then the active lanes. 64-byte aligned (Embree asks for 32 at `N` = 8 and 64 at
/// 16), so each field loads as one AVX-512 vector (or two AVX2 ones). `t_max` bounds `t` as
/// in [`super::Accel::closest`]; the fields callers do not set keep the values the
/// single-ray queries use (`tnear` 0, time 0, every mask bit, id = lane, flags 0).
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct RayPacket<const N: usize> {
    /// Origin x per lane.
    pub org_x: [f32; N],
    /// Origin y per lane.
    pub org_y: [f32; N],
    /// Origin z per lane.
    pub org_z: [f32; N],
    #[allow(dead_code)] // Embree's, read or written by the library only.
    tnear: [f32; N],
    /// Direction x per lane (need not be unit length).
    pub dir_x: [f32; N],
    /// Direction y per lane.
    pub dir_y: [f32; N],
    /// Direction z per lane.
    pub dir_z: [f32; N],
    #[allow(dead_code)] // Embree's, read or written by the library only.
    time: [f32; N],
    /// Upper bound of `t` per lane (`+∞` for none; Embree's `tfar`): a hit lane's `t` after
    /// a closest-hit query, `-∞` on an occluded lane after an occlusion query.
    pub t_max: [f32; N],
    #[allow(dead_code)] // Embree's, read or written by the library only.
    mask: [u32; N],
    #[allow(dead_code)] // Embree's, read or written by the library only.
    id: [u32; N],
    #[allow(dead_code)] // Embree's, read or written by the library only.
    flags: [u32; N],
    /// The closest hits of the last closest-hit query.
    pub hits: HitPacket<N>,
    active: LaneMask,
}

/// The closest hits of a [`RayPacket`] in Embree 4.4's `RTCHitN` layout (9·4·`N` bytes:
/// `Ng` x/y/z, u, v, primID, geomID, instID, instPrimID), then the hit lanes: lane `i`
/// holds a hit when bit `i` of [`HitPacket::hit`] is set; the other lanes' values are
/// unspecified. The hit's `t` is its ray's `t_max` ([`RayPacket::hit`]).
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct HitPacket<const N: usize> {
    #[allow(dead_code)] // Embree's, read or written by the library only.
    ng: [[f32; N]; 3],
    /// Barycentric weight of vertex 1.
    pub u: [f32; N],
    /// Barycentric weight of vertex 2.
    pub v: [f32; N],
    /// Triangle index into the scene's triangle array.
    pub prim: [u32; N],
    /// Embree's geometry id: [`NO_GEOMETRY`] on a lane without a hit (Embree's backend
    /// only).
    #[allow(dead_code)]
    pub(super) geom: [u32; N],
    #[allow(dead_code)] // Embree's, read or written by the library only.
    inst: [[u32; N]; 2],
    /// The lanes that hit something.
    pub hit: LaneMask,
}

impl<const N: usize> Default for HitPacket<N>
where
    Lanes<N>: PacketWidth,
{
    fn default() -> Self {
        HitPacket {
            ng: [[0.0; N]; 3],
            u: [0.0; N],
            v: [0.0; N],
            prim: [u32::MAX; N],
            geom: [NO_GEOMETRY; N],
            inst: [[NO_GEOMETRY; N]; 2],
            hit: 0,
        }
    }
}

impl<const N: usize> Default for RayPacket<N>
where
    Lanes<N>: PacketWidth,
{
    #[inline]
    fn default() -> Self {
        RayPacket {
            org_x: [0.0; N],
            org_y: [0.0; N],
            org_z: [0.0; N],
            tnear: [0.0; N],
            dir_x: [0.0; N],
            dir_y: [0.0; N],
            dir_z: [0.0; N],
            time: [0.0; N],
            t_max: [0.0; N],
            mask: [u32::MAX; N],
            id: std::array::from_fn(|lane| lane as u32),
            flags: [0; N],
            hits: HitPacket::default(),
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
    #[inline]
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

    /// Lane `lane`'s closest hit after a closest-hit query, if any (its `t` is the lane's
    /// `t_max`, which the query lowered to it).
    #[inline]
    pub fn hit(&self, lane: usize) -> Option<RawHit> {
        (self.hits.hit & (1 << lane) != 0).then(|| RawHit {
            t: self.t_max[lane],
            prim: self.hits.prim[lane],
            u: self.hits.u[lane],
            v: self.hits.v[lane],
        })
    }

    /// Sets lane `lane`'s closest hit to `hit` (`None`: no hit) as a closest-hit query
    /// would: its `t` into the lane's `t_max` (a hit found by an earlier query, such as a
    /// camera ray's traced in its own packet).
    #[inline]
    pub fn set_hit(&mut self, lane: usize, hit: Option<RawHit>) {
        match hit {
            Some(h) => {
                self.t_max[lane] = h.t;
                self.hits.prim[lane] = h.prim;
                self.hits.u[lane] = h.u;
                self.hits.v[lane] = h.v;
                self.hits.hit |= 1 << lane;
            }
            None => self.hits.hit &= !(1 << lane),
        }
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

    /// The active lanes a backend can trace (see the module docs), tested over all lanes
    /// at once.
    #[inline]
    pub fn traceable(&self) -> LaneMask {
        let line = self.lines();
        self.active & mask_where::<N>(|i| (line[i] != 0) & (self.t_max[i] > 0.0))
    }

    /// The active lanes with a non-finite origin or direction, a zero direction or a NaN
    /// `t_max` (the rays [`crate::math::Ray::is_valid`] refuses).
    #[inline]
    pub fn untraceable(&self) -> LaneMask {
        let line = self.lines();
        self.active & mask_where::<N>(|i| (line[i] == 0) | self.t_max[i].is_nan())
    }

    /// Per lane, 1 where the origin and the direction are finite and the direction is not
    /// zero, else 0. Tested on the IEEE 754 binary32 bit patterns without the sign: a value
    /// is finite when they are below `0x7F80_0000` (∞'s), ±0 when they are 0; so the loop
    /// has no branch (and no NaN-dropping `max`).
    #[inline(always)]
    fn lines(&self) -> [u32; N] {
        let m = |x: f32| x.to_bits() & 0x7FFF_FFFF;
        let mut line = [0; N];
        for (i, l) in line.iter_mut().enumerate() {
            let d = m(self.dir_x[i]).max(m(self.dir_y[i])).max(m(self.dir_z[i]));
            let o = m(self.org_x[i]).max(m(self.org_y[i])).max(m(self.org_z[i]));
            *l = u32::from((o.max(d) < 0x7F80_0000) & (d != 0));
        }
        line
    }
}

/// The lanes `i < N` for which `test(i)` holds, as a loop over all `N` lanes.
#[inline(always)]
pub(super) fn mask_where<const N: usize>(test: impl Fn(usize) -> bool) -> LaneMask {
    let mut mask: LaneMask = 0;
    for i in 0..N {
        mask |= LaneMask::from(test(i)) << i;
    }
    mask
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
/// → hit), written as Embree writes them: the traceable lanes' hits (`t` into `t_max`),
/// every other lane without one.
#[inline]
pub fn closest_lanes<const N: usize>(
    rays: &mut RayPacket<N>,
    closest: impl Fn(Vec3, Vec3, f32) -> Option<RawHit>,
) where
    Lanes<N>: PacketWidth,
{
    rays.hits.hit = 0;
    for lane in lanes(rays.traceable()) {
        if let Some(h) = closest(rays.origin(lane), rays.dir(lane), rays.t_max[lane]) {
            rays.t_max[lane] = h.t;
            rays.hits.prim[lane] = h.prim;
            rays.hits.u[lane] = h.u;
            rays.hits.v[lane] = h.v;
            rays.hits.hit |= 1 << lane;
        }
    }
}

/// A packet's occluded lanes found lane by lane with a single-ray query (their `t_max`
/// set to `-∞`, as Embree marks them).
#[inline]
pub fn occluded_lanes<const N: usize>(
    rays: &mut RayPacket<N>,
    occluded: impl Fn(Vec3, Vec3, f32) -> bool,
) -> LaneMask
where
    Lanes<N>: PacketWidth,
{
    let mut blocked: LaneMask = 0;
    for lane in lanes(rays.traceable()) {
        if occluded(rays.origin(lane), rays.dir(lane), rays.t_max[lane]) {
            rays.t_max[lane] = f32::NEG_INFINITY;
            blocked |= 1 << lane;
        }
    }
    blocked
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coordinates that stress the lane tests: signed zeros, NaN, ±∞, the largest finite.
    const ODD: [f32; 7] = [
        0.0,
        -0.0,
        1.5,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
    ];

    /// The lane-loop masks against the single-ray rules lane by lane
    /// ([`crate::math::Ray::is_valid`] for `untraceable`), at both widths.
    fn masks_match_rules<const N: usize>()
    where
        Lanes<N>: PacketWidth,
    {
        let mut checked = 0;
        let mut k = 0usize;
        let mut odd = || {
            k = k.wrapping_mul(31).wrapping_add(7);
            ODD[k % ODD.len()]
        };
        for round in 0..64 {
            let mut p = RayPacket::<N>::new();
            for lane in 0..N {
                let o = Vec3::new(odd(), odd(), odd());
                let d = Vec3::new(odd(), odd(), odd());
                p.set(lane, o, d, odd());
            }
            p.set_active((round as u32).wrapping_mul(0x9E37_79B9) >> 7);
            for lane in 0..N {
                let (o, d, t) = (p.origin(lane), p.dir(lane), p.t_max[lane]);
                let on = p.active() & (1 << lane) != 0;
                let line = o.is_finite() && d.is_finite() && d != Vec3::ZERO;
                let ray = crate::math::Ray {
                    origin: o,
                    dir: d,
                    t_max: t,
                    skipped: 0.0,
                };
                let bit = 1 << lane;
                assert_eq!(
                    p.traceable() & bit != 0,
                    on && line && t > 0.0,
                    "{o} {d} {t}"
                );
                assert_eq!(
                    p.untraceable() & bit != 0,
                    on && !ray.is_valid(),
                    "{o} {d} {t}"
                );
                checked += usize::from(on && line && t > 0.0);
            }
        }
        assert!(checked > 0);
    }

    #[test]
    fn traceable_lanes_follow_the_single_ray_rules() {
        masks_match_rules::<8>();
        masks_match_rules::<16>();
    }

    /// The lane-by-lane queries write hits and occlusion into the packet as Embree does.
    #[test]
    fn lane_queries_write_into_the_packet() {
        let mut p = RayPacket::<8>::new();
        p.set(1, Vec3::ZERO, Vec3::X, 10.0);
        p.set(2, Vec3::ZERO, Vec3::ZERO, 10.0);
        p.set(3, Vec3::ZERO, Vec3::Y, 10.0);
        p.hits.hit = RayPacket::<8>::FULL;
        let hit = |_: Vec3, d: Vec3, _: f32| {
            (d == Vec3::X).then_some(RawHit {
                t: 2.5,
                prim: 7,
                u: 0.25,
                v: 0.5,
            })
        };
        closest_lanes(&mut p, hit);
        assert_eq!(p.hits.hit, 0b10);
        assert_eq!(p.hit(1), hit(Vec3::ZERO, Vec3::X, 10.0));
        assert_eq!((p.t_max[1], p.t_max[3]), (2.5, 10.0));
        assert_eq!(occluded_lanes(&mut p, |_, d, _| d != Vec3::X), 0b1000);
        assert_eq!(p.t_max[3], f32::NEG_INFINITY);
    }
}
