//! Closest-hit throughput of the acceleration backends on a generated 1M-triangle mesh
//! (criterion reports rays/s: every benchmark is one pass over a 262,144-ray set, 1 thread).
//!
//! Mesh: [`displaced_icosphere`], an icosahedron whose faces are split 224×224 and pushed
//! out by 6 octaves of radial sine noise (the `raybench` mesh: 1,003,520 closed triangles).
//! Ray sets: [`coherent_rays`] (pinhole camera, 8×8 tiles) and [`incoherent_rays`] (from
//! random surface points, cosine-distributed in/out, random order). Directions are unit.
//!
//! Groups: `raw_embree_rtcIntersect1` (bare FFI loop, the ceiling), `embree_backend`
//! (`EmbreeAccel::closest`), `bvh_backend` (`BvhAccel::closest`), and the full intersection
//! layer (`Scene::intersect`, which builds the hit record: position, normals, uv, material,
//! front_face) on each backend: `iris_layer_embree`, `iris_layer_bvh`.
//!
//! The `embree4-rs` 0.0.16 wrapper is not benchmarked: it declares the Embree 4.2
//! `RTCRayHit` (80 bytes) while the Embree 4.4 library writes 96 (`instPrimID` at byte 80),
//! i.e. 4 bytes past its stack value on every hit; see `src/accel/embree.rs`.
//!
//! Group `shared_scenes/<scene>/<backend>/<set>` (issue 6): the same layer on real scenes
//! from `../shared/assets` (or `IRIS_SHARED_ASSETS`; SKIPPED when absent), with
//! [`SHARED_RAYS`] rays per set: **coherent** = the scene's camera rays (first camera, or
//! the auto-framing one) over a 256 × 256 image in 8×8 tiles; **incoherent** = origins
//! uniform in the scene's bounding box, directions uniform on the sphere, in random order.
//! The hit fraction and the share of rays on which Embree and the BVH agree are printed.
//!
//! Group `axis_rays/<backend>/<set>` (issue 7): orthographic rays exactly along −Z (two
//! zero direction components) over the mesh vs the same rays tilted by 1 mrad, on each
//! backend. Before the BVH backend used a finite inverse for zero components, obvhs
//! accepted every node for such rays (NaN box distances); the ratio axis/tilted shows the
//! cost of axis-aligned rays now.
//!
//! Run: `cargo bench --bench accel` (add `-- --quick` for a short run;
//! `cargo bench --bench accel -- shared_scenes` for the real scenes alone).
#![forbid(unsafe_code)]

mod common;
use common::splitmix::Rng;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::Vec3;
use iris::accel::bvh::BvhAccel;
use std::collections::HashMap;
use std::time::Duration;

/// Rays per set (one criterion iteration traces them all).
const RAYS: usize = 1 << 18;
/// Face subdivision of the icosahedron: 20·224² = 1,003,520 triangles.
const SUBDIV: u32 = 224;

/// Closed, watertight icosphere with faces split `n`×`n`, radially displaced by 6 octaves
/// of sine noise (about ±0.1 of the unit radius). Shared vertices are generated once
/// (keyed by their integer barycentric position on the icosahedron), so there are no cracks.
pub fn displaced_icosphere(n: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let (ico, faces) = iris::authoring::shapes::icosahedron();
    let ico: Vec<Vec3> = ico.iter().map(|v| v.as_vec3()).collect();
    let octaves: Vec<(Vec3, f32, f32, f32)> = (0..6)
        .map(|k| {
            let f = 2f32.powi(k + 1) * 1.7;
            let axis = Vec3::new(
                (k as f32 * 1.3).sin(),
                (k as f32 * 2.1).cos(),
                0.5 + k as f32 * 0.37,
            )
            .normalize();
            (axis, f, 0.05 / 1.6f32.powi(k), k as f32 * 0.9)
        })
        .collect();
    let mut positions = Vec::new();
    let mut ids: HashMap<[(u32, u32); 3], u32> = HashMap::new();
    let mut vertex = |weights: [(u32, u32); 3]| -> u32 {
        // Canonical key: (corner id, weight) sorted by id, so faces sharing an edge agree.
        let mut key = weights.map(|(c, w)| if w == 0 { (u32::MAX, 0) } else { (c, w) });
        key.sort_unstable();
        *ids.entry(key).or_insert_with(|| {
            let dir = key
                .iter()
                .filter(|(c, _)| *c != u32::MAX)
                .fold(Vec3::ZERO, |s, &(c, w)| s + ico[c as usize] * w as f32)
                .normalize();
            let bump: f32 = octaves
                .iter()
                .map(|&(a, f, amp, ph)| amp * (f * dir.dot(a) + ph + 3.0 * dir.x * dir.z).sin())
                .sum();
            positions.push(dir * (1.0 + bump));
            positions.len() as u32 - 1
        })
    };
    let mut indices = Vec::with_capacity(20 * (n * n) as usize);
    for [a, b, c] in faces {
        let at = |i: u32, j: u32| [(a, n - i - j), (b, i), (c, j)];
        let mut grid = vec![vec![0u32; (n + 1) as usize]; (n + 1) as usize];
        for i in 0..=n {
            for j in 0..=n - i {
                grid[i as usize][j as usize] = vertex(at(i, j));
            }
        }
        for i in 0..n as usize {
            for j in 0..n as usize - i {
                indices.push([grid[i][j], grid[i + 1][j], grid[i][j + 1]]);
                if i + j + 1 < n as usize {
                    indices.push([grid[i + 1][j], grid[i + 1][j + 1], grid[i][j + 1]]);
                }
            }
        }
    }
    (positions, indices)
}

/// Pinhole camera rays from (0, 0, 3.5) towards the origin, `RAYS` pixels (512²) traced in
/// 8×8 tiles; the field of view makes the unit-ish sphere cover about 64 % of the image.
pub fn coherent_rays() -> Vec<(Vec3, Vec3)> {
    let side = (RAYS as f64).sqrt() as usize;
    let eye = Vec3::new(0.0, 0.0, 3.5);
    let tan_half = (1.1 / (3.5f32 * 3.5 - 1.1 * 1.1).sqrt()) / 0.9;
    let mut rays = Vec::with_capacity(side * side);
    for ty in (0..side).step_by(8) {
        for tx in (0..side).step_by(8) {
            for y in ty..ty + 8 {
                for x in tx..tx + 8 {
                    let px = ((x as f32 + 0.5) / side as f32 * 2.0 - 1.0) * tan_half;
                    let py = (1.0 - (y as f32 + 0.5) / side as f32 * 2.0) * tan_half;
                    rays.push((eye, Vec3::new(px, py, -1.0).normalize()));
                }
            }
        }
    }
    rays
}

/// Rays leaving random surface points (uniform over a random triangle, offset 1e-4 along
/// the geometric normal), cosine-distributed about +normal or −normal with equal odds.
pub fn incoherent_rays(positions: &[Vec3], indices: &[[u32; 3]]) -> Vec<(Vec3, Vec3)> {
    let mut rng = Rng(0x1C0_4E7E);
    (0..RAYS)
        .map(|_| {
            let tri = indices[(rng.next_u64() % indices.len() as u64) as usize]
                .map(|k| positions[k as usize]);
            let (mut a, mut b) = (rng.f32(), rng.f32());
            if a + b > 1.0 {
                (a, b) = (1.0 - a, 1.0 - b);
            }
            let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
            let n = if rng.next_u64() & 1 == 0 { n } else { -n };
            let p = tri[0] + (tri[1] - tri[0]) * a + (tri[2] - tri[0]) * b + n * 1e-4;
            let (r, phi) = (rng.f32().sqrt(), std::f32::consts::TAU * rng.f32());
            let (t, bt) = n.any_orthonormal_pair();
            let d = t * (r * phi.cos()) + bt * (r * phi.sin()) + n * (1.0 - r * r).max(0.0).sqrt();
            (p, d.normalize())
        })
        .collect()
}

fn configure<'a>(
    c: &'a mut Criterion,
    name: &str,
) -> criterion::BenchmarkGroup<'a, criterion::measurement::WallTime> {
    let mut g = c.benchmark_group(name);
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5))
        .throughput(Throughput::Elements(RAYS as u64));
    g
}

/// Benchmarks `trace` (one ray → hit distance or ∞) over both ray sets.
fn bench_sets(
    c: &mut Criterion,
    name: &str,
    sets: &[(&str, Vec<(Vec3, Vec3)>)],
    trace: impl Fn(Vec3, Vec3) -> f32,
) {
    let mut g = configure(c, name);
    for (set, rays) in sets {
        g.bench_with_input(BenchmarkId::from_parameter(set), rays, |bch, rays| {
            bch.iter(|| {
                rays.iter()
                    .map(|&(o, d)| trace(o, d))
                    .filter(|t| t.is_finite())
                    .count()
            })
        });
    }
    g.finish();
}

/// The full intersection layer on `backend`: one `Scene::intersect` per ray.
fn layer(
    c: &mut Criterion,
    name: &str,
    positions: &[Vec3],
    indices: &[[u32; 3]],
    sets: &[(&str, Vec<(Vec3, Vec3)>)],
    backend: iris::accel::Backend,
) {
    let desc = iris::scene::desc::SceneDesc {
        source: "bench".into(),
        meshes: vec![iris::scene::desc::MeshDesc {
            name: "displaced icosphere".into(),
            positions: positions.to_vec(),
            indices: indices.to_vec(),
            ..Default::default()
        }],
        ..Default::default()
    };
    let scene = iris::scene::Scene::build(desc, backend).expect("scene");
    bench_sets(c, name, sets, |o, d| {
        scene
            .intersect(&iris::math::Ray::new(o, d))
            .map_or(f32::INFINITY, |h| h.t)
    });
}

fn backends(c: &mut Criterion) {
    let (positions, indices) = displaced_icosphere(SUBDIV);
    let sets = [
        ("coherent", coherent_rays()),
        ("incoherent", incoherent_rays(&positions, &indices)),
    ];
    eprintln!(
        "mesh: {} triangles, {} vertices; {RAYS} rays per set",
        indices.len(),
        positions.len()
    );

    let bvh = BvhAccel::build(&positions, &indices);
    #[cfg(feature = "embree")]
    {
        embree::all(c, &positions, &indices, &sets, &bvh);
        layer(
            c,
            "iris_layer_embree",
            &positions,
            &indices,
            &sets,
            iris::accel::Backend::Embree,
        );
    }
    layer(
        c,
        "iris_layer_bvh",
        &positions,
        &indices,
        &sets,
        iris::accel::Backend::Bvh,
    );
    bench_sets(c, "bvh_backend", &sets, |o, d| {
        bvh.closest(o, d, f32::INFINITY)
            .map_or(f32::INFINITY, |h| h.t)
    });
}

#[cfg(feature = "embree")]
mod embree {
    use super::*;
    use iris::accel::embree::{embree_version, enable_flush_to_zero, EmbreeAccel};

    pub fn all(
        c: &mut Criterion,
        positions: &[Vec3],
        indices: &[[u32; 3]],
        sets: &[(&str, Vec<(Vec3, Vec3)>)],
        bvh: &BvhAccel,
    ) {
        enable_flush_to_zero();
        let t0 = std::time::Instant::now();
        let accel = EmbreeAccel::build(positions, indices).expect("embree build");
        eprintln!(
            "embree {} ({}), build {:.2} s",
            embree_version(),
            env!("IRIS_EMBREE_SOURCE"),
            t0.elapsed().as_secs_f64()
        );
        for (set, rays) in sets {
            let mut t = vec![0.0; rays.len()];
            accel.raw_closest_batch(rays, &mut t);
            let hits = t.iter().filter(|t| t.is_finite()).count();
            let agree = |f: &dyn Fn(Vec3, Vec3) -> f32| {
                let same = |a: f32, b: f32| a == b || (a - b).abs() <= 1e-4 * b.abs();
                rays.iter()
                    .zip(&t)
                    .filter(|&(&(o, d), &t)| same(f(o, d), t))
                    .count()
            };
            let bvh_agree = agree(&|o, d| {
                bvh.closest(o, d, f32::INFINITY)
                    .map_or(f32::INFINITY, |h| h.t)
            });
            eprintln!(
                "{set}: hit fraction {:.3}; agreement with raw embree: bvh {:.5}%",
                hits as f64 / rays.len() as f64,
                100.0 * bvh_agree as f64 / rays.len() as f64
            );
        }

        let mut g = configure(c, "raw_embree_rtcIntersect1");
        for (set, rays) in sets {
            let mut out = vec![0.0; rays.len()];
            g.bench_with_input(BenchmarkId::from_parameter(set), rays, |bch, rays| {
                bch.iter(|| {
                    accel.raw_closest_batch(rays, &mut out);
                    std::hint::black_box(&out);
                })
            });
        }
        g.finish();
        bench_sets(c, "embree_backend", sets, |o, d| {
            accel
                .closest(o, d, f32::INFINITY)
                .map_or(f32::INFINITY, |h| h.t)
        });
        // The same backend with build quality MEDIUM (the default above is HIGH).
        let t0 = std::time::Instant::now();
        let medium =
            EmbreeAccel::build_with_quality(positions, indices, Some(false)).expect("embree build");
        eprintln!("embree MEDIUM build {:.2} s", t0.elapsed().as_secs_f64());
        bench_sets(c, "embree_backend_medium", sets, |o, d| {
            medium
                .closest(o, d, f32::INFINITY)
                .map_or(f32::INFINITY, |h| h.t)
        });
    }
}

/// Rays per set on the shared scenes (256²).
const SHARED_RAYS: usize = 1 << 16;

/// The scene's camera rays over a 256 × 256 image, traced in 8×8 tiles.
fn camera_rays(scene: &iris::scene::Scene) -> Vec<(Vec3, Vec3)> {
    let side = (SHARED_RAYS as f64).sqrt() as u32;
    let (desc, _) = iris::app::choose_camera(scene, None, 1.0).expect("camera");
    let cam = iris::camera::Camera::new(&desc, side, side);
    let mut rays = Vec::with_capacity(SHARED_RAYS);
    for ty in (0..side).step_by(8) {
        for tx in (0..side).step_by(8) {
            for y in ty..ty + 8 {
                for x in tx..tx + 8 {
                    let r = cam.generate_ray(glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
                    rays.push((r.origin, r.dir));
                }
            }
        }
    }
    rays
}

/// Origins uniform in the bounding box `(lo, hi)`, unit directions uniform on the sphere.
fn box_rays(lo: Vec3, hi: Vec3) -> Vec<(Vec3, Vec3)> {
    let mut rng = Rng(0xB0C5_5EED);
    (0..SHARED_RAYS)
        .map(|_| {
            let o = lo + (hi - lo) * Vec3::new(rng.f32(), rng.f32(), rng.f32());
            let z = 1.0 - 2.0 * rng.f32();
            let phi = std::f32::consts::TAU * rng.f32();
            let r = (1.0 - z * z).max(0.0).sqrt();
            (o, Vec3::new(r * phi.cos(), r * phi.sin(), z))
        })
        .collect()
}

/// `Scene::intersect` throughput per backend on real scenes (see the module docs).
fn shared_scenes(c: &mut Criterion) {
    let dir = std::env::var_os("IRIS_SHARED_ASSETS")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| {
            std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/assets")
        });
    if !dir.is_dir() {
        eprintln!("SKIPPED shared_scenes: ../shared/assets not found (set IRIS_SHARED_ASSETS)");
        return;
    }
    let scenes = [
        (
            "CornellBox-Water",
            "obj/CornellBox-McGuire/CornellBox-Water.obj",
        ),
        (
            "GlassVaseFlowers",
            "khronos/GlassVaseFlowers/GlassVaseFlowers.glb",
        ),
        (
            "DispersionTest",
            "khronos/DispersionTest/DispersionTest.glb",
        ),
        (
            "TransmissionTest",
            "khronos/TransmissionTest/TransmissionTest.glb",
        ),
    ];
    let mut backends = vec![("bvh", iris::accel::Backend::Bvh)];
    if cfg!(feature = "embree") {
        backends.insert(0, ("embree", iris::accel::Backend::Embree));
    }
    let mut g = c.benchmark_group("shared_scenes");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .throughput(Throughput::Elements(SHARED_RAYS as u64));
    for (name, file) in scenes {
        let built: Vec<_> = backends
            .iter()
            .filter_map(
                |&(b, backend)| match iris::app::load(&dir.join(file), backend) {
                    Ok((scene, _)) => Some((b, scene)),
                    Err(e) => {
                        eprintln!("SKIPPED {name} on {b}: {e}");
                        None
                    }
                },
            )
            .collect();
        let Some((_, first)) = built.first() else {
            continue;
        };
        let sets = [
            ("coherent", camera_rays(first)),
            ("incoherent", box_rays(first.bounds().0, first.bounds().1)),
        ];
        let trace = |scene: &iris::scene::Scene, (o, d): (Vec3, Vec3)| {
            scene
                .intersect(&iris::math::Ray::new(o, d))
                .map_or(f32::INFINITY, |h| h.t)
        };
        for (set, rays) in &sets {
            let t: Vec<Vec<f32>> = built
                .iter()
                .map(|(_, s)| rays.iter().map(|&r| trace(s, r)).collect())
                .collect();
            let hits = t[0].iter().filter(|t| t.is_finite()).count();
            let agree = t.last().map_or(0, |last| {
                t[0].iter()
                    .zip(last)
                    .filter(|&(a, b)| a == b || (a - b).abs() <= 1e-4 * b.abs())
                    .count()
            });
            eprintln!(
                "{name} ({} triangles) {set}: hit fraction {:.3}; {} agree with {}: {:.3}%",
                first.triangle_count(),
                hits as f64 / rays.len() as f64,
                built.last().map_or("", |b| b.0),
                built[0].0,
                100.0 * agree as f64 / rays.len() as f64
            );
        }
        for (b, scene) in &built {
            for (set, rays) in &sets {
                g.bench_with_input(
                    BenchmarkId::new(format!("{name}/{b}"), set),
                    rays,
                    |bch, rays| {
                        bch.iter(|| {
                            rays.iter()
                                .map(|&r| trace(scene, r))
                                .filter(|t| t.is_finite())
                                .count()
                        })
                    },
                );
            }
        }
    }
    g.finish();
}

/// One ray (origin, direction) → hit distance or ∞.
type Tracer = Box<dyn Fn(Vec3, Vec3) -> f32>;

/// Orthographic rays on a 128 × 128 grid over the mesh's box, along −Z or tilted 1 mrad.
fn ortho_rays(positions: &[Vec3], tilt: bool) -> Vec<(Vec3, Vec3)> {
    let (lo, hi) = positions.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(a, b), p| (a.min(*p), b.max(*p)),
    );
    let d = if tilt {
        Vec3::new(1e-3, 7e-4, -1.0).normalize()
    } else {
        Vec3::NEG_Z
    };
    (0..128 * 128)
        .map(|i| {
            let (u, v) = ((i % 128) as f32 / 127.0, (i / 128) as f32 / 127.0);
            let o = Vec3::new(
                lo.x + u * (hi.x - lo.x),
                lo.y + v * (hi.y - lo.y),
                hi.z + 1.0,
            );
            (o, d)
        })
        .collect()
}

fn axis_rays(c: &mut Criterion) {
    let (positions, indices) = displaced_icosphere(SUBDIV / 4);
    let sets = [
        ("along_axis", ortho_rays(&positions, false)),
        ("tilted_1mrad", ortho_rays(&positions, true)),
    ];
    let mut g = c.benchmark_group("axis_rays");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .throughput(Throughput::Elements(sets[0].1.len() as u64));
    let bvh = BvhAccel::build(&positions, &indices);
    let bvh_tracer: (&str, Tracer) = (
        "bvh",
        Box::new(move |o, d| {
            bvh.closest(o, d, f32::INFINITY)
                .map_or(f32::INFINITY, |h| h.t)
        }),
    );
    #[cfg(feature = "embree")]
    let embree_tracer: Option<(&str, Tracer)> = {
        let e = iris::accel::embree::EmbreeAccel::build(&positions, &indices).expect("embree");
        Some((
            "embree",
            Box::new(move |o, d| {
                e.closest(o, d, f32::INFINITY)
                    .map_or(f32::INFINITY, |h| h.t)
            }),
        ))
    };
    #[cfg(not(feature = "embree"))]
    let embree_tracer: Option<(&str, Tracer)> = None;
    let accels: Vec<(&str, Tracer)> = std::iter::once(bvh_tracer).chain(embree_tracer).collect();
    for (name, trace) in &accels {
        for (set, rays) in &sets {
            g.bench_with_input(BenchmarkId::new(*name, set), rays, |bch, rays| {
                bch.iter(|| {
                    rays.iter()
                        .map(|&(o, d)| trace(o, d))
                        .filter(|t| t.is_finite())
                        .count()
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, axis_rays, shared_scenes, backends);
criterion_main!(benches);
