//! Probes of how light moves through a scene, for the render plan's `--method auto`
//! ([`crate::plan::resolve_method`]): fixed seeds, so the plan and the render always agree.
//!
//! - [`has_caustic_paths`]: does any light reach a diffuse-like surface through specular
//!   bounces only?
//! - [`volume_caustic_share`]: how much of the light scattered in media arrives there
//!   through specular bounces (a beam through a prism into haze, a lamp behind a glass);
//! - [`kept_share`]: how much of the light a diffuse bounce keeps in the scene (an enclosed
//!   room keeps its albedo's worth, a stone on a studio floor loses nearly all of it to the
//!   open sky).
//!
//! Units: shares of luminance (Rec. 709 Y of the photons' RGB power), dimensionless.

use super::emit::{PhotonEmitter, PhotonNumbers, DEFAULT_AIM};
use super::trace::{trace, trace_in_media, Roulette, TraceSettings};
use crate::math::Rng;
use crate::photon::aim::Aim;
use crate::scene::Scene;
use glam::Vec3;
use std::ops::ControlFlow;

/// Whether, among `n` photons from the lights (fixed seed, RGB, emitted as the renderers
/// emit them: Halton numbers, aimed at the caustic makers with [`DEFAULT_AIM`]), at least
/// one reaches a diffuse-like surface after specular bounces only.
pub fn has_caustic_paths(scene: &Scene, emitter: &PhotonEmitter, n: u32) -> bool {
    let settings = TraceSettings {
        max_depth: 8,
        roulette: Roulette::Throughput,
    };
    let numbers = PhotonNumbers::new(0xCA05_71C5);
    (0..n).any(|i| {
        let mut rng = Rng::new(&[0xCA05_71C5, i as u64]);
        let Some(ph) = emitter.emit_index(scene, &numbers, i as u64, DEFAULT_AIM) else {
            return false;
        };
        let mut found = false;
        trace::<Vec3>(scene, &ph, (), &settings, &mut rng, |v, _| {
            found |= v.caustic && v.power != Vec3::ZERO;
        });
        found
    })
}

/// Of the power `n` photons (fixed seed, RGB, emitted as the lights emit, unaimed) bring to
/// their first non-delta hit, the share that arrives at a second non-delta hit: the
/// scene's mean albedo times the chance that light leaving a lit surface meets another one,
/// in [0, 1] up to the noise of `n` photons (Russian roulette keeps the expectation). 0 when
/// no photon reaches a non-delta surface.
///
/// A closed room returns about its albedo (the McGuire Cornell box: ≈ 0.5); an object on a
/// floor under open lights returns a few per cent: where most of the light that reaches the
/// camera has bounced before, light subpaths reach it more cheaply than the camera's own
/// (BENCHMARKS.md "Choosing VCM and BPT").
pub fn kept_share(scene: &Scene, emitter: &PhotonEmitter, n: u32) -> f64 {
    let settings = TraceSettings {
        max_depth: 2,
        roulette: Roulette::Throughput,
    };
    const KEY: u64 = 0x6E7C_105E;
    let numbers = PhotonNumbers::new(KEY);
    let (mut first, mut second) = (0.0f64, 0.0f64);
    for i in 0..n {
        let mut rng = Rng::new(&[KEY, u64::from(i)]);
        let Some(ph) = emitter.emit_index(scene, &numbers, u64::from(i), Aim::Off) else {
            continue;
        };
        let mut k = 0;
        trace::<Vec3>(scene, &ph, (), &settings, &mut rng, |v, _| {
            let y = f64::from(crate::light::env::luminance(v.power));
            if y.is_finite() {
                match k {
                    0 => first += y,
                    1 => second += y,
                    _ => {}
                }
            }
            k += 1;
        });
    }
    if first > 0.0 {
        second / first
    } else {
        0.0
    }
}

/// Of the power `n` photons (fixed seed, RGB, emitted as the hybrid emits them, aimed at
/// the caustic makers with [`DEFAULT_AIM`]) scatter at their first event in a medium, the
/// share that got there through ≥ 1 specular bounce (L S+ M), in [0, 1]; 0 when no photon
/// scatters in a medium. The path tracer reaches such light only when a phase-sampled ray
/// happens to find the light through the glass (never for a point light); the hybrid's
/// volumetric caustic map carries it ([`crate::integrator::volume_map`]).
pub fn volume_caustic_share(scene: &Scene, emitter: &PhotonEmitter, n: u32) -> f64 {
    let settings = TraceSettings {
        max_depth: 8,
        roulette: Roulette::Throughput,
    };
    const KEY: u64 = 0x7015_CA05;
    let numbers = PhotonNumbers::new(KEY);
    let (mut all, mut caustic) = (0.0f64, 0.0f64);
    for i in 0..n {
        let mut rng = Rng::new(&[KEY, u64::from(i)]);
        let Some(ph) = emitter.emit_index(scene, &numbers, u64::from(i), DEFAULT_AIM) else {
            continue;
        };
        let mut first = true;
        trace_in_media::<Vec3>(
            scene,
            &ph,
            (),
            &settings,
            &mut rng,
            |_, _| ControlFlow::Continue(()),
            |v, power, _| {
                if std::mem::take(&mut first) {
                    let y = f64::from(crate::light::env::luminance(power));
                    if y.is_finite() {
                        all += y;
                        if v.caustic {
                            caustic += y;
                        }
                    }
                }
                ControlFlow::Continue(())
            },
        );
    }
    if all > 0.0 {
        caustic / all
    } else {
        0.0
    }
}
