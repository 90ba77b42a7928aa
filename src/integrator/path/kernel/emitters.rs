//! Light with an area or at infinity in the kernel, as the scalar path tracer takes it
//! ([`crate::integrator::path::vertex`], [`crate::shading::next_event`]):
//! - what a path meets ([`arrive`]): the emission of the surface hit (its emitting side
//!   only) and the environment along a ray that escapes, each times β and MIS-weighted
//!   against the next-event estimation that could have sampled it — the power heuristic
//!   of the previous bounce's BSDF pdf and the light's solid-angle pdf (the light
//!   sampler's pmf times [`lights::area_pdf`] or [`lights::environment_pdf`]), weight 1 for
//!   camera rays and after delta bounces;
//! - next-event estimation at Lambert and glossy lanes ([`next_event`]): one light chosen uniformly
//!   among the scene's light sampler's (its [`LightId`] order, pmf 1/n), a punctual one by
//!   [`super::shade::light`], an emissive triangle by the scene's area lights (the triangle
//!   by power with the member number, the point uniform by area with the position numbers,
//!   [`crate::light::area::AreaLights::sample`]; single-sided emitters seen from behind
//!   give nothing) or a direction of the environment ([`crate::light::env::Environment::sample`]
//!   with the position numbers), weighted by the power heuristic against the density of
//!   the lane's own BSDF sampling ([`super::shade::Toward`]: |cos θ|/π at a Lambert lane).
//!
//! The light tables' reads (the emitting triangle's corners, a map's texels) are calls per
//! lane into the scalar code, over the lanes that need them; the weights and values are
//! plain loops over all lanes with selects.
//!
//! Emission is the scene's RGB value turned into the lane's channels at the point it is
//! weighed ([`super::colour`]): the surface's by [`super::colour::emitted`] (with the
//! exact shape it names), the environment's by [`super::colour::illuminant`] on escape and
//! [`super::colour::emitted`] for next-event estimation, as the scalar path does.
//!
//! Units: radiance in `M` channels; pdfs per steradian; world space.

use super::super::light_sample::mis;
use super::colour::{emitted, illuminant, set_lane, Channels};
use super::features::Tables;
use super::glossy::Lobes;
use super::hits::{dot, Hits, V3};
use super::numbers::Draws;
use super::shade::{aim, incident, light, Toward};
use super::state::{Rays, Throughput};
use crate::accel::packet::{lanes, LaneMask, Lanes, PacketWidth, RayPacket};
use crate::light::LightId;
use crate::scene::Scene;
use crate::shading::lights;
use crate::spectrum::Lambdas;
use glam::{Vec2, Vec3};

/// Adds to `l` the light the lanes meet: at the lanes `hit` of `h` the emission of the
/// surface toward the path, at the `alive` lanes that missed the environment along their
/// ray in `rays`, each times β of `st` and weighted against next-event estimation, at the
/// lanes' wavelengths `lam`.
#[inline(always)]
pub fn arrive<const N: usize, const M: usize>(
    (tables, scene): (&Tables, &Scene),
    rays: &RayPacket<N>,
    (h, lam): (&Hits<N, M>, &[Lambdas; N]),
    (hit, alive): (LaneMask, LaneMask),
    st: &Throughput<N, M>,
    l: &mut Channels<N, M>,
) where
    Lanes<N>: PacketWidth,
{
    let mut le: Channels<N, M> = [[0.0; N]; M];
    let mut pdf = [0.0f32; N];
    let mut shows = [false; N];
    for i in lanes(hit) {
        let m = h.material[i] as usize;
        let (rgb, two_sided) = tables.emission[m];
        let front = dot(&h.wo, &h.ng, i) > 0.0;
        shows[i] = (front || two_sided) && rgb != [0.0; 3];
        if !shows[i] {
            continue;
        }
        let e = emitted::<M>(rgb, tables.emitter_shapes[m].as_ref(), &lam[i]);
        set_lane(&mut le, i, e);
        if !st.prev_delta[i] {
            let from = Vec3::new(st.prev_p[0][i], st.prev_p[1][i], st.prev_p[2][i]);
            let at = Vec3::new(h.p[0][i], h.p[1][i], h.p[2][i]);
            pdf[i] = lights::area_pdf(scene, h.prim[i], from, at);
        }
    }
    let missed = alive & !hit;
    if let (Some(env), true) = (scene.environment(), missed != 0) {
        for i in lanes(missed) {
            let d = Vec3::new(rays.dir_x[i], rays.dir_y[i], rays.dir_z[i]).normalize();
            let e = illuminant::<M>(env.eval(d).to_array(), &lam[i]);
            shows[i] = true;
            set_lane(&mut le, i, e);
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
        for c in 0..M {
            let v = l[c][i] + st.beta[c][i] * le[c][i] * w;
            l[c][i] = if shows[i] { v } else { l[c][i] };
        }
    }
}

/// A light sample with an area or at infinity seen from a lane: the unit direction toward
/// it, radiance (RGB) over its solid-angle pdf and the emitting material (for its spectral
/// shape; `u32::MAX` for the environment), that pdf, and where the shadow ray aims (a
/// point, or a direction when `distant`).
struct Sampled<const N: usize> {
    wi: V3<N>,
    incident: V3<N>,
    material: [u32; N],
    pdf: [f32; N],
    target: V3<N>,
    distant: [bool; N],
    ok: [bool; N],
}

/// Next-event estimation at the lanes `on` of `h` (the glossy lanes' BSDFs in `lobes`) with
/// the numbers `u`: the light chosen among `tables.sampled` (pmf 1/n), its contribution
/// β · f · incident · n · |cos θ| · w
/// (unblocked, at the lanes' wavelengths `lam`) into `value`, its shadow ray into `shadow`
/// and its flag into `traced`.
#[inline(always)]
pub fn next_event<const N: usize, const M: usize>(
    (tables, scene, lam): (&Tables, &Scene, &[Lambdas; N]),
    u: &Draws<N>,
    (on, h, beta, lobes): (&[bool; N], &Hits<N, M>, &Channels<N, M>, &Lobes<N>),
    (value, shadow, traced): (&mut Channels<N, M>, &mut Rays<N>, &mut [bool; N]),
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
    let lit = (tables, inv_pmf, lam);
    light(
        lit,
        (&punctual, &pointed),
        (lobes, h, beta),
        (value, shadow, traced),
    );
    if spread == 0 {
        return;
    }
    let s = sample((tables, scene), (u, &chosen), h, spread);
    let spreads: [bool; N] = std::array::from_fn(|i| spread & (1 << i) != 0);
    let by = Toward::new(lobes, h, &spreads, &s.wi);
    let mut counts = [false; N];
    let mut scale = [0.0f32; N];
    for i in 0..N {
        counts[i] = s.ok[i] && by.counts[i];
        let w = mis(s.pdf[i] / inv_pmf, by.pdf[i]);
        scale[i] = by.cos[i] * inv_pmf * by.scale[i] * w;
        let target = [s.target[0][i], s.target[1][i], s.target[2][i]];
        aim(counts[i], h, i, (target, s.distant[i]), shadow);
        traced[i] |= counts[i];
    }
    let shape = |i: usize| {
        let m = s.material[i] as usize;
        tables.emitter_shapes.get(m).and_then(Option::as_ref)
    };
    let e = incident::<N, M>((&s.incident, &counts), shape, lam);
    for i in 0..N {
        for c in 0..M {
            let v = beta[c][i] * by.g[c][i] * e[c][i] * scale[i];
            value[c][i] = if counts[i] { v } else { value[c][i] };
        }
    }
}

/// The samples of the emissive triangles or the environment at the lanes `spread` (those
/// whose `chosen` light is one of them), from the scalar light code lane by lane.
#[inline(always)]
fn sample<const N: usize, const M: usize>(
    (tables, scene): (&Tables, &Scene),
    (u, chosen): (&Draws<N>, &[usize; N]),
    h: &Hits<N, M>,
    spread: LaneMask,
) -> Sampled<N> {
    let mut s = Sampled {
        wi: [[0.0; N]; 3],
        incident: [[0.0; N]; 3],
        material: [u32::MAX; N],
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
            LightId::Area => area(scene, p, u.light_member[i], up),
            LightId::Environment => scene.environment().and_then(|env| {
                let e = env.sample(up)?;
                Some((e.wi, e.radiance / e.pdf, e.pdf, e.wi, u32::MAX))
            }),
            LightId::Punctual(_) => None,
        };
        if let Some((wi, incident, pdf, target, material)) = got {
            let distant = material == u32::MAX;
            s.material[i] = material;
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

/// A point on the emissive triangles for the receiver at `p` ([`lights::area_at`], the
/// scalar path's sample with its textured emission): direction, radiance over pdf,
/// solid-angle pdf, the point, the emitting material; `None` when the density is
/// degenerate or a single-sided emitter faces away.
#[inline(always)]
fn area(scene: &Scene, p: Vec3, uc: f32, up: Vec2) -> Option<(Vec3, Vec3, f32, Vec3, u32)> {
    let (s, incident, _) = lights::area_at(scene, p, uc, up)?;
    let material = scene.triangle(s.prim).material();
    Some((s.wi, incident, s.pdf, s.point, material))
}
