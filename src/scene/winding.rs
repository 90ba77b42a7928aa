//! Winding repair: make every connected component of a mesh consistently wound and, when it
//! is closed, wound counter-clockwise seen from outside, so the intersection layer's
//! convention (`ng = (p1−p0)×(p2−p0)` points out of the object, [`crate::interaction`])
//! holds even for artists' files whose triangles disagree.
//!
//! Method (the classic manifold orientation pass, e.g. Botsch et al., *Polygon Mesh
//! Processing*, §2.5 "orientability"):
//! 1. **Weld by position** ([`crate::scene::weld`], the rule every closedness test uses):
//!    vertices within 2⁻²⁰ of the mesh's size are one corner, so flat-shaded meshes (one
//!    vertex per facet corner, like [`crate::authoring::gem`]) and seams whose copies differ
//!    in the last bits are still connected. A triangle whose corners weld together (a
//!    sliver thinner than the tolerance) joins nothing and counts as open. Positions are
//!    world-space metres as in [`MeshDesc`].
//! 2. **Edge adjacency.** An undirected edge used by exactly two triangles joins them; two
//!    triangles agree when they traverse the shared edge in **opposite** directions. Edges
//!    used by one triangle are borders; by three or more, non-manifold: neither joins.
//! 3. **Propagate.** Breadth-first from the lowest-numbered unvisited triangle, each
//!    neighbour gets the flip parity that makes it agree. A component is *non-orientable*
//!    when a cycle contradicts itself (Möbius strip); it is left exactly as it was.
//! 4. **Choose the side.** A *closed* component (no border and no non-manifold edge) is
//!    oriented so its signed volume `Σ p0·(p1×p2)/6` (divergence theorem) is positive —
//!    unless it lies inside an odd number of the mesh's other closed components. Such a
//!    shell is either a cavity (a bubble in a gem: it must face into the cavity, negative
//!    volume) or a part modelled inside another (a pin inside a spectacle frame: outward);
//!    the mesh's shading normals decide when it has them (the side they agree with, by
//!    area), otherwise it is taken as a cavity. An open component cannot be oriented
//!    "outward": it takes the side its shading normals agree with, or without normals the
//!    winding of the majority of its triangle area.
//!
//! Invariants: only the order of each triangle's corners changes (a flip swaps the last
//! two indices); triangles keep their index in the mesh; the result depends only on the
//! input (no hashing order, no threads), so it is deterministic. Cost: O(T log T) for T
//! triangles (the O(V) weld, one sort of the 3T directed edges), plus, for closed shells whose bounding
//! boxes nest, one winding-number sum over the outer shell per nested shell.

use crate::scene::desc::MeshDesc;
use glam::DVec3;

/// What [`orient`] did to one mesh.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WindingReport {
    /// Connected components (by manifold edges).
    pub components: usize,
    /// Triangles whose winding was reversed.
    pub flipped: usize,
    /// Open components (with a border or a non-manifold edge): consistent, side unknown.
    pub open: usize,
    /// Components that cannot be oriented consistently (left unchanged).
    pub non_orientable: usize,
}

/// Per triangle, for each of its three edges, the neighbour across it and whether that
/// neighbour traverses the edge in the same direction (`None` for a border or a
/// non-manifold edge), plus whether any edge is a border or non-manifold, per triangle.
type Adjacency = (Vec<[Option<(u32, bool)>; 3]>, Vec<bool>);

fn adjacency(tris: &[[u32; 3]], corner: &[u32]) -> Adjacency {
    // (min, max, triangle, edge slot, forward?) sorted groups the uses of each edge.
    let mut uses: Vec<(u32, u32, u32, u8, bool)> = Vec::with_capacity(tris.len() * 3);
    let mut open = vec![false; tris.len()];
    for (t, tri) in tris.iter().enumerate() {
        let [a, b, c] = tri.map(|v| corner[v as usize]);
        if a == b || b == c || a == c {
            open[t] = true; // collapsed by the weld: joins nothing
            continue;
        }
        for e in 0..3 {
            let a = corner[tri[e] as usize];
            let b = corner[tri[(e + 1) % 3] as usize];
            uses.push((a.min(b), a.max(b), t as u32, e as u8, a < b));
        }
    }
    uses.sort_unstable();
    let mut adj = vec![[None; 3]; tris.len()];
    let mut i = 0;
    while i < uses.len() {
        let mut j = i + 1;
        while j < uses.len() && (uses[j].0, uses[j].1) == (uses[i].0, uses[i].1) {
            j += 1;
        }
        let group = &uses[i..j];
        if let [x, y] = group {
            let same = x.4 == y.4;
            adj[x.2 as usize][x.3 as usize] = Some((y.2, same));
            adj[y.2 as usize][y.3 as usize] = Some((x.2, same));
        } else {
            for u in group {
                open[u.2 as usize] = true;
            }
        }
        i = j;
    }
    (adj, open)
}

/// Repairs the winding of `mesh` in place (see the module docs) and reports what it did.
/// Triangles whose corners collapse after welding must have been removed first (they are
/// skipped as borders otherwise, which is harmless).
pub fn orient(mesh: &mut MeshDesc) -> WindingReport {
    let corner = crate::scene::weld::weld(&mesh.positions).corner;
    let (adj, open_tri) = adjacency(&mesh.indices, &corner);
    let n = mesh.indices.len();
    let mut flip = vec![false; n];
    let mut seen = vec![false; n];
    let mut report = WindingReport::default();
    let mut queue = std::collections::VecDeque::new();
    let mut closed_components = Vec::new();
    for seed in 0..n {
        if seen[seed] {
            continue;
        }
        report.components += 1;
        let mut members = Vec::new();
        seen[seed] = true;
        queue.push_back(seed);
        let mut consistent = true;
        let mut closed = true;
        while let Some(t) = queue.pop_front() {
            members.push(t);
            closed &= !open_tri[t];
            for (u, same) in adj[t].iter().flatten() {
                let (u, want) = (*u as usize, flip[t] ^ same);
                if !seen[u] {
                    seen[u] = true;
                    flip[u] = want;
                    queue.push_back(u);
                } else if flip[u] != want {
                    consistent = false;
                }
            }
        }
        if !consistent {
            report.non_orientable += 1;
            members.iter().for_each(|&t| flip[t] = false);
        } else if closed {
            closed_components.push(members);
        } else {
            report.open += 1;
            let vote = normal_vote(mesh, &members, &flip);
            let reverse = if vote != 0.0 {
                vote < 0.0
            } else {
                flipped_area_majority(mesh, &members, &flip)
            };
            if reverse {
                members.iter().for_each(|&t| flip[t] ^= true);
            }
        }
    }
    orient_closed(mesh, &closed_components, &mut flip);
    for (tri, &f) in mesh.indices.iter_mut().zip(&flip) {
        if f {
            tri.swap(1, 2);
            report.flipped += 1;
        }
    }
    report
}

/// The corners of triangle `t` as f64 points, in the winding `flip` gives it.
fn corners(mesh: &MeshDesc, t: usize, flip: bool) -> [DVec3; 3] {
    let [a, mut b, mut c] = mesh.indices[t];
    if flip {
        std::mem::swap(&mut b, &mut c);
    }
    [a, b, c].map(|i| mesh.positions[i as usize].as_dvec3())
}

/// Step 4 for the closed components: a shell nested inside an odd number of the mesh's
/// other closed shells bounds a cavity (an air bubble modelled in the same mesh as its
/// gem), so "outward" for it means towards the cavity: negative volume. Nesting is decided
/// by the generalized winding number of a point of the shell with respect to each other
/// shell whose bounding box holds it (|w| > ½ means inside).
fn orient_closed(mesh: &MeshDesc, shells: &[Vec<usize>], flip: &mut [bool]) {
    let boxes: Vec<(DVec3, DVec3)> = shells
        .iter()
        .map(|m| {
            m.iter()
                .flat_map(|&t| corners(mesh, t, false))
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p), hi.max(p))
                })
        })
        .collect();
    for (c, members) in shells.iter().enumerate() {
        let [a, b, d] = corners(mesh, members[0], false);
        let q = (a + b + d) / 3.0;
        let depth = shells
            .iter()
            .enumerate()
            .filter(|&(o, other)| {
                let (lo, hi) = boxes[o];
                o != c
                    && q.cmpge(lo).all()
                    && q.cmple(hi).all()
                    && winding_number(mesh, other, flip, q).abs() > 0.5
            })
            .count();
        let volume = signed_volume(mesh, members, flip);
        let vote = normal_vote(mesh, members, flip);
        let reverse = if depth % 2 == 0 {
            volume < 0.0
        } else if vote != 0.0 {
            vote < 0.0 // a part inside another, or a cavity: the artist's normals decide
        } else {
            volume > 0.0 // a cavity faces inward
        };
        if reverse {
            members.iter().for_each(|&t| flip[t] ^= true);
        }
    }
}

/// How much the component's shading normals agree with its faces as currently flipped:
/// Σ (p1−p0)×(p2−p0) · (n0+n1+n2) (area-weighted); 0 when the mesh has no normals. Used
/// only where geometry cannot decide (open components, shells nested inside others).
fn normal_vote(mesh: &MeshDesc, members: &[usize], flip: &[bool]) -> f64 {
    if mesh.normals.len() != mesh.positions.len() {
        return 0.0;
    }
    members
        .iter()
        .map(|&t| {
            let [p0, p1, p2] = corners(mesh, t, flip[t]);
            let n: DVec3 = mesh.indices[t]
                .iter()
                .map(|&i| mesh.normals[i as usize].as_dvec3())
                .filter(|n| n.is_finite())
                .sum();
            (p1 - p0).cross(p2 - p0).dot(n)
        })
        .sum()
}

/// Generalized winding number of the shell about `q`: the solid angles its triangles
/// subtend, over 4π (Van Oosterom & Strackee 1983, "The solid angle of a plane triangle",
/// IEEE Trans. Biomed. Eng. 30(2)).
fn winding_number(mesh: &MeshDesc, members: &[usize], flip: &[bool], q: DVec3) -> f64 {
    let total: f64 = members
        .iter()
        .map(|&t| {
            let [a, b, c] = corners(mesh, t, flip[t]).map(|p| p - q);
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            let num = a.dot(b.cross(c));
            let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
            2.0 * num.atan2(den)
        })
        .sum();
    total / (4.0 * std::f64::consts::PI)
}

/// Six times the signed volume enclosed by the component (positive when wound outward).
/// Taken about the component's first corner so large offsets do not cancel precision.
fn signed_volume(mesh: &MeshDesc, members: &[usize], flip: &[bool]) -> f64 {
    let o = corners(mesh, members[0], false)[0];
    members
        .iter()
        .map(|&t| {
            let [p0, p1, p2] = corners(mesh, t, flip[t]).map(|p| p - o);
            p0.dot(p1.cross(p2))
        })
        .sum()
}

/// Whether the parity assignment reverses more triangle area than it keeps (then the
/// whole component is reversed, so the majority keeps its authored winding).
fn flipped_area_majority(mesh: &MeshDesc, members: &[usize], flip: &[bool]) -> bool {
    let (mut kept, mut flipped) = (0.0, 0.0);
    for &t in members {
        let [p0, p1, p2] = corners(mesh, t, false);
        let area = (p1 - p0).cross(p2 - p0).length();
        if flip[t] {
            flipped += area;
        } else {
            kept += area;
        }
    }
    flipped > kept
}
