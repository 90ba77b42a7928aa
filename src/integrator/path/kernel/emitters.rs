//! Light with an area or at infinity in the kernel, as the scalar path tracer takes it
//! ([`crate::integrator::path::vertex`], [`crate::shading::next_event`]):
//! - what a path meets ([`arrive`]): the emission of the surface hit (its emitting side
//!   only) and the environment along a ray that escapes, each times β and MIS-weighted
//!   against the next-event estimation that could have sampled it — the power heuristic
//!   of the previous bounce's BSDF pdf and the light's solid-angle pdf (the light
//!   sampler's pmf times [`lights::area_pdf`] or [`lights::environment_pdf`]), weight 1 for
//!   camera rays and after delta bounces;
//! - next-event estimation at Lambert lanes ([`next_event`]): one light chosen uniformly
//!   among the scene's light sampler's (its [`LightId`] order, pmf 1/n), a punctual one by
//!   [`super::shade::light`], an emissive triangle by the scene's area lights (the triangle
//!   by power with the member number, the point uniform by area with the position numbers,
//!   [`crate::light::area::AreaLights::sample`]; single-sided emitters seen from behind
//!   give nothing) or a direction of the environment ([`crate::light::env::Environment::sample`]
//!   with the position numbers), weighted by the power heuristic against the Lambert pdf
//!   |cos θ|/π.
//!
//! The light tables' reads (the emitting triangle's corners, a map's texels) are calls per
//! lane into the scalar code, over the lanes that need them; the weights and values are
//! plain loops over all lanes with selects.
//!
//! Units: radiance linear RGB; pdfs per steradian; world space.

use super::super::light_sample::mis;
use super::features::Tables;
use super::hits::{dot, Hits, V3};
use super::numbers::Draws;
use super::shade::{aim, light, Rays, Throughput};
use crate::accel::packet::{lanes, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::light::LightId;
use crate::scene::Scene;
use crate::shading::lights;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// Adds to `l` the light the lanes meet: at the lanes `hit` of `h` the emission of the
/// surface toward the path, at the `alive` lanes that missed the environment along their
/// ray in `rays`, each times β of `st` and weighted against next-event estimation.
#[inline(always)]
pub fn arrive<const N: usize>(
    (tables, scene): (&Tables, &Scene),
    rays: &RayPacket<N>,
    h: &Hits<N>,
    (hit, alive): (LaneMask, LaneMask),
    st: &Throughput<N>,
    l: &mut V3<N>,
) where
    Lanes<N>: PacketWidth,
{
    let mut le: V3<N> = [[0.0; N]; 3];
    let mut pdf = [0.0f32; N];
    let mut shows = [false; N];
    for i in lanes(hit) {
        let (rgb, two_sided) = tables.emission[h.material[i] as usize];
        let front = dot(&h.wo, &h.ng, i) > 0.0;
        shows[i] = (front || two_sided) && rgb != [0.0; 3];
        (0..3).for_each(|c| le[c][i] = rgb[c]);
        if shows[i] && !st.prev_delta[i] {
            let from = Vec3::new(st.prev_p[0][i], st.prev_p[1][i], st.prev_p[2][i]);
            let at = Vec3::new(h.p[0][i], h.p[1][i], h.p[2][i]);
            pdf[i] = lights::area_pdf(scene, h.prim[i], from, at);
        }
    }
    let missed = alive & !hit;
    if let (Some(env), true) = (scene.environment(), missed != 0) {
        for i in lanes(missed) {
            let d = Vec3::new(rays.dir_x[i], rays.dir_y[i], rays.dir_z[i]).normalize();
            let e = env.eval(d);
            shows[i] = true;
            (0..3).for_each(|c| le[c][i] = e[c]);
            if !st.prev_delta[i] {
                pdf[i] = lights::environment_pdf(scene, d);
            }
        }
    }
    for i in 0..N {
        let w = if st.prev_delta[i] {
            1.0
        } else {
            mis(st.prev_pdf[i], pdf[i])
        };
        for c in 0..3 {
            let v = l[c][i] + st.beta[c][i] * le[c][i] * w;
            l[c][i] = if shows[i] { v } else { l[c][i] };
        }
    }
}

/// A light sample with an area or at infinity seen from a lane: the unit direction toward
/// it, radiance over its solid-angle pdf, that pdf, and where the shadow ray aims (a point,
/// or a direction when `distant`).
struct Sampled<const N: usize> {
    wi: V3<N>,
    incident: V3<N>,
    pdf: [f32; N],
    target: V3<N>,
    distant: [bool; N],
    ok: [bool; N],
}

/// Next-event estimation at the lanes `on` of `h` with the numbers `u`: the light chosen
/// among `tables.sampled` (pmf 1/n), its contribution β · f · incident · n · |cos θ| · w
/// (unblocked) into `value`, its shadow ray into `shadow` and its flag into `traced`.
#[inline(always)]
pub fn next_event<const N: usize>(
    (tables, scene): (&Tables, &Scene),
    u: &Draws<N>,
    (on, h, beta): (&[bool; N], &Hits<N>, &V3<N>),
    (value, shadow, traced): (&mut V3<N>, &mut Rays<N>, &mut [bool; N]),
) {
    let n = tables.sampled.len();
    if n == 0 {
        return;
    }
    let chosen: [usize; N] =
        std::array::from_fn(|i| ((u.light_choice[i] * n as f32) as usize).min(n - 1));
    let mut punctual = [u32::MAX; N];
    let mut spread: LaneMask = 0;
    for (i, &k) in chosen.iter().enumerate() {
        match tables.sampled[k] {
            LightId::Punctual(j) => punctual[i] = j,
            _ => spread |= u32::from(on[i]) << i,
        }
    }
    let inv_pmf = n as f32;
    let pointed = std::array::from_fn(|i| on[i] && punctual[i] != u32::MAX);
    let lit = (&tables.lights[..], inv_pmf);
    light(lit, &punctual, &pointed, h, beta, value, shadow, traced);
    if spread == 0 {
        return;
    }
    let s = sample((tables, scene), (u, &chosen), h, spread);
    for i in 0..N {
        let cos_o = dot(&h.ns, &h.wo, i);
        let cos_i = h.ns[0][i] * s.wi[0][i] + h.ns[1][i] * s.wi[1][i] + h.ns[2][i] * s.wi[2][i];
        let f_nonzero = h.rgb[0][i] > 0.0 || h.rgb[1][i] > 0.0 || h.rgb[2][i] > 0.0;
        let counts = s.ok[i] && cos_o * cos_i > 0.0 && f_nonzero;
        let w = mis(s.pdf[i] / inv_pmf, cos_i.abs() * FRAC_1_PI);
        let scale = cos_i.abs() * inv_pmf * FRAC_1_PI * w;
        for c in 0..3 {
            let v = beta[c][i] * h.rgb[c][i] * s.incident[c][i] * scale;
            value[c][i] = if counts { v } else { value[c][i] };
        }
        let target = [s.target[0][i], s.target[1][i], s.target[2][i]];
        aim(counts, h, i, (target, s.distant[i]), shadow);
        traced[i] |= counts;
    }
}

/// The samples of the emissive triangles or the environment at the lanes `spread` (those
/// whose `chosen` light is one of them), from the scalar light code lane by lane.
#[inline(always)]
fn sample<const N: usize>(
    (tables, scene): (&Tables, &Scene),
    (u, chosen): (&Draws<N>, &[usize; N]),
    h: &Hits<N>,
    spread: LaneMask,
) -> Sampled<N> {
    let mut s = Sampled {
        wi: [[0.0; N]; 3],
        incident: [[0.0; N]; 3],
        pdf: [1.0; N],
        target: [[0.0; N]; 3],
        distant: [false; N],
        ok: [false; N],
    };
    for i in lanes(spread) {
        let k = chosen[i];
        let up = Vec2::new(u.light_position[0][i], u.light_position[1][i]);
        let p = Vec3::new(h.p[0][i], h.p[1][i], h.p[2][i]);
        let got = match tables.sampled[k] {
            LightId::Area => area(tables, scene, p, u.light_member[i], up),
            LightId::Environment => scene.environment().and_then(|env| {
                let e = env.sample(up)?;
                Some((e.wi, e.radiance / e.pdf, e.pdf, e.wi, true))
            }),
            LightId::Punctual(_) => None,
        };
        if let Some((wi, incident, pdf, target, distant)) = got {
            for c in 0..3 {
                s.wi[c][i] = wi[c];
                s.incident[c][i] = incident[c];
                s.target[c][i] = target[c];
            }
            (s.pdf[i], s.distant[i], s.ok[i]) = (pdf, distant, true);
        }
    }
    s
}

/// A point on the emissive triangles for the receiver at `p` ([`lights::area`] without
/// the hit record): direction, radiance over pdf, solid-angle pdf, the point; `None` when
/// the density is degenerate or a single-sided emitter faces away.
#[inline(always)]
fn area(
    tables: &Tables,
    scene: &Scene,
    p: Vec3,
    uc: f32,
    up: Vec2,
) -> Option<(Vec3, Vec3, f32, Vec3, bool)> {
    let s = scene.area_lights().sample(p, uc, up)?;
    if s.pdf.is_nan() || s.pdf <= 0.0 {
        return None;
    }
    let (rgb, two_sided) = tables.emission[scene.triangle(s.prim).material() as usize];
    if !two_sided && s.normal.dot(s.wi) >= 0.0 {
        return None;
    }
    Some((s.wi, Vec3::from_array(rgb) / s.pdf, s.pdf, s.point, false))
}
