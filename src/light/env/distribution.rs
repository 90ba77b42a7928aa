//! Piecewise-constant 1D and 2D distributions on [0, 1) and [0, 1)², for sampling
//! proportional to a tabulated non-negative function (pbrt-v4 §A.5.1 `PiecewiseConstant1D`
//! and §A.5.2 `PiecewiseConstant2D`).
//!
//! Invariants: `func` values are finite and ≥ 0; `cdf` has `n + 1` entries, `cdf[0] = 0`,
//! `cdf[n] = 1`, non-decreasing. Sums are accumulated in f64 so maps with millions of
//! texels keep a monotone, correctly normalised CDF. A function that is zero everywhere has
//! integral 0; it gets a uniform CDF (as in pbrt) but every pdf it reports is 0, and the
//! 2D distribution never selects such a row because its marginal weight is 0.

use glam::Vec2;

/// Largest f32 below 1, so samples stay in [0, 1).
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// A piecewise-constant density on [0, 1) with `func.len()` equal-width pieces.
#[derive(Debug, Clone)]
pub struct PiecewiseConstant1D {
    func: Vec<f32>,
    cdf: Vec<f32>,
    func_int: f64,
    /// Guide table (the cutpoint method, Chen & Asau 1974; Devroye, "Non-Uniform Random
    /// Variate Generation", §III.2.4): `guide[k]` is the piece [`Self::sample`] returns for
    /// u = k / n, a start for a short forward scan instead of a binary search over the
    /// whole CDF. Expected pieces scanned ≤ 2; the piece found is the same.
    guide: Vec<u32>,
}

impl PiecewiseConstant1D {
    /// Builds the distribution of `func` (non-finite or negative values are treated as 0).
    pub fn new(func: Vec<f32>) -> Self {
        let func: Vec<f32> = func
            .into_iter()
            .map(|f| if f.is_finite() && f > 0.0 { f } else { 0.0 })
            .collect();
        let n = func.len().max(1);
        let mut sums = Vec::with_capacity(n + 1);
        let mut acc = 0.0f64;
        sums.push(0.0f64);
        for &f in &func {
            acc += f as f64 / n as f64;
            sums.push(acc);
        }
        let func_int = acc;
        let cdf = if func_int > 0.0 {
            let mut c: Vec<f32> = sums.iter().map(|s| (s / func_int) as f32).collect();
            if let Some(last) = c.last_mut() {
                *last = 1.0;
            }
            c
        } else {
            (0..=n).map(|i| i as f32 / n as f32).collect()
        };
        let guide = (0..n)
            .map(|k| find_by_search(&cdf, k as f32 / n as f32, n) as u32)
            .collect();
        PiecewiseConstant1D {
            func,
            cdf,
            func_int,
            guide,
        }
    }

    /// The piece of `u`: the largest i with `cdf[i] <= u`, clamped to [0, n − 1] (pbrt's
    /// `FindInterval`; pieces of zero width are never returned unless everything is zero).
    fn find(&self, u: f32) -> usize {
        let n = self.func.len().max(1);
        if !(0.0..1.0).contains(&u) {
            return find_by_search(&self.cdf, u, n);
        }
        // k / n ≤ u, so the guide's piece is at or before u's; scan forward from it.
        let mut i = self.guide[((u * n as f32) as usize).min(n - 1)] as usize;
        // u·n may round up to the next k: step back first.
        while i > 0 && self.cdf[i] > u {
            i -= 1;
        }
        while i + 1 < n && self.cdf[i + 1] <= u {
            i += 1;
        }
        i
    }

    /// Number of pieces.
    pub fn len(&self) -> usize {
        self.func.len()
    }

    /// True if there are no pieces.
    pub fn is_empty(&self) -> bool {
        self.func.is_empty()
    }

    /// ∫₀¹ f(x) dx.
    pub fn integral(&self) -> f64 {
        self.func_int
    }

    /// The density at piece `i` (0 if out of range or the integral is 0).
    pub fn pdf_at(&self, i: usize) -> f32 {
        match self.func.get(i) {
            Some(&f) if self.func_int > 0.0 => (f as f64 / self.func_int) as f32,
            _ => 0.0,
        }
    }

    /// Samples x ∈ [0, 1) for `u` ∈ [0, 1): returns (x, pdf(x), piece index).
    pub fn sample(&self, u: f32) -> (f32, f32, usize) {
        let n = self.func.len().max(1);
        let o = self.find(u);
        let (c0, c1) = (self.cdf[o], self.cdf[o + 1]);
        let mut du = u - c0;
        if c1 > c0 {
            du /= c1 - c0;
        }
        let x = ((o as f32 + du.clamp(0.0, 1.0)) / n as f32).min(ONE_MINUS_EPSILON);
        (x, self.pdf_at(o), o)
    }
}

/// The largest i with `cdf[i] <= u`, clamped to [0, n − 1], by binary search.
fn find_by_search(cdf: &[f32], u: f32, n: usize) -> usize {
    cdf.partition_point(|&c| c <= u)
        .saturating_sub(1)
        .min(n - 1)
}

/// A piecewise-constant density on [0, 1)² over an `nu` × `nv` grid: a marginal over rows
/// (v) and one conditional per row (u), as in pbrt-v4 `PiecewiseConstant2D`.
#[derive(Debug, Clone)]
pub struct PiecewiseConstant2D {
    conditional: Vec<PiecewiseConstant1D>,
    marginal: PiecewiseConstant1D,
}

impl PiecewiseConstant2D {
    /// Builds the distribution of the row-major `func` with `nu` columns and `nv` rows.
    /// Requires `func.len() == nu * nv` (missing entries count as 0).
    pub fn new(func: &[f32], nu: usize, nv: usize) -> Self {
        let conditional: Vec<PiecewiseConstant1D> = (0..nv)
            .map(|v| {
                let row = (0..nu)
                    .map(|u| func.get(v * nu + u).copied().unwrap_or(0.0))
                    .collect();
                PiecewiseConstant1D::new(row)
            })
            .collect();
        let marginal =
            PiecewiseConstant1D::new(conditional.iter().map(|c| c.integral() as f32).collect());
        PiecewiseConstant2D {
            conditional,
            marginal,
        }
    }

    /// ∫∫ f(u, v) du dv.
    pub fn integral(&self) -> f64 {
        self.marginal.integral()
    }

    /// Samples (u, v) ∈ [0, 1)²: `u.y` picks the row, `u.x` the column. Returns the point
    /// and its density with respect to du dv.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (v, pdf_v, row) = self.marginal.sample(u.y);
        match self.conditional.get(row) {
            Some(c) => {
                let (x, pdf_u, _) = c.sample(u.x);
                (Vec2::new(x, v), pdf_u * pdf_v)
            }
            None => (Vec2::new(0.0, v), 0.0),
        }
    }

    /// Density with respect to du dv of the piece at column `iu`, row `iv`.
    pub fn pdf_at(&self, iu: usize, iv: usize) -> f32 {
        let (Some(c), integral) = (self.conditional.get(iv), self.marginal.integral()) else {
            return 0.0;
        };
        if integral <= 0.0 {
            return 0.0;
        }
        match c.func.get(iu) {
            Some(&f) => (f as f64 / integral) as f32,
            None => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rng;

    /// The guide table finds exactly the piece the binary search finds, for functions with
    /// runs of zeros, a single spike and all zeros, at random u, at every k/n and just
    /// below and above it, and outside [0, 1).
    #[test]
    fn guide_table_finds_the_binary_search_piece() {
        let mut rng = Rng::new(&[17]);
        let mut funcs: Vec<Vec<f32>> = vec![vec![0.0; 7], vec![1.0], vec![0.0, 0.0, 5.0, 0.0]];
        for n in [2usize, 3, 10, 64, 1000] {
            funcs.push(
                (0..n)
                    .map(|_| {
                        let r = rng.next_f32();
                        if r < 0.4 {
                            0.0
                        } else {
                            r * r * 10.0
                        }
                    })
                    .collect(),
            );
        }
        let mut spike = vec![0.0f32; 4096];
        spike[1234] = 1e6;
        spike[99] = 1e-3;
        funcs.push(spike);
        for f in funcs {
            let d = PiecewiseConstant1D::new(f);
            let n = d.len().max(1);
            let mut us: Vec<f32> = (0..2000).map(|_| rng.next_f32()).collect();
            for k in 0..=n {
                let c = k as f32 / n as f32;
                us.extend([
                    c,
                    f32::from_bits(c.to_bits().saturating_sub(1)),
                    f32::from_bits(c.to_bits() + 1),
                ]);
            }
            us.extend(d.cdf.iter().copied());
            us.extend([0.0, ONE_MINUS_EPSILON, 1.0, 2.0, -1.0, f32::NAN]);
            for u in us {
                assert_eq!(d.find(u), find_by_search(&d.cdf, u, n), "n {n}, u {u}");
            }
        }
    }
}
