//! Which triangles touch another object: the build-time filter for the intersection
//! layer's coincident-surface probe ([`Scene::coincident`]), so that only hits where two
//! objects really share a face pay for it.
//!
//! A triangle is marked [`TriangleData::TOUCHES`] when a face of a *different mesh*, or a
//! face of its own mesh facing the opposite way (a sheet thinner than the merge distance),
//! crosses
//! the normal segment `q ± MERGE_SCALE·mag·ng` through one of four points `q` of it (the
//! centroid and the points at barycentrics (2/3, 1/6, 1/6) and permutations), where `mag` is
//! its largest vertex coordinate magnitude — the same probe and distance the intersection
//! layer uses at render time; the face found is marked too. Only triangles of volumetric
//! materials are probed (the only hits that look for partners): four short segment
//! queries per volumetric triangle at build time (measured in `tests/stiff_geometry.rs`). Four points per triangle catch faces that cover a quarter or so of it; a
//! partner covering only a sliver away from all four points is missed (that sliver then
//! renders as two interfaces).
//!
//! [`Scene::coincident`]: crate::scene::Scene::coincident

use super::{Scene, TriangleData};
use crate::interaction::{geometric_normal, MERGE_SCALE};
use rayon::prelude::*;

/// Marks [`TriangleData::TOUCHES`] on every triangle that shares a face with another mesh,
/// or with a face of its own mesh facing the other way (the two sides of a sheet thinner
/// than the merge distance: the offset rule cannot resolve it, so it is crossed as one
/// interface too).
pub(super) fn mark_touching(scene: &mut Scene) {
    let s: &Scene = scene;
    let probed = |i: usize| -> Vec<u32> {
        let td = &s.triangle_data[i];
        let mesh = s.triangle_mesh[i];
        if !s.materials[td.material() as usize].is_volume() {
            return Vec::new();
        }
        let [p0, p1, p2] = td.p;
        let mag = p0.abs().max(p1.abs()).max(p2.abs()).max_element();
        let half = mag * MERGE_SCALE;
        let Some(ng) = geometric_normal(td.p) else {
            return Vec::new();
        };
        let (a, b) = (2.0 / 3.0, 1.0 / 6.0);
        let points = [
            (p0 + p1 + p2) / 3.0,
            p0 * a + (p1 + p2) * b,
            p1 * a + (p0 + p2) * b,
            p2 * a + (p0 + p1) * b,
        ];
        let mut found = Vec::new();
        for q in points {
            let (_, hits) = s.probe(q, ng, half);
            for h in hits.as_slice() {
                let other = &s.triangle_data[h.prim as usize];
                let [o0, o1, o2] = other.p;
                let facing_back = (o1 - o0).cross(o2 - o0).dot(ng) < 0.0;
                if s.triangle_mesh[h.prim as usize] != mesh || facing_back {
                    found.push(h.prim);
                }
            }
        }
        if !found.is_empty() {
            found.push(i as u32);
        }
        found
    };
    let marked: Vec<u32> = (0..s.triangle_data.len())
        .into_par_iter()
        .flat_map_iter(probed)
        .collect();
    for &i in &marked {
        scene.triangle_data[i as usize].info |= TriangleData::TOUCHES;
    }
    let count = scene
        .triangle_data
        .iter()
        .filter(|t| t.info & TriangleData::TOUCHES != 0)
        .count();
    if count > 0 {
        scene.notes.push(format!(
            "{count} triangles lie on another object's faces (touching volumes are crossed as one interface there)"
        ));
    }
}
