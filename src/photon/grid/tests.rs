//! Hash-grid tests against brute force, on the kd-tree tests' point sets.

use super::*;
use crate::photon::kdtree::dist2;
use crate::photon::kdtree::tests::{point_sets, queries};

/// Brute force: every (d², index) with d² ≤ r², sorted.
fn brute(points: &[Photon], p: Vec3, r: f32) -> Vec<(f32, u32)> {
    let r2 = r * r;
    let mut v: Vec<(f32, u32)> = points
        .iter()
        .enumerate()
        .filter(|(_, q)| q.position().is_finite())
        .map(|(i, q)| (dist2(p.to_array(), q.pos_array()), i as u32))
        .filter(|&(d2, _)| d2 <= r2)
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    v
}

fn query(grid: &HashGrid, p: Vec3, r: f32) -> Vec<(f32, u32)> {
    let mut v = Vec::new();
    grid.for_each_within(p, r, |i, d2| v.push((d2, i)));
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    v
}

#[test]
fn matches_brute_force() {
    // Exact equality: both sides use `dist2` and the same `d2 ≤ r²` test, and the padded cell
    // range covers every point that test can accept.
    let mut grid = HashGrid::new();
    for n in [0, 1, 50, 3000] {
        for (name, set) in point_sets(n) {
            for build_r in [0.01, 0.1, 0.5] {
                grid.rebuild(&set, build_r);
                assert_eq!(grid.len(), n);
                for q in queries(&set, 40) {
                    // r = 0 finds exact duplicates; r above the build radius is allowed too.
                    for r in [0.0, 0.5 * build_r, build_r, 3.0 * build_r, 100.0] {
                        let got = query(&grid, q, r);
                        assert_eq!(got, brute(&set, q, r), "{name} n={n} R={build_r} r={r}");
                    }
                }
            }
        }
    }
}

#[test]
fn nan_huge_and_degenerate_inputs() {
    let mut pts = point_sets(500).swap_remove(0).1;
    pts.push(Photon::new(Vec3::NAN, Vec3::Z, [0.0; 4], 0));
    pts.push(Photon::new(
        Vec3::new(1.0, f32::INFINITY, 0.0),
        Vec3::Z,
        [0.0; 4],
        0,
    ));
    for big in [1e20f32, -3e38, 1e30] {
        for j in 0..5 {
            pts.push(Photon::new(
                Vec3::new(big, big * 0.5, big + big * (j as f32 * 1e-6)),
                Vec3::Z,
                [0.0; 4],
                0,
            ));
        }
    }
    let mut grid = HashGrid::new();
    for r in [0.05, 0.0, f32::NAN, f32::INFINITY, 1e-30, 3e38] {
        grid.rebuild(&pts, r);
        assert_eq!(grid.len(), pts.len() - 2, "non-finite points are skipped");
        let mut qs = queries(&pts[..500], 30);
        qs.extend(pts[502..].iter().map(|p| p.position()));
        for q in qs {
            for qr in [0.0, 0.05, 1e25] {
                assert_eq!(
                    query(&grid, q, qr),
                    brute(&pts, q, qr),
                    "R={r} r={qr} q={q}"
                );
            }
        }
    }
    // Bad query arguments report nothing.
    grid.rebuild(&pts, 0.1);
    for (p, r) in [(Vec3::NAN, 0.1), (Vec3::ZERO, f32::NAN), (Vec3::ZERO, -1.0)] {
        grid.for_each_within(p, r, |_, _| panic!("bad query reported a point"));
    }
    // Empty input.
    grid.rebuild(&[], 0.1);
    assert!(grid.is_empty());
    grid.for_each_within(Vec3::ZERO, 1.0, |_, _| {
        panic!("empty grid reported a point")
    });
}

#[test]
fn all_points_in_one_cell() {
    let set = point_sets(2000).swap_remove(4).1; // "one point"
    let mut grid = HashGrid::new();
    grid.rebuild(&set, 0.1);
    let got = query(&grid, set[0].position(), 0.0);
    assert_eq!(got.len(), 2000);
    assert_eq!(got, brute(&set, set[0].position(), 0.0));
    assert!(query(&grid, Vec3::new(5.0, 5.0, 5.0), 0.1).is_empty());
}

#[test]
fn rebuild_reuses_memory_and_is_deterministic() {
    let sets = point_sets(4000);
    let mut grid = HashGrid::new();
    grid.rebuild(&sets[0].1, 0.05);
    let cap = grid.capacity();
    assert!(cap > 0);
    let q = queries(&sets[0].1, 20);
    let order = |g: &HashGrid| {
        let mut v = Vec::new();
        for &p in &q {
            g.for_each_within(p, 0.05, |i, d2| v.push((i, d2)));
        }
        v
    };
    let first = order(&grid);
    // Same input size, different sets and radii: the allocation must not grow.
    for (i, (_, set)) in sets.iter().enumerate().cycle().take(12) {
        grid.rebuild(set, 0.02 + 0.01 * i as f32);
        assert_eq!(grid.capacity(), cap, "capacity grew on rebuild {i}");
    }
    grid.rebuild(&sets[0].1, 0.05);
    // Same visiting order (not just the same set) after rebuilds, and with 1 or 2 threads.
    assert_eq!(order(&grid), first);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        let mut g = HashGrid::new();
        pool.install(|| g.rebuild(&sets[0].1, 0.05));
        assert_eq!(order(&g), first, "{threads} threads");
    }
}
