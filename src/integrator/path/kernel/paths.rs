//! The kernel's bounce loop ([`run`]): `N` camera paths in structure-of-arrays form
//! ([`Paths`]: the next rays, throughput, radiance, η scale, bounce counts, job, random
//! stream, alive mask) go through one loop. Each turn traces the alive lanes' rays as one
//! packet ([`Scene::intersect_packet`]), builds their hits over the lanes ([`Hits`]),
//! shades the Lambert lanes (next-event estimation, then the bounce) and the dielectric
//! lanes ([`super::shade`]), traces the shadow rays as one packet
//! ([`Scene::occluded_packet`]) and adds what they let through; a lane whose path ended
//! writes its radiance to its job's slot and takes the batch's next job (refill).
//!
//! A path that escapes ends (the kernel's scenes have no environment). Each lane draws
//! one vertex's decisions per turn ([`Draws`]) from its own stream ([`super::rng`]), so a
//! job's numbers, and its estimate, do not depend on its lane, its neighbours or the
//! packet width.

use super::super::Dispersion;
use super::features::Tables;
use super::handoff::{self, Handed};
use super::hits::{Hits, V3};
use super::numbers::Draws;
use super::rng;
use super::shade::{glass, lambert, light, Rays, Throughput};
use crate::accel::packet::{lanes, Coherence, HitPacket, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::math::Ray;
use crate::render::{Context, Job, Starts};
use crate::scene::Scene;
use glam::{Vec2, Vec3};

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
    /// Each lane's random stream.
    counter: [u32; N],
    salt: [u32; N],
    /// The volumetric material each lane is inside ([`AIR`]: none).
    inside: [u32; N],
    /// Delta bounces since the last non-delta one ([`NONE_YET`] before the first).
    since: [u32; N],
    /// The lanes with a path in flight.
    alive: LaneMask,
}

/// [`Paths::inside`] of a lane in air.
const AIR: u32 = u32::MAX;
/// [`Paths::since`] of a lane before its first non-delta bounce.
const NONE_YET: u32 = u32::MAX;

impl<const N: usize> Paths<N> {
    fn new() -> Self {
        Paths {
            next: Rays::new(),
            st: Throughput {
                beta: [[0.0; N]; 3],
                eta_scale: [1.0; N],
                depth: [0; N],
                deltas: [0; N],
            },
            l: [[0.0; N]; 3],
            job: [0; N],
            counter: [0; N],
            salt: [0; N],
            inside: [AIR; N],
            since: [NONE_YET; N],
            alive: 0,
        }
    }

    /// Starts job `j` (`job`) on lane `i`: its stream, its camera ray (jittered with its
    /// first two numbers), unit throughput, no radiance.
    fn start(&mut self, i: usize, (j, job): (usize, Job), starts: &Starts, seed: u64) {
        let (mut counter, salt) = rng::key(seed, job.x, job.y, job.k);
        let jitter = Vec2::new(
            rng::draw_one(&mut counter, salt),
            rng::draw_one(&mut counter, salt),
        );
        let ray = starts.camera_ray(job, jitter);
        for c in 0..3 {
            self.next.o[c][i] = ray.origin[c];
            self.next.d[c][i] = ray.dir[c];
            self.st.beta[c][i] = 1.0;
            self.l[c][i] = 0.0;
        }
        self.next.t_max[i] = ray.t_max;
        self.st.eta_scale[i] = 1.0;
        self.st.depth[i] = 0;
        self.st.deltas[i] = 0;
        self.job[i] = j as u32;
        self.inside[i] = AIR;
        self.since[i] = NONE_YET;
        (self.counter[i], self.salt[i]) = (counter, salt);
        self.alive |= 1 << i;
    }

    /// Hands lane `i`, whose ray in `packet` met `raw`'s hit on a material the kernel does
    /// not shade, to the scalar path tracer ([`handoff::finish`]) for `job` (begun by
    /// `starts`) under `rules`: adds the rest of its path's radiance to its own, with the
    /// job's numbers in `ctx`. Returns the rays traced.
    fn hand_over(
        &mut self,
        i: usize,
        scene: &Scene,
        (packet, raw): (&RayPacket<N>, &HitPacket<N>),
        (starts, job, rules): (&Starts, Job, (u32, &Dispersion)),
        ctx: &mut Context,
    ) -> u64
    where
        Lanes<N>: PacketWidth,
    {
        let Some(r) = raw.get(i) else { return 0 };
        starts.start(job, ctx);
        let handed = Handed {
            beta: Vec3::new(self.st.beta[0][i], self.st.beta[1][i], self.st.beta[2][i]),
            eta_scale: self.st.eta_scale[i],
            depth: self.st.depth[i],
            deltas: self.st.deltas[i],
            since_diffuse: (self.since[i] != NONE_YET).then_some(self.since[i]),
            inside: (self.inside[i] != AIR).then_some(self.inside[i]),
        };
        let ray = Ray::new(packet.origin(i), packet.dir(i));
        let e = handoff::finish(scene, rules, &handed, (ray, r), ctx);
        (0..3).for_each(|c| self.l[c][i] += e[c]);
        ctx.rays
    }

    /// After the shading of hits `h`: a Lambert bounce is non-delta (no delta bounces
    /// since); the dielectric counts one more delta bounce and leaves the lane inside its
    /// volume when the next ray goes to the back of its outward normal (enter and exit by
    /// the sign of dot(ray, normal), as the intersection layer's rule).
    #[inline(always)]
    fn track(&mut self, h: &Hits<N>) {
        for i in 0..N {
            let since = if self.since[i] == NONE_YET {
                NONE_YET
            } else {
                self.since[i] + 1
            };
            let d = [self.next.d[0][i], self.next.d[1][i], self.next.d[2][i]];
            let back = d[0] * h.ng[0][i] + d[1] * h.ng[1][i] + d[2] * h.ng[2][i] < 0.0;
            let inside = if back { h.material[i] } else { AIR };
            self.since[i] = if h.lambert[i] {
                0
            } else if h.glass[i] {
                since
            } else {
                self.since[i]
            };
            self.inside[i] = if h.glass[i] { inside } else { self.inside[i] };
        }
    }

    /// The next rays of the alive lanes as a packet.
    #[inline(always)]
    fn packet(&self, packet: &mut RayPacket<N>)
    where
        Lanes<N>: PacketWidth,
    {
        rays_into(&self.next, packet);
        packet.set_active(self.alive);
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

/// Estimates `jobs` (begun by `starts`, numbers keyed by `seed`) on `N` lanes with at most
/// `max_depth` non-delta bounces a path, writing job `i`'s linear RGB radiance to `out[i]`.
/// Returns the rays traced.
#[inline(always)]
pub fn run<const N: usize>(
    tables: &Tables,
    scene: &Scene,
    (starts, jobs): (&Starts, &[Job]),
    (seed, max_depth, dispersion): (u64, u32, Dispersion),
    out: &mut [Vec3],
) -> u64
where
    Lanes<N>: PacketWidth,
{
    let mut p = Paths::<N>::new();
    let mut ctx = starts.context();
    let (mut next_job, mut rays) = (0usize, 0u64);
    let mut packet = RayPacket::<N>::new();
    let mut raw = HitPacket::<N>::default();
    let n_lights = tables.lights.len() as u32;
    loop {
        for i in 0..N {
            if p.alive & (1 << i) == 0 && next_job < jobs.len() {
                p.start(i, (next_job, jobs[next_job]), starts, seed);
                next_job += 1;
            }
        }
        if p.alive == 0 {
            return rays;
        }
        p.packet(&mut packet);
        scene.intersect_packet(&packet, Coherence::Incoherent, &mut raw);
        rays += u64::from(p.alive.count_ones());
        let hit = raw.hit & p.alive;
        let h = Hits::new(scene, &tables.shades, &packet, &raw, hit);
        for i in lanes(hit & mask(&h.scalar)) {
            let job = jobs[p.job[i] as usize];
            let rules = (max_depth, &dispersion);
            rays += p.hand_over(i, scene, (&packet, &raw), (starts, job, rules), &mut ctx);
        }
        let u = Draws::draw(&mut p.counter, &p.salt);
        let k: [u32; N] = std::array::from_fn(|i| {
            ((u.light_choice[i] * n_lights as f32) as u32).min(n_lights.max(1) - 1)
        });
        let mut value: V3<N> = [[0.0; N]; 3];
        let mut shadow = Rays::<N>::new();
        let mut traced = [false; N];
        let beta = p.st.beta;
        light(
            &tables.lights,
            &k,
            &h.lambert,
            &h,
            &beta,
            &mut value,
            &mut shadow,
            &mut traced,
        );
        let ends_l = lambert(
            &h.lambert,
            &h,
            (&u.direction[0], &u.direction[1], &u.roulette),
            max_depth,
            &mut p.st,
            &mut p.next,
        );
        let ends_g = glass(&h.glass, &h, &u.lobe, &mut p.st, &mut p.next);
        p.track(&h);
        let traced = mask(&traced);
        if traced != 0 {
            let mut sp = RayPacket::<N>::new();
            rays_into(&shadow, &mut sp);
            sp.set_active(traced);
            let blocked = scene.occluded_packet(&sp);
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
