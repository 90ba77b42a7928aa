//! One photon pass: what the progressive methods built on passes share (SPPM, the hybrid,
//! VCM/BPT, and the photon budget's pilot that chooses the hybrid's photon count).
//!
//! A render is a sequence of passes p = 0, 1, …; each pass
//! - draws ONE set of wavelengths shared by its photons (or light subpaths) and camera
//!   paths ([`pass_lambda`]: a golden-ratio sequence over passes offset by the seed, as
//!   pbrt-v4 SPPM's per-pass `lambda`), so every gather, connection and merge meets the
//!   same lanes;
//! - gathers within the pass's radius ([`RadiusSequence`]: Knaus & Zwicker 2011's
//!   r²ₚ = r₀² · Πᵢ₌₁..ₚ (i + α)/(i + 1), the first radius from the pixel footprint,
//!   [`first_radius`]), pairing a camera path's lanes with the photons' ([`GatherLanes`],
//!   [`photon_term`]);
//! - is one unit of the progressive driver ([`passes`]: progress, checkpoints, the
//!   observer, the time limit and stop requests between passes are
//!   [`crate::render::drive`]'s).
//!
//! Shards: pass p depends on earlier passes only through the radius, a function of r₀ and
//! p; a shard starting at pass k chooses r₀ as pass 0 of one render does and replays the
//! factors of passes 0..k ([`RadiusSequence::replay`]), so its passes are bit for bit those
//! of one render.
//!
//! Photon paths end by Russian roulette and the delta-bounce cap of
//! [`crate::shading::termination`], as camera paths do.

mod lanes;
mod radius;

pub(in crate::integrator) use lanes::{photon_term, GatherLanes};
pub use radius::{first_radius, pixel_footprint, radius2_factor, RadiusSequence};

use crate::error::Result;
use crate::render::{drive_passes, Film, Observer, Prepass, RenderSettings, RenderStats, Round};
use crate::render::{RoundEnv, Schedule};
use crate::spectrum::Carrier;

/// The hero variate of pass `pass`'s shared wavelengths: a golden-ratio sequence over
/// passes, offset by the seed.
pub fn pass_wavelength_variate(pass: u32, seed: u64) -> f32 {
    let u = (0.5 + pass as f64 * 0.618_033_988_749_895 + (seed % 1024) as f64 * 0.1).fract();
    (u as f32).min(1.0 - f32::EPSILON)
}

/// The wavelengths pass `pass` of a render with seed `seed` shares among its photons and
/// camera paths ([`pass_wavelength_variate`]).
pub fn pass_lambda<C: Carrier>(pass: u32, seed: u64) -> C::Lambda {
    C::sample_lambda(pass_wavelength_variate(pass, seed))
}

/// The pass loop: `step(film, pass, lambda, env)` for each pass of `schedule` (absolute
/// indices, a shard's range) with the pass's wavelengths `lambda` ([`pass_lambda`]), one
/// pass per round of the progressive driver ([`drive_passes`]: progress, checkpoints, the
/// observer, the time limit, stop requests before any round after the first).
pub fn passes<C: Carrier>(
    settings: &RenderSettings,
    schedule: Schedule,
    setup: Prepass,
    observer: Option<Observer>,
    mut step: impl FnMut(&mut Film, u32, C::Lambda, &RoundEnv) -> Result<Round>,
) -> Result<(Film, RenderStats)> {
    drive_passes(settings, schedule, setup, observer, |film, pass, env| {
        step(film, pass, pass_lambda::<C>(pass, settings.seed), env)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The variate is in [0, 1), differs between consecutive passes and seeds, and is a
    /// function of (pass, seed) alone.
    #[test]
    fn the_pass_variate_is_a_function_of_pass_and_seed() {
        for seed in [0u64, 1, 7, 1023, 1024, u64::MAX] {
            for pass in 0..200 {
                let u = pass_wavelength_variate(pass, seed);
                assert!((0.0..1.0).contains(&u), "{u}");
                assert_eq!(u.to_bits(), pass_wavelength_variate(pass, seed).to_bits());
                assert_ne!(u, pass_wavelength_variate(pass + 1, seed));
            }
        }
        assert_eq!(pass_wavelength_variate(0, 0), 0.5);
        assert_ne!(pass_wavelength_variate(3, 1), pass_wavelength_variate(3, 2));
    }
}
