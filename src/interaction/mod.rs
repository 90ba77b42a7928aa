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
//!   (which bound the hit position's; [`Triangle::offset`]). The error of a hit point computed from barycentrics
//!   is a few ulps of those magnitudes, so the offset is scale-free: a model at 1e-4 m and
//!   at 1e4 m behaves the same (Wächter & Binder 2019, "A Fast and Robust Method for
//!   Avoiding Self-Intersection", Ray Tracing Gems ch. 6, offset the origin by a multiple of
//!   the position's ulp; we use one magnitude for all three axes so coordinates near zero on
//!   a large triangle are covered too). No other module adds an epsilon. A spawned ray
//!   records the part of its line the offset skipped ([`Ray::skipped`]) for media to count,
//!   and a medium's scattering event within that offset of a surface is kept as a depth
//!   below the surface's plane ([`BandPoint`]), so no ray from it starts on the wrong side.
//! - Alpha-masked (glTF `MASK`) hits below the cutoff are skipped here, so integrators never
//!   see them.
//! - Coincident surfaces ([`Scene::coincident`]): where two objects share a face (water
//!   filling a glass, two prisms in optical contact), the surfaces within [`MERGE_SCALE`] ×
//!   the coordinate magnitude of a hit, measured along its normal, are reported together so
//!   the caller crosses them as one interface, and the hit's offset grows to clear them all
//!   (otherwise the ray spawned past the first face would start behind the second and never
//!   see it).
//! - Packets ([`Scene::intersect_packet`], [`Scene::occluded_packet`]): up to 16 rays in
//!   one backend query (Embree `rtcIntersect8/16`, `rtcOccluded8/16`) give lane by lane
//!   exactly the answers of [`Scene::intersect`] and [`Scene::occluded`]: the backends'
//!   packet hits equal their single-ray hits bit for bit (`tests/accel/accel_packets.rs`), the
//!   hit record is built by the same code ([`Scene::lane_hit`]), and a lane whose first
//!   hit is an alpha cut-out is traced again alone.

mod band;

use band::skipped;
pub use band::{BandPoint, Leave};

use crate::accel::packet::{lanes, Coherence, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::accel::RawHit;
use crate::material::TexCoords;
use crate::math::Ray;
use crate::scene::triangle::{geometric_normal, MERGE_SCALE, OFFSET_SCALE};
use crate::scene::{Scene, Triangle};
use glam::Vec3;

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

    /// The faces crossed with the hit: what shading reads of them (material and side).
    pub fn faces(&self) -> CoincidentFaces {
        let mut faces = CoincidentFaces::default();
        for c in self.iter() {
            faces.items[faces.len as usize] = Face {
                material: c.material,
                front_face: c.front_face,
            };
            faces.len += 1;
        }
        faces
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

/// A coincident face crossed with a hit: its material and the side the ray meets
/// (`front_face` for the ray's direction, as [`SurfaceHit::front_face`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Face {
    /// Material index.
    pub material: u32,
    /// Whether the ray enters it.
    pub front_face: bool,
}

/// The faces of a [`CoincidentSet`] as the per-hit step carries them: 40 bytes instead of
/// the full hits, which only [`crate::shading::meet`] reads.
#[derive(Debug, Clone, Copy, Default)]
pub struct CoincidentFaces {
    items: [Face; MAX_COINCIDENT],
    len: u8,
}

impl CoincidentFaces {
    /// The faces.
    pub fn iter(&self) -> impl Iterator<Item = Face> + '_ {
        self.items[..self.len as usize].iter().copied()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
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
    /// Texture coordinates (TEXCOORD_0 and TEXCOORD_1).
    pub uv: TexCoords,
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

/// The offset rule on plain coordinates (what [`SurfaceHit::spawn_ray`] applies): the
/// origin of a ray leaving the point `p` of a surface with unit geometric normal `ng` toward
/// `dir`, moved by `offset` along `ng` to the side `dir` leaves to. For callers that hold
/// their hits as arrays over lanes (the SoA path kernel); the same operations in the same
/// order as the hit's own, so both give the same origin bit for bit.
#[inline(always)]
pub fn offset_point(p: [f32; 3], ng: [f32; 3], offset: f32, dir: [f32; 3]) -> [f32; 3] {
    let along = dir[0] * ng[0] + dir[1] * ng[1] + dir[2] * ng[2];
    let side = if along >= 0.0 { 1.0 } else { -1.0 };
    let s = side * offset;
    [p[0] + ng[0] * s, p[1] + ng[1] * s, p[2] + ng[2] * s]
}

impl SurfaceHit {
    /// The origin for a ray leaving toward `dir`: offset along `ng` to that side
    /// ([`offset_point`]).
    #[inline]
    fn offset_origin(&self, dir: Vec3) -> Vec3 {
        let (p, ng) = (self.p.to_array(), self.ng.to_array());
        Vec3::from_array(offset_point(p, ng, self.offset, dir.to_array()))
    }

    /// A point inside a medium where a path scatters off no surface, seen along `wo` (unit,
    /// back toward where the path came from): rays leave from `p` itself, as nothing is
    /// there to re-hit. It names no triangle or material (`prim` and `material` are
    /// `u32::MAX`); only its position, `wo` and the spawn methods are meaningful.
    pub fn in_medium(p: Vec3, wo: Vec3) -> SurfaceHit {
        SurfaceHit {
            t: 0.0,
            p,
            ng: wo,
            ns: wo,
            uv: TexCoords::default(),
            prim: u32::MAX,
            material: u32::MAX,
            front_face: true,
            wo,
            offset: 0.0,
        }
    }

    /// A ray leaving the surface in unit direction `dir` (reflection, refraction, bounce);
    /// its [`Ray::skipped`] is the part of its line the offset skipped.
    #[inline]
    pub fn spawn_ray(&self, dir: Vec3) -> Ray {
        Ray {
            origin: self.offset_origin(dir),
            dir,
            t_max: f32::INFINITY,
            skipped: skipped(self.offset, dir, self.ng),
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
            skipped: skipped(self.offset, target - self.p, self.ng),
        }
    }
}

impl Scene {
    /// A ray leaving the point `p` of triangle `prim` in direction `dir` (photons emitted
    /// from an emissive triangle), offset by the same rule as [`SurfaceHit::spawn_ray`].
    pub fn spawn_from_triangle(&self, prim: u32, p: Vec3, dir: Vec3) -> Ray {
        let t = self.triangle(prim);
        let ng = geometric_normal(t.p).unwrap_or(Vec3::Z);
        let side = if dir.dot(ng) >= 0.0 { 1.0 } else { -1.0 };
        let offset = t.magnitude() * OFFSET_SCALE;
        Ray {
            skipped: skipped(offset, dir, ng),
            ..Ray::new(p + ng * (side * offset), dir)
        }
    }

    /// Builds the hit record for a raw backend hit.
    fn make_hit(&self, ray: &Ray, t: f32, prim: u32, u: f32, v: f32) -> SurfaceHit {
        let tri = self.triangle(prim);
        let [p0, p1, p2] = tri.p;
        let w = 1.0 - u - v;
        let p = p0 * w + p1 * u + p2 * v;
        let ng = geometric_normal([p0, p1, p2]).unwrap_or(Vec3::Z);
        let ns = if tri.has(Triangle::HAS_NORMALS) {
            let normals = &self.vertices().normals;
            let [i0, i1, i2] = tri.vertices.map(|i| i as usize);
            let n = (normals[i0] * w + normals[i1] * u + normals[i2] * v).normalize_or(ng);
            if n.dot(ng) < 0.0 {
                -n
            } else {
                n
            }
        } else {
            ng
        };
        let inv_len = ray.dir.length_recip();
        SurfaceHit {
            t: t / inv_len,
            p,
            ng,
            ns,
            uv: self.tex_coords(prim, [w, u, v]),
            prim,
            material: tri.material(),
            front_face: ray.dir.dot(ng) < 0.0,
            wo: -ray.dir * inv_len,
            offset: tri.offset(),
        }
    }

    /// Whether the hit is an alpha cut-out to be skipped.
    fn is_cut_out(&self, hit: &SurfaceHit) -> bool {
        self.has_cutouts()
            && self
                .material(hit.material)
                .is_cut_out(&self.textures_at(hit.uv))
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
            let raw = self.accel().closest(r.origin, r.dir, r.t_max)?;
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
    /// [`Triangle::TOUCHES`] at scene build ([`crate::scene::contact`]) are probed: a
    /// scene without touching objects pays nothing.
    pub fn coincident(&self, hit: &SurfaceHit) -> (SurfaceHit, CoincidentSet) {
        let mut set = CoincidentSet::default();
        let mut out = *hit;
        let touches = self.triangle(hit.prim).has(Triangle::TOUCHES);
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

    /// Whether anything opaque blocks `ray` within `[0, t_max)`. A ray with a non-finite
    /// origin or direction is blocked (no light arrives along it).
    pub fn occluded(&self, ray: &Ray) -> bool {
        if !ray.is_valid() {
            return true;
        }
        if !self.has_cutouts() {
            return self.accel().occluded(ray.origin, ray.dir, ray.t_max);
        }
        self.intersect(ray).is_some()
    }
}

impl Scene {
    /// The backend's closest hits of the packet `rays`, written into it; lane `i`'s
    /// [`Scene::intersect`] is then [`Scene::lane_hit`] of its ray and `rays.hit(i)`.
    /// Invalid lanes ([`RayPacket::untraceable`]) get none. With [`Coherence::Incoherent`]
    /// each lane's hit is the single-ray hit exactly; Embree's coherent (frustum) traversal
    /// visits nodes in another order and may break an exact tie between coplanar
    /// overlapping triangles the other way.
    #[inline]
    pub fn intersect_packet<const N: usize>(&self, rays: &mut RayPacket<N>, coherence: Coherence)
    where
        Lanes<N>: PacketWidth,
    {
        self.accel().closest_packet(rays, coherence);
    }

    /// [`Scene::intersect`] of `ray` given the backend's closest hit `raw` along it (a lane
    /// of [`Scene::intersect_packet`]): the same hit record, and past an alpha cut-out the
    /// ray traced again alone.
    #[inline]
    pub fn lane_hit(&self, ray: &Ray, raw: Option<RawHit>) -> Option<SurfaceHit> {
        let r = raw?;
        let hit = self.make_hit(ray, r.t, r.prim, r.u, r.v);
        if self.is_cut_out(&hit) {
            self.intersect(ray)
        } else {
            Some(hit)
        }
    }

    /// [`Scene::occluded`] of every active lane of `rays` in one packet query: bit `i` set
    /// when lane `i` is blocked (an invalid ray is blocked; an inactive lane is not). With
    /// alpha cut-outs in the scene, lane by lane. The query may write into `rays` (see
    /// [`crate::accel::packet`]).
    pub fn occluded_packet<const N: usize>(&self, rays: &mut RayPacket<N>) -> LaneMask
    where
        Lanes<N>: PacketWidth,
    {
        if self.has_cutouts() {
            let mut blocked: LaneMask = 0;
            for lane in lanes(rays.active()) {
                let ray = Ray {
                    origin: rays.origin(lane),
                    dir: rays.dir(lane),
                    t_max: rays.t_max[lane],
                    skipped: 0.0,
                };
                if self.occluded(&ray) {
                    blocked |= 1 << lane;
                }
            }
            return blocked;
        }
        // The backends leave untraceable lanes unoccluded; the single-ray query blocks them.
        let invalid = rays.untraceable();
        invalid | self.accel().occluded_packet(rays, Coherence::Incoherent)
    }
}
