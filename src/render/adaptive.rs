//! Adaptive sampling: which tiles of the film take the next rounds' units. The driver asks at
//! every checkpoint ([`super::drive`]); a resting tile keeps its sums and its count and, when
//! it wakes, goes on from its own next unit, so each tile always holds the contiguous units
//! `first..first + count` ([`super::Film`]).
//!
//! The rule, per tile t of `P_t` pixels that has taken `n_t` units and traced `R_t` rays,
//! when the image has taken `D` units (the driver's count):
//! - `e_t²`: the tile's relative MSE estimated from two halves, the mean over its pixels
//!   and channels of [`half_pair_terms`]' relative term; the image's estimate
//!   ([`crate::image::metrics::half_buffer_estimate`]) is the pixel-weighted mean of them.
//!   The halves are the ones the render is judged by ([`super::Progress::judged`]): the
//!   denoised halves when the error-target stop checks a denoised image, so samples go
//!   where the picture the stop sees is noisy (the denoiser cleans a smooth floor at few
//!   samples and a stone's sparkle at many), else the raw halves.
//! - `V_t = n_t·e_t²`: the relative variance of one unit (`e² = V/n`).
//! - `c_t = R_t / (n_t·P_t)`, at least 1: rays per pixel and unit, the cost of one unit.
//! - Neyman's allocation with costs (Cochran, *Sampling Techniques*, 3rd ed. 1977, §5.5)
//!   minimises `Σ P_t·V_t/n_t` for the rays `Σ P_t·c_t·n_t` with `n_t ∝ w_t = √(V_t/c_t)`.
//! - Rounds give the same units to every active tile, so the neediest tiles run at the
//!   image's count `D` and the others should follow in proportion: a tile works while
//!   `n_t ≤ D·w_t/w_ref` and rests once it is ahead. `w_ref` is the pixel-weighted 90th
//!   percentile of `w` (the tiles above it always work), not the largest, so that one tile
//!   with a firefly does not rest the whole image.
//! - A resting tile wakes at a later checkpoint, once the image's count has grown past its
//!   share (or its share has grown).
//! - With an error target `T` (`--target-error`, or the default target), a tile also rests
//!   once `e_t < T/2` (within the lag bound below): a quarter of the target's relative MSE,
//!   so further units there cannot change whether the image meets it. This is Cycles' noise
//!   threshold, tied to the target.
//! - No tile rests before it has [`MIN_UNITS`] units, and none lags the image by more than
//!   [`MAX_LAG`] (a tile with fewer than `D/4` units works, whatever its estimate). The halves
//!   see noise, not bias: a tile's estimate from few units misses rare bright paths (it
//!   looks clean by luck), and a denoised tile from few units is blurred more, which the
//!   denoised halves do not show (without the bound the glass of water stopped further from
//!   the truth than uniform sampling: BENCHMARKS.md, "Adaptive sampling").
//! - If every tile would rest, every tile is active: rounds always take units somewhere.
//!
//! Invariants: the choice is a function of the film's sums, counts and rays, so the same
//! scene, seed and backend give the same image whatever the thread count. Resting is by
//! tile, never by pixel, so a tile's pixels share one count ([`super::Film`]'s invariant).
//!
//! The estimate that stops the render comes from the same halves as the choice. A tile that
//! rests on an estimate low by chance keeps that estimate, so the image's estimate can read
//! low by the resting tiles' share. Tiles pool 256 pixels' terms, which keeps that small;
//! `tests/render/adaptive.rs` measures the estimate against a reference.

use super::film::{Film, TILE};
use crate::image::metrics::half_pair_terms;
use crate::image::ImageRgb;

/// What adaptive sampling needs from the render: the error target, if a target stops it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adaptive {
    /// The render's error target (relative RMSE), which sets the absolute threshold `T/2`.
    pub target: Option<f64>,
}

/// Units a tile takes before it may rest.
pub const MIN_UNITS: u64 = 32;

/// The most a tile lags behind the image: it works while it has fewer than `D/MAX_LAG`
/// units.
pub const MAX_LAG: f64 = 4.0;

/// Per tile, the relative MSE estimated from the halves `a` and `b` of `film`'s image
/// (row-major, `film`'s size): the mean over the tile's pixels and channels.
pub fn tile_errors(film: &Film, (a, b): (&ImageRgb, &ImageRgb), absolute: bool) -> Vec<f64> {
    let term = |x: f32, y: f32| {
        let (v, rel, _) = half_pair_terms(f64::from(x), f64::from(y));
        if absolute {
            v
        } else {
            rel
        }
    };
    let tiles_x = a.width.div_ceil(TILE) as usize;
    let mut sums = vec![0.0f64; film.tiles()];
    for (i, (pa, pb)) in a.data.iter().zip(&b.data).enumerate() {
        let (x, y) = (i % a.width as usize, i / a.width as usize);
        let t = (y / TILE as usize) * tiles_x + x / TILE as usize;
        sums[t] += (0..3).map(|c| term(pa[c], pb[c])).sum::<f64>();
    }
    film.tile_states()
        .zip(sums)
        .map(|(s, sum)| sum / (3 * s.pixels.max(1)) as f64)
        .collect()
}

/// The tiles that take the next rounds' units (see the module docs), from the film and its
/// halves after `done` units of the image.
pub fn choose(
    film: &Film,
    halves: (&ImageRgb, &ImageRgb),
    absolute: bool,
    done: u64,
    adaptive: &Adaptive,
) -> Vec<bool> {
    let e2 = tile_errors(film, halves, absolute);
    let states: Vec<_> = film.tile_states().collect();
    // Per tile: P, c and V.
    let terms: Vec<(f64, f64, f64)> = states
        .iter()
        .zip(&e2)
        .map(|(s, e2)| {
            let (n, p) = (s.units.max(1) as f64, s.pixels as f64);
            let cost = (s.rays as f64 / (n * p.max(1.0))).max(1.0);
            (p, cost, n * e2)
        })
        .collect();
    let w: Vec<f64> = terms.iter().map(|&(_, c, v)| (v / c).sqrt()).collect();
    let w_ref = percentile(&w, &terms.iter().map(|t| t.0).collect::<Vec<_>>(), 0.9);
    let floor = adaptive.target.map_or(0.0, |t| 0.25 * t * t);
    let active: Vec<bool> = states
        .iter()
        .zip(w.iter().zip(&e2))
        .map(|(s, (&w, &e2))| {
            // With no error in nine tenths of the image (w_ref = 0), the tiles with any
            // error keep the image's pace and the others rest.
            let share = match (w_ref > 0.0, w > 0.0) {
                (true, _) => w / w_ref,
                (false, true) => f64::INFINITY,
                (false, false) => 0.0,
            };
            let (n, d) = (s.units as f64, done as f64);
            let lagging = n < d / MAX_LAG;
            let behind = n <= d * share.max(1.0 / MAX_LAG);
            s.units < MIN_UNITS || (behind && (e2 >= floor || lagging))
        })
        .collect();
    if active.iter().any(|&a| a) {
        active
    } else {
        vec![true; active.len()]
    }
}

/// The smallest of `values` at or above which lies the share `q` of the total `weights`
/// (the weighted `q` quantile); 0 for no values.
fn percentile(values: &[f64], weights: &[f64], q: f64) -> f64 {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let total: f64 = weights.iter().sum();
    let mut seen = 0.0;
    for &i in &order {
        seen += weights[i];
        if seen >= q * total {
            return values[i];
        }
    }
    order.last().map_or(0.0, |&i| values[i])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::FilmTile;
    use glam::{DVec3, Vec3};
    use rayon::iter::ParallelIterator;

    /// A 32×16 film (two tiles) whose tile `t` took `units[t]` units with `rays[t]` rays,
    /// every pixel's halves `a[t]` and `b[t]` (all channels).
    fn film(
        units: [u64; 2],
        rays: [u64; 2],
        a: [f64; 2],
        b: [f64; 2],
    ) -> (Film, ImageRgb, ImageRgb) {
        let mut film = Film::new(32, 16, 0);
        let tiles: Vec<FilmTile> = film.par_tiles_mut().collect();
        for (t, mut tile) in tiles.into_iter().enumerate() {
            let mut bad = 0;
            for i in 0..tile.slots() {
                for k in 0..units[t] {
                    let v = if k % 2 == 0 { a[t] } else { b[t] };
                    tile.add(i, k, DVec3::splat(v), &mut bad);
                }
            }
            tile.take(units[t], rays[t]);
        }
        let (ha, hb) = film.halves();
        (film, ha, hb)
    }

    #[test]
    fn tile_errors_are_the_half_buffer_terms_per_tile() {
        let (f, a, b) = film([32, 32], [0, 0], [0.9, 2.0], [1.1, 2.0]);
        let e2 = tile_errors(&f, (&a, &b), false);
        // Tile 0: (0.2)²/4 / (1² + 0.01) = 0.01/1.01 (every pixel and channel); tile 1: 0.
        assert!((e2[0] - 0.01 / 1.01).abs() < 1e-6, "{e2:?}");
        // Absolute (display values): (0.2)²/4 = 0.01.
        let abs = tile_errors(&f, (&a, &b), true);
        assert!((abs[0] - 0.01).abs() < 1e-6 && abs[1] == 0.0, "{abs:?}");
        assert_eq!(e2[1], 0.0);
        // Their pixel-weighted mean is the image's estimate.
        let whole = crate::image::metrics::half_buffer_estimate(&a, &b).unwrap();
        assert!((whole.rel_mse - 0.5 * e2[0]).abs() < 1e-9);
        assert_eq!(a.data[0], Vec3::splat(0.9));
    }

    #[test]
    fn a_clean_tile_rests_and_a_noisy_one_works() {
        // Equal units (32) and costs; tile 1 has 1/100 of tile 0's variance, so its share
        // is √(1/100) = 0.1 of tile 0's (the 90th percentile of two equal-sized tiles is
        // the larger), below the lag bound ¼: 32 > 32·¼, it rests.
        let (f, a, b) = film([32, 32], [256 * 32, 256 * 32], [0.9, 0.99], [1.1, 1.01]);
        let none = Adaptive { target: None };
        assert_eq!(choose(&f, (&a, &b), false, 32, &none), [true, false]);
        // Below MIN_UNITS nothing rests, however clean.
        let (f, a, b) = film([32, 28], [256 * 32, 256 * 28], [0.9, 1.0], [1.1, 1.0]);
        assert_eq!(choose(&f, (&a, &b), false, 32, &none), [true, true]);
        // No tile lags by more than MAX_LAG: at 128 the clean tile's 32 is a quarter.
        let (f, a, b) = film([128, 32], [256 * 128, 256 * 32], [0.9, 0.99], [1.1, 1.01]);
        assert_eq!(choose(&f, (&a, &b), false, 128, &none), [true, true]);
    }

    #[test]
    fn units_and_cost_enter_the_shares() {
        // Tile 1 took 64 units with e² 0.45× tile 0's 32: V = n·e² is 0.9× tile 0's (√:
        // 0.949). At equal cost it is ahead (64 > 64·0.949) and rests; tile 0 works.
        let none = Adaptive { target: None };
        let (lo, hi) = ([0.9, 1.0 - 0.067], [1.1, 1.0 + 0.067]);
        let (f, a, b) = film([32, 64], [256 * 32, 256 * 64], lo, hi);
        assert_eq!(choose(&f, (&a, &b), false, 64, &none), [true, false]);
        // With tile 0 at 16 rays per pixel and unit, its share falls to √(1/16)/0.949 =
        // 0.26 of tile 1's: tile 1 works and tile 0 (32 > 64·0.26) rests.
        let (f, a, b) = film([32, 64], [16 * 256 * 32, 256 * 64], lo, hi);
        assert_eq!(choose(&f, (&a, &b), false, 64, &none), [false, true]);
    }

    #[test]
    fn the_reference_share_is_a_weighted_percentile() {
        let w = [5.0, 1.0, 2.0, 100.0];
        assert_eq!(percentile(&w, &[1.0; 4], 0.9), 100.0);
        // One outlier among many: the 90th percentile ignores it.
        let mut w = vec![1.0; 19];
        w.push(1000.0);
        assert_eq!(percentile(&w, &[1.0; 20], 0.9), 1.0);
        assert_eq!(percentile(&[3.0, 7.0], &[9.0, 1.0], 0.9), 3.0);
        assert_eq!(percentile(&[], &[], 0.9), 0.0);
    }

    #[test]
    fn the_target_rests_tiles_below_half_of_it_and_never_all() {
        // Tile 0 at 128 units, relative RMSE √(0.01/1.01) ≈ 0.0995; tile 1 at 32, 0.0249:
        // √V is 1.125 and 0.141, a share of 1/8, raised to the lag bound ¼: at D = 128
        // tile 1 (32 ≤ 128/4) works.
        let (f, a, b) = film([128, 32], [256 * 128, 256 * 32], [0.9, 0.975], [1.1, 1.025]);
        let none = Adaptive { target: None };
        assert_eq!(choose(&f, (&a, &b), false, 128, &none), [true, true]);
        // Target 0.06: tile 1 is below 0.03 and rests (it lags by exactly the bound, not
        // more); tile 0 is not.
        let t = Adaptive { target: Some(0.06) };
        assert_eq!(choose(&f, (&a, &b), false, 128, &t), [true, false]);
        let (f, a, b) = film([129, 32], [256 * 129, 256 * 32], [0.9, 0.975], [1.1, 1.025]);
        assert_eq!(
            choose(&f, (&a, &b), false, 129, &t),
            [true, true],
            "beyond the bound it works"
        );
        // Equal tiles both below half the target: neither would work, so both do.
        let (f, a, b) = film([32, 32], [256 * 32, 256 * 32], [0.99, 0.99], [1.01, 1.01]);
        let t = Adaptive { target: Some(0.1) };
        assert_eq!(choose(&f, (&a, &b), false, 32, &t), [true, true]);
    }
}
