//! The film: per-pixel sums of linear RGB radiance (W·sr⁻¹·m⁻² per channel) kept in two
//! halves, the one accumulator of every method (per-sample methods add sample k to half
//! k mod 2; SPPM and the hybrid add pass p to half p mod 2).
//!
//! Invariants:
//! - Every value enters through [`FilmTile::add`]: the guard ([`super::guard::admit`])
//!   drops non-finite and out-of-range values, and the sums are exact fixed-point integers
//!   ([`crate::image::fixed`]), so they do not depend on the order of additions: a shard's sums
//!   added to the others' are the sums of one render of all the units.
//! - A film takes the units `first..`, by absolute index (`first` > 0 for a shard): unit k
//!   goes to half k mod 2 and draws the sampler's index k.
//! - Storage is tile by tile (`TILE²` slots per tile, row-major inside the tile; slots
//!   outside the image stay zero), so each parallel tile owns one contiguous chunk.
//! - Each tile counts the units (samples or passes) it has taken, always the contiguous
//!   range `first..first + count`; all tiles hold the same count unless a round was
//!   interrupted between tiles or adaptive sampling rested some ([`Film::set_active`]:
//!   a resting tile takes no units, and when it wakes it goes on from its own count).
//! - The two halves are independent estimates of the same image: their difference
//!   estimates the error without a reference
//!   ([`crate::image::metrics::half_buffer_estimate`]).
//!
//! Colour conversion happens before a value reaches the film (spectral samples are turned
//! into RGB by [`crate::spectrum::Carrier::to_rgb`] in the sample step).

use super::guard;
use crate::image::exact::{half_means, ExactImage};
use crate::image::fixed::{parity_counts, pixel_mean, FixedRgb, PixelSums};
use crate::image::ImageRgb;
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// Tile edge in pixels.
pub const TILE: u32 = 16;
/// Slots (pixels) per tile.
pub const TILE_PIXELS: usize = (TILE * TILE) as usize;

/// Two half images' per-pixel sums and the units each tile has taken.
pub struct Film {
    width: u32,
    height: u32,
    tiles_x: u32,
    first: u64,
    sums: Vec<PixelSums>,
    counts: Vec<u64>,
    /// Rays each tile has traced ([`FilmTile::take`]): its cost, for adaptive sampling.
    rays: Vec<u64>,
    /// Whether each tile takes units in the next rounds ([`Film::set_active`]).
    active: Vec<bool>,
}

/// What adaptive sampling knows of one tile ([`Film::tile_states`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TileState {
    /// Pixels of the tile inside the image.
    pub pixels: u64,
    /// Units taken.
    pub units: u64,
    /// Rays traced for them.
    pub rays: u64,
    /// Whether it takes units in the next rounds.
    pub active: bool,
}

/// One tile of the film, borrowed for one round: its pixels' sums (slot `i` is pixel
/// `(x0 + i mod TILE, y0 + i / TILE)`; slots with [`FilmTile::pixel`] `None` lie outside
/// the image) and its unit count.
pub struct FilmTile<'a> {
    /// The tile's top-left pixel.
    pub origin: (u32, u32),
    sums: &'a mut [PixelSums],
    count: &'a mut u64,
    rays: &'a mut u64,
    active: bool,
    first: u64,
    size: (u32, u32),
}

impl FilmTile<'_> {
    /// The pixel of slot `i`, or `None` outside the image.
    pub fn pixel(&self, i: usize) -> Option<(u32, u32)> {
        pixel_of(self.origin, self.size, i)
    }

    /// Slots in the tile ([`TILE_PIXELS`]).
    pub fn slots(&self) -> usize {
        self.sums.len()
    }

    /// Adds `v` (linear RGB) to slot `i`'s half `unit mod 2` (`unit` is the absolute unit
    /// index), unless the guard refuses it ([`guard::admit`]: NaN, infinite or beyond the
    /// fixed-point range), which counts it in `bad`. The one way into the film.
    #[inline]
    pub fn add(&mut self, i: usize, unit: u64, v: DVec3, bad: &mut u64) {
        let v = guard::admit(v, bad);
        let s = &mut self.sums[i][(unit % 2) as usize];
        *s = *s + FixedRgb::from_dvec3(v);
    }

    /// Marks the tile as having taken every unit before `end` (absolute index) from the
    /// film's first.
    pub fn done_until(&mut self, end: u64) {
        *self.count = end.saturating_sub(self.first);
    }

    /// Whether the tile takes units this round (adaptive sampling rests the others).
    pub fn active(&self) -> bool {
        self.active
    }

    /// The absolute index of the tile's next unit: `first +` the units it has taken.
    pub fn next_unit(&self) -> u64 {
        self.first + *self.count
    }

    /// Marks `n` more units as taken, which traced `rays` rays.
    pub fn take(&mut self, n: u64, rays: u64) {
        *self.count += n;
        *self.rays += rays;
    }
}

/// The top-left pixel of tile `t` (tiles row-major, `tiles_x` per row).
fn tile_origin(tiles_x: u32, t: usize) -> (u32, u32) {
    let t = t as u32;
    ((t % tiles_x) * TILE, (t / tiles_x) * TILE)
}

/// The pixel of slot `i` of the tile at `origin` in an image of `size`, if inside.
fn pixel_of(origin: (u32, u32), size: (u32, u32), i: usize) -> Option<(u32, u32)> {
    let (x, y) = (origin.0 + i as u32 % TILE, origin.1 + i as u32 / TILE);
    (x < size.0 && y < size.1).then_some((x, y))
}

impl Film {
    /// An empty film of `width × height` pixels taking the units `first..` (absolute
    /// indices; 0 unless it renders a shard).
    pub fn new(width: u32, height: u32, first: u64) -> Self {
        let tiles_x = width.div_ceil(TILE);
        let tiles = tiles_x as usize * height.div_ceil(TILE) as usize;
        Film {
            width,
            height,
            tiles_x,
            first,
            sums: vec![[FixedRgb::ZERO; 2]; tiles * TILE_PIXELS],
            counts: vec![0; tiles],
            rays: vec![0; tiles],
            active: vec![true; tiles],
        }
    }

    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.counts.len()
    }

    /// Slots over all tiles (`tiles() · TILE²`): the length of per-slot side buffers kept
    /// in film order (SPPM's visible points).
    pub fn slots(&self) -> usize {
        self.sums.len()
    }

    /// The absolute index of the film's first unit.
    pub fn first(&self) -> u64 {
        self.first
    }

    /// The top-left pixel of tile `t`.
    fn origin(&self, t: usize) -> (u32, u32) {
        tile_origin(self.tiles_x, t)
    }

    /// The tiles, in parallel, for one round.
    pub fn par_tiles_mut(&mut self) -> impl IndexedParallelIterator<Item = FilmTile<'_>> {
        let (tiles_x, size, first) = (self.tiles_x, (self.width, self.height), self.first);
        self.sums
            .par_chunks_mut(TILE_PIXELS)
            .zip(self.counts.par_iter_mut())
            .zip(self.rays.par_iter_mut())
            .zip(self.active.par_iter())
            .enumerate()
            .map(move |(t, (((sums, count), rays), &active))| FilmTile {
                origin: tile_origin(tiles_x, t),
                sums,
                count,
                rays,
                active,
                first,
                size,
            })
    }

    /// Rests the tiles whose `active` entry is false (adaptive sampling): rounds skip them
    /// until a later call wakes them. `active` has one entry per tile.
    pub fn set_active(&mut self, active: Vec<bool>) {
        debug_assert_eq!(active.len(), self.active.len());
        self.active = active;
    }

    /// Per tile: the pixels inside the image, the units taken, the rays traced and whether
    /// it is active, in tile order.
    pub fn tile_states(&self) -> impl Iterator<Item = TileState> + '_ {
        (0..self.counts.len()).map(|t| TileState {
            pixels: self.tile_pixels(t),
            units: self.counts[t],
            rays: self.rays[t],
            active: self.active[t],
        })
    }

    /// Pixels of the active tiles.
    pub fn active_pixels(&self) -> u64 {
        self.tile_states()
            .filter(|t| t.active)
            .map(|t| t.pixels)
            .sum()
    }

    /// The fewest and the most units any tile has taken.
    pub fn unit_span(&self) -> (u64, u64) {
        let min = self.counts.iter().copied().min().unwrap_or(0);
        let max = self.counts.iter().copied().max().unwrap_or(0);
        (min, max)
    }

    /// Pixels of tile `t` inside the image.
    fn tile_pixels(&self, t: usize) -> u64 {
        let (x0, y0) = self.origin(t);
        let tw = TILE.min(self.width - x0) as u64;
        let th = TILE.min(self.height - y0) as u64;
        tw * th
    }

    /// Calls `f(pixel index, sums, units of the pixel's tile)` for every pixel.
    fn for_each_pixel(&self, mut f: impl FnMut(usize, &PixelSums, u64)) {
        let (w, h) = (self.width, self.height);
        for (t, tile) in self.sums.chunks(TILE_PIXELS).enumerate() {
            let origin = self.origin(t);
            for (i, s) in tile.iter().enumerate() {
                if let Some((x, y)) = pixel_of(origin, (w, h), i) {
                    f((y * w + x) as usize, s, self.counts[t]);
                }
            }
        }
    }

    /// The image `f(sums, units of the pixel's tile)` in row-major order.
    fn image(&self, f: impl Fn(&PixelSums, u64) -> Vec3) -> ImageRgb {
        let mut img = ImageRgb::new(self.width, self.height);
        self.for_each_pixel(|i, s, n| img.data[i] = f(s, n));
        img
    }

    /// The mean of every pixel's units.
    pub fn mean(&self) -> ImageRgb {
        self.image(pixel_mean)
    }

    /// The two halves' means: units of even and of odd absolute index. When some pixel
    /// has an empty half (one unit, or a shard of one), both are the mean, so error
    /// estimates are 0 then ([`ExactImage::halves`], the same rule).
    pub fn halves(&self) -> (ImageRgb, ImageRgb) {
        let first = self.first;
        if self
            .counts
            .iter()
            .any(|&n| parity_counts(first, n).contains(&0))
        {
            let m = self.mean();
            return (m.clone(), m);
        }
        let a = self.image(|s, n| half_means(s, parity_counts(first, n)).0);
        let b = self.image(|s, n| half_means(s, parity_counts(first, n)).1);
        (a, b)
    }

    /// The exact sums and per-pixel unit counts in row-major order, for a partial image
    /// ([`crate::output::partial`]).
    pub fn exact(&self) -> ExactImage {
        let mut e = ExactImage::new(self.width, self.height);
        self.for_each_pixel(|i, s, n| {
            e.sums[i] = *s;
            e.units[i] = parity_counts(self.first, n);
        });
        e
    }

    /// The units every tile has reached.
    pub fn done(&self) -> u64 {
        self.counts.iter().copied().min().unwrap_or(0)
    }

    /// Pixel units (samples; SPPM: pixel passes) taken over the image.
    pub fn pixel_samples(&self) -> u64 {
        self.tile_states().map(|t| t.pixels * t.units).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::fixed::LIMIT;

    #[test]
    fn slots_map_to_every_pixel_once() {
        let mut film = Film::new(37, 20, 0);
        let mut seen = vec![0u32; 37 * 20];
        let tiles: Vec<Vec<Option<(u32, u32)>>> = film
            .par_tiles_mut()
            .map(|t| (0..TILE_PIXELS).map(|i| t.pixel(i)).collect())
            .collect();
        assert_eq!(tiles.len(), 3 * 2);
        for px in tiles {
            for (x, y) in px.into_iter().flatten() {
                seen[(y * 37 + x) as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
    }

    /// A film of 3×2 pixels given units `first..first + n` of value 4 (even index) and 2
    /// (odd index), one round.
    fn film_of(first: u64, n: u64) -> Film {
        let mut film = Film::new(3, 2, first);
        film.par_tiles_mut().for_each(|mut t| {
            let mut bad = 0;
            for i in 0..t.slots() {
                for k in first..first + n {
                    let v = if k % 2 == 0 { 4.0 } else { 2.0 };
                    t.add(i, k, DVec3::splat(v), &mut bad);
                }
            }
            t.done_until(first + n);
        });
        film
    }

    #[test]
    fn halves_split_units_by_parity() {
        // Three units: 0 and 2 in half 0, 1 in half 1.
        let film = film_of(0, 3);
        assert_eq!(film.mean().data[0], Vec3::splat(10.0 / 3.0));
        let (a, b) = film.halves();
        assert_eq!(a.data[5], Vec3::splat(4.0));
        assert_eq!(b.data[5], Vec3::splat(2.0));
        assert_eq!(film.done(), 3);
        assert_eq!(film.pixel_samples(), 18);
        // A shard from unit 5: 5, 7 odd, 6 even.
        let film = film_of(5, 3);
        assert_eq!(film.mean().data[1], Vec3::splat(8.0 / 3.0));
        let (a, b) = film.halves();
        assert_eq!((a.data[1], b.data[1]), (Vec3::splat(4.0), Vec3::splat(2.0)));
        assert_eq!(film.exact().units[1], [1, 2]);
        // One unit: both halves are the mean.
        let film = film_of(3, 1);
        let (a, b) = film.halves();
        assert_eq!((a.data[2], b.data[2]), (Vec3::splat(2.0), Vec3::splat(2.0)));
    }

    #[test]
    fn the_guard_keeps_bad_values_out() {
        let mut film = Film::new(2, 1, 0);
        let mut bad = 0;
        for mut t in film.par_tiles_mut().collect::<Vec<_>>() {
            t.add(0, 0, DVec3::new(1.0, f64::NAN, 0.0), &mut bad);
            t.add(0, 1, DVec3::splat(2.0 * LIMIT), &mut bad);
            t.add(0, 2, DVec3::splat(0.5), &mut bad);
            t.done_until(3);
        }
        assert_eq!(bad, 2);
        assert_eq!(film.mean().data[0], Vec3::splat(0.5 / 3.0));
    }

    /// A 20×3 film of units `first..first + n` (value 1 + k/8 for unit k, plus the pixel
    /// index), whose exact sums ([`ExactImage`]) the merge tests add up.
    fn ramp_film(first: u64, n: u64) -> Film {
        let mut film = Film::new(20, 3, first);
        film.par_tiles_mut().for_each(|mut t| {
            let mut bad = 0;
            for i in 0..t.slots() {
                for k in first..first + n {
                    let v = 1.0 + k as f64 / 8.0 + i as f64 * 0.37;
                    t.add(i, k, DVec3::new(v, v * 0.1, -v), &mut bad);
                }
            }
            t.done_until(first + n);
        });
        film
    }

    #[test]
    fn split_films_add_up_to_the_whole_bit_for_bit() {
        let whole = ramp_film(0, 11);
        let mut merged = ramp_film(7, 4).exact();
        merged.add(&ramp_film(0, 3).exact());
        merged.add(&ramp_film(3, 4).exact());
        assert_eq!(merged, whole.exact());
        assert_eq!(merged.mean(), whole.mean());
        assert_eq!(merged.halves(), whole.halves());
        assert_eq!(merged.unit_span(), (11, 11));
        assert_eq!(merged.pixel_units(), 60 * 11);
    }

    #[test]
    fn an_empty_half_makes_both_halves_the_mean() {
        let one = ramp_film(4, 1).exact();
        let (a, b) = one.halves();
        assert_eq!(a, one.mean());
        assert_eq!(b, one.mean());
    }
}
