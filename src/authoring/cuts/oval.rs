//! The oval brilliant: the round brilliant's 73 facets ([`Brilliant`]) stretched along X
//! by the length/width ratio.
//!
//! Frame: metres, +Y up, girdle plane y = 0, length along X, width along Z, table up.
//!
//! A stretch (x, y, z) ↦ (s·x, y, z) is linear, so it maps planes to planes and convex
//! solids to convex solids: every facet stays planar and the stone convex by construction
//! (no triangulation of warped facets). A facet with unit normal n becomes one with normal
//! ∝ (nₓ/s, n_y, n_z) (inverse transpose). Hence the facets whose plane of symmetry is the
//! YZ plane (bezels and pavilion mains at ±Z, the ends of the minor axis) keep the round
//! brilliant's crown and pavilion angles exactly, and along the major axis an angle α
//! becomes atan(tan α / s) (the ends of an oval are shallower, as in real ovals, where
//! this is what makes the "bow-tie").
//!
//! [`Oval::standard`]: length/width 1.4 (the middle of the usual 1.35–1.50 range in
//! grading guides) over Tolkowsky's proportions across the width.

use super::super::gem::Brilliant;
use glam::DVec3;

/// Length/width of [`Oval::standard`].
pub const OVAL_RATIO: f64 = 1.4;

/// An oval brilliant: `brilliant` (its diameter is the width) stretched along X by `ratio`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oval {
    /// Proportions across the width (minor axis).
    pub brilliant: Brilliant,
    /// Length / width, ≥ 1.
    pub ratio: f64,
}

impl Oval {
    /// Length/width [`OVAL_RATIO`], Tolkowsky proportions across the width; `length`
    /// metres long.
    pub fn standard(length: f64) -> Self {
        Oval {
            brilliant: Brilliant::tolkowsky(length / OVAL_RATIO),
            ratio: OVAL_RATIO,
        }
    }

    /// The facets as planar polygons (the brilliant's, stretched), either winding.
    pub fn polygons(&self) -> Vec<Vec<DVec3>> {
        let s = DVec3::new(self.ratio, 1.0, 1.0);
        self.brilliant
            .polygons()
            .into_iter()
            .map(|poly| poly.into_iter().map(|p| p * s).collect())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::authoring::gem::newell;

    #[test]
    fn stretched_facets_stay_planar_and_minor_axis_angles_are_kept() {
        let oval = Oval::standard(0.008);
        let polys = oval.polygons();
        assert_eq!(polys.len(), 73);
        let mut at_crown_angle = 0;
        for poly in &polys {
            // Outward: away from the stone's centre (the origin).
            let centre = poly.iter().sum::<DVec3>() / poly.len() as f64;
            let n = newell(poly) * newell(poly).dot(centre).signum();
            // Planarity: every vertex within 1e-15 m of the facet's plane (f64 rounding
            // of mm-sized coordinates is ~1e-18 m per operation).
            for p in poly {
                assert!(n.dot(*p - poly[0]).abs() < 1e-15);
            }
            let tilt = n.y.acos().to_degrees();
            if n.y > 0.0 && n.x.abs() < 1e-9 && (tilt - 34.5).abs() < 1e-9 {
                at_crown_angle += 1;
            }
        }
        // The two bezels at ±Z.
        assert_eq!(at_crown_angle, 2);
    }
}
