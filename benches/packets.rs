//! Packet queries against single rays, one thread: `Accel::closest` (Embree:
//! `rtcIntersect1`) against `Accel::closest_packet` at 8 and 16 lanes (`rtcIntersect8/16`),
//! and `Accel::occluded` (`rtcOccluded1`) against `occluded_packet` (`rtcOccluded8/16`), on
//! real scenes. Criterion reports rays/s; each iteration traces one whole ray set.
//!
//! Scenes: CornellBox-Water (`../shared/assets`, or `IRIS_SHARED_ASSETS`; SKIPPED when
//! absent); the caustic sphere, read from `IRIS_PEERS_CS` when set (the peers harness's
//! `cs.glb`), else Iris's own `iris::assets::bench::caustic_sphere`; and
//! `assets/gems/round_diamond.glb`.
//!
//! Ray sets, from the scene's camera (the first one, or the automatic framing) over a
//! 256 × 256 image traversed in 4 × 4 pixel blocks, so a 16-ray packet is one block and an
//! 8-ray packet half of one:
//! - **camera**: the pixel-centre rays (packets traced with `Coherence::Coherent`);
//! - **secondary**: from each camera hit, offset 10⁻⁴ × the scene's diagonal along the
//!   geometric normal facing the camera, a cosine-distributed diffuse bounce direction;
//! - **shadow**: from the same points towards a point sampled on a light (an emissive
//!   triangle, else a punctual light, else a point above the scene), `t_max` just short of
//!   it (`occluded` queries).
//!
//! Secondary and shadow rays are packed in pixel order over the pixels whose camera ray hit
//! (as a lane renderer refilling finished lanes would pack them) and traced `Incoherent`.
//! Every backend compiled in is measured, plus `embree_avx2`: Embree on a device made with
//! `isa=avx2`, i.e. its AVX2 kernels (native packets of 8) on an AVX-512 CPU, to choose
//! the width for AVX2 machines. The BVH answers packets lane by lane; it is measured at 1
//! and 16 lanes to show what the packet API costs it. At 16 lanes Embree is also measured
//! with the other coherence hint (`16_incoherent_hint` for camera rays,
//! `16_coherent_hint` for the others).
//!
//! Run: `cargo bench --bench packets` (`-- --quick` for a short run).
#![forbid(unsafe_code)]

mod common;
use common::splitmix::Rng;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::{Vec2, Vec3};
use iris::accel::packet::{Coherence, Lanes, PacketWidth, RayPacket};
use iris::accel::{Accel, Backend};
use iris::scene::Scene;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

/// Image side: 256² camera rays per scene.
const SIDE: u32 = 256;

/// One ray: origin, direction, `t_max`.
type LaneRay = (Vec3, Vec3, f32);

/// The scenes to measure, by name.
fn scenes() -> Vec<(String, Scene)> {
    let mut out = Vec::new();
    let load = |out: &mut Vec<_>, name: &str, path: &Path| match iris::app::load(path, Backend::Bvh)
    {
        Ok((scene, _)) => out.push((name.to_string(), scene)),
        Err(e) => eprintln!("SKIPPED {name}: {e}"),
    };
    match common::shared_assets() {
        Some(dir) => load(
            &mut out,
            "CornellBox-Water",
            &dir.join("obj/CornellBox-McGuire/CornellBox-Water.obj"),
        ),
        None => eprintln!("SKIPPED CornellBox-Water: ../shared/assets not found"),
    }
    match std::env::var_os("IRIS_PEERS_CS") {
        Some(cs) => load(&mut out, "caustic_sphere_cs.glb", Path::new(&cs)),
        None => {
            let (desc, _) = iris::assets::bench::caustic_sphere(None);
            let desc = iris::scene::validate::validate(desc).expect("caustic sphere");
            out.push((
                "caustic_sphere_builtin".into(),
                Scene::build(desc, Backend::Bvh).expect("caustic sphere"),
            ));
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    load(
        &mut out,
        "round_diamond",
        &root.join("assets/gems/round_diamond.glb"),
    );
    out
}

/// The camera rays in 4 × 4 pixel blocks, block after block.
fn camera_rays(scene: &Scene) -> Vec<LaneRay> {
    let (desc, _) = iris::app::choose_camera(scene, None, 1.0).expect("camera");
    let cam = iris::camera::Camera::new(&desc, SIDE, SIDE);
    let mut rays = Vec::with_capacity((SIDE * SIDE) as usize);
    for by in (0..SIDE).step_by(4) {
        for bx in (0..SIDE).step_by(4) {
            for y in by..by + 4 {
                for x in bx..bx + 4 {
                    let r = cam.generate_ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
                    rays.push((r.origin, r.dir, f32::INFINITY));
                }
            }
        }
    }
    rays
}

/// Where a shadow ray from `p` goes: `(point, true)`, a point on a light, or `(direction,
/// false)` towards a directional light.
fn light_target(scene: &Scene, p: Vec3, rng: &mut Rng) -> (Vec3, bool) {
    if let Some(e) = scene
        .area_lights()
        .sample_point(rng.f32(), Vec2::new(rng.f32(), rng.f32()))
    {
        return (e.point, true);
    }
    let lights = scene.lights();
    if !lights.is_empty() {
        let l = &lights[(rng.next_u64() % lights.len() as u64) as usize];
        if let Some(s) = l.light.sample_li(p) {
            return match s.position {
                Some(q) => (q, true),
                None => (s.wi, false),
            };
        }
    }
    let (lo, hi) = scene.bounds();
    (
        Vec3::new(
            (lo.x + hi.x) * 0.5,
            hi.y + (hi.y - lo.y),
            (lo.z + hi.z) * 0.5,
        ),
        true,
    )
}

/// Secondary (diffuse bounce) and shadow rays from the camera rays' hits, in pixel order.
fn bounce_rays(scene: &Scene, accel: &Accel, camera: &[LaneRay]) -> (Vec<LaneRay>, Vec<LaneRay>) {
    let (lo, hi) = scene.bounds();
    let eps = 1e-4 * (hi - lo).length();
    let mut rng = Rng(0x5EC0_DA27);
    let (mut secondary, mut shadow) = (Vec::new(), Vec::new());
    for &(o, d, t) in camera {
        let Some(h) = accel.closest(o, d, t) else {
            continue;
        };
        let [a, b, c] = scene.triangle(h.prim).p;
        let mut n = (b - a).cross(c - a).normalize_or_zero();
        if n.dot(d) > 0.0 {
            n = -n;
        }
        let p = o + d * h.t + n * eps;
        let (r, phi) = (rng.f32().sqrt(), std::f32::consts::TAU * rng.f32());
        let (s, bt) = n.any_orthonormal_pair();
        let w = s * (r * phi.cos()) + bt * (r * phi.sin()) + n * (1.0 - r * r).max(0.0).sqrt();
        secondary.push((p, w, f32::INFINITY));
        shadow.push(match light_target(scene, p, &mut rng) {
            (q, true) => (p, q - p, 1.0 - 1e-4),
            (wi, false) => (p, wi, f32::INFINITY),
        });
    }
    (secondary, shadow)
}

/// `rays` cut into packets of `N` (the last one partly active).
fn packets<const N: usize>(rays: &[LaneRay]) -> Vec<RayPacket<N>>
where
    Lanes<N>: PacketWidth,
{
    rays.chunks(N)
        .map(|chunk| {
            let mut p = RayPacket::new();
            for (lane, &(o, d, t)) in chunk.iter().enumerate() {
                p.set(lane, o, d, t);
            }
            p
        })
        .collect()
}

/// The queries write into the packet (Embree traces it in place), so each traces a copy,
/// as a caller fills a packet before each query.
fn closest_n<const N: usize>(accel: &Accel, packets: &[RayPacket<N>], c: Coherence) -> u32
where
    Lanes<N>: PacketWidth,
{
    packets
        .iter()
        .map(|p| {
            let mut q = *p;
            accel.closest_packet(black_box(&mut q), c);
            q.hits.hit.count_ones()
        })
        .sum()
}

fn occluded_n<const N: usize>(accel: &Accel, packets: &[RayPacket<N>], c: Coherence) -> u32
where
    Lanes<N>: PacketWidth,
{
    packets
        .iter()
        .map(|p| {
            let mut q = *p;
            accel.occluded_packet(black_box(&mut q), c).count_ones()
        })
        .sum()
}

/// Every measurement of one scene on one backend.
fn bench_scene(c: &mut Criterion, name: &str, backend: &str, accel: &Accel, scene: &Scene) {
    let camera = camera_rays(scene);
    let (secondary, shadow) = bounce_rays(scene, accel, &camera);
    eprintln!(
        "{name} ({} triangles) on {backend}: {} camera rays, {} hit (a secondary and a shadow ray each); packet width {}",
        scene.triangle_count(),
        camera.len(),
        secondary.len(),
        accel.packet_width()
    );
    let embree = backend.starts_with("embree");
    for (set, rays, coherence) in [
        ("camera", &camera, Coherence::Coherent),
        ("secondary", &secondary, Coherence::Incoherent),
        ("shadow", &shadow, Coherence::Incoherent),
    ] {
        let mut g = c.benchmark_group(format!("packets/{name}/{set}"));
        g.sample_size(20)
            .warm_up_time(Duration::from_secs(1))
            .measurement_time(Duration::from_secs(3))
            .throughput(Throughput::Elements(rays.len() as u64));
        let (p8, p16) = (packets::<8>(rays), packets::<16>(rays));
        let id = |w: &str| BenchmarkId::new(backend, w);
        let (other, other_name) = match coherence {
            Coherence::Coherent => (Coherence::Incoherent, "16_incoherent_hint"),
            Coherence::Incoherent => (Coherence::Coherent, "16_coherent_hint"),
        };
        if set == "shadow" {
            g.bench_function(id("1"), |b| {
                b.iter(|| {
                    rays.iter()
                        .filter(|r| accel.occluded(r.0, r.1, r.2))
                        .count()
                })
            });
            if embree {
                g.bench_function(id("8"), |b| b.iter(|| occluded_n(accel, &p8, coherence)));
            }
            g.bench_function(id("16"), |b| b.iter(|| occluded_n(accel, &p16, coherence)));
            if embree {
                g.bench_function(id(other_name), |b| {
                    b.iter(|| occluded_n(accel, &p16, other))
                });
            }
        } else {
            // Every field of the hit is consumed, as the packet queries write them all.
            g.bench_function(id("1"), |b| {
                b.iter(|| {
                    rays.iter()
                        .filter(|r| black_box(accel.closest(r.0, r.1, r.2)).is_some())
                        .count()
                })
            });
            if embree {
                g.bench_function(id("8"), |b| b.iter(|| closest_n(accel, &p8, coherence)));
            }
            g.bench_function(id("16"), |b| b.iter(|| closest_n(accel, &p16, coherence)));
            if embree {
                g.bench_function(id(other_name), |b| b.iter(|| closest_n(accel, &p16, other)));
            }
        }
        g.finish();
    }
}

fn packets_vs_single(c: &mut Criterion) {
    #[cfg(feature = "embree")]
    iris::accel::embree::enable_flush_to_zero();
    for (name, scene) in scenes() {
        let indices: Vec<[u32; 3]> = scene.triangles().iter().map(|t| t.vertices).collect();
        for (backend, kind) in common::backends() {
            let accel = Accel::build(kind, scene.positions(), &indices).expect("accel");
            bench_scene(c, &name, backend, &accel, &scene);
        }
        // Embree's AVX2 kernels (native width 8) on the same CPU, when it has AVX-512.
        #[cfg(all(feature = "embree", target_arch = "x86_64"))]
        if std::arch::is_x86_feature_detected!("avx512f") {
            let e = iris::accel::embree::EmbreeAccel::build_with_config(
                scene.positions(),
                &indices,
                None,
                "verbose=0,isa=avx2",
            )
            .expect("embree with isa=avx2");
            bench_scene(c, &name, "embree_avx2", &Accel::Embree(e), &scene);
        }
    }
}

criterion_group!(benches, packets_vs_single);
criterion_main!(benches);
