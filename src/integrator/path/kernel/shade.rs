//! The kernel's shading over the lanes, each a plain loop over fixed-size arrays that LLVM
//! vectorises (compiled for the CPU's widest vectors by the caller's dispatch,
//! [`super::estimate`]): next-event estimation at Lambert lanes toward one punctual light
//! ([`light`]), the cosine-sampled Lambert bounce with the bounce limit and Russian
//! roulette ([`lambert`]), the smooth dielectric's Fresnel-weighted reflection or refraction
//! ([`glass`]), and the spawned rays ([`spawn`]).
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
//! Units: radiance linear RGB; world space.

use super::features::Punctual;
use super::hits::{dot, Hits, V3};
use crate::interaction::{offset_point, SHADOW_EPSILON};
use crate::light::punctual::{cone_falloff, range_window};
use crate::shading::MAX_DELTA_BOUNCES;
use std::f32::consts::{FRAC_1_PI, TAU};

/// The per-lane state the bounces update: throughput, η scale, bounce counts, the
/// previous bounce (for the MIS weight of emission the path meets next, as the scalar
/// path's `Prev`) and the glass volume the path is in.
pub struct Throughput<const N: usize> {
    /// Throughput β.
    pub beta: V3<N>,
    /// Product of η'² over the refractions (Russian roulette reads β · η scale).
    pub eta_scale: [f32; N],
    /// Non-delta bounces.
    pub depth: [u32; N],
    /// Delta bounces.
    pub deltas: [u32; N],
    /// The previous bounce was delta (or the ray is the camera's): no MIS.
    pub prev_delta: [bool; N],
    /// The previous bounce's BSDF pdf (solid angle).
    pub prev_pdf: [f32; N],
    /// The previous bounce's position.
    pub prev_p: V3<N>,
    /// The glass volume the path is in: its material index + 1, or 0 in air.
    pub medium: [u32; N],
}

impl<const N: usize> Throughput<N> {
    /// No paths yet.
    pub fn new() -> Self {
        Throughput {
            beta: [[0.0; N]; 3],
            eta_scale: [1.0; N],
            depth: [0; N],
            deltas: [0; N],
            prev_delta: [true; N],
            prev_pdf: [0.0; N],
            prev_p: [[0.0; N]; 3],
            medium: [0; N],
        }
    }

    /// Lane `i` starts a camera path: no previous bounce to weigh against, in air.
    pub fn restart(&mut self, i: usize) {
        self.prev_delta[i] = true;
        self.prev_pdf[i] = 0.0;
        self.medium[i] = 0;
    }

    /// Where `on`, lane `i` records its bounce at `h`'s lane `i` with BSDF pdf `pdf`
    /// (`delta`: a delta bounce).
    #[inline(always)]
    fn bounced(&mut self, on: bool, h: &Hits<N>, i: usize, (pdf, delta): (f32, bool)) {
        self.prev_delta[i] = if on { delta } else { self.prev_delta[i] };
        self.prev_pdf[i] = if on { pdf } else { self.prev_pdf[i] };
        for c in 0..3 {
            self.prev_p[c][i] = if on { h.p[c][i] } else { self.prev_p[c][i] };
        }
    }
}

/// Rays in SoA form: origin, direction, `t_max`.
pub struct Rays<const N: usize> {
    /// Origin.
    pub o: V3<N>,
    /// Direction.
    pub d: V3<N>,
    /// Upper bound of t.
    pub t_max: [f32; N],
}

impl<const N: usize> Rays<N> {
    /// No rays yet.
    pub fn new() -> Self {
        Rays {
            o: [[0.0; N]; 3],
            d: [[0.0; N]; 3],
            t_max: [0.0; N],
        }
    }
}

/// The origin of a ray leaving hit lane `i` toward `dir`: the intersection layer's offset
/// rule ([`offset_point`]).
#[inline(always)]
fn origin<const N: usize>(h: &Hits<N>, i: usize, dir: [f32; 3]) -> [f32; 3] {
    let p = [h.p[0][i], h.p[1][i], h.p[2][i]];
    let ng = [h.ng[0][i], h.ng[1][i], h.ng[2][i]];
    offset_point(p, ng, h.offset[i], dir)
}

/// Where `on`, sets lane `i` of `out` to the ray leaving hit lane `i` along the unit `dir`
/// (a select, not a branch, so the lane loop stays one vector loop).
#[inline(always)]
pub fn spawn<const N: usize>(on: bool, h: &Hits<N>, i: usize, dir: [f32; 3], out: &mut Rays<N>) {
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
pub fn aim<const N: usize>(
    on: bool,
    h: &Hits<N>,
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

/// Next-event estimation at the lanes `on` toward the punctual light of index `k[i]` among
/// `lights`, chosen with probability 1/`inv_pmf`: adds to `value` the unweighted-by-shadow
/// contribution β · f · E⊥ · `inv_pmf` · |cos θ| of each lane whose sample counts, sets its
/// shadow ray in `shadow` and its flag in `traced`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn light<const N: usize>(
    (lights, inv_pmf): (&[Punctual], f32),
    k: &[u32; N],
    on: &[bool; N],
    h: &Hits<N>,
    beta: &V3<N>,
    value: &mut V3<N>,
    shadow: &mut Rays<N>,
    traced: &mut [bool; N],
) {
    let n = inv_pmf;
    for (j, l) in lights.iter().enumerate() {
        for i in 0..N {
            let mine = on[i] && k[i] == j as u32;
            let (wi, e, ok, target) = incidence(l, h, i);
            let cos_o = dot(&h.ns, &h.wo, i);
            let cos_i = h.ns[0][i] * wi[0] + h.ns[1][i] * wi[1] + h.ns[2][i] * wi[2];
            let f_nonzero = h.rgb[0][i] > 0.0 || h.rgb[1][i] > 0.0 || h.rgb[2][i] > 0.0;
            let counts = mine && ok && cos_o * cos_i > 0.0 && f_nonzero;
            let w = cos_i.abs() * n * FRAC_1_PI;
            for c in 0..3 {
                let v = beta[c][i] * h.rgb[c][i] * e[c] * w;
                value[c][i] = if counts { v } else { value[c][i] };
            }
            let target = if l.directional { wi } else { target };
            aim(counts, h, i, (target, l.directional), shadow);
            traced[i] |= counts;
        }
    }
}

/// The light `l` at hit lane `i`: unit direction toward it, E⊥ (lux), whether it reaches
/// the point (inside its cone and range, not at it), and its position.
#[inline(always)]
fn incidence<const N: usize>(
    l: &Punctual,
    h: &Hits<N>,
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
pub fn lambert<const N: usize>(
    on: &[bool; N],
    h: &Hits<N>,
    (u1, u2, u_rr): (&[f32; N], &[f32; N], &[f32; N]),
    max_depth: u32,
    st: &mut Throughput<N>,
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
        let mut q = 0.0f32;
        for c in 0..3 {
            let b = st.beta[c][i] * h.rgb[c][i];
            st.beta[c][i] = if on[i] { b } else { st.beta[c][i] };
            q = q.max(st.beta[c][i] * st.eta_scale[i]);
        }
        let depth = st.depth[i] + 1;
        st.depth[i] = if on[i] { depth } else { st.depth[i] };
        // Russian roulette after three non-delta bounces: q ≥ 1 always survives, q < 1
        // with probability q (NaN never), and the survivor is divided by min(q, 1).
        let rr = depth >= 3;
        let survives = !rr || q >= 1.0 || u_rr[i] < q;
        let divisor = if rr && q < 1.0 { q } else { 1.0 };
        for c in 0..3 {
            let b = st.beta[c][i] / divisor;
            st.beta[c][i] = if on[i] { b } else { st.beta[c][i] };
        }
        // A black albedo (an emitter's) leaves nothing to carry: the path ends.
        let dark = q == 0.0;
        ends[i] = on[i] && (cos_o == 0.0 || z == 0.0 || depth >= max_depth || !survives || dark);
        played[i] = on[i] && rr && q < 1.0 && depth < max_depth;
        st.bounced(on[i], h, i, (z.abs() * FRAC_1_PI, false));
        spawn(on[i], h, i, wi, next);
    }
    (ends, played)
}

/// The smooth dielectric at the lanes `on` with the number `u`: reflection with
/// probability F (exact unpolarised Fresnel, either side), else refraction (β times the
/// tint over η'², η scale times η'²); one more delta bounce. The next ray into `next`;
/// returns the lanes whose path ends here.
#[inline(always)]
pub fn glass<const N: usize>(
    on: &[bool; N],
    h: &Hits<N>,
    u: &[f32; N],
    st: &mut Throughput<N>,
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
        for k in 0..3 {
            let t = if reflect { 1.0 } else { h.rgb[k][i] };
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
