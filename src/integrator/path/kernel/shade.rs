//! The kernel's shading over the lanes, each a plain loop over fixed-size arrays that LLVM
//! vectorises (compiled for the CPU's widest vectors by the caller's dispatch,
//! [`super::estimate`]): next-event estimation at Lambert and glossy lanes toward one
//! punctual light ([`light`], the lanes' BSDFs toward it: [`Toward`]), the cosine-sampled
//! Lambert bounce with the bounce limit and Russian roulette ([`lambert`], the roulette
//! shared with the glossy lanes: [`survive`]), the smooth dielectric's Fresnel-weighted
//! reflection or refraction ([`glass`]), and the spawned rays ([`spawn`]).
//!
//! Each does what the scalar path tracer does at such a vertex
//! ([`crate::integrator::path`]): the light chosen uniformly with pmf 1/n
//! ([`crate::light::sampler`]), its value f · E⊥ / pmf · |cos θ| with weight 1 (a delta
//! light), no shadow ray where f is zero; the Lambert throughput times the albedo
//! (f·|cos|/pdf); the dielectric's reflection chosen with probability F, its transmission
//! divided by η'² (radiance transport) with η'² counted in the η scale Russian roulette
//! reads; roulette after three non-delta bounces with survival min(1, max(β · η scale)),
//! drawn only below 1 ([`crate::shading::termination`]); delta bounces capped at
//! [`MAX_DELTA_BOUNCES`]. Rays leave by the intersection layer's one offset rule
//! ([`crate::interaction`]: along `ng`, to the side the ray leaves to).
//!
//! Units: radiance in `M` channels ([`super::colour`]); world space.

use super::colour::{emitted, set_lane, spectral, Channels};
use super::features::{Punctual, Tables};
use super::glossy::Lobes;
use super::hits::{dot, Hits, V3};
use super::state::{Rays, Throughput};
use crate::accel::packet::{lanes, LaneMask};
use crate::interaction::{offset_point, SHADOW_EPSILON};
use crate::light::punctual::{cone_falloff, range_window};
use crate::shading::MAX_DELTA_BOUNCES;
use crate::spectrum::{EmitterShape, Lambdas};
use std::f32::consts::{FRAC_1_PI, TAU};

/// The origin of a ray leaving hit lane `i` toward `dir`: the intersection layer's offset
/// rule ([`offset_point`]).
#[inline(always)]
fn origin<const N: usize, const M: usize>(h: &Hits<N, M>, i: usize, dir: [f32; 3]) -> [f32; 3] {
    let p = [h.p[0][i], h.p[1][i], h.p[2][i]];
    let ng = [h.ng[0][i], h.ng[1][i], h.ng[2][i]];
    offset_point(p, ng, h.offset[i], dir)
}

/// Where `on`, sets lane `i` of `out` to the ray leaving hit lane `i` along the unit `dir`
/// (a select, not a branch, so the lane loop stays one vector loop).
#[inline(always)]
pub fn spawn<const N: usize, const M: usize>(
    on: bool,
    h: &Hits<N, M>,
    i: usize,
    dir: [f32; 3],
    out: &mut Rays<N>,
) {
    let o = origin(h, i, dir);
    for c in 0..3 {
        out.o[c][i] = if on { o[c] } else { out.o[c][i] };
        out.d[c][i] = if on { dir[c] } else { out.d[c][i] };
    }
    out.t_max[i] = if on { f32::INFINITY } else { out.t_max[i] };
}

/// Where `on`, sets lane `i` of `shadow` to the shadow ray from hit lane `i` toward the
/// point `target`, or along the unit direction `target` when `distant`: the intersection
/// layer's `spawn_ray_to` (up to 1 − [`SHADOW_EPSILON`] of the way) and `spawn_ray`.
#[inline(always)]
pub fn aim<const N: usize, const M: usize>(
    on: bool,
    h: &Hits<N, M>,
    i: usize,
    (target, distant): ([f32; 3], bool),
    shadow: &mut Rays<N>,
) {
    let toward = if distant {
        target
    } else {
        [0, 1, 2].map(|c| target[c] - h.p[c][i])
    };
    let o = origin(h, i, toward);
    for c in 0..3 {
        let d = if distant { target[c] } else { target[c] - o[c] };
        shadow.o[c][i] = if on { o[c] } else { shadow.o[c][i] };
        shadow.d[c][i] = if on { d } else { shadow.d[c][i] };
    }
    let t_max = if distant {
        f32::INFINITY
    } else {
        1.0 - SHADOW_EPSILON
    };
    shadow.t_max[i] = if on { t_max } else { shadow.t_max[i] };
}

/// The lanes' BSDFs toward one direction each (next-event estimation): `g` and `scale`
/// give f = g · scale (Lambert lanes: the albedo and 1/π, kept apart so their products
/// round as the Lambert estimate always has; glossy lanes: f from [`Lobes::eval`]
/// and 1), `pdf` the density with which the vertex's own sampling picks the direction,
/// `cos` = |cos θi| at the shading normal, and `counts` where the BSDF scatters toward it
/// (f ≠ 0: a Lambert lane's on the side of `wo`; a glossy lane's where its lobe says,
/// through the surface too for rough glass).
pub struct Toward<const N: usize, const M: usize> {
    pub g: Channels<N, M>,
    pub scale: [f32; N],
    pub pdf: [f32; N],
    pub cos: [f32; N],
    pub counts: [bool; N],
}

impl<const N: usize, const M: usize> Toward<N, M> {
    /// The BSDFs of the lanes `on` of `h` (the glossy lanes' in `lobes`) toward the unit
    /// directions `wi`.
    #[inline(always)]
    pub fn new(lobes: &Lobes<N>, h: &Hits<N, M>, on: &[bool; N], wi: &V3<N>) -> Self {
        let mut t = Toward {
            g: h.col,
            scale: [FRAC_1_PI; N],
            pdf: [0.0; N],
            cos: [0.0; N],
            counts: [false; N],
        };
        let mut glossy: LaneMask = 0;
        for (i, &on) in on.iter().enumerate() {
            let cos_o = dot(&h.ns, &h.wo, i);
            let cos_i = dot(&h.ns, wi, i);
            let f_nonzero = (0..M).any(|c| h.col[c][i] > 0.0);
            t.cos[i] = cos_i.abs();
            t.pdf[i] = cos_i.abs() * FRAC_1_PI;
            t.counts[i] = on && cos_o * cos_i > 0.0 && f_nonzero;
            glossy |= u32::from(on && h.glossy[i]) << i;
        }
        for i in lanes(glossy) {
            let w = [wi[0][i], wi[1][i], wi[2][i]];
            let Some((f, pdf)) = lobes.eval::<M>(i, w) else {
                continue;
            };
            set_lane(&mut t.g, i, f);
            (t.scale[i], t.pdf[i]) = (1.0, pdf);
            t.counts[i] = f.iter().any(|v| *v > 0.0);
        }
        t
    }
}

/// Next-event estimation at the lanes `on` toward the punctual light of index `k[i]` among
/// the table's lights, chosen with probability 1/`inv_pmf`: adds to `value` the
/// unweighted-by-shadow contribution β · f · E⊥ · `inv_pmf` · |cos θ| of each lane whose
/// sample counts (E⊥ at the lane's wavelengths `lam`, f the lane's BSDF: [`Toward`]), sets
/// its shadow ray in `shadow` and its flag in `traced`.
#[inline(always)]
pub fn light<const N: usize, const M: usize>(
    (tables, inv_pmf, lam): (&Tables, f32, &[Lambdas; N]),
    (k, on): (&[u32; N], &[bool; N]),
    (lobes, h, beta): (&Lobes<N>, &Hits<N, M>, &Channels<N, M>),
    (value, shadow, traced): (&mut Channels<N, M>, &mut Rays<N>, &mut [bool; N]),
) {
    if !on.contains(&true) {
        return;
    }
    let n = inv_pmf;
    let mut e_rgb: V3<N> = [[0.0; N]; 3];
    let mut wi: V3<N> = [[0.0; N]; 3];
    let mut target: V3<N> = [[0.0; N]; 3];
    let mut distant = [false; N];
    let mut reaches = [false; N];
    for (j, l) in tables.lights.iter().enumerate() {
        for i in 0..N {
            let mine = on[i] && k[i] == j as u32;
            let (w, e, ok, at) = incidence(l, h, i);
            let at = if l.directional { w } else { at };
            for c in 0..3 {
                e_rgb[c][i] = if mine { e[c] } else { e_rgb[c][i] };
                wi[c][i] = if mine { w[c] } else { wi[c][i] };
                target[c][i] = if mine { at[c] } else { target[c][i] };
            }
            distant[i] = if mine { l.directional } else { distant[i] };
            reaches[i] |= mine && ok;
        }
    }
    let by = Toward::new(lobes, h, on, &wi);
    let mut w = [0.0f32; N];
    let mut counts = [false; N];
    for i in 0..N {
        let counted = reaches[i] && by.counts[i];
        w[i] = if counted {
            by.cos[i] * n * by.scale[i]
        } else {
            0.0
        };
        counts[i] = counted;
        let to = [target[0][i], target[1][i], target[2][i]];
        aim(counted, h, i, (to, distant[i]), shadow);
        traced[i] |= counted;
    }
    let e = incident::<N, M>(
        (&e_rgb, &counts),
        |i| tables.light_shapes[k[i] as usize].as_ref(),
        lam,
    );
    for i in 0..N {
        for c in 0..M {
            let v = beta[c][i] * by.g[c][i] * e[c][i] * w[i];
            value[c][i] = if counts[i] { v } else { value[c][i] };
        }
    }
}

/// The light's RGB value `rgb` at the lanes `on` in `M` channels at each lane's
/// wavelengths `lam` (the shape of lane `i`'s light `shape(i)`): a copy in RGB.
#[inline(always)]
pub fn incident<'a, const N: usize, const M: usize>(
    (rgb, on): (&V3<N>, &[bool; N]),
    shape: impl Fn(usize) -> Option<&'a EmitterShape>,
    lam: &[Lambdas; N],
) -> Channels<N, M> {
    let mut e = [[0.0; N]; M];
    if spectral::<M>() {
        for i in (0..N).filter(|&i| on[i]) {
            let v = emitted::<M>([rgb[0][i], rgb[1][i], rgb[2][i]], shape(i), &lam[i]);
            (0..M).for_each(|c| e[c][i] = v[c]);
        }
    } else {
        (0..M).for_each(|c| e[c] = rgb[c]);
    }
    e
}

/// The light `l` at hit lane `i`: unit direction toward it, E⊥ (lux), whether it reaches
/// the point (inside its cone and range, not at it), and its position.
#[inline(always)]
fn incidence<const N: usize, const M: usize>(
    l: &Punctual,
    h: &Hits<N, M>,
    i: usize,
) -> ([f32; 3], [f32; 3], bool, [f32; 3]) {
    if l.directional {
        return (l.at, l.intensity, true, l.at);
    }
    let v = [0, 1, 2].map(|c| l.at[c] - h.p[c][i]);
    let d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let d = d2.sqrt();
    let wi = v.map(|x| x / d);
    let cd = -(wi[0] * l.axis[0] + wi[1] * l.axis[1] + wi[2] * l.axis[2]);
    let w = cone_falloff(cd, l.cos_inner, l.cos_outer) * range_window(d, Some(l.range));
    let e = l.intensity.map(|x| x * (w / d2));
    (wi, e, d2 > 0.0 && w > 0.0, l.at)
}

/// sin and cos of 2π`t` for `t` ∈ [0, 1), branch-free: the quadrant from round(4t), then
/// Taylor polynomials on [−π/4, π/4] (errors below 4e-7).
#[inline(always)]
fn sincos_tau(t: f32) -> (f32, f32) {
    let q = (t * 4.0).round();
    let x = (t - q * 0.25) * TAU;
    let x2 = x * x;
    let s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0)));
    let c = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0)));
    // Quadrant k: (sin, cos) = (s, c), (c, −s), (−s, −c), (−c, s).
    let k = (q as i32) & 3;
    let (a, b) = if k & 1 != 0 { (c, s) } else { (s, c) };
    let sin = if k & 2 != 0 { -a } else { a };
    let cos = if k == 1 || k == 2 { -b } else { b };
    (sin, cos)
}

/// The Lambert bounce at the lanes `on` with the numbers `u1`, `u2` (direction) and
/// `u_rr` (roulette): the cosine-sampled direction on `wo`'s side in the frame of `ns`
/// (Duff et al. 2017, as [`crate::math::Frame::from_normal`]), β times the albedo, one
/// more non-delta bounce, Russian roulette; the next ray into `next`. Returns the lanes
/// whose path ends here, and those that played the roulette (read `u_rr`: survival below
/// 1 after three non-delta bounces, the bounce limit not reached).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn lambert<const N: usize, const M: usize>(
    on: &[bool; N],
    h: &Hits<N, M>,
    (u1, u2, u_rr): (&[f32; N], &[f32; N], &[f32; N]),
    max_depth: u32,
    st: &mut Throughput<N, M>,
    next: &mut Rays<N>,
) -> ([bool; N], [bool; N]) {
    let (mut ends, mut played) = ([false; N], [false; N]);
    for i in 0..N {
        let n = [h.ns[0][i], h.ns[1][i], h.ns[2][i]];
        let sign = 1f32.copysign(n[2]);
        let a = -1.0 / (sign + n[2]);
        let b = n[0] * n[1] * a;
        let s = [1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]];
        let t = [b, sign + n[1] * n[1] * a, -n[1]];
        let cos_o = dot(&h.ns, &h.wo, i);
        let r = u1[i].sqrt();
        let (sn, cs) = sincos_tau(u2[i]);
        let z = (1.0 - u1[i]).max(0.0).sqrt();
        let z = if cos_o < 0.0 { -z } else { z };
        let wi = [0, 1, 2].map(|c| s[c] * (r * cs) + t[c] * (r * sn) + n[c] * z);
        for c in 0..M {
            let b = st.beta[c][i] * h.col[c][i];
            st.beta[c][i] = if on[i] { b } else { st.beta[c][i] };
        }
        let (end, play) = survive(on[i], i, u_rr[i], max_depth, st);
        ends[i] = on[i] && (cos_o == 0.0 || z == 0.0 || end);
        played[i] = play;
        st.bounced(on[i], h, i, (z.abs() * FRAC_1_PI, false));
        spawn(on[i], h, i, wi, next);
    }
    (ends, played)
}

/// One more non-delta bounce of lane `i` where `on`, its throughput already times the
/// bounce's weight: the bounce limit, then Russian roulette on `u_rr` after three
/// non-delta bounces — q = max(β · η scale) ≥ 1 always survives, q < 1 with probability q
/// (NaN never), the survivor divided by min(q, 1). Returns whether the path ends here (a
/// black throughput, an emitter's black albedo, ends it too: nothing is left to carry) and
/// whether it played the roulette (read `u_rr`).
#[inline(always)]
pub fn survive<const N: usize, const M: usize>(
    on: bool,
    i: usize,
    u_rr: f32,
    max_depth: u32,
    st: &mut Throughput<N, M>,
) -> (bool, bool) {
    let q = (0..M).fold(0.0f32, |q, c| q.max(st.beta[c][i] * st.eta_scale[i]));
    let depth = st.depth[i] + 1;
    st.depth[i] = if on { depth } else { st.depth[i] };
    let rr = depth >= 3;
    let survives = !rr || q >= 1.0 || u_rr < q;
    let divisor = if rr && q < 1.0 { q } else { 1.0 };
    for c in 0..M {
        let b = st.beta[c][i] / divisor;
        st.beta[c][i] = if on { b } else { st.beta[c][i] };
    }
    let dark = q == 0.0;
    let ends = on && (depth >= max_depth || !survives || dark);
    (ends, on && rr && q < 1.0 && depth < max_depth)
}

/// The smooth dielectric at the lanes `on` with the number `u`: reflection with
/// probability F (exact unpolarised Fresnel, either side), else refraction (β times the
/// tint over η'², η scale times η'²); one more delta bounce. The next ray into `next`;
/// returns the lanes whose path ends here.
#[inline(always)]
pub fn glass<const N: usize, const M: usize>(
    on: &[bool; N],
    h: &Hits<N, M>,
    u: &[f32; N],
    st: &mut Throughput<N, M>,
    next: &mut Rays<N>,
) -> [bool; N] {
    let mut ends = [false; N];
    for i in 0..N {
        let c = dot(&h.ns, &h.wo, i);
        let etap = if c > 0.0 { h.eta[i] } else { 1.0 / h.eta[i] };
        let ci = c.abs();
        let cos2t = (etap * etap - (1.0 - ci) * (1.0 + ci)) / (etap * etap);
        let ct = cos2t.max(0.0).sqrt();
        let rp = (etap * ci - ct) / (etap * ci + ct);
        let rs = (ci - etap * ct) / (ci + etap * ct);
        let f = if cos2t < 0.0 {
            1.0
        } else {
            (0.5 * (rp * rp + rs * rs)).clamp(0.0, 1.0)
        };
        let reflect = u[i] < f;
        let flip = if c > 0.0 { 1.0 } else { -1.0 };
        let mut wt = [0.0; 3];
        let mut wr = [0.0; 3];
        for k in 0..3 {
            let n = h.ns[k][i] * flip;
            wt[k] = -(h.wo[k][i] - ci * n) / etap - ct * n;
            wr[k] = 2.0 * c * h.ns[k][i] - h.wo[k][i];
        }
        let rlen = 1.0 / (wt[0] * wt[0] + wt[1] * wt[1] + wt[2] * wt[2]).sqrt();
        let wi = [0, 1, 2].map(|k| if reflect { wr[k] } else { wt[k] * rlen });
        let weight = if reflect { 1.0 } else { 1.0 / (etap * etap) };
        for k in 0..M {
            let t = if reflect { 1.0 } else { h.col[k][i] };
            let b = st.beta[k][i] * t * weight;
            st.beta[k][i] = if on[i] { b } else { st.beta[k][i] };
        }
        let es = st.eta_scale[i] * if reflect { 1.0 } else { etap * etap };
        st.eta_scale[i] = if on[i] { es } else { st.eta_scale[i] };
        let deltas = st.deltas[i] + 1;
        st.deltas[i] = if on[i] { deltas } else { st.deltas[i] };
        ends[i] = on[i] && (c == 0.0 || deltas > MAX_DELTA_BOUNCES);
        // A refraction enters the glass from outside (c > 0) or leaves it.
        let entered = if c > 0.0 { h.material[i] + 1 } else { 0 };
        st.medium[i] = if on[i] && !reflect {
            entered
        } else {
            st.medium[i]
        };
        st.bounced(on[i], h, i, (0.0, true));
        spawn(on[i], h, i, wi, next);
    }
    ends
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The polynomial sin/cos agree with the library's to 1e-6 over [0, 1).
    #[test]
    fn sincos_matches_the_library() {
        for k in 0..10_000 {
            let t = k as f32 / 10_000.0;
            let (s, c) = sincos_tau(t);
            let (es, ec) = (TAU * t).sin_cos();
            assert!(
                (s - es).abs() < 1e-6 && (c - ec).abs() < 1e-6,
                "{t}: {s} {c}"
            );
        }
    }
}
