//! The smoothest bounded spectrum with a given linear colour: the fit behind the Smits basis
//! of [`super::upsample`].
//!
//! Problem (Smits 1999, §3): over node values s ∈ [0, 1]^N minimise Σ_j (s_{j+1} − s_j)²
//! subject to R·s = t (three linear colour constraints). Method: solve the equality-
//! constrained problem through its KKT system; while a node leaves [0, 1], pin the worst
//! offender to its bound (one more equality) and solve again. Pinned nodes are never
//! released, so the result is feasible and smooth but not guaranteed to be the exact QP
//! optimum; the colour constraint is met to solver precision (~1e-12), which the tests of
//! `upsample` check.

/// Fits node values; see the module docs. Falls back to the last feasible-in-colour solution
/// clamped to [0, 1] if pinning makes the system singular (never for the sRGB basis colours).
pub(super) fn fit_smooth_spectrum<const N: usize>(r: &[[f64; N]; 3], t: [f64; 3]) -> [f32; N] {
    let mut pinned: Vec<(usize, f64)> = Vec::new();
    let mut best = [0.0f64; N];
    for _ in 0..N {
        let Some(s) = solve_kkt(r, t, &pinned) else {
            break;
        };
        best = s;
        // Worst bound violation beyond a 1e-9 slack.
        let mut worst: Option<(usize, f64, f64)> = None;
        for (j, &v) in s.iter().enumerate() {
            let (excess, bound) = if v < 0.0 { (-v, 0.0) } else { (v - 1.0, 1.0) };
            if excess > 1e-9 && worst.is_none_or(|w| excess > w.1) {
                worst = Some((j, excess, bound));
            }
        }
        match worst {
            Some((j, _, bound)) => pinned.push((j, bound)),
            None => break,
        }
    }
    best.map(|v| v.clamp(0.0, 1.0) as f32)
}

/// Solves min Σ(s_{j+1} − s_j)² s.t. R·s = t and s_j = v for each pinned (j, v), via the
/// KKT system [Q Cᵀ; C 0]·[s; μ] = [0; d] with Q = 2·DᵀD. `None` if singular.
#[allow(clippy::needless_range_loop)] // symmetric fill of a[i][j] and a[j][i] reads best indexed
fn solve_kkt<const N: usize>(
    r: &[[f64; N]; 3],
    t: [f64; 3],
    pinned: &[(usize, f64)],
) -> Option<[f64; N]> {
    let m = 3 + pinned.len();
    let size = N + m;
    let mut a = vec![vec![0.0f64; size + 1]; size];
    // Q = 2·DᵀD for first differences D (tridiagonal 2·[1 −1; −1 1] blocks).
    for j in 0..N - 1 {
        a[j][j] += 2.0;
        a[j + 1][j + 1] += 2.0;
        a[j][j + 1] -= 2.0;
        a[j + 1][j] -= 2.0;
    }
    let mut add_constraint = |row: usize, coeffs: &dyn Fn(usize) -> f64, rhs: f64| {
        for j in 0..N {
            let c = coeffs(j);
            a[N + row][j] = c;
            a[j][N + row] = c;
        }
        a[N + row][size] = rhs;
    };
    for (k, &tk) in t.iter().enumerate() {
        add_constraint(k, &|j| r[k][j], tk);
    }
    for (p, &(idx, v)) in pinned.iter().enumerate() {
        add_constraint(3 + p, &|j| if j == idx { 1.0 } else { 0.0 }, v);
    }
    let x = gauss_solve(a)?;
    let mut s = [0.0f64; N];
    s.copy_from_slice(&x[..N]);
    Some(s)
}

/// Gaussian elimination with partial pivoting on an augmented matrix (n rows, n+1 columns).
fn gauss_solve(mut a: Vec<Vec<f64>>) -> Option<Vec<f64>> {
    let n = a.len();
    for col in 0..n {
        let piv = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-14 {
            return None;
        }
        a.swap(col, piv);
        let pivot_row = a[col].clone();
        for row in a.iter_mut().skip(col + 1) {
            let f = row[col] / pivot_row[col];
            if f != 0.0 {
                for (x, p) in row.iter_mut().zip(&pivot_row).skip(col) {
                    *x -= f * p;
                }
            }
        }
    }
    let mut x = vec![0.0f64; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|j| a[i][j] * x[j]).sum();
        x[i] = (a[i][n] - s) / a[i][i];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_solves_small_system() {
        // 2x + y = 5, x − y = 1 → (2, 1).
        let x = gauss_solve(vec![vec![2.0, 1.0, 5.0], vec![1.0, -1.0, 1.0]]).unwrap();
        assert!((x[0] - 2.0).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12);
        assert!(gauss_solve(vec![vec![1.0, 1.0, 1.0], vec![2.0, 2.0, 2.0]]).is_none());
    }

    #[test]
    fn fit_meets_constraint_and_bounds() {
        // Mean of the first half = 0.9, of the second half = 0.1, total mean free: the
        // smoothest answer ramps between the halves and must be pinned at neither bound.
        const N: usize = 8;
        let mut r = [[0.0f64; N]; 3];
        for j in 0..4 {
            r[0][j] = 0.25;
            r[1][j + 4] = 0.25;
        }
        r[2][0] = 1.0;
        let s = fit_smooth_spectrum(&r, [0.9, 0.1, 0.95]);
        let got: [f64; 3] = [0, 1, 2].map(|k| (0..N).map(|j| r[k][j] * s[j] as f64).sum());
        for (g, w) in got.iter().zip([0.9, 0.1, 0.95]) {
            assert!((g - w).abs() < 1e-6, "{got:?}");
        }
        assert!(s.iter().all(|&v| (0.0..=1.0).contains(&v)), "{s:?}");
        // A target above the reachable maximum (all ones gives 1.0) ends clamped, not NaN.
        let s = fit_smooth_spectrum(&r, [1.5, 0.1, 0.95]);
        assert!(s.iter().all(|&v| (0.0..=1.0).contains(&v)), "{s:?}");
    }
}
