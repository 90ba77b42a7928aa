//! A photon at the smooth surface of a birefringent crystal: the forward twin of the camera
//! path's step (`crate::integrator::path::polarized`'s `crystal_step`), with the same
//! geometry ([`crate::polar::crystal`]) and the same Fresnel model, applied to the photon's
//! Stokes column instead of an analyzer row.
//!
//! From outside the photon reflects with probability R̄ (the unpolarized reflectance at the
//! mean index of the modes that propagate; 1 when none does) or refracts with 1 − R̄ into a
//! mode m chosen with probability w_m / Σw, w_m = (P_m·T_m·S)₀ the power its polarizer P_m
//! passes of the transmitted light ([`crate::polar::modes`], [`Travel::Along`]); inside it
//! refracts out with 1 − R̄ or reflects into either mode, weighted the same way after R. The
//! weight of the step is the true power over its probability, so the photon's expected
//! power is the light's whatever the choices: (M·S)₀ / R̄ for a reflection outside or a
//! refraction out, Σw / (1 − R̄) into a mode, Σw / R̄ for an internal reflection. Photons
//! carry flux (importance transport): no 1/η² on refraction (pbrt-v4 §9.5.2).
//!
//! Frames: world space; `light.k` is the photon's direction outside and its mode's wave
//! normal inside, where the photon moves along the mode's ray direction (the walk-off).

use crate::polar::crystal::{Indicatrix, Mode};
use crate::polar::fresnel;
use crate::polar::interface::{meet, Inside, Meeting, Outside};
use crate::polar::modes::{along_ray, choose, split, Chosen, InMode, Travel};
use crate::polar::stokes::{mul, Light, Mueller};
use crate::shading::polarized::s_basis;
use glam::Vec3;

/// What a photon's bounce at a crystal surface gives.
#[derive(Debug, Clone, Copy)]
pub(super) struct Step {
    /// The photon's new direction of motion (world, unit).
    pub dir: Vec3,
    /// The mode it travels in, `None` outside the crystal.
    pub inside: Option<InMode>,
    /// Whether it crossed the surface.
    pub crossed: bool,
    /// Its light after the bounce (s₀ = 1).
    pub light: Light,
    /// The factor on its power: the true power over the choice's probability.
    pub weight: f32,
}

/// The mode of a photon met inside the crystal in none, moving along the ray `d` (its
/// light is inside, or it left a surface inside that is not the crystal's): chosen with
/// `u` by the power each mode's polarizer passes of its light ([`along_ray`]); with the
/// light in that mode and the factor on its power (the true power over the choice's
/// probability: Σw, the light's s₀ = 1 shared between the two orthogonal modes). `None`
/// when nothing passes.
pub(super) fn start(
    c: &Indicatrix,
    d: Vec3,
    light: &Light,
    u: f32,
) -> Option<(InMode, Light, f32)> {
    let s = light.x;
    let chosen = along_ray(c, d, (&light.in_basis(s), s), Travel::Along, u)?;
    let ((which, mode, (v, _), total), x) = chosen;
    let (light, _) = Light::normalized(v, x, mode.k)?;
    let inside = InMode {
        which,
        k: mode.k,
        d: mode.d,
    };
    Some((inside, light, total))
}

/// The bounce of a photon moving along `d` at a crystal surface with outward unit normal
/// `n`, `n_out` the index outside, in mode `state` (`None`: arriving from outside), with
/// `light`, choosing with `u` (reflect or refract; which mode). `None` when it ends.
pub(super) fn bounce(
    c: &Indicatrix,
    (n, n_out): (Vec3, f32),
    d: Vec3,
    state: Option<InMode>,
    light: &Light,
    u: (f32, f32),
) -> Option<Step> {
    match meet(c, (n, n_out), d, state)? {
        Meeting::Inside(inside) => from_inside(&inside, (n, n_out), state?.k, light, u),
        Meeting::Outside(outside) => from_outside(&outside, (n, n_out), d, light, u),
    }
}

/// The photon arrives from outside: it reflects, or refracts into a mode.
fn from_outside(
    o: &Outside,
    (n, n1): (Vec3, f32),
    d: Vec3,
    light: &Light,
    u: (f32, f32),
) -> Option<Step> {
    let s = s_basis(d, n, light.x);
    if u.0 < o.r_mean {
        let (r, _) = fresnel::dielectric(o.cos1, o.n_reflect / n1);
        return leave(light, (&r, s), o.reflected, (false, o.r_mean));
    }
    let v = light.in_basis(s);
    let through = |mode: &Mode| {
        let (_, t_m) = fresnel::dielectric(o.cos1, mode.n / n1);
        mul(&t_m, &v)
    };
    let chosen = choose(&split(o.modes, through, s, Travel::Along), u.1)?;
    into_mode(chosen, 1.0 - o.r_mean, s, true)
}

/// The photon inside along the wave normal `k` meets the surface: it refracts out, or
/// reflects into either mode.
fn from_inside(
    i: &Inside,
    (n, n2): (Vec3, f32),
    k: Vec3,
    light: &Light,
    u: (f32, f32),
) -> Option<Step> {
    let (r, tm) = fresnel::dielectric(i.cos_k, n2 / i.n_mode);
    let s = s_basis(k, n, light.x);
    if let (Some(dir), true) = (i.out, u.0 >= i.r_mean) {
        return leave(light, (&tm, s), dir, (true, 1.0 - i.r_mean));
    }
    let v = mul(&r, &light.in_basis(s));
    let chosen = choose(&split(i.reflected, |_| v, s, Travel::Along), u.1)?;
    into_mode(chosen, i.r_mean, s, false)
}

/// The step out along `dir` (a reflection outside or a refraction out) through the Mueller
/// matrix `m` in the basis `s`, whose event had probability `p`; `crossed` as in [`Step`].
fn leave(
    light: &Light,
    (m, s): (&Mueller, Vec3),
    dir: Vec3,
    (crossed, p): (bool, f32),
) -> Option<Step> {
    let (light, f) = light.after(m, s, s, dir)?;
    Some(Step {
        dir,
        inside: None,
        crossed,
        light,
        weight: f / p,
    })
}

/// The step into the `chosen` mode, whose interface event had probability `p_interface`:
/// the light becomes the projected one, in the basis `s` ⊥ the mode's wave normal.
fn into_mode(
    (which, mode, (projected, _), total): Chosen,
    p_interface: f32,
    s: Vec3,
    crossed: bool,
) -> Option<Step> {
    let (light, _) = Light::normalized(projected, s, mode.k)?;
    Some(Step {
        dir: mode.ray,
        inside: Some(InMode {
            which,
            k: mode.k,
            d: mode.d,
        }),
        crossed,
        light,
        weight: total / p_interface,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::fresnel_dielectric;
    use crate::polar::crystal::{calcite, Which};

    /// The expected power a photon carries into the crystal, over many choices, is the
    /// unpolarized transmittance split between the modes; into each mode it is half of
    /// it (for unpolarized light at near-normal incidence) within the Fresnel model's
    /// difference between the modes' indices.
    #[test]
    fn unpolarized_photons_split_between_the_modes_by_power() {
        let c = calcite();
        let n = Vec3::X;
        let d = Vec3::new(-1.0, 0.1, 0.3).normalize();
        let light = Light::unpolarized(d);
        let (mut into, mut refl) = ([0.0f64; 2], 0.0f64);
        let m = 4000;
        for i in 0..m {
            for j in 0..m / 100 {
                let u = (
                    (i as f32 + 0.5) / m as f32,
                    (j as f32 + 0.5) / (m / 100) as f32,
                );
                let Some(step) = bounce(&c, (n, 1.0), d, None, &light, u) else {
                    continue;
                };
                let w = f64::from(step.weight) / f64::from(m * (m / 100));
                match step.inside {
                    Some(mode) => into[usize::from(mode.which == Which::Fast)] += w,
                    None => refl += w,
                }
            }
        }
        let cos1 = -d.dot(n);
        let r_o = f64::from(fresnel_dielectric(cos1, 1.6584));
        let r_e = f64::from(fresnel_dielectric(cos1, 1.4864));
        // Each mode receives half the light times its own transmittance (±2 % for the
        // isotropic amplitudes with the mode's index against the mean).
        let expect = [0.5 * (1.0 - r_o), 0.5 * (1.0 - r_e)];
        for (got, want) in into.iter().zip(expect) {
            assert!((got / want - 1.0).abs() < 0.02, "{into:?} vs {expect:?}");
        }
        assert!(
            (refl + into[0] + into[1] - 1.0).abs() < 0.01,
            "{refl} + {into:?}"
        );
    }

    #[test]
    fn a_mode_inside_leaves_fully_polarized_and_keeps_its_power_or_reflects() {
        let c = calcite();
        let n = Vec3::Z;
        let k = Vec3::new(0.2, 0.1, 1.0).normalize();
        let mode = c.mode(k, Which::Slow);
        let inside = InMode {
            which: Which::Slow,
            k: mode.k,
            d: mode.d,
        };
        let x = mode.d;
        let light = Light {
            s: [1.0, 1.0, 0.0, 0.0],
            x,
            k: mode.k,
        };
        let out = bounce(&c, (n, 1.0), mode.ray, Some(inside), &light, (0.99, 0.5)).unwrap();
        assert!(out.crossed && out.inside.is_none());
        let dop = crate::polar::stokes::degree(&out.light.s);
        assert!((dop - 1.0).abs() < 1e-3, "{dop}");
        let back = bounce(&c, (n, 1.0), mode.ray, Some(inside), &light, (0.0, 0.5)).unwrap();
        assert!(!back.crossed && back.inside.is_some() && back.dir.z < 0.0);
    }
}
