//! Ray queries on a committed [`EmbreeAccel`]: closest hit, occlusion, every hit along a
//! segment, and a bare benchmark loop. Rays use `tnear = 0`, `tfar = t_max` (units of the
//! unnormalised direction) and mask `0xFFFF_FFFF`; `t_max` NaN or ≤ 0 finds nothing.

use super::ffi::{collect_filter, CollectContext, QueryArgs, Ray, RayHit, INVALID_ID};
use super::EmbreeAccel;
use crate::accel::{HitList, RawHit};
use embree4_sys as sys;
use glam::Vec3;
use std::ffi::c_void;

impl EmbreeAccel {
    /// Closest hit in `[0, t_max)`.
    #[inline]
    pub fn closest(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<RawHit> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        let mut rh = RayHit::new(origin, dir, t_max);
        let mut args = QueryArgs::incoherent();
        // SAFETY: the scene is committed; `rh` has the library's 16-byte-aligned `RTCRayHit`
        // layout and `args` its `RTCIntersectArguments` layout (see the module docs).
        unsafe {
            sys::rtcIntersect1(
                self.scene,
                (&mut rh as *mut RayHit).cast(),
                (&mut args as *mut QueryArgs).cast(),
            );
        }
        (rh.hit.geom_id != INVALID_ID).then_some(RawHit {
            t: rh.ray.tfar,
            prim: rh.hit.prim_id,
            u: rh.hit.u,
            v: rh.hit.v,
        })
    }

    /// Any hit in `[0, t_max)`.
    #[inline]
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        if t_max.is_nan() || t_max <= 0.0 {
            return false;
        }
        let mut ray = Ray::new(origin, dir, t_max);
        let mut args = QueryArgs::incoherent();
        // SAFETY: as in `closest`, with the `RTCRay` and `RTCOccludedArguments` layouts.
        unsafe {
            sys::rtcOccluded1(
                self.scene,
                (&mut ray as *mut Ray).cast(),
                (&mut args as *mut QueryArgs).cast(),
            );
        }
        ray.tfar == f32::NEG_INFINITY
    }

    /// Every hit in `[0, t_max)` (up to [`crate::accel::MAX_HITS`]): an argument filter records
    /// each candidate and rejects it, so Embree keeps traversing until none is left.
    pub fn all_hits(&self, origin: Vec3, dir: Vec3, t_max: f32) -> HitList {
        let mut ctx = CollectContext {
            base: [INVALID_ID; 4],
            hits: HitList::default(),
        };
        if t_max.is_nan() || t_max <= 0.0 {
            return ctx.hits;
        }
        let mut rh = RayHit::new(origin, dir, t_max);
        let mut args = QueryArgs::incoherent();
        args.flags |= sys::RTCRayQueryFlags::INVOKE_ARGUMENT_FILTER.0;
        args.context = (&mut ctx as *mut CollectContext).cast();
        args.filter = collect_filter as *const c_void;
        // SAFETY: as in `closest`; `args.context` points at `ctx`, whose first field stands
        // in for the `RTCRayQueryContext` (instance ids, set invalid as
        // `rtcInitRayQueryContext` does) and which outlives the call; `collect_filter` only
        // reads through the pointers Embree passes it.
        unsafe {
            sys::rtcIntersect1(
                self.scene,
                (&mut rh as *mut RayHit).cast(),
                (&mut args as *mut QueryArgs).cast(),
            );
        }
        ctx.hits
    }

    /// Benchmark baseline: a bare `rtcIntersect1` loop over `(origin, dir)` rays with
    /// `t_max = ∞`, writing the hit `t` (or `+∞` on a miss) to `out_t`.
    ///
    /// # Panics
    /// If `out_t` is shorter than `rays`.
    pub fn raw_closest_batch(&self, rays: &[(Vec3, Vec3)], out_t: &mut [f32]) {
        assert!(out_t.len() >= rays.len(), "out_t shorter than rays");
        let mut args = QueryArgs::incoherent();
        for (&(o, d), t) in rays.iter().zip(out_t) {
            let mut rh = RayHit::new(o, d, f32::INFINITY);
            // SAFETY: as in `closest`.
            unsafe {
                sys::rtcIntersect1(
                    self.scene,
                    (&mut rh as *mut RayHit).cast(),
                    (&mut args as *mut QueryArgs).cast(),
                );
            }
            *t = if rh.hit.geom_id == INVALID_ID {
                f32::INFINITY
            } else {
                rh.ray.tfar
            };
        }
    }
}
