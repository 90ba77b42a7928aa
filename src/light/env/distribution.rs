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
        PiecewiseConstant1D {
            func,
            cdf,
            func_int,
        }
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
        // Largest i with cdf[i] <= u, clamped to [0, n-1] (pbrt's FindInterval); pieces of
        // zero width are therefore never returned unless everything is zero.
        let o = self
            .cdf
            .partition_point(|&c| c <= u)
            .saturating_sub(1)
            .min(n - 1);
        let (c0, c1) = (self.cdf[o], self.cdf[o + 1]);
        let mut du = u - c0;
        if c1 > c0 {
            du /= c1 - c0;
        }
        let x = ((o as f32 + du.clamp(0.0, 1.0)) / n as f32).min(ONE_MINUS_EPSILON);
        (x, self.pdf_at(o), o)
    }
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
