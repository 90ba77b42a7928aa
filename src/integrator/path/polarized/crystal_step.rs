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

use crate::optics::fresnel_dielectric;
use crate::polar::crystal::{Crystal, Mode, Which, BOTH};
use crate::polar::fresnel;
use crate::polar::stokes::{row_mul, Analyzer};
use glam::Vec3;

/// The mode a camera path is in inside a crystal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct InCrystal {
    /// Which mode.
    pub which: Which,
    /// Its wave normal, along the path.
    pub k: Vec3,
    /// Its D field direction.
    pub d: Vec3,
}

/// What a bounce at a crystal surface gives.
#[derive(Debug, Clone, Copy)]
pub(super) struct CrystalBounce {
    /// The path's new direction (world, unit).
    pub dir: Vec3,
    /// The mode it travels in, `None` outside the crystal.
    pub inside: Option<InCrystal>,
    /// Whether the path crossed the surface.
    pub crossed: bool,
    /// The analyzer before the bounce.
    pub analyzer: Analyzer,
    /// The refraction's radiance factor 1/η'² (1 for a reflection).
    pub radiance: f32,
}

/// The bounce of a path travelling along `d` at a crystal surface with outward unit normal
/// `n`, `n_out` the index outside, the path in `state` inside (`None`: coming from outside),
/// `pol` its analyzer, `u` two numbers (reflect or refract; which mode). `None` when no
/// light can arrive this way.
pub(super) fn bounce(
    c: &Crystal,
    (n, n_out): (Vec3, f32),
    d: Vec3,
    state: Option<InCrystal>,
    pol: &Analyzer,
    u: (f32, f32),
) -> Option<CrystalBounce> {
    match state {
        Some(inside) if d.dot(n) > 0.0 => from_inside(c, (n, n_out), inside, pol, u),
        _ if d.dot(n) < 0.0 => from_outside(c, (n, n_out), d, pol, u),
        _ => None,
    }
}

/// The path arrives from outside: the light reflected outside or refracted out of a mode.
fn from_outside(
    c: &Crystal,
    (n, n1): (Vec3, f32),
    d: Vec3,
    pol: &Analyzer,
    u: (f32, f32),
) -> Option<CrystalBounce> {
    let cos1 = -d.dot(n);
    let t = (d + n * cos1) * n1;
    let modes = BOTH.map(|w| c.refract(t, -n, w).map(|m| (w, m)));
    // The mean index of the modes that propagate (none: total reflection).
    let (sum, count) = modes
        .iter()
        .flatten()
        .fold((0.0, 0.0), |(s, c), (_, m)| (s + m.n, c + 1.0));
    let n_mean = (count > 0.0).then(|| sum / count);
    let r_mean = n_mean.map_or(1.0, |nm| fresnel_dielectric(cos1, nm / n1));
    if u.0 < r_mean {
        let dir = d + n * (2.0 * cos1);
        // With no mode propagating the reflection is total: the mean principal index then
        // gives its retardance (and R = 1 beyond that index's critical angle).
        let n_total = n_mean.unwrap_or((c.n[0] + c.n[1] + c.n[2]) / 3.0);
        let (r, _) = fresnel::dielectric(cos1, n_total / n1);
        let k_in = -dir;
        let s = super::surface::s_basis(k_in, n, pol);
        return Some(CrystalBounce {
            dir,
            inside: None,
            crossed: false,
            analyzer: pol.through(&r, s, s, k_in, r_mean),
            radiance: 1.0,
        });
    }
    let s = super::surface::s_basis(-d, n, pol);
    let a = pol.in_basis(s).a;
    // Light from each mode refracting out toward the path: T then the mode's polarizer.
    let through = |mode: &Mode| {
        let (_, t_m) = fresnel::dielectric(mode.k.dot(n).abs(), n1 / mode.n);
        row_mul(&a, &t_m)
    };
    let weighted = split(modes.map(|m| m.map(|(_, mode)| mode)), through, s);
    let chosen = choose(&weighted, u.1)?;
    let etap = chosen.1.n / n1;
    Some(into_mode(
        chosen,
        1.0 - r_mean,
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
        inside: Some(InCrystal {
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

/// The path, inside in mode `inside`, meets the surface: the light refracted in from
/// outside or reflected inside out of either mode.
fn from_inside(
    c: &Crystal,
    (n, n2): (Vec3, f32),
    inside: InCrystal,
    pol: &Analyzer,
    u: (f32, f32),
) -> Option<CrystalBounce> {
    let k = inside.k;
    let n_m = c.mode(k, inside.which).n;
    let cos_k = k.dot(n);
    if cos_k <= 0.0 {
        return None;
    }
    let t = (k - n * cos_k) * n_m;
    let t2 = t.length_squared();
    let out = (t2 < n2 * n2).then(|| (t + n * (n2 * n2 - t2).sqrt()) / n2);
    let r_mean = out.map_or(1.0, |_| fresnel_dielectric(cos_k, n2 / n_m));
    if let (Some(dir), true) = (out, u.0 >= r_mean) {
        let (_, tm) = fresnel::dielectric(dir.dot(n), n_m / n2);
        let k_in = -dir;
        let s = super::surface::s_basis(k_in, n, pol);
        let etap = n2 / n_m;
        return Some(CrystalBounce {
            dir,
            inside: None,
            crossed: true,
            analyzer: pol.through(&tm, s, s, k_in, 1.0 - r_mean),
            radiance: 1.0 / (etap * etap),
        });
    }
    let (r, _) = fresnel::dielectric(cos_k, n2 / n_m);
    let s = super::surface::s_basis(-k, n, pol);
    let a = row_mul(&pol.in_basis(s).a, &r);
    let weighted = split(BOTH.map(|w| c.refract(t, -n, w)), |_| a, s);
    let chosen = choose(&weighted, u.1)?;
    Some(into_mode(chosen, r_mean, s, (false, 1.0)))
}

/// Relative index difference below which the two modes are one (along an optic axis, or
/// an isotropic "crystal"): their phase difference over a stone is then a small fraction
/// of a wave, so the light keeps its polarization instead of splitting.
const DEGENERATE: f32 = 1e-5;

/// The modes (slow, fast) the light may come from, each with the analyzer `through` it
/// gives (basis s) projected on the mode's polarization ([`project`]). Degenerate modes
/// ([`DEGENERATE`]) are one wave whose analyzer is not projected: projecting it on an
/// arbitrary basis would depolarize light travelling along an optic axis.
fn split(modes: [Option<Mode>; 2], through: impl Fn(&Mode) -> [f32; 4], s: Vec3) -> [Weighted; 2] {
    if let [Some(slow), Some(fast)] = modes {
        if slow.n - fast.n < DEGENERATE * slow.n {
            let a = through(&slow);
            return [Some((Which::Slow, slow, (a, a[0].max(0.0)))), None];
        }
    }
    let mut out = [None, None];
    for (i, (m, w)) in modes.iter().zip(BOTH).enumerate() {
        out[i] = m.map(|mode| (w, mode, project(&through(&mode), &mode, s)));
    }
    out
}

/// The analyzer row `a` (basis s ⊥ the light's direction −mode.k) through the mode's
/// linear polarizer: (a·P)ᵀ and its weight w = (a·P)₀ ≥ 0.
fn project(a: &[f32; 4], mode: &Mode, s: Vec3) -> ([f32; 4], f32) {
    let k_light = -mode.k;
    let y = k_light.cross(s);
    let psi = mode.d.dot(y).atan2(mode.d.dot(s));
    let (sin2, cos2) = (2.0 * psi).sin_cos();
    let w = (0.5 * (a[0] + a[1] * cos2 + a[2] * sin2)).max(0.0);
    ([w, w * cos2, w * sin2, 0.0], w)
}

/// A mode the light may come from, with its projected analyzer and weight.
type Weighted = Option<(Which, Mode, ([f32; 4], f32))>;

/// The chosen mode, its projected analyzer and weight, and the weights' sum.
type Chosen = (Which, Mode, ([f32; 4], f32), f32);

/// Picks one of the weighted modes with probability w / Σw using `u`; returns it with Σw.
fn choose(weighted: &[Weighted; 2], u: f32) -> Option<Chosen> {
    let total: f32 = weighted.iter().flatten().map(|(_, _, (_, w))| *w).sum();
    if total.is_nan() || total <= 0.0 {
        return None;
    }
    let mut acc = 0.0;
    let mut last = None;
    for (w, mode, p) in weighted.iter().flatten() {
        acc += p.1;
        last = Some((*w, *mode, *p, total));
        if u * total < acc {
            break;
        }
    }
    last
}
