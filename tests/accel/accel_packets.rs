//! Packet queries (`Accel::closest_packet`, `Accel::occluded_packet`) against the
//! single-ray queries, lane by lane, on every backend compiled in (and Embree's AVX2
//! kernels besides its AVX-512 ones), at widths 8 and 16, both coherence hints: the same
//! hits bit for bit (t, triangle, barycentrics) and the same occlusion, on real meshes (a gem of assets/, and CornellBox-Water and GlassVaseFlowers
//! from the shared assets when present), with random active masks, `t_max` limits
//! (finite, +∞, 0, negative, NaN) and rays no backend can trace (NaN or infinite origin or
//! direction, zero direction), which report no hit and no occlusion and are listed by
//! `RayPacket::untraceable`.

use crate::common;
use common::splitmix::Rng;

use glam::Vec3;
use iris::accel::packet::{Coherence, Lanes, PacketWidth, RayPacket};
use iris::accel::{Accel, RawHit};
use std::path::Path;

/// Packets per ray kind and scene.
const PACKETS: usize = 1500;

/// A scene's triangles: positions and vertex indices in the scene's triangle order.
struct Mesh {
    name: String,
    positions: Vec<Vec3>,
    indices: Vec<[u32; 3]>,
    lo: Vec3,
    hi: Vec3,
}

fn mesh(path: &Path) -> Mesh {
    let (scene, _) = iris::app::load(path, iris::accel::Backend::Bvh)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let (lo, hi) = scene.bounds();
    Mesh {
        name: path.file_name().unwrap().to_string_lossy().into_owned(),
        positions: scene.positions().to_vec(),
        indices: scene.triangles().iter().map(|t| t.vertices).collect(),
        lo,
        hi,
    }
}

fn meshes() -> Vec<Mesh> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut v = vec![mesh(&root.join("assets/gems/round_diamond.glb"))];
    if let Some(shared) = common::shared_assets() {
        v.push(mesh(
            &shared.join("obj/CornellBox-McGuire/CornellBox-Water.obj"),
        ));
        v.push(mesh(
            &shared.join("khronos/GlassVaseFlowers/GlassVaseFlowers.glb"),
        ));
    }
    v
}

/// One ray of a packet: origin, direction, `t_max`.
type LaneRay = (Vec3, Vec3, f32);

/// A `t_max` for a ray of a scene of diagonal `diag`: mostly +∞ or a random fraction of the
/// diagonal (cutting hits short), sometimes 0, negative or NaN.
fn t_max(rng: &mut Rng, diag: f32) -> f32 {
    match rng.next_u64() % 16 {
        0 => 0.0,
        1 => -diag * rng.f32(),
        2 => f32::NAN,
        3..=8 => f32::INFINITY,
        _ => diag * 1.5 * rng.f32(),
    }
}

/// Rays from uniform points in the (enlarged) box in uniform directions.
fn box_ray(rng: &mut Rng, m: &Mesh) -> LaneRay {
    let pad = (m.hi - m.lo) * 0.25;
    let diag = (m.hi - m.lo).length();
    (
        rng.in_box(m.lo - pad, m.hi + pad),
        rng.unit_vector() * (0.5 + rng.f32()),
        t_max(rng, diag),
    )
}

/// Rays leaving a point on a random triangle (no offset) in a random direction: hits at
/// and near t = 0 and at grazing angles, where rounding differences would show.
fn surface_ray(rng: &mut Rng, m: &Mesh) -> LaneRay {
    let [a, b, c] = m.indices[(rng.next_u64() % m.indices.len() as u64) as usize]
        .map(|k| m.positions[k as usize]);
    let (mut s, mut t) = (rng.f32(), rng.f32());
    if s + t > 1.0 {
        (s, t) = (1.0 - s, 1.0 - t);
    }
    let p = a + (b - a) * s + (c - a) * t;
    (p, rng.unit_vector(), t_max(rng, (m.hi - m.lo).length()))
}

/// Neighbouring camera-like rays: one eye outside the box, directions through a small
/// jittered patch around a random point of the box.
fn camera_packet(rng: &mut Rng, m: &Mesh, n: usize) -> Vec<LaneRay> {
    let diag = (m.hi - m.lo).length();
    let centre = (m.lo + m.hi) * 0.5;
    let eye = centre + rng.unit_vector() * diag * 1.5;
    let target = rng.in_box(m.lo, m.hi);
    (0..n)
        .map(|_| {
            let jitter = (rng.unit_vector() * rng.f32()) * diag * 0.02;
            (eye, target + jitter - eye, f32::INFINITY)
        })
        .collect()
}

/// A ray no backend can trace.
fn bad_ray(rng: &mut Rng) -> LaneRay {
    let o = Vec3::new(0.1, 0.2, 5.0);
    match rng.next_u64() % 6 {
        0 => (Vec3::new(f32::NAN, 0.0, 5.0), Vec3::NEG_Z, f32::INFINITY),
        1 => (Vec3::new(0.0, f32::INFINITY, 5.0), Vec3::NEG_Z, 10.0),
        2 => (o, Vec3::new(0.0, f32::NAN, -1.0), f32::INFINITY),
        3 => (o, Vec3::new(0.0, 0.0, f32::NEG_INFINITY), f32::INFINITY),
        4 => (o, Vec3::ZERO, f32::INFINITY),
        _ => (o, Vec3::NEG_Z, f32::NAN),
    }
}

fn same(a: Option<RawHit>, b: Option<RawHit>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            a.prim == b.prim
                && a.t.to_bits() == b.t.to_bits()
                && a.u.to_bits() == b.u.to_bits()
                && a.v.to_bits() == b.v.to_bits()
        }
        _ => false,
    }
}

/// Whether the single-ray queries can trace `r` (what `RayPacket::traceable` admits).
fn traceable((o, d, t): LaneRay) -> bool {
    o.is_finite() && d.is_finite() && d != Vec3::ZERO && t > 0.0
}

/// Traces `rays` (one per lane, `None` = inactive) as a packet and lane by lane and
/// compares; returns the number of hits compared.
fn check_packet<const N: usize>(
    accel: &Accel,
    rays: &[Option<LaneRay>],
    coherence: Coherence,
    what: &str,
) -> usize
where
    Lanes<N>: PacketWidth,
{
    let mut p = RayPacket::<N>::new();
    // Inactive lanes hold garbage: it must be ignored.
    p.org_x = [f32::NAN; N];
    p.dir_y = [f32::INFINITY; N];
    for (lane, r) in rays.iter().enumerate() {
        if let Some((o, d, t)) = *r {
            p.set(lane, o, d, t);
        }
    }
    // Stale results must be cleared. The queries write into the packet: each traces a copy.
    p.hits.hit = RayPacket::<N>::FULL;
    let mut hits = p;
    accel.closest_packet(&mut hits, coherence);
    let occluded = accel.occluded_packet(&mut p.clone(), coherence);
    let mut compared = 0;
    for (lane, r) in rays.iter().enumerate() {
        let ctx = || {
            format!(
                "{what}, {} N={N} {coherence:?} lane {lane}: {r:?}",
                accel.name()
            )
        };
        let bit = 1u32 << lane;
        match *r {
            None => {
                assert!(hits.hit(lane).is_none(), "{}: inactive lane hit", ctx());
                assert_eq!(occluded & bit, 0, "{}: inactive lane occluded", ctx());
                assert_eq!(p.untraceable() & bit, 0, "{}", ctx());
            }
            Some(ray) if !traceable(ray) => {
                assert!(hits.hit(lane).is_none(), "{}: untraceable lane hit", ctx());
                assert_eq!(occluded & bit, 0, "{}: untraceable lane occluded", ctx());
                let invalid = !iris::math::Ray {
                    origin: ray.0,
                    dir: ray.1,
                    t_max: ray.2,
                    skipped: 0.0,
                }
                .is_valid();
                assert_eq!(p.untraceable() & bit != 0, invalid, "{}", ctx());
                // The single-ray queries find nothing either: for t_max ≤ 0 or NaN by
                // their contract, for the rest as both backends behave on these rays.
                assert!(accel.closest(ray.0, ray.1, ray.2).is_none(), "{}", ctx());
                assert!(!accel.occluded(ray.0, ray.1, ray.2), "{}", ctx());
            }
            Some((o, d, t)) => {
                let single = accel.closest(o, d, t);
                let packet = hits.hit(lane);
                assert!(
                    same(single, packet),
                    "{}: single {single:?}, packet {packet:?}",
                    ctx()
                );
                assert_eq!(
                    occluded & bit != 0,
                    accel.occluded(o, d, t),
                    "{}: occlusion differs",
                    ctx()
                );
                compared += usize::from(single.is_some());
            }
        }
    }
    compared
}

/// A random active mask over `n` lanes: empty, full, or each lane with probability ½.
fn mask(rng: &mut Rng, n: usize) -> u32 {
    match rng.next_u64() % 8 {
        0 => 0,
        1..=3 => (1u32 << n) - 1,
        _ => rng.next_u64() as u32 & ((1u32 << n) - 1),
    }
}

fn run<const N: usize>(accel: &Accel, m: &Mesh, rng: &mut Rng)
where
    Lanes<N>: PacketWidth,
{
    let mut compared = [0usize; 3];
    for _ in 0..PACKETS {
        let active = mask(rng, N);
        let lane_ray = |rng: &mut Rng, lane: usize, kind: usize| {
            (active & (1 << lane) != 0).then(|| match kind {
                0 => box_ray(rng, m),
                _ => surface_ray(rng, m),
            })
        };
        for kind in [0, 1] {
            let coherence = match rng.next_u64() % 2 {
                0 => Coherence::Coherent,
                _ => Coherence::Incoherent,
            };
            let mut rays: Vec<_> = (0..N).map(|lane| lane_ray(rng, lane, kind)).collect();
            // A few untraceable lanes in one packet in eight.
            if rng.next_u64().is_multiple_of(8) {
                let lane = (rng.next_u64() % N as u64) as usize;
                rays[lane] = Some(bad_ray(rng));
            }
            compared[kind] += check_packet::<N>(accel, &rays, coherence, &m.name);
        }
        let cam: Vec<_> = camera_packet(rng, m, N)
            .into_iter()
            .enumerate()
            .map(|(lane, r)| (active & (1 << lane) != 0).then_some(r))
            .collect();
        compared[2] += check_packet::<N>(accel, &cam, Coherence::Coherent, &m.name);
        check_packet::<N>(accel, &cam, Coherence::Incoherent, &m.name);
    }
    eprintln!(
        "{} {} N={N}: hits compared: box {}, surface {}, camera {}",
        m.name,
        accel.name(),
        compared[0],
        compared[1],
        compared[2]
    );
    // The comparison must have had something to compare.
    assert!(compared.iter().all(|&c| c > PACKETS / 4), "{compared:?}");
}

/// Every backend compiled in, plus Embree running its AVX2 kernels (`isa=avx2`) when the
/// CPU would otherwise give it the AVX-512 ones.
fn accels(m: &Mesh) -> Vec<Accel> {
    let v: Vec<Accel> = common::backends()
        .into_iter()
        .map(|b| Accel::build(b, &m.positions, &m.indices).expect("build"))
        .collect();
    #[cfg(all(feature = "embree", target_arch = "x86_64"))]
    let mut v = v;
    #[cfg(all(feature = "embree", target_arch = "x86_64"))]
    if std::arch::is_x86_feature_detected!("avx512f") {
        let e = iris::accel::embree::EmbreeAccel::build_with_config(
            &m.positions,
            &m.indices,
            None,
            "verbose=0,isa=avx2",
        )
        .expect("build with isa=avx2");
        assert_eq!(e.native_packet_width(), Some(8));
        v.push(Accel::Embree(e));
    }
    v
}

#[test]
fn packets_match_single_rays_on_real_meshes() {
    for m in meshes() {
        for accel in accels(&m) {
            let mut rng = Rng(0x9AC4_E75E ^ m.indices.len() as u64);
            run::<8>(&accel, &m, &mut rng);
            run::<16>(&accel, &m, &mut rng);
        }
    }
}

#[test]
fn packet_width_is_8_or_16() {
    let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
    for backend in common::backends() {
        let accel = Accel::build(backend, &tri, &[[0, 1, 2]]).expect("build");
        assert!(
            [8, 16].contains(&accel.packet_width()),
            "{backend:?}: {}",
            accel.packet_width()
        );
    }
}

#[test]
fn empty_scene_and_empty_packet_find_nothing() {
    for backend in common::backends() {
        let accel = Accel::build(backend, &[], &[]).expect("build");
        let mut p = RayPacket::<16>::new();
        for lane in 0..16 {
            p.set(lane, Vec3::ZERO, Vec3::X, f32::INFINITY);
        }
        p.hits.hit = RayPacket::<16>::FULL;
        accel.closest_packet(&mut p, Coherence::Coherent);
        assert_eq!(p.hits.hit, 0, "{backend:?}");
        assert_eq!(accel.occluded_packet(&mut p, Coherence::Incoherent), 0);
        // A packet with no active lane on a real triangle.
        let tri = Accel::build(backend, &[Vec3::ZERO, Vec3::X, Vec3::Y], &[[0, 1, 2]]).unwrap();
        let mut p = RayPacket::<8>::new();
        p.set(0, Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z, f32::INFINITY);
        tri.closest_packet(&mut p, Coherence::Incoherent);
        assert_eq!(p.hits.hit, 1, "{backend:?}");
        assert_eq!(p.t_max[0], 1.0, "{backend:?}: the hit's t");
        p.set_active(0);
        tri.closest_packet(&mut p, Coherence::Incoherent);
        assert_eq!(p.hits.hit, 0, "{backend:?}");
        assert_eq!(tri.occluded_packet(&mut p, Coherence::Incoherent), 0);
    }
}
