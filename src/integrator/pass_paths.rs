//! The camera side of one pass of a progressive photon method (SPPM, the hybrid): one path
//! per pixel of the active tiles, from the pixel's sample `k` = its tile's next unit
//! ([`FilmTile::next_unit`]: `pass` unless adaptive sampling rested the tile in earlier
//! passes of the hybrid; SPPM never rests tiles), at the pass's wavelengths, added to the
//! film's half `k mod 2`. Tiles run in parallel. Within a tile the paths run one after the other,
//! or for the hybrid in lanes ([`path::estimate_lanes`]), which give the same estimates bit
//! for bit, or through the structure-of-arrays kernel ([`path::kernel`]) where the method
//! gives its rules and the scene is in the kernel's class (its estimates equal the scalar
//! vertex's up to float rounding). SPPM's paths stop at a visible point, which neither
//! returns, so SPPM stays on single rays.
//!
//! Units: linear RGB radiance on the film; the carrier `C` along the paths.

use super::path::polarized::PolarizedGather;
use super::path::{self, LaneWidth, Strategy, VisiblePoint};
use super::Context;
use crate::camera::Camera;
use crate::render::{primary_ray, Film, FilmTile, Job, Starts, TILE_PIXELS};
use crate::sampler::PixelSampler;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::Vec3;
use rayon::prelude::*;

/// The camera side of one pass of a progressive photon method (SPPM, the hybrid): one path
/// per pixel, from the pixel's sample `pass` of `sampler` through [`primary_ray`] and
/// [`path::camera_path`] under the method's `strategy`, at the pass's wavelengths `lambda`.
pub(super) struct PassPaths<'a, C: Carrier, S: Strategy<C>> {
    pub scene: &'a Scene,
    pub camera: &'a Camera,
    pub sampler: PixelSampler,
    pub max_depth: u32,
    pub lambda: C::Lambda,
    /// What the method asks of its camera paths.
    pub strategy: S,
    /// Lanes for paths that do not stop at a visible point ([`Strategy::STOPS`]).
    pub lanes: LaneWidth,
    /// Polarized camera paths (the polarized hybrid): what the camera looks through and
    /// the caustic map's polarized gather ([`path::polarized::radiance`]; `strategy` then
    /// unused, single rays).
    pub polarized: Option<(path::polarized::Polarization, PolarizedGather<'a, C>)>,
    /// The render's cancellation ([`crate::render::guard::Cancel`]): once set, the tiles
    /// not yet started are skipped (the pass is then incomplete, to be thrown away).
    pub cancel: &'a crate::render::guard::Cancel,
    /// The kernel's tables and the method's rules for it: the paths run there, and each
    /// pixel's linear RGB estimate goes to the film as it is (for a method whose `keep`
    /// is the carrier's conversion to RGB and nothing else).
    pub kernel: Option<(&'a path::kernel::Tables, path::kernel::Rules<'a>)>,
}

impl<C: Carrier, S: Strategy<C>> PassPaths<'_, C, S> {
    /// Traces every pixel's path of the active tiles, tiles in parallel, and adds `keep((x,
    /// y), L, visible point, slot)` (the pixel's RGB) to the film's half `k mod 2` (see the
    /// module docs). `slots` has one entry per film slot, handed to `keep` (a zero-sized
    /// type when it keeps nothing); with `done`, each traced tile then counts one unit
    /// more. Returns the rays and bad samples.
    pub fn trace<T: Send>(
        &self,
        film: &mut Film,
        slots: &mut [T],
        done: bool,
        keep: impl Fn((u32, u32), C, Option<VisiblePoint<C>>, &mut T) -> Vec3 + Sync,
    ) -> (u64, u64) {
        let lanes = !S::STOPS && self.lanes != LaneWidth::Scalar && self.polarized.is_none();
        film.par_tiles_mut()
            .zip(slots.par_chunks_mut(TILE_PIXELS))
            .map(|(mut tile, tile_slots)| {
                if !tile.active() || self.cancel.is_cancelled() {
                    return (0, 0);
                }
                let (rays, bad) = if let Some(kernel) = &self.kernel {
                    self.tile_kernel(&mut tile, kernel)
                } else if lanes {
                    self.tile_lanes(&mut tile, tile_slots, &keep)
                } else {
                    self.tile_scalar(&mut tile, tile_slots, &keep)
                };
                if done {
                    tile.take(1, rays);
                }
                (rays, bad)
            })
            .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1))
    }
}

/// What a pass adds per pixel: `keep((x, y), L, visible point, slot)` as RGB.
type Keep<'k, C, T> = &'k (dyn Fn((u32, u32), C, Option<VisiblePoint<C>>, &mut T) -> Vec3 + Sync);

impl<C: Carrier, S: Strategy<C>> PassPaths<'_, C, S> {
    /// One tile's paths one after the other; returns the rays and bad samples.
    fn tile_scalar<T>(&self, tile: &mut FilmTile, slots: &mut [T], keep: Keep<C, T>) -> (u64, u64) {
        let k = tile.next_unit();
        let (mut rays, mut bad) = (0, 0);
        for (i, slot) in slots.iter_mut().enumerate() {
            let Some((x, y)) = tile.pixel(i) else {
                continue;
            };
            let mut ctx = Context {
                sample: self.sampler.start(x, y, k),
                rays: 0,
            };
            let ray = primary_ray(self.camera, x, y, false, &mut ctx.sample);
            let (l, vp) = match self.polarized {
                Some((polarization, gather)) => {
                    let a = polarization.analyzer(self.camera.basis(), ray.dir);
                    let rules = (self.max_depth, Some(gather));
                    let l = path::polarized::radiance(
                        self.scene,
                        &ray,
                        rules,
                        self.lambda,
                        a,
                        &mut ctx,
                    );
                    (l, None)
                }
                None => path::camera_path::<C, S>(
                    self.scene,
                    &ray,
                    (self.max_depth, &self.strategy),
                    self.lambda,
                    &mut ctx,
                ),
            };
            tile.add(i, k, keep((x, y), l, vp, slot).as_dvec3(), &mut bad);
            rays += ctx.rays;
        }
        (rays, bad)
    }

    /// The jobs of `tile`'s `n` pixels for its next unit `k`, each with its pixel's index.
    fn jobs(tile: &FilmTile, n: usize, k: u64) -> (Vec<(usize, Job)>, Vec<Job>) {
        let pixels: Vec<(usize, Job)> = (0..n)
            .filter_map(|i| tile.pixel(i).map(|(x, y)| (i, Job { x, y, k })))
            .collect();
        let jobs = pixels.iter().map(|&(_, j)| j).collect();
        (pixels, jobs)
    }

    /// One tile's paths through the kernel ([`path::kernel::estimate`] with the method's
    /// `rules`); returns the rays and bad samples.
    fn tile_kernel(
        &self,
        tile: &mut FilmTile,
        (tables, rules): &(&path::kernel::Tables, path::kernel::Rules),
    ) -> (u64, u64) {
        let k = tile.next_unit();
        let starts = Starts::new(self.camera, &self.sampler, false, false);
        let (pixels, jobs) = Self::jobs(tile, tile.slots(), k);
        let mut out = vec![Vec3::ZERO; jobs.len()];
        let rays = path::kernel::estimate(tables, self.scene, (&starts, &jobs), rules, &mut out);
        let mut bad = 0;
        for (&(i, _), rgb) in pixels.iter().zip(out) {
            tile.add(i, k, rgb.as_dvec3(), &mut bad);
        }
        (rays, bad)
    }

    /// One tile's paths in lanes ([`path::estimate_lanes`] with the pass's wavelengths, as
    /// [`path::camera_path`]); returns the rays and bad samples.
    fn tile_lanes<T>(&self, tile: &mut FilmTile, slots: &mut [T], keep: Keep<C, T>) -> (u64, u64) {
        let k = tile.next_unit();
        let starts = Starts::new(self.camera, &self.sampler, false, false);
        let (pixels, jobs) = Self::jobs(tile, slots.len(), k);
        let mut out = vec![C::ZERO; jobs.len()];
        let rules = (self.max_depth, &self.strategy);
        let estimate = |i: usize, l: C, _: &C::Lambda| out[i] = l;
        let rays = path::estimate_lanes(
            self.scene,
            self.lanes,
            rules,
            (&starts, &jobs),
            Some(self.lambda),
            estimate,
        );
        let mut bad = 0;
        for (&(i, job), l) in pixels.iter().zip(out) {
            tile.add(
                i,
                k,
                keep((job.x, job.y), l, None, &mut slots[i]).as_dvec3(),
                &mut bad,
            );
        }
        (rays, bad)
    }
}
