//! The offset band of a surface ([`BandPoint`]): the layer between a surface's plane and
//! the origin of the rays spawned from it ([`SurfaceHit::spawn_ray`]), where f32 positions
//! cannot tell which side of the surface a point is on. A medium whose mean free path is
//! shorter than the offset scatters there; the band keeps such a point as its depth below
//! the plane, so every ray leaving it stays on its side. Distances in world units; the band
//! is taken as planar at the hit (its thickness is a few ulps of the coordinates).

use super::SurfaceHit;
use crate::math::Ray;
use glam::Vec3;

/// Smallest |cos θ| between a ray and a surface's normal the band counts with: a ray more
/// grazing than 1/16 counts its skipped part and band depths as if at that angle, so the
/// band's points stay within 16 offsets of the hit (its planar approximation).
const MIN_BAND_COS: f32 = 1.0 / 16.0;

/// The length of the line along `dir` (any length) between a surface with unit normal `ng`
/// and a point `offset` off it ([`SurfaceHit::spawn_ray`]'s origin), the angle capped at
/// [`MIN_BAND_COS`].
#[inline]
pub(super) fn skipped(offset: f32, dir: Vec3, ng: Vec3) -> f32 {
    let cos = dir.normalize_or_zero().dot(ng).abs();
    offset / cos.max(MIN_BAND_COS)
}

impl SurfaceHit {
    /// The same surface point met by a ray travelling along the unit direction `dir`, `t`
    /// from where that ray started: what a path leaving a [`BandPoint`] toward its surface
    /// arrives at.
    pub fn met_along(&self, dir: Vec3, t: f32) -> SurfaceHit {
        SurfaceHit {
            t,
            wo: -dir,
            front_face: dir.dot(self.ng) < 0.0,
            ..*self
        }
    }

    /// Whether the ray that met this surface started within its band (at most its offset
    /// away), so that which side of the surface it started on is not resolved.
    pub fn is_within_band(&self) -> bool {
        self.t <= self.offset
    }

    /// The band behind the origin of `ray`, which was spawned from this surface: the point
    /// at parameter `t` ∈ [−`ray.skipped`, 0) of the ray's unit-direction line, if it lies
    /// between the surface and the origin.
    pub fn band_behind(&self, ray: &Ray, t: f32) -> Option<BandPoint> {
        let dir = ray.dir.normalize();
        let side = if dir.dot(self.ng) >= 0.0 { 1.0 } else { -1.0 };
        let depth = self.offset + t * (dir.dot(self.ng) * side).max(MIN_BAND_COS);
        BandPoint::new(*self, side, depth)
    }

    /// The band before this hit: the point `before` short of it along the ray that met it,
    /// if it lies within the band.
    pub fn band_before(&self, before: f32) -> Option<BandPoint> {
        let side = if self.wo.dot(self.ng) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let depth = before * (self.wo.dot(self.ng) * side).max(MIN_BAND_COS);
        BandPoint::new(*self, side, depth)
    }
}

/// A point in a medium within a surface's offset band (module docs), kept as its depth below
/// the surface's plane. Rays leaving it ([`Leave`]) go deeper into the medium from the
/// surface's offset origin, with the rest of the band as their [`Ray::skipped`], or toward
/// the surface by meeting it after the distance left to its plane.
#[derive(Debug, Clone, Copy)]
pub struct BandPoint {
    surface: SurfaceHit,
    /// +1: the point lies on `ng`'s side of the surface, −1 behind it.
    side: f32,
    /// Distance from the surface's plane, in (0, offset].
    depth: f32,
}

/// How a ray leaves a [`BandPoint`].
#[derive(Debug, Clone, Copy)]
pub enum Leave {
    /// Away from the surface: this ray, from the surface's offset origin, with the band's
    /// rest as its [`Ray::skipped`].
    Ray(Ray),
    /// Toward the surface: it meets `hit` (re-met along the ray's direction) after
    /// `distance` in the medium.
    Meets {
        /// The surface, met along the direction.
        hit: SurfaceHit,
        /// Distance to it.
        distance: f32,
    },
}

impl BandPoint {
    fn new(surface: SurfaceHit, side: f32, depth: f32) -> Option<BandPoint> {
        (depth > 0.0 && depth <= surface.offset).then_some(BandPoint {
            surface,
            side,
            depth,
        })
    }

    /// The surface whose band it is in.
    pub fn surface(&self) -> &SurfaceHit {
        &self.surface
    }

    /// Its position (world space): at the hit, `depth` off the plane.
    pub fn position(&self) -> Vec3 {
        self.surface.p + self.surface.ng * (self.side * self.depth)
    }

    /// How a ray in the unit direction `dir` leaves it.
    pub fn leave(&self, dir: Vec3) -> Leave {
        self.leaving(dir, |s| s.spawn_ray(dir))
    }

    /// How a shadow ray toward `target` leaves it: away from the surface, the surface's
    /// [`SurfaceHit::spawn_ray_to`] with the band's rest skipped; toward it,
    /// [`Leave::Meets`].
    pub fn leave_to(&self, target: Vec3) -> Leave {
        let dir = (target - self.position()).normalize_or_zero();
        self.leaving(dir, |s| s.spawn_ray_to(target))
    }

    fn leaving(&self, dir: Vec3, spawn: impl Fn(&SurfaceHit) -> Ray) -> Leave {
        let away = dir.dot(self.surface.ng) * self.side;
        let cos = away.abs().max(MIN_BAND_COS);
        if away > 0.0 {
            Leave::Ray(Ray {
                skipped: (self.surface.offset - self.depth) / cos,
                ..spawn(&self.surface)
            })
        } else {
            let distance = self.depth / cos;
            Leave::Meets {
                hit: self.surface.met_along(dir, distance),
                distance,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::TexCoords;

    /// A hit on the plane z = 0 (normal +Z) at the origin, met from above, offset `offset`.
    fn hit(offset: f32) -> SurfaceHit {
        SurfaceHit {
            t: 2.0,
            p: Vec3::ZERO,
            ng: Vec3::Z,
            ns: Vec3::Z,
            uv: TexCoords::default(),
            prim: 0,
            material: 0,
            front_face: true,
            wo: Vec3::Z,
            offset,
        }
    }

    /// A spawned ray records the line its offset skipped: offset / |cos θ| (capped at 16
    /// offsets when grazing), to either side; a ray from a point in a medium skips nothing.
    #[test]
    fn spawned_rays_record_what_the_offset_skipped() {
        let h = hit(1e-3);
        let d = Vec3::new(0.6, 0.0, -0.8);
        let r = h.spawn_ray(d);
        assert!((r.skipped - 1e-3 / 0.8).abs() < 1e-9);
        assert!((r.origin.z + 1e-3).abs() < 1e-9 && (r.at(-r.skipped).z).abs() < 1e-9);
        let grazing = h.spawn_ray(Vec3::new(1.0, 0.0, 1e-4).normalize());
        assert!((grazing.skipped - 16e-3).abs() < 1e-7);
        let to = h.spawn_ray_to(Vec3::new(0.0, 0.0, 5.0));
        assert!((to.skipped - 1e-3).abs() < 1e-9);
        assert_eq!(
            SurfaceHit::in_medium(Vec3::ONE, Vec3::X)
                .spawn_ray(Vec3::Y)
                .skipped,
            0.0
        );
    }

    /// A point of the band keeps its side: rays away from the surface start at its offset
    /// origin with the rest of the band skipped, rays toward it meet it after the distance
    /// left to the plane (not traced, so never from the wrong side), whatever the depth.
    #[test]
    fn a_band_point_leaves_on_its_side() {
        let h = hit(1e-3);
        // Behind the origin of a ray spawned into the surface (z < 0 side).
        let r = h.spawn_ray(-Vec3::Z);
        let b = h.band_behind(&r, -0.25e-3).expect("in the band");
        assert!((b.position().z + 0.75e-3).abs() < 1e-9);
        match b.leave(-Vec3::Z) {
            Leave::Ray(ray) => {
                assert!((ray.origin.z + 1e-3).abs() < 1e-9);
                assert!((ray.skipped - 0.25e-3).abs() < 1e-9);
            }
            other => panic!("{other:?}"),
        }
        match b.leave(Vec3::new(0.6, 0.0, 0.8)) {
            Leave::Meets { hit: m, distance } => {
                assert!((distance - 0.75e-3 / 0.8).abs() < 1e-9);
                assert!(!m.front_face && m.wo.z < 0.0);
            }
            other => panic!("{other:?}"),
        }
        // Before a hit met from above (z > 0 side), and outside the band.
        let b = h.band_before(0.5e-3).expect("in the band");
        assert!((b.position().z - 0.5e-3).abs() < 1e-9);
        assert!(h.band_before(2e-3).is_none());
        assert!(matches!(b.leave(Vec3::Z), Leave::Ray(_)));
        assert!(matches!(
            b.leave_to(Vec3::new(0.0, 0.0, -4.0)),
            Leave::Meets { .. }
        ));
    }
}
