//! The film: per-pixel sums of linear RGB radiance (W·sr⁻¹·m⁻² per channel) kept in two
//! halves, the one accumulator of every method (per-sample methods add sample k to half
//! k mod 2; SPPM adds pass p to half p mod 2).
//!
//! Invariants:
//! - Storage is tile by tile (`TILE²` slots per tile, row-major inside the tile; slots
//!   outside the image stay zero), so each parallel tile owns one contiguous chunk.
//! - Each tile counts the units (samples or passes) it has taken; all tiles hold the same
//!   count unless a round was interrupted between tiles.
//! - The two halves are independent estimates of the same image: their difference
//!   estimates the error without a reference ([`crate::measure::metrics::half_buffer_estimate`]).
//!
//! Colour conversion happens before a value reaches the film (spectral samples are turned
//! into RGB by [`crate::spectrum::Carrier::to_rgb`] in the sample step).

use crate::output::ImageRgb;
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
    sums: Vec<[DVec3; 2]>,
    counts: Vec<u64>,
}

/// One tile of the film, borrowed for one round: its pixels' sums (slot `i` is pixel
/// `(x0 + i mod TILE, y0 + i / TILE)`; slots with [`FilmTile::pixel`] `None` lie outside
/// the image) and its unit count.
pub struct FilmTile<'a> {
    /// The tile's top-left pixel.
    pub origin: (u32, u32),
    /// Per-slot sums of the two halves.
    pub sums: &'a mut [[DVec3; 2]],
    /// Units (samples or passes) this tile has taken.
    pub count: &'a mut u64,
    size: (u32, u32),
}

impl FilmTile<'_> {
    /// The pixel of slot `i`, or `None` outside the image.
    pub fn pixel(&self, i: usize) -> Option<(u32, u32)> {
        pixel_of(self.origin, self.size, i)
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
    /// An empty film of `width × height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        let tiles_x = width.div_ceil(TILE);
        let tiles = tiles_x as usize * height.div_ceil(TILE) as usize;
        Film {
            width,
            height,
            tiles_x,
            sums: vec![[DVec3::ZERO; 2]; tiles * TILE_PIXELS],
            counts: vec![0; tiles],
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

    /// The top-left pixel of tile `t`.
    fn origin(&self, t: usize) -> (u32, u32) {
        tile_origin(self.tiles_x, t)
    }

    /// The tiles, in parallel, for one round.
    pub fn par_tiles_mut(&mut self) -> impl IndexedParallelIterator<Item = FilmTile<'_>> {
        let (tiles_x, size) = (self.tiles_x, (self.width, self.height));
        self.sums
            .par_chunks_mut(TILE_PIXELS)
            .zip(self.counts.par_iter_mut())
            .enumerate()
            .map(move |(t, (sums, count))| FilmTile {
                origin: tile_origin(tiles_x, t),
                sums,
                count,
                size,
            })
    }

    /// The image `f(sums, units of the pixel's tile)` in row-major order.
    fn image(&self, f: impl Fn(&[DVec3; 2], u64) -> DVec3) -> ImageRgb {
        let (w, h) = (self.width, self.height);
        let mut data = vec![Vec3::ZERO; w as usize * h as usize];
        for (t, tile) in self.sums.chunks(TILE_PIXELS).enumerate() {
            let origin = self.origin(t);
            for (i, s) in tile.iter().enumerate() {
                if let Some((x, y)) = pixel_of(origin, (w, h), i) {
                    data[(y * w + x) as usize] = f(s, self.counts[t]).as_vec3();
                }
            }
        }
        ImageRgb {
            width: w,
            height: h,
            data,
        }
    }

    /// The mean of every pixel's units.
    pub fn mean(&self) -> ImageRgb {
        self.image(|s, n| (s[0] + s[1]) / n.max(1) as f64)
    }

    /// The two halves' means (of n units, half 0 has ⌈n/2⌉, half 1 ⌊n/2⌋; an empty half 1
    /// is a copy of half 0, so error estimates from one unit are 0).
    pub fn halves(&self) -> (ImageRgb, ImageRgb) {
        let a = self.image(|s, n| s[0] / n.div_ceil(2).max(1) as f64);
        let b = if self.counts.iter().all(|&n| n >= 2) {
            self.image(|s, n| s[1] / (n / 2) as f64)
        } else {
            a.clone()
        };
        (a, b)
    }

    /// The units every tile has reached.
    pub fn done(&self) -> u64 {
        self.counts.iter().copied().min().unwrap_or(0)
    }

    /// Pixel units (samples; SPPM: pixel passes) taken over the image.
    pub fn pixel_samples(&self) -> u64 {
        (0..self.counts.len())
            .map(|t| {
                let (x0, y0) = self.origin(t);
                let tw = TILE.min(self.width - x0) as u64;
                let th = TILE.min(self.height - y0) as u64;
                tw * th * self.counts[t]
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_map_to_every_pixel_once() {
        let mut film = Film::new(37, 20);
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

    #[test]
    fn halves_split_units_by_parity() {
        let mut film = Film::new(3, 2);
        film.par_tiles_mut().for_each(|t| {
            for s in t.sums.iter_mut() {
                // Three units: 1 and 3 in half 0, 2 in half 1.
                *s = [DVec3::splat(4.0), DVec3::splat(2.0)];
            }
            *t.count = 3;
        });
        assert_eq!(film.mean().data[0], Vec3::splat(2.0));
        let (a, b) = film.halves();
        assert_eq!(a.data[5], Vec3::splat(2.0));
        assert_eq!(b.data[5], Vec3::splat(2.0));
        assert_eq!(film.done(), 3);
        assert_eq!(film.pixel_samples(), 18);
    }
}
