//! A round brilliant cut: 57 facets plus a faceted girdle, flat-shaded, closed and convex.
//!
//! Frame: metres, +Y up, the girdle plane is y = 0 before [`Brilliant::resting`] turns the
//! stone onto a pavilion facet. Angles are measured in each facet's plane of symmetry
//! (the plane through the Y axis and the facet's apex), as for the Tolkowsky proportions
//! (crown 34.5°, pavilion 40.75°, table 53 % of the diameter: [`Brilliant::tolkowsky`];
//! GIA, "Round Brilliant Cut Diamond Anatomy"). Every proportion is a field, so other
//! cuts (e.g. [`super::cuts`]' oval) reuse the facet layout.
//!
//! Facets (k = 0…7, θₖ = k·45°; rings of vertices at θₖ or θₖ + 22.5°):
//! - table: octagon Tₖ (θₖ);
//! - 8 stars (Tₖ, Tₖ₊₁, Mₖ), Mₖ at θₖ + 22.5°;
//! - 8 bezels (Tₖ, Mₖ₋₁, G₂ₖ, Mₖ): kites, planar because the midpoint of Mₖ₋₁Mₖ is put
//!   on the segment TₖG₂ₖ (`star_depth` of the way down);
//! - 16 upper girdle facets (Mₖ, G₂ₖ, G₂ₖ₊₁), (Mₖ, G₂ₖ₊₁, G₂ₖ₊₂); girdle ring G (16
//!   vertices at j·22.5°, y = +girdle/2);
//! - 16 girdle facets: vertical rectangles between G and the ring B at y = −girdle/2;
//! - 16 lower girdle facets and 8 pavilion mains (culet C, Lₖ₋₁, B₂ₖ, Lₖ), built like
//!   the crown with the culet in place of the table (`lower_girdle_depth` of the way from
//!   B₂ₖ to C).
//!
//! Every facet owns its vertices and their normal is the facet's (flat shading); each
//! polygon is fanned from its first vertex and wound counter-clockwise seen from outside
//! (checked against the vector from the stone's centre). Positions are computed once per
//! ring vertex in `f64` with `+ − × ÷ √` and [`sin_cos`], then rounded to `f32`, so shared
//! corners are bit-identical (watertight after welding) on every platform.

use super::lathe::sin_cos;
use super::shapes::TriMesh;
use glam::DVec3;

/// Facets of [`Brilliant::build`]: table 1, stars 8, bezels 8, upper girdle 16, girdle 16,
/// lower girdle 16, pavilion mains 8.
pub const BRILLIANT_FACETS: usize = 73;

/// Proportions of a round brilliant, lengths in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Brilliant {
    /// Girdle diameter.
    pub diameter: f64,
    /// Table octagon's corner radius / girdle radius.
    pub table: f64,
    /// Crown angle, degrees.
    pub crown_angle: f64,
    /// Pavilion angle, degrees.
    pub pavilion_angle: f64,
    /// Girdle thickness / diameter.
    pub girdle: f64,
    /// How far down the bezel ridge the star facets reach, in (0, 1).
    pub star_depth: f64,
    /// How far from the girdle towards the culet the lower girdle facets reach, in (0, 1).
    pub lower_girdle_depth: f64,
}

impl Brilliant {
    /// Marcel Tolkowsky's proportions ("Diamond Design", 1919, as tabulated by GIA): table
    /// 53 % of the girdle diameter (corner to corner), crown 34.5°, pavilion 40.75°, girdle
    /// 2 % of the diameter; stars half-way down the bezels, lower girdles 77 % of the way to
    /// the culet (typical modern values, GIA "Round Brilliant Cut Diamond Anatomy").
    pub fn tolkowsky(diameter: f64) -> Self {
        Brilliant {
            table: 0.53,
            ..Brilliant::ideal(diameter)
        }
    }

    /// Tolkowsky-like proportions with a slightly larger (56 %) table, as used by the
    /// ruby demonstration scene.
    pub fn ideal(diameter: f64) -> Self {
        Brilliant {
            diameter,
            table: 0.56,
            crown_angle: 34.5,
            pavilion_angle: 40.75,
            girdle: 0.02,
            star_depth: 0.5,
            lower_girdle_depth: 0.77,
        }
    }

    /// The stone, girdle plane y = 0, table up.
    pub fn build(&self) -> TriMesh {
        self.facets(&|p| p).0
    }

    /// The stone lying on pavilion main 2 (the one facing +Z, so the table tilts towards
    /// +Z), its lowest facet `gap` above y = 0, centred over the origin in x and z.
    pub fn resting(&self, gap: f64) -> TriMesh {
        let (_, normals) = self.facets(&|p| p);
        let n = normals[BRILLIANT_FACETS - 8 + 2];
        let rotate = |v: DVec3| rotate_onto(v, n, DVec3::NEG_Y);
        let (rotated, _) = self.facets(&rotate);
        let lowest = rotated
            .positions
            .iter()
            .map(|p| f64::from(p.y))
            .fold(f64::INFINITY, f64::min);
        let lift = gap - lowest;
        self.facets(&|p| rotate(p) + DVec3::Y * lift).0
    }

    /// The facets as planar polygons (girdle plane y = 0, table up, centred on the Y
    /// axis), in the order of the module docs, each wound either way (callers orient them).
    pub fn polygons(&self) -> Vec<Vec<DVec3>> {
        let rg = self.diameter / 2.0;
        let rt = self.table * rg;
        let half_girdle = self.girdle * self.diameter / 2.0;
        let crown_h = (rg - rt) * tan_deg(self.crown_angle);
        let pavilion_h = rg * tan_deg(self.pavilion_angle);
        let at = |r: f64, y: f64, sixteenth: u32| {
            let (s, c) = sin_cos(std::f64::consts::PI * f64::from(sixteenth % 16) / 8.0);
            DVec3::new(r * c, y, r * s)
        };
        let (_, cos_half) = sin_cos(std::f64::consts::PI / 8.0);
        let y_table = half_girdle + crown_h;
        let y_culet = -half_girdle - pavilion_h;
        // Side ring of a kite: its pair's midpoint lies `depth` of the way from (r0, y0)
        // to (r1, y1), 22.5° away from the kite's axis.
        let side = |r0: f64, y0: f64, r1: f64, y1: f64, depth: f64| {
            ((r0 + depth * (r1 - r0)) / cos_half, y0 + depth * (y1 - y0))
        };
        let (rm, ym) = side(rt, y_table, rg, half_girdle, self.star_depth);
        let (rl, yl) = side(rg, -half_girdle, 0.0, y_culet, self.lower_girdle_depth);
        let t = |k: u32| at(rt, y_table, 2 * (k % 8));
        let m = |k: u32| at(rm, ym, 2 * (k % 8) + 1);
        let g = |j: u32| at(rg, half_girdle, j % 16);
        let b = |j: u32| at(rg, -half_girdle, j % 16);
        let l = |k: u32| at(rl, yl, 2 * (k % 8) + 1);
        let culet = DVec3::new(0.0, y_culet, 0.0);

        let mut polys: Vec<Vec<DVec3>> = vec![(0..8).map(t).collect()];
        polys.extend((0..8).map(|k| vec![t(k), t(k + 1), m(k)]));
        polys.extend((0..8).map(|k| vec![t(k), m(k + 7), g(2 * k), m(k)]));
        for k in 0..8 {
            polys.push(vec![m(k), g(2 * k), g(2 * k + 1)]);
            polys.push(vec![m(k), g(2 * k + 1), g(2 * k + 2)]);
        }
        polys.extend((0..16).map(|j| vec![g(j), g(j + 1), b(j + 1), b(j)]));
        for k in 0..8 {
            polys.push(vec![l(k), b(2 * k), b(2 * k + 1)]);
            polys.push(vec![l(k), b(2 * k + 1), b(2 * k + 2)]);
        }
        polys.extend((0..8).map(|k| vec![culet, l(k + 7), b(2 * k), l(k)]));
        polys
    }

    /// Builds the facets with every vertex (and normal, by its linear part) mapped by
    /// `map`, a rigid motion; returns the mesh and each facet's unit outward normal
    /// (before mapping), in the order of the module docs.
    fn facets(&self, map: &dyn Fn(DVec3) -> DVec3) -> (TriMesh, Vec<DVec3>) {
        let polys = self.polygons();
        let mut mesh = TriMesh::default();
        let mut normals = Vec::with_capacity(polys.len());
        let origin = map(DVec3::ZERO);
        for mut poly in polys {
            let mut n = newell(&poly);
            let centre = poly.iter().sum::<DVec3>() / poly.len() as f64;
            if n.dot(centre) < 0.0 {
                poly.reverse();
                n = -n;
            }
            normals.push(n);
            let mapped_n = (map(n) - origin).normalize();
            let base = mesh.positions.len() as u32;
            for p in &poly {
                mesh.positions.push(map(*p).as_vec3());
                mesh.normals.push(mapped_n.as_vec3());
            }
            for i in 1..poly.len() as u32 - 1 {
                mesh.indices.push([base, base + i, base + i + 1]);
            }
        }
        (mesh, normals)
    }
}

/// tan of an angle in degrees, from [`sin_cos`].
pub(crate) fn tan_deg(degrees: f64) -> f64 {
    let (s, c) = sin_cos(degrees.to_radians());
    s / c
}

/// Unit normal of a planar polygon by Newell's method (robust for near-degenerate ones;
/// M. Newell, see F. S. Hill, "Computer Graphics", 1990, §4.5.2).
pub(crate) fn newell(poly: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        n += DVec3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    n.normalize()
}

/// Rotates `v` by the rotation taking unit `from` to unit `to` about `from × to`
/// (Rodrigues' formula v cos θ + (k×v) sin θ + k (k·v)(1 − cos θ); no trigonometry needed:
/// cos θ = from·to, sin θ = |from × to|). `from` must not be ±`to`.
pub(crate) fn rotate_onto(v: DVec3, from: DVec3, to: DVec3) -> DVec3 {
    let axis = from.cross(to);
    let (sin, cos) = (axis.length(), from.dot(to));
    let k = axis / sin;
    v * cos + k.cross(v) * sin + k * k.dot(v) * (1.0 - cos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Largest signed distance of any vertex in front of any facet plane (≤ 0 for a convex
    /// solid).
    fn worst_convexity(m: &TriMesh) -> f64 {
        let mut worst = f64::NEG_INFINITY;
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
            let n = (b - a).cross(c - a).normalize();
            for p in &m.positions {
                worst = worst.max(n.dot(p.as_dvec3() - a));
            }
        }
        worst
    }

    #[test]
    fn brilliant_is_convex_with_73_flat_facets() {
        let d = 0.02;
        for mesh in [
            Brilliant::ideal(d).build(),
            Brilliant::ideal(d).resting(1e-4),
        ] {
            // 1e-7 m: coordinates ≤ 0.02 m are rounded to f32 by ≤ 1e-9 m, which tilts a
            // plane through a ≥ 0.5 mm triangle by ≤ 4e-6 rad, i.e. ≤ 8e-8 m over 0.02 m;
            // a non-convex cut puts vertices ≥ 1e-5 m in front of a plane.
            assert!(worst_convexity(&mesh) < 1e-7, "{}", worst_convexity(&mesh));
            let mut normals: Vec<[u32; 3]> = mesh
                .normals
                .iter()
                .map(|n| n.to_array().map(f32::to_bits))
                .collect();
            normals.sort_unstable();
            normals.dedup();
            assert_eq!(normals.len(), BRILLIANT_FACETS);
        }
    }

    #[test]
    fn resting_stone_lies_on_a_facet_and_tilts_towards_plus_z() {
        let mesh = Brilliant::ideal(0.02).resting(1e-4);
        let lowest = mesh
            .positions
            .iter()
            .map(|p| p.y)
            .fold(f32::INFINITY, f32::min);
        assert!((lowest - 1e-4).abs() < 1e-7, "{lowest}");
        // The face-down facet: at least 4 vertices (a kite) at the lowest height.
        let on_ground = mesh.positions.iter().filter(|p| p.y < 1e-4 + 1e-7).count();
        assert!(on_ground >= 4, "{on_ground}");
        // The table normal (+Y before) turns by the pavilion angle, 40.75°, towards +Z
        // (1e-5: f32 rounding of a unit vector, with margin).
        let table = mesh.normals[0];
        let tilt = 40.75f32.to_radians();
        assert!(
            (table - Vec3::new(0.0, tilt.cos(), tilt.sin())).length() < 1e-5,
            "{table}"
        );
    }
}
