//! The kernel's bounce loop ([`run`]): `N` camera paths in structure-of-arrays form
//! ([`Paths`]: the next rays, throughput, radiance, η scale, bounce counts, job, sample
//! stream, alive mask) go through one loop. A lane takes its job with the camera ray's
//! first hit already known ([`CameraRays`]: the batch's camera rays traced as coherent
//! packets of their own). Each turn traces the bounce rays of the other alive lanes as one
//! packet ([`Scene::intersect_packet`]), merges in the first hits of the lanes just
//! started, builds the hits over the lanes ([`Hits`]),
//! shades the Lambert lanes (next-event estimation, then the bounce) and the dielectric
//! lanes ([`super::shade`]), traces the shadow rays as one packet
//! ([`Scene::occluded_packet`]) and adds what they let through; a lane whose path ended
//! writes its radiance to its job's slot and takes the batch's next job (refill).
//!
//! Light a path meets (an emitter's emission, the environment on escape) and Beer–Lambert
//! absorption are [`super::emitters`] and [`super::volumes`]; a path that escapes ends
//! there. Each lane holds its job's sample stream, restarted by the render's sampler
//! ([`Starts::start`], which also makes the camera ray), and draws its vertex's decisions
//! from the scalar path tracer's schedule ([`Draws`]), so a job's numbers, and its
//! estimate, do not depend on its lane, its neighbours or the packet width. A lane that
//! meets a material the kernel does not shade hands its path to the scalar vertex
//! ([`super::handoff`]) before the kernel counts anything at that hit.

use super::super::state::Prev;
use super::super::Dispersion;
use super::camera::{ray_into, CameraRays, Started};
use super::class::Class;
use super::emitters::{arrive, next_event};
use super::features::Tables;
use super::handoff::{self, Handed};
use super::hits::{Hits, V3};
use super::numbers::{Draws, Vertices};
use super::shade::{glass, lambert, Rays, Throughput};
use super::volumes::absorb;
use crate::accel::packet::{lanes, Coherence, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::accel::RawHit;
use crate::light::LightId;
use crate::math::Ray;
use crate::render::{Context, Job, Starts};
use crate::scene::Scene;
use glam::Vec3;

/// The state of `N` camera paths.
struct Paths<const N: usize> {
    /// The rays to trace next.
    next: Rays<N>,
    /// Throughput, η scale, bounce counts.
    st: Throughput<N>,
    /// Radiance so far.
    l: V3<N>,
    /// The job (index into the batch) each lane estimates.
    job: [u32; N],
    /// Each lane's sample stream (boxed: taking a job swaps pointers, not the sampler's
    /// state).
    ctx: [Box<Context>; N],
    /// Delta bounces since the last non-delta one ([`NONE_YET`] before the first).
    since: [u32; N],
    /// The lanes with a path in flight.
    alive: LaneMask,
}

/// [`Paths::since`] of a lane before its first non-delta bounce.
const NONE_YET: u32 = u32::MAX;

impl<const N: usize> Paths<N> {
    fn new(starts: &Starts) -> Self {
        Paths {
            next: Rays::new(),
            st: Throughput::new(),
            l: [[0.0; N]; 3],
            job: [0; N],
            ctx: std::array::from_fn(|_| Box::new(starts.context())),
            since: [NONE_YET; N],
            alive: 0,
        }
    }

    /// Starts the job `s` on lane `i` (its sample stream already swapped into the lane's
    /// context): its camera ray, unit throughput, no radiance.
    fn start(&mut self, i: usize, s: &Started) {
        ray_into(&mut self.next, i, s);
        for c in 0..3 {
            self.st.beta[c][i] = 1.0;
            self.l[c][i] = 0.0;
        }
        self.st.eta_scale[i] = 1.0;
        self.st.depth[i] = 0;
        self.st.deltas[i] = 0;
        self.st.restart(i);
        self.job[i] = s.job as u32;
        self.since[i] = NONE_YET;
        self.alive |= 1 << i;
    }

    /// Hands lane `i`, whose ray in `packet` met its hit on a material the kernel does
    /// not shade, to the scalar path tracer ([`handoff::finish`]) under `rules`, with the
    /// lane's own sample stream: adds the rest of its path's radiance to its own. Returns
    /// the rays traced.
    fn hand_over(
        &mut self,
        i: usize,
        scene: &Scene,
        packet: &RayPacket<N>,
        rules: (u32, &Dispersion),
    ) -> u64
    where
        Lanes<N>: PacketWidth,
    {
        let Some(r) = packet.hit(i) else { return 0 };
        let st = &self.st;
        let handed = Handed {
            beta: Vec3::new(st.beta[0][i], st.beta[1][i], st.beta[2][i]),
            eta_scale: st.eta_scale[i],
            depth: st.depth[i],
            deltas: st.deltas[i],
            since_diffuse: (self.since[i] != NONE_YET).then_some(self.since[i]),
            inside: st.medium[i].checked_sub(1),
            prev: Prev {
                delta: st.prev_delta[i],
                pdf: st.prev_pdf[i],
                p: Vec3::new(st.prev_p[0][i], st.prev_p[1][i], st.prev_p[2][i]),
            },
        };
        let ray = Ray::new(packet.origin(i), packet.dir(i));
        let ctx = &mut self.ctx[i];
        let before = ctx.rays;
        let e = handoff::finish(scene, rules, &handed, (ray, r), ctx);
        (0..3).for_each(|c| self.l[c][i] += e[c]);
        ctx.rays - before
    }

    /// After the shading of hits `h`: a Lambert bounce is non-delta (no delta bounces
    /// since); the dielectric counts one more delta bounce.
    #[inline(always)]
    fn track(&mut self, h: &Hits<N>) {
        for i in 0..N {
            let since = if self.since[i] == NONE_YET {
                NONE_YET
            } else {
                self.since[i] + 1
            };
            self.since[i] = if h.lambert[i] {
                0
            } else if h.glass[i] {
                since
            } else {
                self.since[i]
            };
        }
    }

    /// The next rays of the lanes `trace` as a packet (the other lanes' rays are there too,
    /// inactive: the hit records read every lane's direction).
    #[inline(always)]
    fn packet(&self, packet: &mut RayPacket<N>, trace: LaneMask)
    where
        Lanes<N>: PacketWidth,
    {
        rays_into(&self.next, packet);
        packet.set_active(trace);
    }
}

/// Copies `rays` into `packet`'s arrays.
#[inline(always)]
fn rays_into<const N: usize>(rays: &Rays<N>, packet: &mut RayPacket<N>)
where
    Lanes<N>: PacketWidth,
{
    packet.org_x = rays.o[0];
    packet.org_y = rays.o[1];
    packet.org_z = rays.o[2];
    packet.dir_x = rays.d[0];
    packet.dir_y = rays.d[1];
    packet.dir_z = rays.d[2];
    packet.t_max = rays.t_max;
}

/// The lanes set in `flags`.
#[inline(always)]
fn mask<const N: usize>(flags: &[bool; N]) -> LaneMask {
    (0..N).fold(0, |m, i| m | (u32::from(flags[i]) << i))
}

/// Estimates `jobs` (begun by `starts`) on `N` lanes with at most
/// `max_depth` non-delta bounces a path, writing job `i`'s linear RGB radiance to `out[i]`.
/// Returns the rays traced.
#[inline(always)]
pub fn run<const N: usize, K: Class>(
    tables: &Tables,
    scene: &Scene,
    (starts, jobs): (&Starts, &[Job]),
    (max_depth, dispersion): (u32, Dispersion),
    out: &mut [Vec3],
) -> u64
where
    Lanes<N>: PacketWidth,
{
    let mut p = Paths::<N>::new(starts);
    let mut cameras = CameraRays::<N>::new(starts);
    let mut rays = 0u64;
    let mut packet = RayPacket::<N>::new();
    let mut first: [Option<RawHit>; N] = [None; N];
    let area = tables
        .sampled
        .iter()
        .any(|l| !matches!(l, LightId::Punctual(_)));
    loop {
        let mut fresh: LaneMask = 0;
        for (i, first) in first.iter_mut().enumerate() {
            if p.alive & (1 << i) == 0 {
                let batch = (starts, jobs);
                let Some(s) = cameras.take(scene, batch, &mut p.ctx[i], &mut rays) else {
                    break;
                };
                p.start(i, &s);
                *first = s.hit;
                fresh |= 1 << i;
            }
        }
        if p.alive == 0 {
            return rays;
        }
        let trace = p.alive & !fresh;
        p.packet(&mut packet, trace);
        if trace != 0 {
            scene.intersect_packet(&mut packet, Coherence::Incoherent);
            rays += u64::from(trace.count_ones());
        }
        // The query may overwrite the untraced lanes' rays: the hit records read them.
        for i in lanes(fresh) {
            let (o, d) = (&p.next.o, &p.next.d);
            let dir = Vec3::new(d[0][i], d[1][i], d[2][i]);
            packet.set(i, Vec3::new(o[0][i], o[1][i], o[2][i]), dir, f32::INFINITY);
            packet.set_hit(i, first[i]);
        }
        let hit = packet.hits.hit & p.alive;
        let h = Hits::new(scene, &tables.shades, &packet, &packet.hits, hit);
        let handed = if K::HANDS_OVER {
            hit & mask(&h.scalar)
        } else {
            0
        };
        for i in lanes(handed) {
            rays += p.hand_over(i, scene, &packet, (max_depth, &dispersion));
        }
        let kept = hit & !handed;
        if K::ABSORBS {
            absorb(tables, &packet, (&h, kept), &mut p.st);
        }
        if K::LIT_BY_AREA {
            let seen = (kept, p.alive & !handed);
            arrive((tables, scene), &packet, &h, seen, &p.st, &mut p.l);
        }
        let at = Vertices {
            index: std::array::from_fn(|i| p.st.depth[i] + p.st.deltas[i]),
            lambert: &h.lambert,
            glass: &h.glass,
            roulette: std::array::from_fn(|i| p.st.depth[i] + 1 >= 3),
            lights: tables.sampled.len(),
            area,
        };
        let u = Draws::draw(&mut p.ctx, &at);
        let mut value: V3<N> = [[0.0; N]; 3];
        let mut shadow = Rays::<N>::new();
        let mut traced = [false; N];
        let beta = p.st.beta;
        let out_nee = (&mut value, &mut shadow, &mut traced);
        next_event((tables, scene), &u, (&h.lambert, &h, &beta), out_nee);
        let (ends_l, played) = lambert(
            &h.lambert,
            &h,
            (&u.direction[0], &u.direction[1], &u.roulette),
            max_depth,
            &mut p.st,
            &mut p.next,
        );
        Draws::played(&mut p.ctx, &at, mask(&played));
        let ends_g = glass(&h.glass, &h, &u.lobe, &mut p.st, &mut p.next);
        p.track(&h);
        let traced = mask(&traced);
        if traced != 0 {
            let mut sp = RayPacket::<N>::new();
            rays_into(&shadow, &mut sp);
            sp.set_active(traced);
            let blocked = scene.occluded_packet(&mut sp);
            rays += u64::from(traced.count_ones());
            for i in lanes(traced & !blocked) {
                (0..3).for_each(|c| p.l[c][i] += value[c][i]);
            }
        }
        let shaded = mask(&h.lambert) | mask(&h.glass);
        let ended = (p.alive & !(hit & shaded)) | mask(&ends_l) | mask(&ends_g);
        for i in lanes(ended & p.alive) {
            out[p.job[i] as usize] = Vec3::new(p.l[0][i], p.l[1][i], p.l[2][i]);
        }
        p.alive &= !ended;
    }
}
