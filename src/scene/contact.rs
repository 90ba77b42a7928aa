//! Which triangles touch another object: the build-time filter for the intersection
//! layer's coincident-surface probe ([`Scene::coincident`]), so that only hits where two
//! objects really share a face pay for it.
//!
//! A triangle is marked [`TriangleData::TOUCHES`] when a face of a *different mesh* — or of
//! its own mesh facing the other way, the two sides of a sheet thinner than the merge
//! distance (candidates from [`super::thin`]) — crosses
//! the normal segment `q ± MERGE_SCALE·mag·ng` through one of four points `q` of it (the
//! centroid and the points at barycentrics (2/3, 1/6, 1/6) and permutations), where `mag` is
//! its largest vertex coordinate magnitude — the same probe and distance the intersection
//! layer uses at render time; the face found is marked too. Only triangles of volumetric
//! materials are probed (the only hits that look for partners), and only those whose
//! bounding box, grown by the merge distance, overlaps another mesh's: a lone gem costs
//! nothing. Four points per triangle catch faces that cover a quarter or so of it; a
//! partner covering only a sliver away from all four points is missed (that sliver then
//! renders as two interfaces).
//!
//! [`Scene::coincident`]: crate::scene::Scene::coincident

use super::{Scene, TriangleData};
// An upward import, on purpose: the last step of `Scene::build` marks touching faces with
// the intersection layer's own merge distance and coincident-surface probe, so build time
// and render time use one rule (the design card: one layer, one offset rule).
use crate::interaction::MERGE_SCALE;
use glam::Vec3;
use rayon::prelude::*;

/// An axis-aligned box.
#[derive(Debug, Clone, Copy)]
struct Aabb {
    lo: Vec3,
    hi: Vec3,
}

impl Aabb {
    fn empty() -> Self {
        Aabb {
            lo: Vec3::splat(f32::INFINITY),
            hi: Vec3::splat(f32::NEG_INFINITY),
        }
    }

    fn of(p: &[Vec3; 3]) -> Self {
        Aabb {
            lo: p[0].min(p[1]).min(p[2]),
            hi: p[0].max(p[1]).max(p[2]),
        }
    }

    fn union(self, o: Aabb) -> Self {
        Aabb {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    fn grown(self, d: f32) -> Self {
        Aabb {
            lo: self.lo - d,
            hi: self.hi + d,
        }
    }

    fn overlaps(&self, o: &Aabb) -> bool {
        self.lo.cmple(o.hi).all() && o.lo.cmple(self.hi).all()
    }
}

/// Marks [`TriangleData::TOUCHES`] on every triangle that shares a face with another mesh
/// or lies on the other side of a thin sheet of its own mesh (a step of
/// [`Scene::build`](super::Scene::build), on the scene it is building); returns how many
/// triangles are marked.
pub(super) fn mark_touching(scene: &mut Scene) -> usize {
    let n_mesh = scene.meshes.len();
    let volume = |i: usize| {
        let m = scene.triangle_data[i].material() as usize;
        scene.materials[m].is_volume()
    };
    let thin = super::thin::sheet_candidates(&scene.triangle_data, &scene.triangle_mesh, volume);
    let mut boxes = vec![Aabb::empty(); n_mesh];
    for (td, &m) in scene.triangle_data.iter().zip(&scene.triangle_mesh) {
        boxes[m as usize] = boxes[m as usize].union(Aabb::of(&td.p));
    }
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
        let bb = Aabb::of(&td.p).grown(half);
        let near_other = boxes
            .iter()
            .enumerate()
            .any(|(k, b)| k as u32 != mesh && b.overlaps(&bb));
        let ng = (p1 - p0).cross(p2 - p0).normalize_or_zero();
        if (!near_other && !thin[i]) || ng == Vec3::ZERO {
            return Vec::new();
        }
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
                let [o0, o1, o2] = s.triangle_data[h.prim as usize].p;
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
    scene
        .triangle_data
        .iter()
        .filter(|t| t.info & TriangleData::TOUCHES != 0)
        .count()
}
