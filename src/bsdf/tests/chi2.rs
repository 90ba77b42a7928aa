//! Pearson χ² goodness-of-fit p-values for the BSDF histograms: the regularised upper
//! incomplete gamma function and the cell-merging rule. Counts are plain f64 sample
//! counts; a p-value is Q(dof/2, χ²/2).

use std::f64::consts::PI;

fn ln_gamma(x: f64) -> f64 {
    // Lanczos (g = 7, n = 9), Numerical Recipes 3rd ed. §6.1.
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Regularised upper incomplete gamma Q(a, x) (Numerical Recipes §6.2: series for
/// x < a + 1, Lentz continued fraction otherwise). χ² p-value = Q(df/2, χ²/2).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let pre = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut ap, mut del) = (a, 1.0 / a);
        let mut sum = del;
        for _ in 0..10_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * pre
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        pre * h
    }
}

#[test]
fn incomplete_gamma_matches_closed_forms() {
    // Q(n, x) = e^{-x} Σ_{k<n} x^k/k! for integer n.
    for &(n, x) in &[
        (1u32, 0.5f64),
        (1, 3.0),
        (3, 2.0),
        (5, 3.0),
        (10, 20.0),
        (40, 30.0),
    ] {
        let mut s = 0.0;
        let mut term = 1.0;
        for k in 0..n {
            if k > 0 {
                term *= x / k as f64;
            }
            s += term;
        }
        let exact = (-x).exp() * s;
        let q = gamma_q(n as f64, x);
        assert!(
            (q - exact).abs() < 1e-9 * exact.max(1e-3),
            "Q({n},{x}) {q} vs {exact}"
        );
    }
}

/// χ² test of observed vs expected counts (plus a "no sample" cell); merges cells with
/// expected < 5 (Mitsuba `ChiSquareTest`). Returns the p-value.
pub(in crate::bsdf) fn chi2_pvalue(obs: &[f64], exp: &[f64]) -> f64 {
    let (mut chi2, mut dof) = (0.0, 0usize);
    let (mut po, mut pe) = (0.0, 0.0);
    for (&o, &e) in obs.iter().zip(exp) {
        if e <= 0.0 {
            assert!(o == 0.0, "{o} samples where the pdf is 0");
            continue;
        }
        if e < 5.0 {
            po += o;
            pe += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if pe > 0.0 {
        chi2 += (po - pe) * (po - pe) / pe;
        dof += 1;
    }
    gamma_q((dof.saturating_sub(1)).max(1) as f64 / 2.0, chi2 / 2.0)
}
