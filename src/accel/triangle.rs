//! Watertight ray–triangle intersection (Woop, Benthin & Wald 2013, "Watertight
//! Ray/Triangle Intersection", JCGT 2(1)), two-sided, with no epsilon: a hit is any
//! `t` in `[0, t_max)`. Used by the BVH and brute-force backends so both give the same
//! answer on shared edges. Barycentrics follow Embree: `p = (1-u-v)·p0 + u·p1 + v·p2`.

use glam::Vec3;

/// Per-ray constants of the watertight test (the shear that maps the ray to +z).
#[derive(Debug, Clone, Copy)]
pub struct RayPrep {
    origin: Vec3,
    kx: usize,
    ky: usize,
    kz: usize,
    sx: f32,
    sy: f32,
    sz: f32,
}

impl RayPrep {
    /// Precomputes the shear for a ray with non-zero direction.
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        let a = dir.abs();
        let kz = if a.x > a.y {
            if a.x > a.z {
                0
            } else {
                2
            }
        } else if a.y > a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if dir[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let sz = 1.0 / dir[kz];
        RayPrep {
            origin,
            kx,
            ky,
            kz,
            sx: dir[kx] * sz,
            sy: dir[ky] * sz,
            sz,
        }
    }

    /// Intersects one triangle; returns `(t, u, v)` if `0 <= t < t_max`.
    #[inline]
    pub fn intersect(&self, p0: Vec3, p1: Vec3, p2: Vec3, t_max: f32) -> Option<(f32, f32, f32)> {
        let (kx, ky, kz) = (self.kx, self.ky, self.kz);
        let a = p0 - self.origin;
        let b = p1 - self.origin;
        let c = p2 - self.origin;
        let ax = a[kx] - self.sx * a[kz];
        let ay = a[ky] - self.sy * a[kz];
        let bx = b[kx] - self.sx * b[kz];
        let by = b[ky] - self.sy * b[kz];
        let cx = c[kx] - self.sx * c[kz];
        let cy = c[ky] - self.sy * c[kz];
        let mut e0 = cx * by - cy * bx;
        let mut e1 = ax * cy - ay * cx;
        let mut e2 = bx * ay - by * ax;
        // Fall back to double precision on exact zeros (edges), as the paper prescribes.
        if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 {
            e0 = (cx as f64 * by as f64 - cy as f64 * bx as f64) as f32;
            e1 = (ax as f64 * cy as f64 - ay as f64 * cx as f64) as f32;
            e2 = (bx as f64 * ay as f64 - by as f64 * ax as f64) as f32;
        }
        if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
            return None;
        }
        let det = e0 + e1 + e2;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let az = self.sz * a[kz];
        let bz = self.sz * b[kz];
        let cz = self.sz * c[kz];
        let t_scaled = e0 * az + e1 * bz + e2 * cz;
        // Two-sided: compare with the sign of det folded in.
        let (t_scaled, det_abs) = if det < 0.0 {
            (-t_scaled, -det)
        } else {
            (t_scaled, det)
        };
        if t_scaled < 0.0 || t_scaled >= t_max * det_abs {
            return None;
        }
        let inv = 1.0 / det;
        let t = t_scaled / det_abs;
        if t.is_nan() || t >= t_max {
            return None;
        }
        Some((t, e1 * inv, e2 * inv))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_centre_with_barycentrics() {
        let (p0, p1, p2) = (Vec3::ZERO, Vec3::X, Vec3::Y);
        let o = Vec3::new(0.25, 0.25, 1.0);
        let r = RayPrep::new(o, -Vec3::Z);
        let (t, u, v) = r.intersect(p0, p1, p2, f32::INFINITY).unwrap();
        assert!((t - 1.0).abs() < 1e-6 && (u - 0.25).abs() < 1e-6 && (v - 0.25).abs() < 1e-6);
        // Two-sided: from below too.
        let r = RayPrep::new(Vec3::new(0.25, 0.25, -2.0), Vec3::Z);
        assert!((r.intersect(p0, p1, p2, f32::INFINITY).unwrap().0 - 2.0).abs() < 1e-6);
        // Behind the origin or beyond t_max: miss.
        assert!(RayPrep::new(o, Vec3::Z)
            .intersect(p0, p1, p2, f32::INFINITY)
            .is_none());
        assert!(r.intersect(p0, p1, p2, 1.5).is_none());
    }

    #[test]
    fn shared_edge_is_watertight() {
        // Two triangles sharing the diagonal; rays through the diagonal must hit one.
        let q = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        for i in 0..1000 {
            let s = i as f32 / 999.0;
            let o = Vec3::new(s, s, 1.0);
            let r = RayPrep::new(o, Vec3::new(0.0, 0.0, -1.0));
            let h1 = r.intersect(q[0], q[1], q[2], f32::INFINITY);
            let h2 = r.intersect(q[0], q[2], q[3], f32::INFINITY);
            assert!(h1.is_some() || h2.is_some(), "leak at s={s}");
        }
    }
}
