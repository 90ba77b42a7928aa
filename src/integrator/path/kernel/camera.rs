//! The camera rays of a batch as their own coherent packets ([`CameraRays`]): the jobs'
//! camera rays are made and traced `N` at a time in job order, with Embree's coherent
//! hint ([`Coherence::Coherent`]: neighbouring jobs are samples of one pixel or of
//! neighbouring pixels of one tile), and each job's first hit kept, so the bounce loop
//! ([`super::paths`]) starts a lane with its first hit known and its bounce packets carry
//! bounce rays only.
//!
//! A chunk of `N` jobs is traced when the refill has taken every job of the previous
//! one, so the batch's camera rays are traced in job order, `N` per packet (the last
//! packet of a batch may hold fewer), as if all were traced before the bounce loop; each
//! pending job's sample stream ([`Context`], restarted by [`Starts::start`], which makes
//! the camera ray) waits here and is swapped into the lane that takes the job. A job's
//! first hit depends only on its own ray (the coherent hint changes how the backend
//! traverses, not the closest hit, up to which of two triangles a ray exactly on their
//! shared edge or plane meets).

use super::state::Rays;
use crate::accel::packet::{Coherence, Lanes, PacketWidth, RayPacket};
use crate::accel::RawHit;
use crate::render::{Context, Job, Starts};
use crate::scene::Scene;

/// The batch's jobs waiting for a lane: up to `N` of them, their sample streams, camera
/// rays and first hits, lane `l` holding job `first + l`.
pub struct CameraRays<const N: usize> {
    /// The pending jobs' sample streams (lane `l`'s until it is taken; boxed, so that
    /// handing one to a lane swaps pointers, not the sampler's state).
    ctx: [Box<Context>; N],
    /// Their camera rays.
    rays: RayPacket<N>,
    /// Their wavelength numbers (0 in RGB).
    u_lambda: [f32; N],
    /// The batch index of the chunk's first job.
    first: usize,
    /// Jobs in the chunk, and jobs of it taken so far.
    len: usize,
    taken: usize,
}

/// A job leaving [`CameraRays`] for a lane: its batch index, camera ray (origin,
/// direction, `t_max`), wavelength number and first hit (`None`: the ray escaped).
pub struct Started {
    /// Index into the batch.
    pub job: usize,
    /// The number the sample's wavelengths are drawn from ([`Starts::start`]; 0 in RGB).
    pub u_lambda: f32,
    /// Origin, direction, `t_max` of the camera ray.
    pub ray: ([f32; 3], [f32; 3], f32),
    /// The closest hit along it.
    pub hit: Option<RawHit>,
}

impl<const N: usize> CameraRays<N>
where
    Lanes<N>: PacketWidth,
{
    /// No job pending (streams made by `starts`, restarted for each job).
    pub fn new(starts: &Starts) -> Self {
        CameraRays {
            ctx: std::array::from_fn(|_| Box::new(starts.context())),
            rays: RayPacket::new(),
            u_lambda: [0.0; N],
            first: 0,
            len: 0,
            taken: 0,
        }
    }

    /// The next job of `jobs` (begun by `starts`) with its first hit, its sample stream
    /// swapped into `ctx`; `None` when the batch is done. A new chunk's camera rays are
    /// traced as one coherent packet, counted in `traced`.
    #[inline(always)]
    pub fn take(
        &mut self,
        scene: &Scene,
        (starts, jobs): (&Starts, &[Job]),
        ctx: &mut Box<Context>,
        traced: &mut u64,
    ) -> Option<Started> {
        if self.taken == self.len {
            self.trace(scene, (starts, jobs), self.first + self.len)?;
            *traced += self.len as u64;
        }
        let l = self.taken;
        self.taken += 1;
        std::mem::swap(ctx, &mut self.ctx[l]);
        let r = &self.rays;
        Some(Started {
            job: self.first + l,
            u_lambda: self.u_lambda[l],
            ray: (
                [r.org_x[l], r.org_y[l], r.org_z[l]],
                [r.dir_x[l], r.dir_y[l], r.dir_z[l]],
                r.t_max[l],
            ),
            hit: self.rays.hit(l),
        })
    }

    /// Makes and traces the camera rays of the `N` jobs from batch index `first` (fewer at
    /// the batch's end); `None` when there are none.
    #[inline(always)]
    fn trace(
        &mut self,
        scene: &Scene,
        (starts, jobs): (&Starts, &[Job]),
        first: usize,
    ) -> Option<()> {
        let len = jobs.len().saturating_sub(first).min(N);
        if len == 0 {
            return None;
        }
        for l in 0..len {
            let (ray, u_lambda) = starts.start(jobs[first + l], &mut self.ctx[l]);
            self.rays.set(l, ray.origin, ray.dir, ray.t_max);
            self.u_lambda[l] = u_lambda;
        }
        self.rays.set_active(((1u64 << len) - 1) as u32);
        scene.intersect_packet(&mut self.rays, Coherence::Coherent);
        (self.first, self.len, self.taken) = (first, len, 0);
        Some(())
    }
}

/// Sets lane `i` of `rays` to `started`'s camera ray.
#[inline(always)]
pub fn ray_into<const N: usize>(rays: &mut Rays<N>, i: usize, started: &Started) {
    let (o, d, t_max) = started.ray;
    for c in 0..3 {
        rays.o[c][i] = o[c];
        rays.d[c][i] = d[c];
    }
    rays.t_max[i] = t_max;
}
