//! The kernel's bounce loop ([`run`]): `N` camera paths in structure-of-arrays form
//! ([`Paths`]: the next rays, throughput, radiance in `M` channels, η scale, bounce
//! counts, job, sample stream, wavelengths, alive mask) go through one loop. A lane takes its job with the camera ray's
//! first hit already known ([`CameraRays`]: the batch's camera rays traced as coherent
//! packets of their own). Each turn traces the bounce rays of the other alive lanes as one
//! packet ([`Scene::intersect_packet`]), merges in the first hits of the lanes just
//! started, builds the hits over the lanes ([`Hits`]),
//! shades the Lambert and glossy lanes (next-event estimation, then the bounce:
//! [`super::shade`], [`super::glossy`]) and the dielectric lanes, traces the shadow rays
//! as one packet ([`Scene::occluded_packet`]) and adds what they let through; a lane whose path ended
//! writes its radiance to its job's slot and takes the batch's next job (refill).
//!
//! Light a path meets (an emitter's emission, the environment on escape) and Beer–Lambert
//! absorption are [`super::emitters`] and [`super::volumes`]; a path that escapes ends
//! there. Each lane holds its job's sample stream, restarted by the render's sampler
//! ([`Starts::start`], which also makes the camera ray), and draws its vertex's decisions
//! from the scalar path tracer's schedule ([`Draws`]), so a job's numbers, and its
//! estimate, do not depend on its lane, its neighbours or the packet width. A lane that
//! meets a material the kernel does not shade hands its path to the scalar vertex
//! ([`super::handoff`]) before the kernel counts anything at that hit. In spectral
//! transport a lane meeting a dispersive glass with its sample whole splits it there
//! ([`super::branches`]): its waiting sub-paths are its refill before the next job.

use super::branches::{keep_hero, Branches, Resumed};
use super::camera::{ray_into, CameraRays, Started};
use super::class::Class;
use super::colour::{lane, spectral, to_rgb, unset, Channels};
use super::emitters::{arrive, next_event};
use super::features::Tables;
use super::glossy::{self, Lobes};
use super::hits::Hits;
use super::numbers::{Draws, Vertices};
use super::rules::Rules;
use super::shade::{glass, lambert};
use super::state::{Rays, Throughput, NONE_YET};
use super::volumes::absorb;
use crate::accel::packet::{lanes, Coherence, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::accel::RawHit;
use crate::light::LightId;
use crate::render::{Context, Job, Starts};
use crate::scene::Scene;
use crate::spectrum::{Carrier, Lambdas, SampledSpectrum};
use glam::Vec3;

/// The state of `N` camera paths carrying `M` channels.
pub(super) struct Paths<const N: usize, const M: usize> {
    /// The rays to trace next.
    pub(super) next: Rays<N>,
    /// Throughput, η scale, bounce counts.
    pub(super) st: Throughput<N, M>,
    /// Radiance so far.
    pub(super) l: Channels<N, M>,
    /// Each lane's wavelengths (spectral transport; a sub-path's rotated to its lane).
    pub(super) lam: [Lambdas; N],
    /// Split samples and their waiting sub-paths (spectral transport).
    pub(super) branches: Branches<N, M>,
    /// The job (index into the batch) each lane estimates.
    pub(super) job: [u32; N],
    /// Each lane's sample stream (boxed: taking a job swaps pointers, not the sampler's
    /// state).
    pub(super) ctx: [Box<Context>; N],
    /// The lanes with a path in flight.
    pub(super) alive: LaneMask,
}

impl<const N: usize, const M: usize> Paths<N, M> {
    fn new(starts: &Starts) -> Self {
        Paths {
            next: Rays::new(),
            st: Throughput::new(),
            l: [[0.0; N]; M],
            lam: std::array::from_fn(|_| unset()),
            branches: Branches::new(),
            job: [0; N],
            ctx: std::array::from_fn(|_| Box::new(starts.context())),
            alive: 0,
        }
    }

    /// Starts the job `s` on lane `i` (its sample stream already swapped into the lane's
    /// context): its camera ray, wavelengths (`fixed`, or drawn from its sample), unit
    /// throughput, no radiance.
    fn start(&mut self, i: usize, s: &Started, fixed: Option<Lambdas>) {
        ray_into(&mut self.next, i, s);
        (0..M).for_each(|c| self.l[c][i] = 0.0);
        if spectral::<M>() {
            self.lam[i] = fixed.unwrap_or_else(|| SampledSpectrum::sample_lambda(s.u_lambda));
            self.branches.start(i, self.lam[i]);
        }
        self.st.restart(i);
        self.job[i] = s.job as u32;
        self.alive |= 1 << i;
    }

    /// Lane `i`'s path ended: in spectral transport, takes its sample's next waiting
    /// sub-path if there is one (returning the ray to the split vertex, whose hit is
    /// known); otherwise writes its job's linear RGB radiance to `out` and returns `None`.
    fn end(&mut self, i: usize, out: &mut [Vec3]) -> Option<Resumed> {
        let rgb = if spectral::<M>() {
            let at = (&mut self.st, &mut self.l, &mut self.lam);
            if let Some(r) = self.branches.next(i, at) {
                return Some(r);
            }
            let v = self.branches.radiance(i, &self.l);
            to_rgb::<M>(v, &self.branches.sample[i])
        } else {
            to_rgb::<M>(lane(&self.l, i), &self.lam[i])
        };
        out[self.job[i] as usize] = rgb;
        None
    }

    /// At the lanes `on` (kept lanes at a dispersive glass, spectral transport), a whole
    /// sample splits into its wavelengths (or keeps its hero only without the split,
    /// `split` false); `packet` holds the rays that reached the vertices. The hits' η and
    /// tint are the hero's already, which is the sub-path 0's.
    fn disperse(&mut self, on: LaneMask, packet: &RayPacket<N>, split: bool)
    where
        Lanes<N>: PacketWidth,
    {
        for i in lanes(on) {
            if self.lam[i].hero_only {
                continue;
            }
            if split {
                let ray = (packet.origin(i).to_array(), packet.dir(i).to_array());
                let at = (ray, packet.hit(i));
                let state = (&mut self.st, &mut self.l, &mut self.lam);
                self.branches.split(i, at, state);
            } else {
                keep_hero(i, &mut self.st, &mut self.lam);
            }
        }
    }

    /// Lane `i` takes the waiting sub-path `r` of its split sample: its next ray is the
    /// one that reached the split vertex.
    fn resume(&mut self, i: usize, r: &Resumed) {
        let (o, d) = r.ray;
        for c in 0..3 {
            self.next.o[c][i] = o[c];
            self.next.d[c][i] = d[c];
        }
        self.next.t_max[i] = f32::INFINITY;
    }

    /// Shades the hits `h` (in `scene`; `area`: some light has an area or is at
    /// infinity): next-event estimation at the Lambert and glossy lanes with their shadow
    /// rays traced as one packet (counted in `rays`), their bounces and roulette (the
    /// glossy lanes' only in a scene of class `K` that has them, their BSDFs built once),
    /// the dielectric's choice; the next rays into [`Self::next`]. Returns the lanes whose
    /// path ends at their vertex.
    #[inline(always)]
    fn shade<K: Class>(
        &mut self,
        tables: &Tables,
        (scene, h, area): (&Scene, &Hits<N, M>, bool),
        max_depth: u32,
        rays: &mut u64,
    ) -> LaneMask
    where
        Lanes<N>: PacketWidth,
    {
        let at = Vertices {
            index: std::array::from_fn(|i| self.st.depth[i] + self.st.deltas[i]),
            lambert: &h.lambert,
            glossy: &h.glossy,
            glass: &h.glass,
            roulette: std::array::from_fn(|i| self.st.depth[i] + 1 >= 3),
            lights: tables.sampled.len(),
            area,
        };
        let u = Draws::draw(&mut self.ctx, &at);
        let mut value: Channels<N, M> = [[0.0; N]; M];
        let mut shadow = Rays::<N>::new();
        let mut traced = [false; N];
        let beta = self.st.beta;
        let out_nee = (&mut value, &mut shadow, &mut traced);
        let light = (tables, scene, &self.lam);
        let rough: [bool; N] = std::array::from_fn(|i| h.lambert[i] || h.glossy[i]);
        let glossy = if K::GLOSSY { mask(&h.glossy) } else { 0 };
        let lobes = match glossy {
            0 => Lobes::none(),
            on => Lobes::new(scene, h, &self.lam, on),
        };
        next_event(light, &u, (&rough, h, &beta, &lobes), out_nee);
        let (ends_l, played) = lambert(
            &h.lambert,
            h,
            (&u.direction[0], &u.direction[1], &u.roulette),
            max_depth,
            &mut self.st,
            &mut self.next,
        );
        let (ends_s, played_s) = match glossy {
            0 => (0, 0),
            on => glossy::bounce(
                (&lobes, h),
                on,
                &u,
                max_depth,
                (&mut self.st, &mut self.next),
            ),
        };
        Draws::played(&mut self.ctx, &at, mask(&played) | played_s);
        let ends_g = glass(&h.glass, h, &u.lobe, &mut self.st, &mut self.next);
        self.track(h);
        let traced = mask(&traced);
        if traced != 0 {
            let mut sp = RayPacket::<N>::new();
            rays_into(&shadow, &mut sp);
            sp.set_active(traced);
            let blocked = scene.occluded_packet(&mut sp);
            *rays += u64::from(traced.count_ones());
            for i in lanes(traced & !blocked) {
                (0..M).for_each(|c| self.l[c][i] += value[c][i]);
            }
        }
        mask(&ends_l) | ends_s | mask(&ends_g)
    }

    /// After the shading of hits `h`: a Lambert or glossy bounce is non-delta (no delta
    /// bounces since); the dielectric counts one more delta bounce.
    #[inline(always)]
    fn track(&mut self, h: &Hits<N, M>) {
        for (i, was) in self.st.since.iter_mut().enumerate() {
            let since = if *was == NONE_YET { NONE_YET } else { *was + 1 };
            *was = if h.lambert[i] || h.glossy[i] {
                0
            } else if h.glass[i] {
                since
            } else {
                *was
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

/// Estimates `jobs` (begun by `starts`) on `N` lanes carrying `M` channels (as `rules`
/// carry them) under the method's `rules`, writing job `i`'s linear RGB radiance to
/// `out[i]`. Returns the rays traced.
#[inline(always)]
pub fn run<const N: usize, const M: usize, K: Class>(
    tables: &Tables,
    scene: &Scene,
    (starts, jobs): (&Starts, &[Job]),
    rules: &Rules,
    out: &mut [Vec3],
) -> u64
where
    Lanes<N>: PacketWidth,
{
    let (max_depth, fixed, splits) = (rules.max_depth(), rules.fixed(), rules.splits());
    // Whether the method shares the light with another estimator (the full loop only).
    let shares = K::HANDS_OVER && rules.gathers();
    let mut p = Paths::<N, M>::new(starts);
    let mut cameras = CameraRays::<N>::new(starts);
    let mut rays = 0u64;
    let mut packet = RayPacket::<N>::new();
    let mut first: [Option<RawHit>; N] = [None; N];
    // Lanes whose next vertex is a split vertex again, its hit known.
    let mut resumed: LaneMask = 0;
    let area = tables
        .sampled
        .iter()
        .any(|l| !matches!(l, LightId::Punctual(_)));
    loop {
        let mut fresh: LaneMask = resumed;
        for (i, first) in first.iter_mut().enumerate() {
            if p.alive & (1 << i) == 0 {
                let batch = (starts, jobs);
                let Some(s) = cameras.take(scene, batch, &mut p.ctx[i], &mut rays) else {
                    break;
                };
                p.start(i, &s, fixed);
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
        let h = Hits::<N, M>::new((scene, &tables.shades), &packet, &packet.hits, hit, &p.lam);
        // Where the strategy shares the light (before a hand-over changes the records).
        let (gathered, leaves) = if shares {
            let rough = mask(&h.lambert) | mask(&h.glossy);
            rules.shared((hit & rough, p.alive), &p.st)
        } else {
            (0, 0)
        };
        let handed = if K::HANDS_OVER {
            hit & mask(&h.scalar)
        } else {
            0
        };
        let mut goes_on: LaneMask = 0;
        for i in lanes(handed) {
            let (traced, goes) = p.hand_over(i, scene, &packet, rules);
            rays += traced;
            goes_on |= u32::from(goes) << i;
        }
        let kept = hit & !handed;
        // What arrived at a resumed lane's vertex was counted before its split.
        let arrived = kept & !resumed;
        if K::ABSORBS {
            let at = (tables, scene, &p.lam);
            absorb(at, &packet, (&h, arrived), &mut p.st);
        }
        if K::LIT_BY_AREA {
            let seen = (arrived & !leaves, p.alive & !handed & !resumed & !leaves);
            let at = (tables, scene);
            arrive(at, &packet, (&h, &p.lam), seen, &p.st, &mut p.l);
        }
        if spectral::<M>() {
            p.disperse(kept & mask(&h.disperses), &packet, splits);
        }
        if shares {
            p.gather(gathered, scene, &packet, rules);
        }
        let ends = p.shade::<K>(tables, (scene, &h, area), max_depth, &mut rays);
        // A class without glossy lanes never meets one ([`Tables::plain`]); were it to, the
        // lane would end here rather than trace its ray again.
        let glossy = if K::GLOSSY { mask(&h.glossy) } else { 0 };
        let shaded = mask(&h.lambert) | glossy | mask(&h.glass);
        let ended = (p.alive & !(hit & shaded) & !goes_on) | ends;
        resumed = 0;
        for i in lanes(ended & p.alive) {
            match p.end(i, out) {
                Some(r) => {
                    p.resume(i, &r);
                    first[i] = r.hit;
                    resumed |= 1 << i;
                }
                None => p.alive &= !(1 << i),
            }
        }
    }
}
