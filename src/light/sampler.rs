//! Choosing one light among a scene's lights ([`LightSampler`]): the one rule that both
//! sides of multiple importance sampling read — next-event estimation picks a light with
//! [`LightSampler::sample`], the MIS weight of a BSDF-sampled hit on a light asks
//! [`LightSampler::pmf`] — and that the Whitted tracer enumerates and photon emission draws
//! from (pbrt-v4's `LightSampler` with `Sample` and `PMF`; Mitsuba 3's
//! `sample_emitter_direction` / `pdf_emitter_direction` pair).
//!
//! The lights chosen among ([`LightId`]) are the punctual lights one by one, the emissive
//! triangles as one group (within which [`super::area::AreaLights`] picks a triangle by
//! power) and the environment. Two rules:
//! - [`Rule::Uniform`]: each light with probability 1/n. Next-event estimation uses it: a
//!   light's total power says little about what it gives one receiver (a studio's
//!   environment carries most of the flux, its key spots most of the light on the stone),
//!   and with the few lights Iris scenes carry the uniform choice costs at most a factor n.
//!   Against choosing by power for NEE on ten scenes (BENCHMARKS.md, "Light choice for
//!   next-event estimation: uniform or by power"), power gains a little on the Cornell box,
//!   the paper's spheres and a many-light scene, is level on the gems, and loses on the
//!   glasses of water and most on the sunglasses under a studio, whose environment takes
//!   the choices its keys should have; uniform's worst case is bounded, power's is not. A many-light tree (pbrt-v4's `BVHLightSampler`) would pay off only with far more
//!   lights than any scene here carries.
//! - [`Rule::Power`]: in proportion to a weight per light (the luminance of its flux, given
//!   by the caller). Photon emission uses it so that every photon carries about the same
//!   flux.
//!
//! Invariants: the probabilities of the lights sum to 1 (up to f32 rounding); a light the
//! sampler never picks has `pmf` 0; `sample` returns exactly the `pmf` of the light it
//! picks.

/// One light the sampler chooses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LightId {
    /// Punctual light `k` of the scene.
    Punctual(u32),
    /// The emissive triangles, as one group.
    Area,
    /// The environment.
    Environment,
}

/// How the sampler weighs the lights.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// Every light with the same probability.
    Uniform,
    /// In proportion to a weight per light (luminance of its flux).
    Power,
}

/// A choice of one light from a fixed list (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct LightSampler {
    rule: Rule,
    /// The lights, in the order `sample` maps [0, 1) onto them.
    lights: Vec<LightId>,
    /// Probability of each light.
    pmf: Vec<f32>,
    /// Cumulative probability (power rule; last entry exactly 1).
    cdf: Vec<f32>,
}

/// A light picked by [`LightSampler::sample`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightChoice {
    /// The light.
    pub light: LightId,
    /// Its position in [`LightSampler::lights`].
    pub index: usize,
    /// The probability that it was picked (its [`LightSampler::pmf`]).
    pub pmf: f32,
    /// The number that picked it, rescaled to [0, 1) within the light's interval: free to
    /// choose within the light (a triangle of the emissive group).
    pub u_rest: f32,
}

impl LightSampler {
    /// Every light of `lights` with probability 1/n.
    pub fn uniform(lights: Vec<LightId>) -> Self {
        let p = if lights.is_empty() {
            0.0
        } else {
            1.0 / lights.len() as f32
        };
        LightSampler {
            rule: Rule::Uniform,
            pmf: vec![p; lights.len()],
            cdf: Vec::new(),
            lights,
        }
    }

    /// Each light of `weighted` in proportion to its weight; lights whose weight is not
    /// finite and positive are left out (never picked, `pmf` 0).
    pub fn by_power(weighted: Vec<(LightId, f32)>) -> Self {
        let kept: Vec<(LightId, f32)> = weighted
            .into_iter()
            .filter(|(_, w)| w.is_finite() && *w > 0.0)
            .collect();
        let total: f64 = kept.iter().map(|(_, w)| *w as f64).sum();
        let (mut cdf, mut pmf) = (Vec::with_capacity(kept.len()), Vec::new());
        let mut acc = 0.0f64;
        for (_, w) in &kept {
            acc += *w as f64;
            cdf.push((acc / total) as f32);
            pmf.push((*w as f64 / total) as f32);
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        LightSampler {
            rule: Rule::Power,
            lights: kept.into_iter().map(|(id, _)| id).collect(),
            pmf,
            cdf,
        }
    }

    /// The rule the sampler follows.
    pub fn rule(&self) -> Rule {
        self.rule
    }

    /// The lights it picks from, in order.
    pub fn lights(&self) -> &[LightId] {
        &self.lights
    }

    /// Whether there is no light to pick.
    pub fn is_empty(&self) -> bool {
        self.lights.is_empty()
    }

    /// Picks a light with the uniform number `u` ∈ [0, 1); `None` without lights.
    pub fn sample(&self, u: f32) -> Option<LightChoice> {
        let n = self.lights.len();
        if n == 0 {
            return None;
        }
        let (k, lo) = match self.rule {
            Rule::Uniform => {
                let k = ((u * n as f32) as usize).min(n - 1);
                (k, k as f32 * self.pmf[k])
            }
            Rule::Power => {
                let k = self.cdf.partition_point(|&c| c <= u).min(n - 1);
                (k, if k == 0 { 0.0 } else { self.cdf[k - 1] })
            }
        };
        let pmf = self.pmf[k];
        Some(LightChoice {
            light: self.lights[k],
            index: k,
            pmf,
            u_rest: ((u - lo) / pmf).clamp(0.0, 1.0 - f32::EPSILON / 2.0),
        })
    }

    /// The probability that [`Self::sample`] picks `light` (0 for a light it never picks).
    pub fn pmf(&self, light: LightId) -> f32 {
        self.lights
            .iter()
            .position(|&l| l == light)
            .map_or(0.0, |k| self.pmf[k])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lights(n: u32) -> Vec<LightId> {
        let mut v: Vec<LightId> = (0..n).map(LightId::Punctual).collect();
        v.push(LightId::Area);
        v.push(LightId::Environment);
        v
    }

    /// Picks with many stratified numbers: the frequency of each light must match its pmf,
    /// and every pick must report the light's own pmf.
    fn check_frequencies(s: &LightSampler) {
        let n = 100_000;
        let mut count = vec![0usize; s.lights().len()];
        for i in 0..n {
            let u = (i as f32 + 0.5) / n as f32;
            let c = s.sample(u).expect("a light");
            assert_eq!(c.pmf, s.pmf(c.light), "{:?}", c.light);
            assert!((0.0..1.0).contains(&c.u_rest), "{}", c.u_rest);
            let k = s.lights().iter().position(|&l| l == c.light).unwrap();
            count[k] += 1;
        }
        let sum: f32 = s.lights().iter().map(|&l| s.pmf(l)).sum();
        assert!((sum - 1.0).abs() < 1e-5, "pmfs sum to {sum}");
        for (k, &l) in s.lights().iter().enumerate() {
            // Stratified numbers: each count is within one of n·pmf.
            let want = s.pmf(l) as f64 * n as f64;
            assert!(
                (count[k] as f64 - want).abs() <= 1.5,
                "{l:?}: {} vs {want}",
                count[k]
            );
        }
    }

    #[test]
    fn uniform_picks_each_light_equally() {
        let s = LightSampler::uniform(lights(5));
        assert_eq!(s.pmf(LightId::Punctual(3)), 1.0 / 7.0);
        assert_eq!(s.pmf(LightId::Punctual(9)), 0.0);
        check_frequencies(&s);
        assert!(LightSampler::uniform(Vec::new()).sample(0.5).is_none());
    }

    #[test]
    fn power_picks_in_proportion_and_leaves_out_dark_lights() {
        let weighted = vec![
            (LightId::Punctual(0), 1.0),
            (LightId::Punctual(1), 0.0),
            (LightId::Punctual(2), 3.0),
            (LightId::Area, f32::NAN),
            (LightId::Environment, 4.0),
        ];
        let s = LightSampler::by_power(weighted);
        assert_eq!(s.lights().len(), 3);
        assert_eq!(s.pmf(LightId::Punctual(1)), 0.0);
        assert_eq!(s.pmf(LightId::Area), 0.0);
        assert!((s.pmf(LightId::Environment) - 0.5).abs() < 1e-7);
        check_frequencies(&s);
    }

    #[test]
    fn the_rest_of_the_number_is_uniform_within_the_light() {
        let s = LightSampler::by_power(vec![(LightId::Area, 1.0), (LightId::Environment, 3.0)]);
        // u = 0.125 is halfway through the first quarter; u = 0.625 halfway through the rest.
        let a = s.sample(0.125).unwrap();
        assert_eq!(a.light, LightId::Area);
        assert!((a.u_rest - 0.5).abs() < 1e-6);
        let e = s.sample(0.625).unwrap();
        assert_eq!(e.light, LightId::Environment);
        assert!((e.u_rest - 0.5).abs() < 1e-6);
    }
}
