//! Lanes on the scalar vertex ([`super::handoff`]): the kernel's image where lanes meet
//! materials it does not shade agrees with the scalar path tracer's, and a lane comes back
//! to the kernel after such a vertex unless the kernel cannot carry its state on.

use super::super::state::Prev;
use super::super::Dispersion;
use super::handoff::{Back, Handed, Handing};
use super::tests::{
    assert_agrees, build, desc, kernel_image, lambert_floor, rough_dispersive_sphere, scalar_image,
    settings,
};
use super::*;
use crate::accel::packet::{Coherence, RayPacket};
use crate::accel::Backend;
use crate::authoring::scene::placed;
use crate::authoring::shapes::icosphere;
use crate::material::MaterialDesc;
use crate::math::Ray;
use crate::render::Context;
use crate::sampler::{PixelSampler, SamplerKind};
use crate::scene::desc::SceneDesc;
use crate::scene::Scene;
use glam::Vec3;

/// The kernel agrees with the scalar path tracer (as
/// `the_kernel_agrees_with_the_scalar_path_tracer`, same bounds) where lanes hand their
/// paths to the scalar vertex: (a) at a clear-coated floor ([`coated_floor`]), met
/// directly and through the glass (the delta bounces, η scale and throughput carried
/// over), (b) at a rough dispersive glass sphere, (c) at a rough ball of index 2.4 inside
/// the smooth glass sphere (the lane carries the glass it is in, so the ball refracts with 2.4/1.5,
/// not 2.4/1). Handing over without the throughput, or without the glass the lane is in,
/// moves blocks by many σ.
#[test]
fn lanes_handed_to_the_scalar_vertex_agree_with_it() {
    let cases = [
        ("coated floor", desc(coated_floor())),
        ("rough dispersive sphere", rough_dispersive_sphere()),
        ("ball in the glass", ball_in_glass()),
    ];
    for (what, d) in cases {
        let scene = build(d, Backend::Auto);
        let tables = qualify(&scene, true, false).expect("qualifies");
        assert!(
            !tables.scalar.is_empty(),
            "{what}: nothing goes to the scalar vertex"
        );
        let k = kernel_image(&scene, &settings(512, 21), 16);
        let s = scalar_image(&scene, &settings(512, 22));
        let same_seed = scalar_image(&scene, &settings(512, 21)).0;
        assert_agrees(what, (&k, &s, 4), Some(&same_seed));
    }
}

/// The test floor's colour under a clearcoat (KHR_materials_clearcoat, factor 1,
/// roughness 0.3): a layer the kernel leaves to the scalar vertex.
pub(super) fn coated_floor() -> MaterialDesc {
    let mut m = MaterialDesc::diffuse("floor", Vec3::new(0.8, 0.6, 0.4));
    m.layers.clearcoat = 1.0;
    m.layers.clearcoat_roughness = 0.3;
    m
}

/// The test scene of `lanes_handed_to_the_scalar_vertex_agree_with_it`'s case (c): a
/// rough ball of index 2.4 and radius 0.3 inside the smooth glass sphere.
pub(super) fn ball_in_glass() -> SceneDesc {
    let mut inner = desc(lambert_floor());
    let ball = MaterialDesc {
        roughness: 0.2,
        ..MaterialDesc::clear_glass("ball", 2.4, 1.0)
    };
    inner.materials.push(ball);
    inner.meshes.push(placed(
        "ball",
        icosphere(0.3, 2),
        2,
        Some(Vec3::new(0.0, 0.5, 0.0)),
    ));
    inner
}

/// The vertices of 16 paths along `rays` (each with its own sample) on the scalar vertex,
/// handed over in the state `inside` (the volume the lane is in) after no bounce: what
/// follows each.
fn handed_vertices(scene: &Scene, rays: &[Ray], inside: Option<u32>) -> Vec<Back<Vec3>> {
    let handed = Handed {
        eta_scale: 1.0,
        depth: 0,
        deltas: 0,
        since_diffuse: None,
        inside,
        prev: Prev {
            delta: true,
            pdf: 0.0,
            p: Vec3::ZERO,
        },
    };
    let sampler = PixelSampler::new(SamplerKind::Independent, 1, (16, 1), 3);
    let mut out = Vec::new();
    for (k, &ray) in rays.iter().enumerate() {
        let mut packet = RayPacket::<8>::new();
        packet.set(0, ray.origin, ray.dir, ray.t_max);
        packet.set_active(1);
        scene.intersect_packet(&mut packet, Coherence::Incoherent);
        let raw = packet.hit(0).expect("a hit");
        let mut ctx = Context {
            sample: sampler.start(k as u32, 0, 0),
            rays: 0,
        };
        let carried = (Vec3::ONE, ());
        let path = OnScalar {
            max_depth: 64,
            strategy: Dispersion::ALL,
        };
        let lane = Handing::new(handed, carried, (ray, raw));
        out.push(Vertex::<Vec3>::vertex(&path, scene, lane, &mut ctx));
    }
    out
}

/// A lane comes back to the kernel after its vertex on the scalar vertex: camera rays
/// straight down onto the coated floor come back (one non-delta bounce counted, the next
/// ray leaving the floor upward), except those the vertex ends. Inside the glass sphere, at
/// the rough ball inside it, a path reflected stays in the sphere and comes back with it;
/// one refracted into the ball is inside two volumes, which the kernel does not carry: the
/// scalar path follows it to its end.
#[test]
fn a_lane_comes_back_after_the_scalar_vertex() {
    let scene = build(desc(coated_floor()), Backend::Bvh);
    let down: Vec<Ray> = (0..16)
        .map(|k| Ray::new(Vec3::new(-2.0 + 0.25 * k as f32, 1.0, 1.5), -Vec3::Y))
        .collect();
    let mut gone = 0;
    for back in handed_vertices(&scene, &down, None) {
        if let Back::Goes { ray, state, .. } = back {
            assert_eq!((state.depth, state.deltas, state.inside), (1, 0, None));
            assert!(ray.origin.y.abs() < 1e-3 && ray.dir.y > 0.0, "{ray:?}");
            gone += 1;
        }
    }
    assert!(gone >= 8, "only {gone} of 16 paths came back");
    let scene = build(ball_in_glass(), Backend::Bvh);
    let across: Vec<Ray> = (0..16)
        .map(|k| Ray::new(Vec3::new(0.01 * k as f32, 0.5, 0.45), -Vec3::Z))
        .collect();
    let (mut stayed, mut ended) = (0, 0);
    for back in handed_vertices(&scene, &across, Some(1)) {
        match back {
            Back::Goes { state, .. } => {
                assert_eq!(state.inside, Some(1), "reflected: still in the sphere");
                stayed += 1;
            }
            Back::Ended(_) => ended += 1,
        }
    }
    assert!(ended >= 4, "{ended} of 16 paths ended ({stayed} came back)");
}
