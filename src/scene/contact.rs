//! Which triangles touch another object: the build-time filter for the intersection
//! layer's coincident-surface probe ([`Scene::coincident`]), so that only hits where two
//! objects really share a face pay for it.
//!
//! A triangle is marked [`Triangle::TOUCHES`] when a face of a *different mesh* — or of
//! its own mesh facing the other way, the two sides of a sheet thinner than the merge
//! distance (candidates from [`super::thin`]) — crosses
//! the normal segment `q ± d·ng` through one of four points `q` of it (the centroid and the
//! points at barycentrics (2/3, 1/6, 1/6) and permutations), where `d` is its merge distance
//! ([`Triangle::merge_distance`]) — the same probe ([`Scene::probe`]) and distance the
//! intersection layer uses at render time; the face found is marked too. Only triangles of volumetric
//! materials are probed (the only hits that look for partners), and only those whose
//! bounding box, grown by the merge distance, overlaps another mesh's: a lone gem costs
//! nothing. Four points per triangle catch faces that cover a quarter or so of it; a
//! partner covering only a sliver away from all four points is missed (that sliver then
//! renders as two interfaces).
//!
//! [`Scene::coincident`]: crate::scene::Scene::coincident

use super::{Scene, Triangle};
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

/// Marks [`Triangle::TOUCHES`] on every triangle that shares a face with another mesh or
/// lies on the other side of a thin sheet of its own mesh (a step of
/// [`Scene::build`](super::Scene::build), on the scene it is building); returns how many
/// triangles are marked.
pub(super) fn mark_touching(scene: &mut Scene) -> usize {
    let n_mesh = scene.meshes.len();
    let volume = |t: &Triangle| scene.material(t.material()).is_volume();
    let thin = super::thin::sheet_candidates(&scene.triangles, |i| volume(&scene.triangles[i]));
    let mut boxes = vec![Aabb::empty(); n_mesh];
    for t in &scene.triangles {
        boxes[t.mesh as usize] = boxes[t.mesh as usize].union(Aabb::of(&t.p));
    }
    let s: &Scene = scene;
    let probed = |i: usize| -> Vec<u32> {
        let t = &s.triangles[i];
        if !volume(t) {
            return Vec::new();
        }
        let [p0, p1, p2] = t.p;
        let half = t.merge_distance();
        let bb = Aabb::of(&t.p).grown(half);
        let near_other = boxes
            .iter()
            .enumerate()
            .any(|(k, b)| k as u32 != t.mesh && b.overlaps(&bb));
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
                let other = s.triangle(h.prim);
                let [o0, o1, o2] = other.p;
                let facing_back = (o1 - o0).cross(o2 - o0).dot(ng) < 0.0;
                if other.mesh != t.mesh || facing_back {
                    found.push(h.prim);
                }
            }
        }
        if !found.is_empty() {
            found.push(i as u32);
        }
        found
    };
    let marked: Vec<u32> = (0..s.triangles.len())
        .into_par_iter()
        .flat_map_iter(probed)
        .collect();
    for &i in &marked {
        scene.triangles[i as usize].info |= Triangle::TOUCHES;
    }
    scene
        .triangles
        .iter()
        .filter(|t| t.has(Triangle::TOUCHES))
        .count()
}
