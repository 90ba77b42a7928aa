//! The emerald cut: a rectangular step cut with cut (chamfered) corners.
//!
//! Frame: metres, +Y up, length along X, width along Z, girdle plane y = 0 (the girdle
//! band is `girdle · width` thick, centred on it), table up.
//!
//! Construction. Every horizontal outline ("ring") is an octagon with half-length `hl`,
//! half-width `hw` and 45° corner chamfers of leg `c`; its 8 edges are parallel to the
//! girdle's, so the facet between two rings on each edge is a trapezoid (two parallel
//! sides), planar by construction. From one ring to the next the long sides and the ends
//! move in by the same plan distance d (so each tier's side and end facets share one step
//! angle α, rising d·tan α), and the chamfer leg shrinks in proportion to the half-width
//! (the corners keep their shape). A chamfer facet then moves in by d·(2 − c₀/hw₀)/√2 in
//! plan, so its angle is atan(tan α · √2 / (2 − c₀/hw₀)): shallower than the step.
//! - crown: `crown.len()` tiers of equal plan width from the girdle to the table (the
//!   table is the last ring, `table · width` wide);
//! - pavilion: `pavilion.len()` tiers of equal plan width from the girdle to the keel; the
//!   last ring has hw = 0, c = 0: the keel, a ridge along X of length `length − width`;
//!   its side facets are trapezoids, its end and chamfer facets triangles.
//! - girdle: 8 vertical rectangles.
//!
//! Facets: 1 table + 8 per crown tier + 8 girdle + 8 per pavilion tier (for the emerald:
//! 1 + 24 + 8 + 32 = 65, the "classic" emerald with 3 crown and 4 pavilion tiers).
//! The solid is convex when the step angles decrease from the girdle towards the table and
//! towards the keel (as in every faceted stone: a faceted stone is an intersection of
//! half-spaces); [`StepCut::validate`] checks that.
//!
//! Proportions of [`StepCut::emerald`]: there is no Tolkowsky-like standard for step cuts.
//! Length/width 1.5 and table 62 % of the width are the middle of the usual ranges in
//! grading guides (L/W 1.3–1.6, table 61–69 %, total depth 61–67 %, e.g. GIA's and
//! Blue Nile's emerald-cut guides); the step angles, crown 45° / 37° / 28° and pavilion
//! 52° / 45° / 40° / 36° (girdle outwards), are typical of published step-cut faceting
//! diagrams and give a total depth of 64.5 % of the width; corner chamfer legs are 15 %
//! of the width, the girdle 2 %.

use super::super::gem::tan_deg;
use glam::DVec3;

/// Proportions of a step cut, lengths in metres, angles in degrees from the girdle plane.
#[derive(Debug, Clone, PartialEq)]
pub struct StepCut {
    /// Girdle length (along X).
    pub length: f64,
    /// Girdle width (along Z), ≤ `length`.
    pub width: f64,
    /// Corner chamfer leg / width, in [0, 0.5).
    pub corner: f64,
    /// Table width / girdle width, in (0, 1).
    pub table: f64,
    /// Girdle thickness / width.
    pub girdle: f64,
    /// Crown step angles from the girdle to the table, decreasing, in (0°, 90°).
    pub crown: Vec<f64>,
    /// Pavilion step angles from the girdle to the keel, decreasing, in (0°, 90°).
    pub pavilion: Vec<f64>,
}

/// A horizontal octagonal outline (see the module docs).
#[derive(Debug, Clone, Copy)]
struct Ring {
    hl: f64,
    hw: f64,
    c: f64,
    y: f64,
}

impl Ring {
    /// The 8 corners, in order round the outline (edge j joins corners j and j + 1:
    /// 0, 2, 4, 6 chamfers; 1, 5 long sides; 3, 7 ends).
    fn corners(&self) -> [DVec3; 8] {
        let (hl, hw, c, y) = (self.hl, self.hw, self.c, self.y);
        [
            (hl, hw - c),
            (hl - c, hw),
            (-(hl - c), hw),
            (-hl, hw - c),
            (-hl, -(hw - c)),
            (-(hl - c), -hw),
            (hl - c, -hw),
            (hl, -(hw - c)),
        ]
        .map(|(x, z)| DVec3::new(x, y, z))
    }
}

impl StepCut {
    /// The emerald cut of the module docs, `length` metres long.
    pub fn emerald(length: f64) -> Self {
        StepCut {
            length,
            width: length / 1.5,
            corner: 0.15,
            table: 0.62,
            girdle: 0.02,
            crown: vec![45.0, 37.0, 28.0],
            pavilion: vec![52.0, 45.0, 40.0, 36.0],
        }
    }

    /// Whether the proportions give a convex stone with planar facets (see the fields).
    pub fn validate(&self) -> bool {
        let decreasing = |a: &[f64]| {
            !a.is_empty()
                && a.iter().all(|&x| x > 0.0 && x < 90.0)
                && a.windows(2).all(|w| w[1] < w[0])
        };
        self.width > 0.0
            && self.length >= self.width
            && (0.0..0.5).contains(&self.corner)
            && self.table > 0.0
            && self.table < 1.0
            && self.girdle >= 0.0
            && decreasing(&self.crown)
            && decreasing(&self.pavilion)
    }

    /// Ring at half-width `hw` and height `y`, moved in from the girdle by the same plan
    /// distance on the sides and ends, chamfer in proportion to the half-width.
    fn ring(&self, hw: f64, y: f64) -> Ring {
        let hw0 = self.width / 2.0;
        let inset = hw0 - hw;
        Ring {
            hl: self.length / 2.0 - inset,
            hw,
            c: self.corner * self.width * hw / hw0,
            y,
        }
    }

    /// Rings from the girdle (excluded) outwards through `angles`, `tiers` of equal plan
    /// width ending at half-width `hw_end`; `up` = +1 for the crown, −1 for the pavilion.
    fn tiers(&self, y0: f64, hw_end: f64, angles: &[f64], up: f64) -> Vec<Ring> {
        let hw0 = self.width / 2.0;
        let n = angles.len() as f64;
        let d = (hw0 - hw_end) / n;
        let mut y = y0;
        let mut rings = vec![self.ring(hw0, y0)];
        for (i, a) in angles.iter().enumerate() {
            y += up * d * tan_deg(*a);
            let k = (i + 1) as f64;
            // hw0 − k·d written so the last ring lands exactly on hw_end.
            let hw = (hw0 * (n - k) + hw_end * k) / n;
            rings.push(self.ring(hw, y));
        }
        rings
    }

    /// The facets as planar polygons (either winding), in the order table, crown tiers,
    /// girdle, pavilion tiers; the keel tier's degenerate corners are merged, so its end
    /// and chamfer facets are triangles.
    pub fn polygons(&self) -> Vec<Vec<DVec3>> {
        let half_girdle = self.girdle * self.width / 2.0;
        let crown = self.tiers(half_girdle, self.table * self.width / 2.0, &self.crown, 1.0);
        let pavilion = self.tiers(-half_girdle, 0.0, &self.pavilion, -1.0);
        let mut polys = Vec::new();
        if let Some(table) = crown.last() {
            polys.push(table.corners().to_vec());
        }
        let mut band = |rings: &[Ring]| {
            for pair in rings.windows(2) {
                let (a, b) = (pair[0].corners(), pair[1].corners());
                for j in 0..8 {
                    let k = (j + 1) % 8;
                    polys.push(dedup(vec![a[j], a[k], b[k], b[j]]));
                }
            }
        };
        band(&crown);
        band(&[crown[0], pavilion[0]]);
        band(&pavilion);
        polys
    }
}

/// Drops vertices equal to their predecessor (cyclically): a keel tier's quad whose
/// lower edge has collapsed to a point becomes a triangle.
fn dedup(mut poly: Vec<DVec3>) -> Vec<DVec3> {
    poly.dedup();
    while poly.len() > 1 && poly.first() == poly.last() {
        poly.pop();
    }
    poly
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn emerald_has_65_facets_a_keel_and_stated_depth() {
        let cut = StepCut::emerald(0.009);
        assert!(cut.validate());
        let polys = cut.polygons();
        assert_eq!(polys.len(), 65);
        // Keel tier: 2 trapezoids (long sides), 6 triangles (ends and chamfers).
        let keel: Vec<usize> = polys[polys.len() - 8..].iter().map(Vec::len).collect();
        assert_eq!(keel.iter().filter(|&&n| n == 4).count(), 2, "{keel:?}");
        assert_eq!(keel.iter().filter(|&&n| n == 3).count(), 6, "{keel:?}");
        let ys = polys.iter().flatten().map(|p| p.y);
        let (lo, hi) = ys.fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)));
        // Depth / width = 0.02 + (0.38/6)(tan 45 + tan 37 + tan 28)
        //   + (1/8)(tan 52 + tan 45 + tan 40 + tan 36) = 0.6454 (module docs: 64.5 %).
        let depth = (hi - lo) / cut.width;
        assert!((depth - 0.6454).abs() < 5e-4, "{depth}");
    }

    #[test]
    fn bad_proportions_are_rejected() {
        let ok = StepCut::emerald(0.009);
        for bad in [
            StepCut {
                crown: vec![30.0, 40.0],
                ..ok.clone()
            },
            StepCut {
                corner: 0.5,
                ..ok.clone()
            },
            StepCut {
                pavilion: vec![],
                ..ok.clone()
            },
            StepCut {
                width: 0.01,
                ..ok.clone()
            },
        ] {
            assert!(!bad.validate(), "{bad:?}");
        }
    }
}
