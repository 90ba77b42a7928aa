//! **The intersection layer.** Every ray in Iris goes through this module, which enforces
//! the conventions once:
//!
//! - Backends return only `t`, the triangle id and barycentrics; the hit is built here,
//!   identically for every backend.
//! - The geometric normal `ng = normalize((p1-p0)×(p2-p0))` points **out of the object**
//!   (counter-clockwise winding seen from outside) and is never flipped.
//! - `front_face = dot(ray.dir, ng) < 0`: the ray arrives from outside and enters.
//! - The shading normal is the interpolated vertex normal, flipped onto `ng`'s side if an
//!   artist's file has it pointing inward, or `ng` when the mesh has none.
//! - [`SurfaceHit::spawn_ray`] and [`SurfaceHit::spawn_ray_to`] hold the **only ray-offset
//!   rule** in the crate: the origin moves along `ng`, to the side the new ray leaves from,
//!   by [`OFFSET_SCALE`] × the largest coordinate magnitude of the hit triangle's vertices
//!   (which bound the hit position's). The error of a hit point computed from barycentrics
//!   is a few ulps of those magnitudes, so the offset is scale-free: a model at 1e-4 m and
//!   at 1e4 m behaves the same (Wächter & Binder 2019, "A Fast and Robust Method for
//!   Avoiding Self-Intersection", Ray Tracing Gems ch. 6, offset the origin by a multiple of
//!   the position's ulp; we use one magnitude for all three axes so coordinates near zero on
//!   a large triangle are covered too). No other module adds an epsilon.
//! - Alpha-masked (glTF `MASK`) hits below the cutoff are skipped here, so integrators never
//!   see them.
//! - Coincident surfaces ([`Scene::coincident`]): where two objects share a face (water
//!   filling a glass, two prisms in optical contact), the surfaces within [`MERGE_SCALE`] ×
//!   the coordinate magnitude of a hit, measured along its normal, are reported together so
//!   the caller crosses them as one interface, and the hit's offset grows to clear them all
//!   (otherwise the ray spawned past the first face would start behind the second and never
//!   see it).

use crate::accel::HitList;
use crate::math::Ray;
use crate::scene::{Scene, TriangleData};
use glam::{Vec2, Vec3};

/// Offset distance per unit of coordinate magnitude: 2^-18 ≈ 3.8e-6, i.e. 32 ulps of f32.
pub const OFFSET_SCALE: f32 = 1.0 / 262_144.0;

/// Half-length of the coincidence probe per unit of coordinate magnitude: 16 offsets
/// (2^-14 ≈ 6.1e-5). Faces closer than this along the normal are one interface; a real gap
/// that thin is below what the offset rule can resolve anyway.
pub const MERGE_SCALE: f32 = 16.0 * OFFSET_SCALE;

/// Most surfaces merged into one interface with a hit (besides the hit itself).
pub const MAX_COINCIDENT: usize = 4;

/// The other surfaces coincident with a hit, as hits of the same ray on them (same `t` and
/// `wo`, `front_face` for the ray's direction, offset widened like the hit's): one per
/// (material, side), never the hit's own (material, side) — an adjacent triangle of the
/// same surface met at a shared edge.
#[derive(Debug, Clone, Copy, Default)]
pub struct CoincidentSet {
    items: [Option<SurfaceHit>; MAX_COINCIDENT],
    len: usize,
}

impl CoincidentSet {
    /// The coincident surfaces.
    pub fn iter(&self) -> impl Iterator<Item = SurfaceHit> + '_ {
        self.items[..self.len].iter().flatten().copied()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    fn add(&mut self, c: SurfaceHit) {
        let dup = self
            .iter()
            .any(|o| o.material == c.material && o.front_face == c.front_face);
        if !dup && self.len < MAX_COINCIDENT {
            self.items[self.len] = Some(c);
            self.len += 1;
        }
    }
}

/// Shadow rays toward a point stop this fraction short of it (pbrt-v4 `ShadowEpsilon`), so a
/// surface *at* the target never occludes it.
pub const SHADOW_EPSILON: f32 = 1e-4;

/// At most this many alpha cut-outs are skipped along one ray (foliage cards stacked
/// deeper than this are treated as opaque).
const MAX_CUTOUTS: u32 = 64;

/// A ray–surface intersection with everything shading needs.
#[derive(Debug, Clone, Copy)]
pub struct SurfaceHit {
    /// Distance along the (unit-direction) ray.
    pub t: f32,
    /// World-space hit position (from barycentrics, not `o + t·d`).
    pub p: Vec3,
    /// Unit geometric normal, pointing out of the object.
    pub ng: Vec3,
    /// Unit shading normal, on the same side as `ng`.
    pub ns: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Triangle index.
    pub prim: u32,
    /// Material index.
    pub material: u32,
    /// The ray arrived from outside (`dot(dir, ng) < 0`).
    pub front_face: bool,
    /// Unit direction from the hit back toward where the ray came from.
    pub wo: Vec3,
    /// Offset distance for rays leaving this hit.
    offset: f32,
}

impl SurfaceHit {
    /// The origin for a ray leaving toward `dir`: offset along `ng` to that side.
    #[inline]
    fn offset_origin(&self, dir: Vec3) -> Vec3 {
        let side = if dir.dot(self.ng) >= 0.0 { 1.0 } else { -1.0 };
        self.p + self.ng * (side * self.offset)
    }

    /// A ray leaving the surface in unit direction `dir` (reflection, refraction, bounce).
    #[inline]
    pub fn spawn_ray(&self, dir: Vec3) -> Ray {
        Ray {
            origin: self.offset_origin(dir),
            dir,
            t_max: f32::INFINITY,
        }
    }

    /// A shadow ray toward the point `target`: `dir` is the un-normalised segment and
    /// `t_max = 1 − SHADOW_EPSILON`, so only blockers strictly between count.
    #[inline]
    pub fn spawn_ray_to(&self, target: Vec3) -> Ray {
        let origin = self.offset_origin(target - self.p);
        Ray {
            origin,
            dir: target - origin,
            t_max: 1.0 - SHADOW_EPSILON,
        }
    }
}

/// The unit geometric normal `normalize((p1−p0)×(p2−p0))` of a triangle, or `None` when it
/// has none (zero area, or non-finite corners). Tiny triangles whose f32 cross product
/// underflows (edges below ~1e-10 of any unit: |e|⁴ < f32::MIN_POSITIVE) are rescaled by
/// their longest edge component first, so the normal is scale-free like the offset rule.
/// Validation drops every triangle for which this is `None`, so hits never see one.
#[inline]
pub fn geometric_normal([p0, p1, p2]: [Vec3; 3]) -> Option<Vec3> {
    let (e1, e2) = (p1 - p0, p2 - p0);
    let n = e1.cross(e2);
    let rcp = n.length_recip();
    if rcp.is_finite() && rcp > 0.0 {
        return Some(n * rcp);
    }
    // Rare path: rescale (exact for a power of two) and retry.
    let m = e1.abs().max(e2.abs()).max_element();
    if m.is_nan() || m <= 0.0 || m.is_infinite() {
        return None;
    }
    let s = 2f32.powi(-m.log2().floor() as i32);
    let n = (e1 * s).cross(e2 * s);
    let rcp = n.length_recip();
    (rcp.is_finite() && rcp > 0.0).then(|| n * rcp)
}

impl Scene {
    /// A ray leaving the point `p` of triangle `prim` in direction `dir` (photons emitted
    /// from an emissive triangle), offset by the same rule as [`SurfaceHit::spawn_ray`].
    pub fn spawn_from_triangle(&self, prim: u32, p: Vec3, dir: Vec3) -> Ray {
        let [p0, p1, p2] = self.triangle_data[prim as usize].p;
        let ng = geometric_normal([p0, p1, p2]).unwrap_or(Vec3::Z);
        let mag = p0.abs().max(p1.abs()).max(p2.abs()).max_element();
        let side = if dir.dot(ng) >= 0.0 { 1.0 } else { -1.0 };
        Ray::new(p + ng * (side * mag * OFFSET_SCALE), dir)
    }

    /// Builds the hit record for a raw backend hit.
    fn make_hit(&self, ray: &Ray, t: f32, prim: u32, u: f32, v: f32) -> SurfaceHit {
        let td = &self.triangle_data[prim as usize];
        let [p0, p1, p2] = td.p;
        let w = 1.0 - u - v;
        let p = p0 * w + p1 * u + p2 * v;
        let ng = geometric_normal([p0, p1, p2]).unwrap_or(Vec3::Z);
        let ns = if td.info & TriangleData::HAS_NORMALS != 0 {
            let [i0, i1, i2] = self.triangles[prim as usize].map(|i| i as usize);
            let n = (self.normals[i0] * w + self.normals[i1] * u + self.normals[i2] * v)
                .normalize_or(ng);
            if n.dot(ng) < 0.0 {
                -n
            } else {
                n
            }
        } else {
            ng
        };
        let uv = if td.info & TriangleData::HAS_UVS != 0 {
            let [i0, i1, i2] = self.triangles[prim as usize].map(|i| i as usize);
            self.uvs[i0] * w + self.uvs[i1] * u + self.uvs[i2] * v
        } else {
            Vec2::ZERO
        };
        let mag = p0.abs().max(p1.abs()).max(p2.abs()).max_element();
        let inv_len = ray.dir.length_recip();
        SurfaceHit {
            t: t / inv_len,
            p,
            ng,
            ns,
            uv,
            prim,
            material: td.material(),
            front_face: ray.dir.dot(ng) < 0.0,
            wo: -ray.dir * inv_len,
            offset: mag * OFFSET_SCALE,
        }
    }

    /// Whether the hit is an alpha cut-out to be skipped.
    fn is_cut_out(&self, hit: &SurfaceHit) -> bool {
        self.has_cutouts && self.materials[hit.material as usize].is_cut_out(hit.uv, &self.images)
    }

    /// The closest visible surface along `ray`, skipping alpha cut-outs. A ray with a
    /// non-finite origin or direction (a numerical failure upstream) never reaches a
    /// backend: it misses, and whatever it then carries is caught by the film's guard.
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceHit> {
        if !ray.is_valid() {
            return None;
        }
        let mut r = *ray;
        let mut travelled = 0.0;
        for _ in 0..MAX_CUTOUTS {
            let raw = self.accel.closest(r.origin, r.dir, r.t_max)?;
            let mut hit = self.make_hit(&r, raw.t, raw.prim, raw.u, raw.v);
            if !self.is_cut_out(&hit) {
                if travelled > 0.0 {
                    hit.t += travelled;
                    hit.wo = -ray.dir.normalize();
                }
                return Some(hit);
            }
            travelled += hit.t;
            let next = hit.spawn_ray(r.dir.normalize());
            let scale = r.dir.length();
            r = Ray {
                t_max: (r.t_max - raw.t) * scale,
                ..next
            };
        }
        None
    }

    /// The surfaces coincident with `hit` (see the module docs), and `hit` with its offset
    /// widened so that rays spawned from it start beyond all of them, on either side.
    ///
    /// The probe is a segment along the hit's normal through `p`, ±[`MERGE_SCALE`] × the
    /// hit triangle's coordinate magnitude, so it finds coincident faces whatever the
    /// incoming ray's angle. Alpha cut-outs are ignored. Only triangles marked
    /// [`TriangleData::TOUCHES`] at scene build ([`crate::scene::contact`]) are probed: a
    /// scene without touching objects pays nothing.
    pub fn coincident(&self, hit: &SurfaceHit) -> (SurfaceHit, CoincidentSet) {
        let mut set = CoincidentSet::default();
        let mut out = *hit;
        let touches = self.triangle_data[hit.prim as usize].info & TriangleData::TOUCHES != 0;
        if !touches {
            return (out, set);
        }
        let half = hit.offset * (MERGE_SCALE / OFFSET_SCALE);
        let (probe, hits) = self.probe(hit.p, hit.ng, half);
        let dir = -hit.wo;
        for raw in hits.as_slice() {
            if raw.prim == hit.prim {
                continue;
            }
            let other = self.make_hit(&probe, raw.t, raw.prim, raw.u, raw.v);
            if self.is_cut_out(&other) {
                continue;
            }
            let front_face = dir.dot(other.ng) < 0.0;
            if other.material == hit.material && front_face == hit.front_face {
                continue; // the same surface: a neighbouring triangle at a shared edge
            }
            // The partner's plane lies `half − t` along ng from p; clear it by its own offset.
            let gap = (half - raw.t).abs();
            out.offset = out.offset.max(gap + other.offset.max(hit.offset));
            set.add(SurfaceHit {
                t: hit.t,
                wo: hit.wo,
                front_face,
                ..other
            });
        }
        for c in set.items[..set.len].iter_mut().flatten() {
            c.offset = out.offset;
        }
        (out, set)
    }

    /// Every surface crossing the segment `p ± half·ng` (the coincidence probe), with the
    /// probe ray (from `p + half·ng` along `−ng`).
    pub(crate) fn probe(&self, p: Vec3, ng: Vec3, half: f32) -> (Ray, HitList) {
        let probe = Ray {
            origin: p + ng * half,
            dir: -ng,
            t_max: 2.0 * half,
        };
        if half.is_nan() || half <= 0.0 {
            return (probe, HitList::default());
        }
        let hits = self.accel.all_hits(probe.origin, probe.dir, probe.t_max);
        (probe, hits)
    }

    /// Whether anything opaque blocks `ray` within `[0, t_max)`. A ray with a non-finite
    /// origin or direction is blocked (no light arrives along it).
    pub fn occluded(&self, ray: &Ray) -> bool {
        if !ray.is_valid() {
            return true;
        }
        if !self.has_cutouts {
            return self.accel.occluded(ray.origin, ray.dir, ray.t_max);
        }
        self.intersect(ray).is_some()
    }
}
