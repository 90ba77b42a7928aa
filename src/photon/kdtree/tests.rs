//! kd-tree tests against brute force on the shared point sets of [`point_sets`].

use super::*;
use crate::math::Rng;

/// Named random point sets that stress different tree shapes: a uniform cube, points on
/// planes (axis-aligned and tilted: zero extent along an axis), tight clusters, heavy exact
/// duplicates, and everything at one point. Deterministic for a given `n`.
pub(crate) fn point_sets(n: usize) -> Vec<(&'static str, Vec<Photon>)> {
    let mut rng = Rng::new(&[n as u64, 5]);
    let mut u = move || rng.next_f32();
    let mk = |p: Vec3, i: usize| Photon::new(p, Vec3::Z, [i as f32, 0.0, 0.0, 0.0], 0);
    let mut sets = Vec::new();
    let cube: Vec<Vec3> = (0..n)
        .map(|_| Vec3::new(u(), u(), u()) * 2.0 - 1.0)
        .collect();
    sets.push(("cube", cube));
    let planes: Vec<Vec3> = (0..n)
        .map(|i| {
            let (a, b) = (u() * 2.0 - 1.0, u() * 2.0 - 1.0);
            match i % 3 {
                0 => Vec3::new(a, 0.0, b),            // floor y = 0
                1 => Vec3::new(a, b, -1.0),           // wall z = -1
                _ => Vec3::new(a, 0.5 * a + 0.25, b), // tilted plane
            }
        })
        .collect();
    sets.push(("planes", planes));
    let centres: Vec<Vec3> = (0..5).map(|_| Vec3::new(u(), u(), u()) * 10.0).collect();
    let clusters: Vec<Vec3> = (0..n)
        .map(|i| centres[i % 5] + (Vec3::new(u(), u(), u()) - 0.5) * 0.01)
        .collect();
    sets.push(("clusters", clusters));
    let dups: Vec<Vec3> = (0..n)
        .map(|_| (Vec3::new(u(), u(), u()) * 4.0).floor() * 0.25)
        .collect();
    sets.push(("duplicates", dups));
    sets.push(("one point", vec![Vec3::new(0.3, -0.2, 0.1); n]));
    sets.into_iter()
        .map(|(name, ps)| {
            (
                name,
                ps.into_iter().enumerate().map(|(i, p)| mk(p, i)).collect(),
            )
        })
        .collect()
}

/// Query points: some on the data, some off it, some far away.
pub(crate) fn queries(photons: &[Photon], count: usize) -> Vec<Vec3> {
    let mut rng = Rng::new(&[99, photons.len() as u64]);
    let mut u = move || rng.next_f32();
    (0..count)
        .map(|i| match i % 3 {
            0 if !photons.is_empty() => {
                photons[(u() * photons.len() as f32) as usize % photons.len()].position()
            }
            1 => Vec3::new(u(), u(), u()) * 3.0 - 1.5,
            _ => Vec3::new(u(), u(), u()) * 12.0 - 1.0,
        })
        .collect()
}

/// Brute-force kNN: the k smallest (d², index) with d² ≤ max_r2, sorted.
fn brute_knn(ph: &[Photon], p: Vec3, k: usize, max_r2: f32) -> Vec<(f32, u32)> {
    let mut all: Vec<(f32, u32)> = ph
        .iter()
        .enumerate()
        .map(|(i, q)| (dist2(p.to_array(), q.pos_array()), i as u32))
        .filter(|&(d2, _)| d2 <= max_r2)
        .collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    all.truncate(k);
    all
}

fn sorted(mut v: Vec<(f32, u32)>) -> Vec<(f32, u32)> {
    v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    v
}

#[test]
fn knn_matches_brute_force() {
    // Exact equality is the right test: the tree and the brute force compute d² with the
    // same float expression (`dist2`) and pruning is conservative in floating point, so the
    // selected set of (d², index) pairs must be identical, ties included.
    for n in [0, 1, 7, 9, 300, 3000] {
        for (name, set) in point_sets(n) {
            let map = PhotonMap::build(set);
            assert_eq!(map.len(), n);
            let mut out = Vec::new();
            for q in queries(map.photons(), 60) {
                for k in [1, 10, 100, n + 5] {
                    for max_r2 in [f32::INFINITY, 0.04, 0.0] {
                        let far = map.knn(q, k, max_r2, &mut out);
                        let want = brute_knn(map.photons(), q, k, max_r2);
                        let got = sorted(out.clone());
                        assert_eq!(got, want, "{name} n={n} k={k} r2={max_r2} q={q}");
                        let want_far = want.last().map_or(0.0, |e| e.0);
                        assert_eq!(far, want_far);
                    }
                }
            }
        }
    }
}

#[test]
fn radius_query_matches_brute_force() {
    for (name, set) in point_sets(2000) {
        let map = PhotonMap::build(set);
        for q in queries(map.photons(), 60) {
            for r2 in [0.0, 1e-4, 0.01, 0.3, f32::INFINITY] {
                let mut got = Vec::new();
                map.for_each_index_within(q, r2, |i, d2| got.push((d2, i)));
                let mut got2 = Vec::new();
                map.for_each_within(q, r2, |ph, d2| got2.push((d2, ph.power()[0])));
                assert_eq!(got.len(), got2.len());
                let want = brute_knn(map.photons(), q, usize::MAX, r2);
                assert_eq!(sorted(got), want, "{name} r2={r2} q={q}");
            }
        }
    }
}

#[test]
fn every_input_photon_is_kept_once() {
    for (name, set) in point_sets(1000) {
        let map = PhotonMap::build(set);
        // The generator tags each photon with its input index in power lane 0.
        let mut ids: Vec<u32> = map.photons().iter().map(|p| p.power()[0] as u32).collect();
        ids.sort_unstable();
        assert!(ids.iter().copied().eq(0..1000), "{name}");
    }
}

#[test]
fn degenerate_inputs_and_arguments() {
    let empty = PhotonMap::build(Vec::new());
    let mut out = vec![(1.0, 1)];
    assert!(empty.is_empty());
    assert_eq!(empty.knn(Vec3::ZERO, 5, f32::INFINITY, &mut out), 0.0);
    assert!(out.is_empty());
    empty.for_each_within(Vec3::ZERO, 1.0, |_, _| {
        panic!("empty map reported a photon")
    });

    // Non-finite positions are dropped; bad query arguments find nothing.
    let mut set = point_sets(100).swap_remove(0).1;
    set.push(Photon::new(Vec3::NAN, Vec3::Z, [0.0; 4], 0));
    set.push(Photon::new(
        Vec3::new(f32::INFINITY, 0.0, 0.0),
        Vec3::Z,
        [0.0; 4],
        0,
    ));
    let map = PhotonMap::build(set);
    assert_eq!(map.len(), 100);
    assert!(map.get(99).is_some() && map.get(100).is_none());
    for (p, k, r2) in [
        (Vec3::ZERO, 0, 1.0),
        (Vec3::NAN, 5, 1.0),
        (Vec3::ZERO, 5, f32::NAN),
        (Vec3::ZERO, 5, -1.0),
    ] {
        assert_eq!(map.knn(p, k, r2, &mut out), 0.0);
        assert!(out.is_empty());
        if k > 0 {
            map.for_each_within(p, r2, |_, _| panic!("bad arguments reported a photon"));
        }
    }
}

#[test]
fn build_is_deterministic_across_thread_counts() {
    // Above the parallel threshold, so rayon::join is exercised.
    let n = 3 * PAR_THRESHOLD + 17;
    for (name, set) in point_sets(n).into_iter().take(3) {
        let build = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            pool.install(|| PhotonMap::build(set.clone()))
        };
        let (a, b, c) = (build(1), build(2), build(2));
        assert_eq!(a.photons(), b.photons(), "{name}");
        assert_eq!(a.axes, b.axes, "{name}");
        assert_eq!(b.photons(), c.photons(), "{name}");
        let (mut oa, mut ob) = (Vec::new(), Vec::new());
        for q in queries(a.photons(), 20) {
            a.knn(q, 10, f32::INFINITY, &mut oa);
            b.knn(q, 10, f32::INFINITY, &mut ob);
            assert_eq!(oa, ob, "{name}");
        }
    }
}

#[test]
fn knn_reuses_out_without_reallocating() {
    let map = PhotonMap::build(point_sets(5000).swap_remove(0).1);
    let mut out = Vec::with_capacity(50);
    let (ptr, cap) = (out.as_ptr(), out.capacity());
    for q in queries(map.photons(), 100) {
        let far = map.knn(q, 50, f32::INFINITY, &mut out);
        assert_eq!(out.len(), 50);
        // The heap root is the returned maximum.
        assert_eq!(far, out.iter().fold(0.0f32, |a, e| a.max(e.0)));
    }
    assert_eq!((out.as_ptr(), out.capacity()), (ptr, cap));
}
