//! Spectral MIS at rough dispersive dielectrics (Wilkie, Nawaz, Droske, Weidlich, Hanika
//! 2014, "Hero Wavelength Spectral Sampling", EGSR, §4): instead of keeping only the hero
//! wavelength (pbrt-v4 `TerminateSecondary`), a path crossing a rough (GGX) interface whose
//! index depends on λ keeps its 4 lanes. The direction is sampled with the hero's η; lane i
//! is weighted by f_i(wo, wi)·|cos θi| / p_mix, where
//!
//!   p_mix = Σ_j w_j · p_j(wo, wi)
//!
//! is the density of the direction marginalised over which lane is the hero: p_j is the
//! BSDF pdf with lane j's η and w_j ([`Lambdas::hero_weight`](crate::spectrum::Lambdas))
//! the probability that lane j is the hero given the path so far. The lanes are rotations
//! of the hero's sample number by j/4, so a priori each lane is the hero with probability
//! 1/4 and the first such vertex divides by the lane average Σ_j p_j / 4 (the balance
//! heuristic over wavelengths); after it, w_j ← w_j p_j / p_mix (Bayes), which makes the
//! product of the per-vertex factors equal Wilkie et al.'s path-level weight
//! f_i(x̄) / (Σ_j P_j(x̄) / 4) (P_j: the path's density with hero j). pbrt-v4 does the same
//! bookkeeping for chromatic media (`VolPathIntegrator`, `r_u`), not at surfaces.
//!
//! Next-event estimation: the light sample's f is per lane and its MIS weight against BSDF
//! sampling uses p_mix as the BSDF pdf, the same density the BSDF-sampling side records for
//! the emission it finds, so the two strategies' weights still sum to 1 for every lane.
//!
//! A later smooth dispersive interface keeps the hero with the factor 1/w_0
//! ([`Carrier::keep_hero`]). Spectral transport only: RGB paths never get lane indices.
//! Directions are in the local shading frame ([`crate::bsdf`]).

use super::material_bsdf::sample_bsdf;
use crate::bsdf::{Bsdf, BsdfSample, TransportMode};
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

/// Per lane j: f_j(wo, wi) (lane j of the BSDF with η = `etas[j]`) and p_j(wo, wi).
pub fn eval_lanes<C: Carrier>(
    bsdf: &Bsdf<C>,
    etas: &[f32; 4],
    wo: Vec3,
    wi: Vec3,
    mode: TransportMode,
) -> (C, [f32; 4]) {
    let mut f = [0.0; 4];
    let mut p = [0.0; 4];
    for j in 0..4 {
        // The BSDF with lane j's η in place of the hero's (only interfaces carry an η).
        let b = bsdf.with_lane(etas[j], 0).unwrap_or(*bsdf);
        f[j] = b.eval(wo, wi, mode).to_lanes()[j];
        p[j] = b.pdf(wo, wi, mode);
    }
    (C::from_lanes(f), p)
}

/// p_mix = Σ_j w_j p_j: the direction's density with the hero unknown.
pub fn mixture_pdf(w: &[f32; 4], p: &[f32; 4]) -> f32 {
    w.iter().zip(p).map(|(w, p)| w * p).sum()
}

/// f (per lane) and p_mix for a direction `wi` (next-event estimation).
pub fn eval<C: Carrier>(
    bsdf: &Bsdf<C>,
    etas: &[f32; 4],
    wo: Vec3,
    wi: Vec3,
    mode: TransportMode,
    lambda: &C::Lambda,
) -> (C, f32) {
    let (f, p) = eval_lanes(bsdf, etas, wo, wi, mode);
    (f, mixture_pdf(&C::hero_weight(lambda), &p))
}

/// Samples the direction with the hero's η (`bsdf`), returns f per lane and p_mix as the
/// sample's `f` and `pdf`, and updates the hero weights in `lambda` to the posterior
/// w_j p_j / p_mix. `None` when there is no usable sample.
pub fn sample<C: Carrier>(
    bsdf: &Bsdf<C>,
    etas: &[f32; 4],
    wo: Vec3,
    uc: f32,
    u: Vec2,
    mode: TransportMode,
    lambda: &mut C::Lambda,
) -> Option<BsdfSample<C>> {
    let bs = sample_bsdf(bsdf, wo, uc, u, mode)?;
    let (f, p) = eval_lanes(bsdf, etas, wo, bs.wi, mode);
    let w = C::hero_weight(lambda);
    let mix = mixture_pdf(&w, &p);
    if !(mix > 0.0 && mix.is_finite() && f.is_finite()) {
        return None;
    }
    C::set_hero_weight(lambda, std::array::from_fn(|j| w[j] * p[j] / mix));
    Some(BsdfSample { f, pdf: mix, ..bs })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{Lambdas, SampledSpectrum, SampledWavelengths};

    /// With equal indices in every lane the MIS sample is the plain sample (f and pdf), and
    /// the hero weights stay uniform.
    #[test]
    fn equal_indices_change_nothing() {
        let b = Bsdf::Dielectric {
            eta: 1.5,
            alpha: 0.09,
            tint: SampledSpectrum::one(),
        };
        let mut l = Lambdas::new(SampledWavelengths::sample_uniform(0.3));
        let wo = Vec3::new(0.3, 0.1, 0.9).normalize();
        for k in 0..64 {
            let (uc, u) = (
                (k as f32 + 0.5) / 64.0,
                Vec2::new(0.37, (k as f32 * 0.618) % 1.0),
            );
            let plain = sample_bsdf(&b, wo, uc, u, TransportMode::Radiance);
            let mis = sample(&b, &[1.5; 4], wo, uc, u, TransportMode::Radiance, &mut l);
            assert_eq!(plain.is_some(), mis.is_some());
            if let (Some(a), Some(m)) = (plain, mis) {
                assert!((a.pdf - m.pdf).abs() <= 1e-5 * a.pdf, "{a:?} {m:?}");
                assert_eq!(a.f, m.f);
                assert_eq!(a.wi, m.wi);
            }
            for w in l.hero_weight {
                assert!((w - 0.25).abs() < 1e-5, "{:?}", l.hero_weight);
            }
        }
    }

    /// The posterior weights sum to 1 and favour lanes whose η makes the sampled direction
    /// likely; lane 0 (the hero) keeps a positive weight.
    #[test]
    fn posterior_sums_to_one() {
        let b = Bsdf::Dielectric {
            eta: 1.5,
            alpha: 0.09,
            tint: SampledSpectrum::one(),
        };
        let etas = [1.5, 1.6, 1.7, 1.45];
        let wo = Vec3::new(0.5, 0.0, 0.8).normalize();
        let mut l = Lambdas::new(SampledWavelengths::sample_uniform(0.3));
        let mut n = 0;
        for k in 0..64 {
            let (uc, u) = (0.99, Vec2::new((k as f32 + 0.5) / 64.0, 0.3));
            let mut lk = l;
            if sample(&b, &etas, wo, uc, u, TransportMode::Radiance, &mut lk).is_some() {
                let s: f32 = lk.hero_weight.iter().sum();
                assert!((s - 1.0).abs() < 1e-5, "{:?}", lk.hero_weight);
                assert!(lk.hero_weight[0] > 0.0);
                n += 1;
            }
        }
        assert!(n > 32);
        l.hero_weight = [1.0, 0.0, 0.0, 0.0];
        let _ = l;
    }
}
