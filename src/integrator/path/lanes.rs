//! The path tracer in lanes (`--method path`, and the hybrid's camera paths through
//! [`crate::integrator::pass_paths`]): `N` camera samples (8 or 16, the packet width of
//! [`crate::accel::Accel::packet_width`]) walk through one bounce loop together. Each turn
//! of the loop traces the lanes' rays as one packet ([`Scene::intersect_packet`], Embree
//! `rtcIntersect8/16`), takes each lane's vertex with the scalar code ([`vertex::vertex`]),
//! traces the shadow rays of next-event estimation as one packet
//! ([`Scene::occluded_packet`]), and adds what they let through. A lane whose path ends
//! takes the batch's next job at once (refill), so deep glass paths do not leave the
//! packet empty; a sample split into its wavelengths ([`super::split`]) first takes its
//! waiting sub-paths on the same lane, one after the other.
//!
//! Nothing about a sample depends on its lane or its neighbours: its numbers are its own
//! (restarted per job, [`Starts::start`]), the packet queries answer lane by lane exactly
//! as the single-ray queries do, and [`super::walk::Pending::resolve`] adds in the scalar
//! loop's order. So each estimate equals [`super::radiance`]'s bit for bit, whatever the
//! width, and images do not change with it (`tests/render/path_lanes.rs`).
//!
//! Shading is scalar per lane; vectorising it across the lanes is the next step.
//!
//! Width ([`LaneWidth::choose`]): 8 on Embree, whose `rtcIntersect8` beats 16 on partly
//! filled packets of incoherent rays (BENCHMARKS.md, "Lanes: 8 or 16 camera paths per
//! packet"), and single rays on the BVH, which
//! answers packets lane by lane (obvhs has no packet traversal). The environment variable
//! `IRIS_LANES=off|8|16` overrides it for measurements; images do not change.

use super::strategy::Strategy;
use super::vertex;
use super::walk::{Next, Pending, Rules, Walk};
use super::Dispersion;
use crate::accel::packet::{lanes, Coherence, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::accel::Accel;
use crate::error::{Error, Result};
use crate::render::{Context, Job, Starts};
use crate::scene::Scene;
use crate::shading;
use crate::spectrum::{Carrier, SampledSpectrum};
use glam::Vec3;

/// How the path tracer runs its camera paths.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LaneWidth {
    /// One path after the other, single-ray queries.
    Scalar,
    /// 8 paths per packet.
    Eight,
    /// 16 paths per packet.
    Sixteen,
}

impl LaneWidth {
    /// The width for `scene` on this machine (see the module docs), or what
    /// `IRIS_LANES` says (`off`, `8` or `16`; anything else is an error naming it).
    pub fn choose(scene: &Scene) -> Result<LaneWidth> {
        match std::env::var("IRIS_LANES").ok().filter(|v| !v.is_empty()) {
            Some(v) => match v.as_str() {
                "off" => Ok(LaneWidth::Scalar),
                "8" => Ok(LaneWidth::Eight),
                "16" => Ok(LaneWidth::Sixteen),
                _ => Err(Error::Usage(format!(
                    "environment variable IRIS_LANES={v}: expected off, 8 or 16"
                ))),
            },
            // Packets of shadow rays cannot carry media's transmittance.
            None if scene.has_media() => Ok(LaneWidth::Scalar),
            None => Ok(match scene.accel() {
                Accel::Bvh(_) => LaneWidth::Scalar,
                #[allow(unreachable_patterns)]
                _ => LaneWidth::Eight,
            }),
        }
    }

    /// Paths per packet (1 for [`LaneWidth::Scalar`]).
    pub fn lanes(self) -> usize {
        match self {
            LaneWidth::Scalar => 1,
            LaneWidth::Eight => 8,
            LaneWidth::Sixteen => 16,
        }
    }
}

/// The plain path tracer's estimate of `jobs` ([`estimate_lanes`] with its [`Dispersion`]
/// as the strategy, linear RGB into `out`) at `width`, in spectral or RGB transport.
pub fn estimate_path(
    scene: &Scene,
    (rules, width): ((u32, Dispersion), LaneWidth),
    spectral: bool,
    starts: &Starts,
    jobs: &[Job],
    out: &mut [Vec3],
) -> u64 {
    fn at<C: Carrier>(
        scene: &Scene,
        (rules, width): ((u32, Dispersion), LaneWidth),
        run: (&Starts, &[Job]),
        out: &mut [Vec3],
    ) -> u64 {
        let rgb = |i: usize, l: C, lambda: &C::Lambda| out[i] = l.to_rgb(lambda);
        let (max_depth, dispersion) = rules;
        estimate_lanes(scene, width, (max_depth, &dispersion), run, None, rgb)
    }
    if spectral {
        at::<SampledSpectrum>(scene, (rules, width), (starts, jobs), out)
    } else {
        at::<Vec3>(scene, (rules, width), (starts, jobs), out)
    }
}

/// A camera sample in flight on one lane.
struct Lane<C: Carrier> {
    /// Its job's index in the batch.
    job: usize,
    /// The wavelengths it started with (the film's conversion reads them).
    lambda: C::Lambda,
    /// The path so far.
    walk: Walk<C>,
    /// Next-event estimation of its last vertex, waiting for the shadow packet.
    pending: Option<Pending<C>>,
    /// Its numbers and ray count.
    ctx: Context,
}

/// Estimates `jobs` (begun by `starts`) with the path tracer under `strategy`
/// ([`super::camera_path`] with `max_depth`; one that may stop at a visible point is not
/// for lanes, [`Strategy::STOPS`]) on `width` lanes
/// ([`LaneWidth::Scalar`] runs 8: a caller wanting single rays runs the scalar loop), at
/// the wavelengths `lambda` (the pass's of a photon method) or, with `None`, at wavelengths
/// drawn from each job's hero variate; `emit(i, L, wavelengths)` receives job `i`'s
/// radiance and the wavelengths it started with, in the order the paths end. Returns the
/// rays traced.
pub fn estimate_lanes<C: Carrier, S: Strategy<C>>(
    scene: &Scene,
    width: LaneWidth,
    (max_depth, strategy): (u32, &S),
    (starts, jobs): (&Starts, &[Job]),
    lambda: Option<C::Lambda>,
    emit: impl FnMut(usize, C, &C::Lambda),
) -> u64 {
    let (run, rules) = ((starts, jobs), (max_depth, strategy));
    match width {
        LaneWidth::Sixteen => run_lanes::<C, S, 16>(scene, rules, run, lambda, emit),
        _ => run_lanes::<C, S, 8>(scene, rules, run, lambda, emit),
    }
}

/// [`estimate_lanes`] on `N` lanes.
fn run_lanes<C: Carrier, S: Strategy<C>, const N: usize>(
    scene: &Scene,
    (max_depth, strategy): (u32, &S),
    (starts, jobs): (&Starts, &[Job]),
    lambda: Option<C::Lambda>,
    mut emit: impl FnMut(usize, C, &C::Lambda),
) -> u64
where
    Lanes<N>: PacketWidth,
{
    let rules = Rules {
        max_depth,
        strategy,
    };
    let mut lanes_: [Lane<C>; N] = std::array::from_fn(|_| Lane {
        job: 0,
        lambda: C::sample_lambda(0.0),
        walk: Walk::new(
            crate::math::Ray::new(Vec3::ZERO, Vec3::Z),
            C::sample_lambda(0.0),
        ),
        pending: None,
        ctx: starts.context(),
    });
    let mut active: LaneMask = 0;
    let (mut next_job, mut rays) = (0, 0);
    let mut packet = RayPacket::<N>::new();
    loop {
        for (i, lane) in lanes_.iter_mut().enumerate() {
            if active & (1 << i) == 0 && next_job < jobs.len() {
                start(starts, (jobs, next_job), lambda, lane);
                next_job += 1;
                active |= 1 << i;
            }
        }
        if active == 0 {
            return rays;
        }
        for i in lanes(active) {
            let r = &lanes_[i].walk.ray;
            packet.set(i, r.origin, r.dir, r.t_max);
        }
        // Lanes left over from ended paths drop out; untraceable rays find nothing.
        packet.set_active(active);
        // Always Embree's incoherent traversal: its coherent (frustum) traversal visits
        // the nodes in another order and so breaks exact ties between coplanar overlapping
        // triangles differently from the single-ray query.
        scene.intersect_packet(&mut packet, Coherence::Incoherent);
        let mut ended: LaneMask = 0;
        let mut shadows = RayPacket::<N>::new();
        for i in lanes(active) {
            let lane = &mut lanes_[i];
            lane.ctx.rays += 1;
            let w = &lane.walk;
            let hit = w.st.meet.or_else(|| scene.lane_hit(&w.ray, packet.hit(i)));
            let arrival = shading::arrival(scene, &w.ray, hit, &w.st.media, &w.lambda);
            let (nee, next) = vertex::vertex(
                scene,
                &rules,
                &mut lane.walk,
                arrival,
                &mut lane.ctx,
                &mut None,
            );
            // Shadow rays through media are traced alone, for their transmittance.
            if let Some(r) = nee
                .as_ref()
                .filter(|p| p.through.is_none())
                .and_then(|p| p.shadow)
            {
                shadows.set(i, r.origin, r.dir, r.t_max);
            }
            lane.pending = nee;
            if next == Next::End {
                ended |= 1 << i;
            }
        }
        let blocked = if shadows.active() != 0 {
            scene.occluded_packet(&mut shadows)
        } else {
            0
        };
        for i in lanes(active) {
            let lane = &mut lanes_[i];
            match lane.pending.take() {
                Some(p) if p.through.is_some() => {
                    let w = &mut lane.walk;
                    p.resolve_traced(scene, &w.lambda, &mut lane.ctx.rays, &mut w.l);
                }
                Some(p) => p.resolve(blocked & (1 << i) != 0, &mut lane.walk.l),
                None => {}
            }
            if ended & (1 << i) != 0 {
                if lane.walk.next_branch() {
                    // The sample's next wavelength continues on this lane.
                    ended &= !(1 << i);
                } else {
                    emit(lane.job, lane.walk.radiance(), &lane.lambda);
                    rays += lane.ctx.rays;
                }
            }
        }
        active &= !ended;
    }
}

/// Starts job `job` of `jobs` on `lane`: its numbers, camera ray and wavelengths (`fixed`,
/// or as [`crate::integrator::Integrator`]'s per-sample estimate draws them).
fn start<C: Carrier>(
    starts: &Starts,
    (jobs, job): (&[Job], usize),
    fixed: Option<C::Lambda>,
    lane: &mut Lane<C>,
) {
    let (ray, u_lambda) = starts.start(jobs[job], &mut lane.ctx);
    let lambda =
        fixed.unwrap_or_else(|| C::sample_lambda(if C::SPECTRAL { u_lambda } else { 0.0 }));
    lane.job = job;
    lane.lambda = lambda;
    lane.walk = Walk::new(ray, lambda);
    lane.pending = None;
}
