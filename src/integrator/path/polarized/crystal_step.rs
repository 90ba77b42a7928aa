//! A camera path at the smooth surface of a birefringent crystal
//! ([`crate::material::CrystalDesc`]): reflection outside, refraction into one of the two
//! modes, and inside the crystal internal reflection into either mode or refraction out.
//!
//! Light inside the crystal travels in a mode (index n, D direction, ray direction,
//! [`crate::polar::crystal`]). Traced backwards, the path chooses the light's mode where
//! it refracts in or reflects inside: with probability w_m / Σw, w_m = (a·M·P_m)₀ the part
//! of the analyzer a (after the interface's Fresnel matrix M) that the mode's linear
//! polarizer P_m passes, so the analyzer becomes fully polarized along the mode's D field
//! and unpolarized light splits half and half. The path then follows the mode's RAY
//! direction (the walk-off), its wave normal kept for the next interface.
//!
//! Fresnel amplitudes: the isotropic ones ([`crate::polar::fresnel`]) with the mode's index
//! on the crystal side (the mean of the two modes' for the reflection outside, which decides
//! reflect-or-refract). The exact anisotropic coefficients (Weidlich & Wilkie 2008,
//! "Realistic rendering of birefringency in uniaxial crystals", ACM TOG 27(1)) differ by
//! terms of the order of the birefringence over the index (≤ 0.06 for calcite, 0.01 for
//! quartz); the directions, the split of the power between the modes and the walk-off are
//! exact. Radiance crossing into a mode of index n is scaled by (n_i/n_t)² like any
//! refraction (pbrt-v4 §9.5.2).

use crate::polar::crystal::{Indicatrix, Mode};
use crate::polar::fresnel;
use crate::polar::interface::{meet, Inside, Meeting, Outside};
use crate::polar::modes::{along_ray, choose, split, Chosen, InMode, Travel};
use crate::polar::stokes::{row_mul, Analyzer};
use crate::shading::polarized::s_basis;
use glam::Vec3;

/// What a bounce at a crystal surface gives.
#[derive(Debug, Clone, Copy)]
pub(super) struct CrystalBounce {
    /// The path's new direction (world, unit).
    pub dir: Vec3,
    /// The mode it travels in, `None` outside the crystal.
    pub inside: Option<InMode>,
    /// Whether the path crossed the surface.
    pub crossed: bool,
    /// The analyzer before the bounce.
    pub analyzer: Analyzer,
    /// The refraction's radiance factor 1/η'² (1 for a reflection).
    pub radiance: f32,
}

/// The mode of a path met inside the crystal in none, travelling along the ray `d` (it
/// started inside, or left a surface inside that is not the crystal's): chosen with `u`
/// by what each mode's polarizer passes of the analyzer ([`along_ray`]), the analyzer
/// becoming the projected one over the choice's probability. `None` when it passes
/// nothing.
pub(super) fn start(c: &Indicatrix, d: Vec3, pol: &Analyzer, u: f32) -> Option<(InMode, Analyzer)> {
    let s = pol.x;
    let chosen = along_ray(c, d, (&pol.in_basis(s).a, s), Travel::Against, u)?;
    let ((which, mode, (a, weight), total), x) = chosen;
    let scale = total / weight.max(f32::MIN_POSITIVE);
    let inside = InMode {
        which,
        k: mode.k,
        d: mode.d,
    };
    let analyzer = Analyzer {
        a: a.map(|v| v * scale),
        x,
        k: -mode.k,
    };
    Some((inside, analyzer))
}

/// The bounce of a path travelling along `d` at a crystal surface with outward unit normal
/// `n`, `n_out` the index outside, the path in `state` inside (`None`: coming from outside),
/// `pol` its analyzer, `u` two numbers (reflect or refract; which mode). `None` when no
/// light can arrive this way.
pub(super) fn bounce(
    c: &Indicatrix,
    (n, n_out): (Vec3, f32),
    d: Vec3,
    state: Option<InMode>,
    pol: &Analyzer,
    u: (f32, f32),
) -> Option<CrystalBounce> {
    match meet(c, (n, n_out), d, state)? {
        Meeting::Inside(inside) => from_inside(&inside, (n, n_out), state?.k, pol, u),
        Meeting::Outside(outside) => from_outside(&outside, (n, n_out), d, pol, u),
    }
}

/// The path arrives from outside: the light reflected outside or refracted out of a mode.
fn from_outside(
    o: &Outside,
    (n, n1): (Vec3, f32),
    d: Vec3,
    pol: &Analyzer,
    u: (f32, f32),
) -> Option<CrystalBounce> {
    if u.0 < o.r_mean {
        let (r, _) = fresnel::dielectric(o.cos1, o.n_reflect / n1);
        let k_in = -o.reflected;
        let s = s_basis(k_in, n, pol.x);
        return Some(CrystalBounce {
            dir: o.reflected,
            inside: None,
            crossed: false,
            analyzer: pol.through(&r, s, s, k_in, o.r_mean),
            radiance: 1.0,
        });
    }
    let s = s_basis(-d, n, pol.x);
    let a = pol.in_basis(s).a;
    // Light from each mode refracting out toward the path: T then the mode's polarizer.
    let through = |mode: &Mode| {
        let (_, t_m) = fresnel::dielectric(mode.k.dot(n).abs(), n1 / mode.n);
        row_mul(&a, &t_m)
    };
    let chosen = choose(&split(o.modes, through, s, Travel::Against), u.1)?;
    let etap = chosen.1.n / n1;
    Some(into_mode(
        chosen,
        1.0 - o.r_mean,
        s,
        (true, 1.0 / (etap * etap)),
    ))
}

/// The bounce into the `chosen` mode, whose interface was picked with probability
/// `p_interface`: the analyzer becomes the projected one over the choice's probability,
/// in the basis `s` ⊥ the mode's wave normal; `(crossed, radiance)` as in
/// [`CrystalBounce`].
fn into_mode(
    (w, mode, (a_new, weight), total): Chosen,
    p_interface: f32,
    s: Vec3,
    (crossed, radiance): (bool, f32),
) -> CrystalBounce {
    let scale = total / p_interface / weight.max(f32::MIN_POSITIVE);
    CrystalBounce {
        dir: mode.ray,
        inside: Some(InMode {
            which: w,
            k: mode.k,
            d: mode.d,
        }),
        crossed,
        analyzer: Analyzer {
            a: a_new.map(|v| v * scale),
            x: s,
            k: -mode.k,
        },
        radiance,
    }
}

/// The path, inside along the wave normal `k`, meets the surface: the light refracted in
/// from outside or reflected inside out of either mode.
fn from_inside(
    i: &Inside,
    (n, n2): (Vec3, f32),
    k: Vec3,
    pol: &Analyzer,
    u: (f32, f32),
) -> Option<CrystalBounce> {
    if let (Some(dir), true) = (i.out, u.0 >= i.r_mean) {
        let (_, tm) = fresnel::dielectric(dir.dot(n), i.n_mode / n2);
        let k_in = -dir;
        let s = s_basis(k_in, n, pol.x);
        let etap = n2 / i.n_mode;
        return Some(CrystalBounce {
            dir,
            inside: None,
            crossed: true,
            analyzer: pol.through(&tm, s, s, k_in, 1.0 - i.r_mean),
            radiance: 1.0 / (etap * etap),
        });
    }
    let (r, _) = fresnel::dielectric(i.cos_k, n2 / i.n_mode);
    let s = s_basis(-k, n, pol.x);
    let a = row_mul(&pol.in_basis(s).a, &r);
    let chosen = choose(&split(i.reflected, |_| a, s, Travel::Against), u.1)?;
    Some(into_mode(chosen, i.r_mean, s, (false, 1.0)))
}
