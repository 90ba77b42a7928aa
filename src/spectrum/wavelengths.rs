//! Hero-wavelength sampling: four wavelengths per camera path (Wilkie et al. 2014,
//! "Hero Wavelength Spectral Sampling"; pbrt-v4 `SampledWavelengths`).
//!
//! Units: λ in nm, pdf in 1/nm. Invariants: every λ lies in [360, 830]; lane 0 is the hero
//! wavelength; lanes 1–3 are the hero's sample `u` rotated by 1/4, 2/4, 3/4 of the unit
//! interval, so the four lanes stratify the visible range. After
//! [`SampledWavelengths::terminate_secondary`] only lane 0 carries weight (pdf of lanes 1–3
//! is 0 and lane 0's pdf is divided by 4), which keeps the estimator of
//! [`super::SampledSpectrum::to_xyz`] unbiased because that estimator averages over all
//! four lanes.

use super::{SampledSpectrum, LAMBDA_MAX, LAMBDA_MIN, N_LAMBDA};

/// The four wavelengths of a path and their sampling densities. A density is evaluated
/// when it is asked for ([`SampledWavelengths::lane_pdf`]), not when the wavelengths are
/// drawn: the film skips lanes that carry no radiance, so most of them are never needed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampledWavelengths {
    lambda: [f32; N_LAMBDA],
    density: Density,
    /// [`SampledWavelengths::terminate_secondary`] has been applied.
    terminated: bool,
}

/// Which density the wavelengths were drawn from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Density {
    /// [`visible_wavelength_pdf`].
    Visible,
    /// Uniform over 360–830 nm.
    Uniform,
}

/// Density of [`sample_visible_wavelength`] in 1/nm (0 outside 360–830 nm).
/// p(λ) = 0.0039398042 / cosh²(0.0072 (λ − 538)) (pbrt-v4 `VisibleWavelengthsPDF`, a fit to
/// the shape of ȳ that integrates to 1 over 360–830 nm within 1e-5).
pub fn visible_wavelength_pdf(lambda: f32) -> f32 {
    if lambda.is_nan() || !(LAMBDA_MIN..=LAMBDA_MAX).contains(&lambda) {
        return 0.0;
    }
    // cosh via exp in f32: |x| ≤ 2.3 here, so no overflow, and f32 keeps ~1e-7 relative.
    let e = (0.0072 * (lambda - 538.0)).exp();
    let c = 0.5 * (e + 1.0 / e);
    0.003_939_804 / (c * c)
}

/// Inverse CDF of [`visible_wavelength_pdf`]: λ = 538 − 138.888889·atanh(0.85691062 −
/// 1.82750197u) for u in [0, 1) (pbrt-v4 `SampleVisibleWavelengths`), clamped to 360–830 nm
/// against rounding.
pub fn sample_visible_wavelength(u: f32) -> f32 {
    // atanh(y) = ½·ln((1 + y)/(1 − y)), in f32 (|y| ≤ 0.97 for u in [0, 1)).
    let y = 0.856_910_62 - 1.827_502 * u;
    let l = 538.0 - 138.888_89 * 0.5 * ((1.0 + y) / (1.0 - y)).ln();
    if l.is_nan() {
        return LAMBDA_MIN;
    }
    l.clamp(LAMBDA_MIN, LAMBDA_MAX)
}

/// The hero-wavelength number `u` of [`SampledWavelengths::sample_visible`] from a 2D
/// sample `(offset, member)`: `u = (offset + ⌊N·member⌋)/N` with N = [`N_LAMBDA`]. The
/// wavelengths a sample carries, `u + i/N` mod 1, depend only on `u mod 1/N`, which is
/// `offset/N`: a stratified `offset` spreads the sets of a pixel's samples evenly, while
/// `member` picks which of them is the hero (the one a dispersive path keeps), so with a
/// (0, m, 2)-net the heroes are stratified over [0, 1) too. A 1D number `u` directly would
/// stratify the heroes but let two samples whose `u` differ by about a multiple of 1/N carry
/// the same wavelengths (more colour noise than the golden-ratio lattice on a uniform
/// environment at low sample counts: BENCHMARKS.md, "Figures behind choices in the code").
pub fn hero_number(offset: f32, member: f32) -> f32 {
    let n = N_LAMBDA as f32;
    let m = (member * n).floor().clamp(0.0, n - 1.0);
    ((offset + m) / n).min(1.0 - f32::EPSILON)
}

impl SampledWavelengths {
    /// Importance-samples the visible range: hero λ from `u` in [0, 1), companions from
    /// `u + i/4` wrapped to [0, 1) (pbrt-v4 `SampleVisible`).
    pub fn sample_visible(u: f32) -> Self {
        let mut lambda = [0.0; N_LAMBDA];
        for (i, l) in lambda.iter_mut().enumerate() {
            let mut up = u + i as f32 / N_LAMBDA as f32;
            if up >= 1.0 {
                up -= 1.0;
            }
            *l = sample_visible_wavelength(up);
        }
        SampledWavelengths {
            lambda,
            density: Density::Visible,
            terminated: false,
        }
    }

    /// Uniform sampling of 360–830 nm with the same rotation (pdf = 1/470 nm); for tests and
    /// for spectra whose shape is unknown (pbrt-v4 `SampleUniform`).
    pub fn sample_uniform(u: f32) -> Self {
        let range = LAMBDA_MAX - LAMBDA_MIN;
        let mut lambda = [0.0; N_LAMBDA];
        for (i, l) in lambda.iter_mut().enumerate() {
            let mut up = u + i as f32 / N_LAMBDA as f32;
            if up >= 1.0 {
                up -= 1.0;
            }
            *l = (LAMBDA_MIN + up * range).clamp(LAMBDA_MIN, LAMBDA_MAX);
        }
        SampledWavelengths {
            lambda,
            density: Density::Uniform,
            terminated: false,
        }
    }

    /// The four wavelengths in nm; lane 0 is the hero.
    pub fn lambdas(&self) -> [f32; N_LAMBDA] {
        self.lambda
    }

    /// Wavelength of lane `i` in nm. Panics if `i >= 4` (a programming error, not user input).
    pub fn lambda(&self, i: usize) -> f32 {
        self.lambda[i]
    }

    /// The hero wavelength (lane 0) in nm.
    pub fn hero(&self) -> f32 {
        self.lambda[0]
    }

    /// The per-lane sampling densities in 1/nm (0 for terminated lanes).
    pub fn pdf(&self) -> SampledSpectrum {
        SampledSpectrum::new(std::array::from_fn(|i| self.lane_pdf(i)))
    }

    /// The sampling density of lane `i` in 1/nm: the density at its wavelength, 0 for a
    /// terminated companion, and a quarter of it for the hero after
    /// [`Self::terminate_secondary`]. Panics if `i >= 4` (a programming error).
    pub fn lane_pdf(&self, i: usize) -> f32 {
        if self.terminated && i > 0 {
            return 0.0;
        }
        let p = match self.density {
            Density::Visible => visible_wavelength_pdf(self.lambda[i]),
            Density::Uniform => 1.0 / (LAMBDA_MAX - LAMBDA_MIN),
        };
        if self.terminated {
            p / N_LAMBDA as f32
        } else {
            p
        }
    }

    /// Keeps only the hero wavelength: lanes 1–3 get pdf 0 and lane 0's pdf is divided by 4
    /// (pbrt-v4 `TerminateSecondary`). Call at a dispersive interface, before using λ₀'s IOR.
    /// Idempotent.
    pub fn terminate_secondary(&mut self) {
        self.terminated = true;
    }

    /// The same wavelengths with lane `k` first: lane j of the result is lane (j + k) mod 4
    /// of `self`, with its density. A path split into its wavelengths continues lane `k`
    /// as the hero of its own sub-path (`crate::integrator::path`). Panics if `k >= 4` (a
    /// programming error).
    pub fn rotated(&self, k: usize) -> Self {
        assert!(k < N_LAMBDA, "lane {k}");
        SampledWavelengths {
            lambda: rotate_lanes(self.lambda, k),
            ..*self
        }
    }

    /// Whether [`Self::terminate_secondary`] has been applied (all companion pdfs are 0).
    pub fn is_secondary_terminated(&self) -> bool {
        self.terminated
    }
}

/// Per-lane values with lane `k` first: lane j of the result is lane (j + k) mod 4 of `v`
/// (the order of a sub-path that carries lane `k` as its hero,
/// [`SampledWavelengths::rotated`]).
pub fn rotate_lanes<T: Copy>(v: [T; N_LAMBDA], k: usize) -> [T; N_LAMBDA] {
    std::array::from_fn(|j| v[(j + k) % N_LAMBDA])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pdf_integrates_to_one() {
        // Midpoint rule at 0.01 nm: discretisation error ~1e-9; measured |∫p − 1| = 6e-9.
        let n = 47_000;
        let h = (LAMBDA_MAX - LAMBDA_MIN) as f64 / n as f64;
        let s: f64 = (0..n)
            .map(|i| visible_wavelength_pdf(LAMBDA_MIN + ((i as f64 + 0.5) * h) as f32) as f64 * h)
            .sum();
        assert!((s - 1.0).abs() < 1e-5, "∫p = {s}");
    }

    #[test]
    fn inverse_cdf_matches_pdf_chi2() {
        // 1e5 stratified-free samples from a fixed LCG, 47 bins of 10 nm; expected counts from
        // the integrated pdf. χ² with 46 dof: the 99.9 % quantile is 81.4.
        let n = 100_000u32;
        let bins = 47usize;
        let mut counts = vec![0u32; bins];
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..n {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            let u = (state >> 40) as f32 / (1u64 << 24) as f32;
            let l = sample_visible_wavelength(u);
            assert!((LAMBDA_MIN..=LAMBDA_MAX).contains(&l), "{l}");
            let b = (((l - LAMBDA_MIN) / 10.0) as usize).min(bins - 1);
            counts[b] += 1;
        }
        let mut chi2 = 0.0f64;
        for (b, &c) in counts.iter().enumerate() {
            let lo = LAMBDA_MIN as f64 + 10.0 * b as f64;
            let p: f64 = (0..100)
                .map(|k| visible_wavelength_pdf((lo + 0.1 * (k as f64 + 0.5)) as f32) as f64 * 0.1)
                .sum();
            let e = p * n as f64;
            chi2 += (c as f64 - e).powi(2) / e;
        }
        assert!(chi2 < 81.4, "χ² = {chi2}, counts {counts:?}");
    }

    #[test]
    fn companions_are_rotated_and_in_range() {
        for k in 0..1000 {
            let u = k as f32 / 1000.0;
            let w = SampledWavelengths::sample_visible(u);
            for i in 0..N_LAMBDA {
                let mut up = u + i as f32 / 4.0;
                if up >= 1.0 {
                    up -= 1.0;
                }
                assert_eq!(w.lambda(i), sample_visible_wavelength(up));
                assert!((LAMBDA_MIN..=LAMBDA_MAX).contains(&w.lambda(i)));
                assert!(w.pdf()[i] > 0.0);
            }
        }
        assert!((sample_visible_wavelength(0.0) - 360.0).abs() < 0.1);
        assert!((sample_visible_wavelength(0.999_999) - 830.0).abs() < 0.5);
    }

    /// The densities, evaluated when asked for, are the bits of evaluating them when the
    /// wavelengths are drawn (the density at each λ; 1/470 nm uniform; 0 for terminated
    /// companions and the hero's divided by 4).
    #[test]
    fn lazy_pdf_equals_eager() {
        for k in 0..4096 {
            let u = k as f32 / 4096.0;
            for uniform in [false, true] {
                let mut w = if uniform {
                    SampledWavelengths::sample_uniform(u)
                } else {
                    SampledWavelengths::sample_visible(u)
                };
                let eager = w.lambdas().map(|l| {
                    if uniform {
                        1.0 / (LAMBDA_MAX - LAMBDA_MIN)
                    } else {
                        visible_wavelength_pdf(l)
                    }
                });
                assert_eq!(w.pdf().values().map(f32::to_bits), eager.map(f32::to_bits));
                w.terminate_secondary();
                let hero = eager[0] / N_LAMBDA as f32;
                let want = [hero, 0.0, 0.0, 0.0].map(f32::to_bits);
                assert_eq!(w.pdf().values().map(f32::to_bits), want, "u {u}");
            }
        }
    }

    #[test]
    fn rotation_moves_lanes_with_their_densities() {
        for uniform in [false, true] {
            let w = if uniform {
                SampledWavelengths::sample_uniform(0.37)
            } else {
                SampledWavelengths::sample_visible(0.37)
            };
            for k in 0..N_LAMBDA {
                let r = w.rotated(k);
                for j in 0..N_LAMBDA {
                    let i = (j + k) % N_LAMBDA;
                    assert_eq!(r.lambda(j), w.lambda(i));
                    assert_eq!(r.lane_pdf(j).to_bits(), w.lane_pdf(i).to_bits());
                }
            }
            assert_eq!(w.rotated(0), w);
        }
    }

    #[test]
    fn terminate_secondary_keeps_hero() {
        let mut w = SampledWavelengths::sample_visible(0.3);
        let p0 = w.pdf()[0];
        assert!(!w.is_secondary_terminated());
        w.terminate_secondary();
        assert!(w.is_secondary_terminated());
        assert_eq!(w.pdf()[0], p0 / 4.0);
        assert_eq!(&w.pdf().values()[1..], &[0.0; 3]);
        w.terminate_secondary();
        assert_eq!(w.pdf()[0], p0 / 4.0, "idempotent");
    }
}
