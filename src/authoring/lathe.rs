//! Surfaces of revolution about +Y, and the drinking glass with its water built from them.
//!
//! A solid of revolution is given by its **profile**: a path in the half plane (r ≥ 0, y)
//! that is swept around the Y axis in `segments` equal steps (angle a, point
//! `(r·cos a, y, r·sin a)`). The profile is split into **bands**; inside a band vertices are
//! shared (smooth normals, one per profile point), between bands they are duplicated with
//! each band's own normal (a sharp crease), but positions are computed by the same
//! expression, so they are bit-identical and the solid stays watertight after welding.
//!
//! Orientation: with the profile running so that the solid lies on its **left** when r
//! points right and y up (e.g. outward along the bottom, up the outer wall, down the inner
//! wall), the triangles `(Pᵢ,k) (Pᵢ₊₁,k) (Pᵢ₊₁,k+1)` and `(Pᵢ,k) (Pᵢ₊₁,k+1) (Pᵢ,k+1)`
//! wind counter-clockwise seen from outside: their normal is ≈ tangent × ∂/∂a, which is
//! outward. A profile point with r = 0 is one vertex on the axis (a triangle fan).
//!
//! Angles use [`sin_cos`], a Taylor series in `f64` with `+ − × ÷` only, so the output is
//! bit-identical on every platform (platform `sin`/`cos` need not be correctly rounded).
//! Units: metres.

use super::shapes::TriMesh;
use glam::{DVec2, DVec3};

/// sin x and cos x for any finite x (radians), from the Taylor series after reducing x to
/// [−π, π]; absolute error below 4e-15 for |x| ≤ 20 (the largest term there is π³/3! ≈ 5.2, so the
/// cancellation costs a few ulp of 5; the series is cut where π⁴⁰/40! < 1e-28).
pub fn sin_cos(x: f64) -> (f64, f64) {
    use std::f64::consts::PI;
    let turns = (x / (2.0 * PI)).round();
    let r = x - turns * (2.0 * PI);
    let (mut s, mut c, mut term) = (0.0, 0.0, 1.0);
    for n in 0..40u32 {
        match n % 4 {
            0 => c += term,
            1 => s += term,
            2 => c -= term,
            _ => s -= term,
        }
        term = term * r / f64::from(n + 1);
    }
    (s, c)
}

/// One profile point: radius and height (metres) and the unit outward profile normal
/// `(n_r, n_y)` (the 3-D normal is `(n_r·cos a, n_y, n_r·sin a)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfilePoint {
    /// Distance from the Y axis, ≥ 0; exactly 0 puts a single vertex on the axis.
    pub r: f64,
    /// Height.
    pub y: f64,
    /// Outward normal in the (r, y) plane.
    pub normal: DVec2,
}

/// Sweeps profiles around +Y with a fixed number of angular segments.
#[derive(Debug, Clone)]
pub struct Lathe {
    /// (sin a, cos a) for a = 2πk/segments, k = 0 … segments−1.
    angles: Vec<(f64, f64)>,
}

impl Lathe {
    /// A lathe with `segments` ≥ 3 angular steps (clamped).
    pub fn new(segments: u32) -> Self {
        let n = segments.max(3);
        let step = 2.0 * std::f64::consts::PI / f64::from(n);
        Lathe {
            angles: (0..n).map(|k| sin_cos(step * f64::from(k))).collect(),
        }
    }

    /// Number of angular segments.
    pub fn segments(&self) -> usize {
        self.angles.len()
    }

    /// Appends one smooth band (≥ 2 profile points, in profile order) to `mesh`.
    pub fn band(&self, mesh: &mut TriMesh, profile: &[ProfilePoint]) {
        let n = self.angles.len();
        // rings[i][k] = vertex index of profile point i at angle k.
        let rings: Vec<Vec<u32>> = profile
            .iter()
            .map(|p| {
                if p.r == 0.0 {
                    let v = push(mesh, DVec3::new(0.0, p.y, 0.0), DVec3::Y * p.normal.y);
                    vec![v; n]
                } else {
                    self.angles
                        .iter()
                        .map(|&(s, c)| {
                            let pos = DVec3::new(p.r * c, p.y, p.r * s);
                            let nrm = DVec3::new(p.normal.x * c, p.normal.y, p.normal.x * s);
                            push(mesh, pos, nrm.normalize())
                        })
                        .collect()
                }
            })
            .collect();
        for i in 0..profile.len().saturating_sub(1) {
            let (a, b) = (&rings[i], &rings[i + 1]);
            for k in 0..n {
                let k1 = (k + 1) % n;
                if profile[i + 1].r != 0.0 {
                    mesh.indices.push([a[k], b[k], b[k1]]);
                }
                if profile[i].r != 0.0 {
                    mesh.indices.push([a[k], b[k1], a[k1]]);
                }
            }
        }
    }
}

fn push(mesh: &mut TriMesh, p: DVec3, n: DVec3) -> u32 {
    mesh.positions.push(p.as_vec3());
    mesh.normals.push(n.as_vec3());
    (mesh.positions.len() - 1) as u32
}

/// `mesh` seen from the other side: winding reversed and normals negated (same positions).
pub fn reversed(mesh: &TriMesh) -> TriMesh {
    TriMesh {
        positions: mesh.positions.clone(),
        normals: mesh.normals.iter().map(|&n| -n).collect(),
        indices: mesh.indices.iter().map(|&[a, b, c]| [a, c, b]).collect(),
    }
}

/// Appends all of `part` to `mesh`.
pub fn append(mesh: &mut TriMesh, part: &TriMesh) {
    let base = mesh.positions.len() as u32;
    mesh.positions.extend_from_slice(&part.positions);
    mesh.normals.extend_from_slice(&part.normals);
    mesh.indices
        .extend(part.indices.iter().map(|t| t.map(|i| i + base)));
}

/// Dimensions of a tapered tumbler (metres). The outer wall is a cone from radius
/// `bottom_radius` at y = 0 to `top_radius` at y = `height`; the inner wall is the outer
/// one moved `wall` inwards (horizontally); the rim is a half circle of diameter `wall`
/// joining them, its top at y = `height`; the cavity floor is at y = `base`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tumbler {
    /// Outer radius at the foot.
    pub bottom_radius: f64,
    /// Outer radius at the top of the wall (extrapolated to y = `height`).
    pub top_radius: f64,
    /// Overall height.
    pub height: f64,
    /// Horizontal wall thickness.
    pub wall: f64,
    /// Thickness of the solid base (height of the cavity floor).
    pub base: f64,
    /// Height of the water surface, in (base, height − wall/2).
    pub water_level: f64,
    /// Angular segments.
    pub segments: u32,
    /// Segments of the rim's half circle.
    pub rim_segments: u32,
}

/// The glass and the water, each a closed outward-wound solid. The water's side and
/// bottom triangles are the glass's inner wall (below the water level) and cavity floor
/// with the winding reversed: same vertex positions, opposite normals.
#[derive(Debug, Clone, PartialEq)]
pub struct GlassOfWater {
    /// The glass solid.
    pub glass: TriMesh,
    /// The water solid.
    pub water: TriMesh,
    /// The water's triangles shared with the glass (as wound in the glass): the
    /// glass–water interface.
    pub interface: TriMesh,
}

impl Tumbler {
    /// Outer radius at height y (linear taper).
    fn outer(&self, y: f64) -> f64 {
        self.bottom_radius + (self.top_radius - self.bottom_radius) * (y / self.height)
    }

    /// Builds the glass and the water.
    pub fn build(&self) -> GlassOfWater {
        let lathe = Lathe::new(self.segments);
        let rim_y = self.height - self.wall / 2.0;
        // Outward normal of the outer cone (pointing away from the axis, slightly down).
        let slope = (self.top_radius - self.bottom_radius) / self.height;
        let out_n = DVec2::new(1.0, -slope).normalize();
        let pt = |r: f64, y: f64, normal: DVec2| ProfilePoint { r, y, normal };
        let (outer_foot, outer_top) = (self.outer(0.0), self.outer(rim_y));
        let inner = |y: f64| self.outer(y) - self.wall;
        let (inner_top, inner_water, inner_floor) =
            (inner(rim_y), inner(self.water_level), inner(self.base));

        let mut glass = TriMesh::default();
        // Foot: outward from the axis along y = 0, facing down.
        lathe.band(
            &mut glass,
            &[pt(0.0, 0.0, -DVec2::Y), pt(outer_foot, 0.0, -DVec2::Y)],
        );
        lathe.band(
            &mut glass,
            &[pt(outer_foot, 0.0, out_n), pt(outer_top, rim_y, out_n)],
        );
        // Rim: half circle from the outer to the inner wall top; its end points are the
        // walls' own values so positions match bit for bit.
        let centre = DVec2::new((outer_top + inner_top) / 2.0, rim_y);
        let radius = (outer_top - inner_top) / 2.0;
        let m = self.rim_segments.max(2);
        let rim: Vec<ProfilePoint> = (0..=m)
            .map(|j| {
                let (s, c) = sin_cos(std::f64::consts::PI * f64::from(j) / f64::from(m));
                let p = match j {
                    0 => DVec2::new(outer_top, rim_y),
                    j if j == m => DVec2::new(inner_top, rim_y),
                    _ => centre + radius * DVec2::new(c, s),
                };
                pt(p.x, p.y, DVec2::new(c, s))
            })
            .collect();
        lathe.band(&mut glass, &rim);
        // Inner wall (its normal points to the axis), in two bands split at the water line.
        let in_n = -out_n;
        lathe.band(
            &mut glass,
            &[
                pt(inner_top, rim_y, in_n),
                pt(inner_water, self.water_level, in_n),
            ],
        );
        let mut interface = TriMesh::default();
        lathe.band(
            &mut interface,
            &[
                pt(inner_water, self.water_level, in_n),
                pt(inner_floor, self.base, in_n),
            ],
        );
        // Cavity floor: inward to the axis, facing up.
        lathe.band(
            &mut interface,
            &[
                pt(inner_floor, self.base, DVec2::Y),
                pt(0.0, self.base, DVec2::Y),
            ],
        );
        append(&mut glass, &interface);

        let mut water = reversed(&interface);
        // Flat water surface, inward from the wall to the axis, facing up.
        lathe.band(
            &mut water,
            &[
                pt(inner_water, self.water_level, DVec2::Y),
                pt(0.0, self.water_level, DVec2::Y),
            ],
        );
        GlassOfWater {
            glass,
            water,
            interface,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_matches_std_within_4e15() {
        // std's sin/cos are accurate to < 1 ulp on the platforms we test; the series must
        // agree to the error bound documented above.
        for i in -200..=200 {
            let x = f64::from(i) * 0.0731;
            let (s, c) = sin_cos(x);
            assert!((s - x.sin()).abs() < 4e-15, "sin {x}: {s} vs {}", x.sin());
            assert!((c - x.cos()).abs() < 4e-15, "cos {x}: {c} vs {}", x.cos());
        }
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
    }

    #[test]
    fn band_around_a_cylinder_winds_outward() {
        let lathe = Lathe::new(8);
        let mut m = TriMesh::default();
        let n = DVec2::X;
        lathe.band(
            &mut m,
            &[
                ProfilePoint {
                    r: 1.0,
                    y: 0.0,
                    normal: n,
                },
                ProfilePoint {
                    r: 1.0,
                    y: 1.0,
                    normal: n,
                },
            ],
        );
        assert_eq!(m.indices.len(), 16);
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            let face = (b - a).cross(c - a);
            let mid = (a + b + c) / 3.0;
            assert!(face.dot(glam::Vec3::new(mid.x, 0.0, mid.z)) > 0.0);
        }
    }
}
