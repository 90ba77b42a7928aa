//! The pear brilliant: a teardrop girdle outline (one round end, one point) with the round
//! brilliant's 73-facet layout, every facet planar by construction.
//!
//! Frame: metres, +Y up, girdle plane y = 0 (the girdle band straddles it), table up;
//! length along X with the point at +X and the round end at −X (x ∈ [−L/2, L/2]), width
//! along Z (z ∈ [−W/2, W/2]). Azimuths φ are measured in the XZ plane from +X towards +Z;
//! u(φ) = (cos φ, sin φ) is a horizontal unit vector (x, z).
//!
//! Outline. The round end is a half circle of radius R = W/2 centred at x₀ = −L/2 + R;
//! each wing is a circular arc tangent to it at the widest point (x₀, ±R) and passing
//! through the point P = (L/2, 0). With a = L − R, the wing radius is
//! ρ = (a² + R²) / (2R) (from |P − (x₀, R − ρ)| = ρ), and the point's half angle is
//! 90° − φ_w with tan φ_w = (ρ − R)/a. For L/W = 1 the wings are the circle itself and the
//! cut is exactly [`Brilliant::tolkowsky`].
//!
//! Girdle vertices Gⱼ (j = 0…15, top at y = +girdle·W/2, bottom Bⱼ at −): G₀ = P; G₁…G₄
//! on the wing at outline-normal azimuths splitting [φ_w, 90°] in four equal angles (by
//! repeated bisection of unit vectors: only + − × ÷ √), G₄ the widest point; G₅…G₈ on the
//! round end at 112.5°, 135°, 157.5°, 180°; G₉…G₁₅ mirror G₇…G₁ in z. The outward normal
//! uₖ at G₂ₖ (u₀ = +X at the point, the bisector of its normal cone) carries main facet k.
//!
//! Facets (same list and order as [`Brilliant::polygons`]), and why each is planar. Let
//! A = (x₀, y_g + R tan α_c, 0) be the crown apex and C = (x₀, −y_g − R tan α_p, 0) the
//! culet, both on the vertical axis through the round end's centre (y_g = girdle·W/2):
//! - bezel k: the plane through G₂ₖ (top) with horizontal normal uₖ that contains A; at
//!   height y it meets the horizontal plane in the line uₖ·p = uₖ·G₂ₖ − (y − y_g)·dₖ/(R tan α_c),
//!   dₖ = uₖ·(G₂ₖ − x₀) the distance from the axis to the tangent line at G₂ₖ. So the
//!   crown at height y is the girdle's tangent polygon scaled about the axis, as in a
//!   round brilliant;
//! - table at y_T = y_g + (1 − table)·R tan α_c, corner Tₖ = x₀ + table·(G₂ₖ − x₀) (on
//!   bezel k): the octagon T₀…T₇, table·W wide and table·L long;
//! - Mₖ = bezel k ∩ bezel k+1 ∩ {y = y_m}, y_m = y_T + star_depth·(y_g − y_T) (a 2×2
//!   solve), so the bezel kite (Tₖ, Mₖ₋₁, G₂ₖ, Mₖ) lies in bezel k's plane; the stars
//!   (Tₖ, Tₖ₊₁, Mₖ) and upper girdles (Mₖ, G₂ₖ, G₂ₖ₊₁), (Mₖ, G₂ₖ₊₁, G₂ₖ₊₂) are triangles;
//! - girdle: vertical rectangles GⱼGⱼ₊₁Bⱼ₊₁Bⱼ;
//! - pavilion main k: the plane through B₂ₖ with horizontal normal uₖ that contains C;
//!   Lₖ = main k ∩ main k+1 ∩ {y = y_l}, y_l = −y_g + lower_girdle_depth·(y_C + y_g); so the
//!   main (C, Lₖ₋₁, B₂ₖ, Lₖ) is planar and the lower girdles are triangles.
//!
//! Angles: bezel k has the angle atan(R tan α_c / dₖ) and main k atan(R tan α_p / dₖ): the
//! five bezels and five mains of the round end (G₄…G₁₂, dₖ = R) keep the crown and
//! pavilion angles exactly; the wing and point facets are shallower (at the point
//! dₖ = a = L − R), as in real pears, whose flatter point makes the "bow-tie".
//! Convexity is not automatic for an arbitrary outline: the unit tests check that no vertex
//! lies in front of any facet's plane, and that no edge is shorter than 1 % of the width,
//! for L/W from 1 to 2.
//!
//! [`Pear::standard`]: L/W 1.6, inside the ranges retail grading guides give for pears
//! (1.45–1.75 "traditional", waldemarjewellers.com.au pear-cut guide; 1.40–1.60 "very
//! good", beyond4cs.com/shapes/pear/recommended-proportions; 1.50–1.60 preferred,
//! caratsmart.com.au pear guide; no lab publishes a pear standard), with Tolkowsky's
//! proportions across the width (table 53 % of the width, crown 34.5°, pavilion 40.75° at
//! the round end, girdle 2 %): total depth 0.02 + 0.47·tan 34.5°/2 + tan 40.75°/2 = 61.2 %
//! of the width, inside the 58–64 % beyond4cs calls excellent; the table is at the low end
//! of its 53–64 % "good" range (b-miners.com: 53–63 % excellent).

use super::super::gem::{tan_deg, Brilliant};
use super::super::lathe::sin_cos;
use glam::{DVec2, DVec3};

/// Length/width of [`Pear::standard`].
pub const PEAR_RATIO: f64 = 1.6;

/// A pear brilliant: `length` metres long, L/W `ratio`, the round brilliant's proportions
/// (`brilliant`, whose diameter is the width) across the round end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pear {
    /// Proportions across the width; `brilliant.diameter` is the width W.
    pub brilliant: Brilliant,
    /// Length / width, ≥ 1.
    pub ratio: f64,
}

/// A girdle vertex (x, z) and the outward normal carried by its main facets.
#[derive(Debug, Clone, Copy)]
struct Rim {
    p: DVec2,
    u: DVec2,
}

impl Pear {
    /// L/W [`PEAR_RATIO`], Tolkowsky proportions across the width; `length` metres long.
    pub fn standard(length: f64) -> Self {
        Pear {
            brilliant: Brilliant::tolkowsky(length / PEAR_RATIO),
            ratio: PEAR_RATIO,
        }
    }

    /// The 16 girdle vertices in order (see the module docs), G₀ the point.
    fn girdle(&self) -> [Rim; 16] {
        let r = self.brilliant.diameter / 2.0;
        let length = self.ratio * self.brilliant.diameter;
        let x0 = -length / 2.0 + r;
        let a = length - r;
        let rho = (a * a + r * r) / (2.0 * r);
        // Wing centre (upper wing) and the normal azimuths at its ends.
        let centre = DVec2::new(x0, r - rho);
        let tip_normal = DVec2::new(a, rho - r) / rho;
        let bisect = |p: DVec2, q: DVec2| (p + q).normalize();
        let w2 = bisect(tip_normal, DVec2::Y);
        let wing = [tip_normal, bisect(tip_normal, w2), w2, bisect(w2, DVec2::Y)];
        let mut upper = [Rim {
            p: DVec2::new(length / 2.0, 0.0),
            u: DVec2::X,
        }; 9];
        for (j, u) in wing.iter().enumerate().skip(1) {
            upper[j] = Rim {
                p: centre + rho * *u,
                u: *u,
            };
        }
        for (j, rim) in upper.iter_mut().enumerate().skip(4) {
            // 90°, 112.5°, …, 180° on the round end; the widest point exactly (x₀, R).
            let (s, c) = sin_cos(std::f64::consts::PI * (j as f64) / 8.0);
            let u = if j == 4 { DVec2::Y } else { DVec2::new(c, s) };
            rim.p = DVec2::new(x0, 0.0) + r * u;
            rim.u = u;
        }
        let mirror = |v: DVec2| DVec2::new(v.x, -v.y);
        std::array::from_fn(|j| {
            if j <= 8 {
                upper[j]
            } else {
                let m = upper[16 - j];
                Rim {
                    p: mirror(m.p),
                    u: mirror(m.u),
                }
            }
        })
    }

    /// The facets as planar polygons (either winding), in the order of
    /// [`Brilliant::polygons`]: table, 8 stars, 8 bezels, 16 upper girdles, 16 girdle
    /// facets, 16 lower girdles, 8 pavilion mains.
    pub fn polygons(&self) -> Vec<Vec<DVec3>> {
        let b = &self.brilliant;
        let r = b.diameter / 2.0;
        let rims = self.girdle();
        let x0 = -self.ratio * b.diameter / 2.0 + r;
        let y_g = b.girdle * b.diameter / 2.0;
        let tan_c = tan_deg(b.crown_angle);
        let y_t = y_g + (1.0 - b.table) * r * tan_c;
        let y_m = y_t + b.star_depth * (y_g - y_t);
        let pavilion_h = r * tan_deg(b.pavilion_angle);
        let y_c = -y_g - pavilion_h;
        let y_l = -y_g + b.lower_girdle_depth * (y_c + y_g);
        let axis = DVec2::new(x0, 0.0);
        let main = |k: usize| rims[(2 * k) % 16];
        // Offset of main facet k's line at height y (uₖ·p = offset) for a facet through the
        // girdle vertex at height y0 and the apex `h` above it on the axis (crown: h > 0,
        // pavilion: h < 0).
        let line_at = |k: usize, y: f64, y0: f64, h: f64| {
            let g = main(k);
            g.u.dot(g.p) - (y - y0) * g.u.dot(g.p - axis) / h
        };
        let crown_h = r * tan_c;
        let bezel_at = |k: usize, y: f64| line_at(k, y, y_g, crown_h);
        let main_at = |k: usize, y: f64| line_at(k, y, -y_g, -pavilion_h);
        let meet = |k: usize, c0: f64, c1: f64| solve(main(k).u, c0, main(k + 1).u, c1);
        let lift = |p: DVec2, y: f64| DVec3::new(p.x, y, p.y);
        let t = |k: usize| lift(axis + b.table * (main(k).p - axis), y_t);
        let m = |k: usize| {
            let k = k % 8;
            lift(meet(k, bezel_at(k, y_m), bezel_at(k + 1, y_m)), y_m)
        };
        let l = |k: usize| {
            let k = k % 8;
            lift(meet(k, main_at(k, y_l), main_at(k + 1, y_l)), y_l)
        };
        let g = |j: usize| lift(rims[j % 16].p, y_g);
        let bot = |j: usize| lift(rims[j % 16].p, -y_g);
        let c = lift(axis, y_c);

        let mut polys: Vec<Vec<DVec3>> = vec![(0..8).map(t).collect()];
        polys.extend((0..8).map(|k| vec![t(k), t((k + 1) % 8), m(k)]));
        polys.extend((0..8).map(|k| vec![t(k), m(k + 7), g(2 * k), m(k)]));
        for k in 0..8 {
            polys.push(vec![m(k), g(2 * k), g(2 * k + 1)]);
            polys.push(vec![m(k), g(2 * k + 1), g(2 * k + 2)]);
        }
        polys.extend((0..16).map(|j| vec![g(j), g(j + 1), bot(j + 1), bot(j)]));
        for k in 0..8 {
            polys.push(vec![l(k), bot(2 * k), bot(2 * k + 1)]);
            polys.push(vec![l(k), bot(2 * k + 1), bot(2 * k + 2)]);
        }
        polys.extend((0..8).map(|k| vec![c, l(k + 7), bot(2 * k), l(k)]));
        polys
    }
}

/// The point p with u₀·p = c₀ and u₁·p = c₁ (Cramer's rule; u₀, u₁ not parallel).
fn solve(u0: DVec2, c0: f64, u1: DVec2, c1: f64) -> DVec2 {
    let det = u0.x * u1.y - u0.y * u1.x;
    DVec2::new(c0 * u1.y - c1 * u0.y, u0.x * c1 - u1.x * c0) / det
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::authoring::gem::newell;

    /// Largest distance of any vertex in front of any facet's outward plane, and the
    /// largest distance of a facet's own vertices from its plane, over `size`.
    fn convexity_and_planarity(polys: &[Vec<DVec3>], size: f64) -> (f64, f64) {
        let all: Vec<DVec3> = polys.iter().flatten().copied().collect();
        let inside = all.iter().sum::<DVec3>() / all.len() as f64;
        let (mut front, mut off) = (f64::MIN, 0.0f64);
        for poly in polys {
            let centre = poly.iter().sum::<DVec3>() / poly.len() as f64;
            let n = newell(poly) * newell(poly).dot(centre - inside).signum();
            for p in poly {
                off = off.max(n.dot(*p - centre).abs());
            }
            for p in &all {
                front = front.max(n.dot(*p - centre));
            }
        }
        (front / size, off / size)
    }

    #[test]
    fn ratio_one_is_the_round_brilliant() {
        // The same polygons, vertex for vertex, as Tolkowsky's brilliant of the same
        // diameter (1e-15 m: f64 rounding of mm coordinates through a few operations).
        let pear = Pear {
            brilliant: Brilliant::tolkowsky(0.0065),
            ratio: 1.0,
        };
        let (a, b) = (pear.polygons(), Brilliant::tolkowsky(0.0065).polygons());
        assert_eq!(a.len(), b.len());
        for (p, q) in a.iter().zip(&b) {
            assert_eq!(p.len(), q.len());
            for (x, y) in p.iter().zip(q) {
                assert!((*x - *y).length() < 1e-15, "{x} {y}");
            }
        }
    }

    #[test]
    fn pears_are_convex_with_planar_facets_and_no_tiny_edges() {
        for ratio in [1.0, 1.2, 1.45, 1.6, 1.75, 2.0] {
            let length = 0.008;
            let pear = Pear {
                brilliant: Brilliant::tolkowsky(length / ratio),
                ratio,
            };
            let polys = pear.polygons();
            assert_eq!(polys.len(), 73);
            let (front, off) = convexity_and_planarity(&polys, length);
            // Exact construction: only f64 rounding (~1e-16 relative) remains; a dent from
            // a wrong construction is ≥ 1e-4 of the size.
            assert!(front < 1e-12 && off < 1e-12, "{ratio}: {front:e} {off:e}");
            // Every edge ≥ 1 % of the width (the girdle is 2 %), so f32 rounding (6e-8
            // relative) cannot tilt a triangle's normal by more than ~1e-5.
            let width = length / ratio;
            for poly in &polys {
                for (i, p) in poly.iter().enumerate() {
                    let e = (*p - poly[(i + 1) % poly.len()]).length() / width;
                    assert!(e > 0.01, "{ratio}: edge {e}");
                }
            }
            let (lo, hi) = polys.iter().flatten().fold(
                (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
                |(lo, hi), p| (lo.min(*p), hi.max(*p)),
            );
            let (l, w) = (hi.x - lo.x, hi.z - lo.z);
            assert!((l - length).abs() < 1e-15, "{ratio}: {l}");
            assert!((l / w - ratio).abs() < 1e-12, "{ratio}: {}", l / w);
        }
    }
}
