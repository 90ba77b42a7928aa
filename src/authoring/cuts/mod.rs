//! Standard gem cuts with real proportions, for `iris gem` and `assets/gems/`.
//!
//! - [`Cut::Round`]: the round brilliant with Tolkowsky's proportions
//!   ([`Brilliant::tolkowsky`], in [`super::gem`]);
//! - [`Cut::Emerald`]: a rectangular step cut with cut corners ([`step::StepCut`]);
//! - [`Cut::Oval`]: the round brilliant's facets stretched to an ellipse ([`oval::Oval`]);
//! - [`Cut::Pear`]: a teardrop brilliant, the round brilliant's layout on a pear outline
//!   ([`pear::Pear`]).
//!
//! Frame of every cut: metres, +Y up, girdle plane y = 0 (the girdle band straddles it),
//! table up, centred on the Y axis; the length (if any) along X. Every cut is a convex
//! polyhedron whose facets are planar by construction; [`polyhedron`] turns the facet
//! polygons into a flat-shaded mesh (each facet owns its vertices, fanned from its first
//! one, wound counter-clockwise seen from outside). Vertices are computed once in `f64`
//! and rounded to `f32`, so corners shared by facets are bit-identical (the mesh is closed
//! after welding equal positions).
//!
//! [`preview`] wraps a stone in a preview scene (camera, small lights, white floor) and
//! writes it as .glb.

pub mod oval;
pub mod pear;
pub mod preview;
pub mod step;

use super::gem::{newell, Brilliant};
use super::shapes::{push_flat_facing_away, TriMesh};
use crate::error::{Error, Result};
use glam::DVec3;

/// A cut style.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Cut {
    /// Round brilliant, Tolkowsky proportions; size = girdle diameter.
    Round,
    /// Emerald (step) cut, length/width 1.5; size = length.
    Emerald,
    /// Oval brilliant, length/width 1.4; size = length.
    Oval,
    /// Pear brilliant, length/width 1.6, point at +X; size = length.
    Pear,
}

/// Every cut, in the order the CLI lists them.
pub const CUTS: [Cut; 4] = [Cut::Round, Cut::Emerald, Cut::Oval, Cut::Pear];

/// Default `--size`: 6.5 mm (a round diamond of about one carat).
pub const DEFAULT_SIZE_MM: f64 = 6.5;
/// Smallest accepted `--size`, millimetres.
pub const MIN_SIZE_MM: f64 = 0.1;
/// Largest accepted `--size`, millimetres.
pub const MAX_SIZE_MM: f64 = 1000.0;

impl Cut {
    /// The CLI name (`--cut`).
    pub fn name(self) -> &'static str {
        match self {
            Cut::Round => "round",
            Cut::Emerald => "emerald",
            Cut::Oval => "oval",
            Cut::Pear => "pear",
        }
    }

    /// Parses a CLI name (case-insensitive); the error lists the names.
    pub fn parse(s: &str) -> Result<Cut> {
        let key = s.trim().to_ascii_lowercase();
        CUTS.into_iter().find(|c| c.name() == key).ok_or_else(|| {
            let names: Vec<&str> = CUTS.iter().map(|c| c.name()).collect();
            Error::Usage(format!(
                "--cut {s:?}: unknown cut (expected one of: {})",
                names.join(", ")
            ))
        })
    }

    /// The facet polygons of a stone whose size (round: girdle diameter; others: length)
    /// is `size` metres, in the module's frame.
    pub fn polygons(self, size: f64) -> Vec<Vec<DVec3>> {
        match self {
            Cut::Round => Brilliant::tolkowsky(size).polygons(),
            Cut::Emerald => step::StepCut::emerald(size).polygons(),
            Cut::Oval => oval::Oval::standard(size).polygons(),
            Cut::Pear => pear::Pear::standard(size).polygons(),
        }
    }

    /// The stone as a flat-shaded, closed, outward-wound mesh (see [`Cut::polygons`]).
    pub fn mesh(self, size: f64) -> TriMesh {
        polyhedron(self.polygons(size))
    }
}

/// Checks a `--size` in millimetres and returns it in metres.
pub fn size_metres(size_mm: f64) -> Result<f64> {
    if size_mm.is_finite() && (MIN_SIZE_MM..=MAX_SIZE_MM).contains(&size_mm) {
        Ok(size_mm / 1000.0)
    } else {
        Err(Error::Usage(format!(
            "--size {size_mm}: the stone's size (girdle diameter or length) must be between {MIN_SIZE_MM} and {MAX_SIZE_MM} mm"
        )))
    }
}

/// A flat-shaded mesh of the convex polyhedron bounded by the planar polygons `polys`:
/// each polygon is wound so its Newell normal points away from the centroid of all
/// vertices (outward for a convex solid), gets its own vertices with that normal, and is
/// fanned from its first vertex. Polygons with fewer than 3 vertices are skipped.
pub fn polyhedron(polys: Vec<Vec<DVec3>>) -> TriMesh {
    let count: usize = polys.iter().map(Vec::len).sum();
    let inside = polys.iter().flatten().sum::<DVec3>() / count.max(1) as f64;
    let mut mesh = TriMesh::default();
    for poly in polys.into_iter().filter(|p| p.len() >= 3) {
        let n = newell(&poly);
        push_flat_facing_away(&mut mesh, poly, n, inside);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_bad_values_are_usage_errors() {
        for c in CUTS {
            assert_eq!(Cut::parse(c.name()).ok(), Some(c));
        }
        assert_eq!(Cut::parse(" Oval ").ok(), Some(Cut::Oval));
        let err = Cut::parse("pear-shaped").expect_err("unknown").to_string();
        assert!(err.contains("round, emerald, oval, pear"), "{err}");
        assert_eq!(size_metres(6.5).ok(), Some(0.0065));
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 2000.0] {
            assert!(size_metres(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn round_cut_mesh_equals_the_brilliant_builder() {
        // The generic polyhedron builder and Brilliant::build agree for the round cut
        // (same polygons, same orientation rule about the girdle centre).
        let a = Cut::Round.mesh(0.0065);
        let b = Brilliant::tolkowsky(0.0065).build();
        assert_eq!(a.indices, b.indices);
        for (p, q) in a.positions.iter().zip(&b.positions) {
            assert!((*p - *q).length() < 1e-12, "{p} {q}");
        }
    }
}
