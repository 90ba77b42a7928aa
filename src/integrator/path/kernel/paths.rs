//! The kernel's bounce loop ([`run`]): `N` camera paths in structure-of-arrays form
//! ([`Paths`]: the next rays, throughput, radiance, η scale, bounce counts, job, random
//! stream, alive mask) go through one loop. Each turn traces the alive lanes' rays as one
//! packet ([`Scene::intersect_packet`]), builds their hits over the lanes ([`Hits`]),
//! shades the Lambert lanes (next-event estimation, then the bounce) and the dielectric
//! lanes ([`super::shade`]), traces the shadow rays as one packet
//! ([`Scene::occluded_packet`]) and adds what they let through; a lane whose path ended
//! writes its radiance to its job's slot and takes the batch's next job (refill).
//!
//! Light a path meets (an emitter's emission, the environment on escape) and Beer–Lambert
//! absorption are [`super::emitters`] and [`super::volumes`]; a path that escapes ends
//! there. Each lane draws
//! one vertex's decisions per turn ([`Draws`]) from its own stream ([`super::rng`]), so a
//! job's numbers, and its estimate, do not depend on its lane, its neighbours or the
//! packet width.

use super::emitters::{arrive, next_event};
use super::features::Tables;
use super::hits::{Hits, V3};
use super::numbers::Draws;
use super::rng;
use super::shade::{glass, lambert, Rays, Throughput};
use super::volumes::absorb;
use crate::accel::packet::{lanes, Coherence, HitPacket, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::render::{Job, Starts};
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
    /// The lanes with a path in flight.
    alive: LaneMask,
}

impl<const N: usize> Paths<N> {
    fn new() -> Self {
        Paths {
            next: Rays::new(),
            st: Throughput::new(),
            l: [[0.0; N]; 3],
            job: [0; N],
            counter: [0; N],
            salt: [0; N],
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
        self.st.restart(i);
        self.job[i] = j as u32;
        (self.counter[i], self.salt[i]) = (counter, salt);
        self.alive |= 1 << i;
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
    (seed, max_depth): (u64, u32),
    out: &mut [Vec3],
) -> u64
where
    Lanes<N>: PacketWidth,
{
    let mut p = Paths::<N>::new();
    let (mut next_job, mut rays) = (0usize, 0u64);
    let mut packet = RayPacket::<N>::new();
    let mut raw = HitPacket::<N>::default();
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
        absorb(tables, (&packet, &raw), (&h, hit), &mut p.st);
        arrive(
            (tables, scene),
            &packet,
            &h,
            (hit, p.alive),
            &p.st,
            &mut p.l,
        );
        let u = Draws::draw(&mut p.counter, &p.salt);
        let mut value: V3<N> = [[0.0; N]; 3];
        let mut shadow = Rays::<N>::new();
        let mut traced = [false; N];
        let beta = p.st.beta;
        let out_nee = (&mut value, &mut shadow, &mut traced);
        next_event((tables, scene), &u, (&h.lambert, &h, &beta), out_nee);
        let ends_l = lambert(
            &h.lambert,
            &h,
            (&u.direction[0], &u.direction[1], &u.roulette),
            max_depth,
            &mut p.st,
            &mut p.next,
        );
        let ends_g = glass(&h.glass, &h, &u.lobe, &mut p.st, &mut p.next);
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
