//! The glTF BRDF with its specular or metal part at the kernel's lanes
//! ([`super::features::Shade::Glossy`]:
//! Lambert + GGX, KHR_materials_specular, metallic; untextured, isotropic, no layer or
//! film): the scalar BSDF itself per lane — [`Material::opaque_bsdf`] at the material's
//! one shading point ([`Material::untextured`]) and the lane's wavelengths, its eval, pdf
//! and sample ([`crate::bsdf::Bsdf`], glTF 2.0 Appendix B) in the frame
//! [`Frame::from_normal`] of the hit's shading normal, which is the scalar vertex's frame
//! for an isotropic material ([`crate::shading::frame::shading_frame`]) — so a glossy
//! lane's values are the scalar path's.
//!
//! [`bounce`] follows the BSDF sample as the scalar path does
//! ([`crate::integrator::path::state`]'s `advance`): β times f·|cos θi|/pdf, one more
//! non-delta bounce, the bounce limit and Russian roulette ([`super::shade::survive`]),
//! the sample's pdf for the MIS weight of the light the path meets next; no sample (a GGX
//! reflection under the surface, a density that is not positive) ends the path there.
//!
//! These are calls per lane over the glossy lanes (the lobe's square roots, Fresnel and
//! Smith terms are not vectorised); the lanes' other work stays in the vector loops.
//!
//! Units: f per steradian in `M` channels ([`super::colour`]); pdfs per steradian; world
//! space unless said local.

use super::colour::{spectral, take};
use super::hits::Hits;
use super::numbers::Draws;
use super::shade::{spawn, survive};
use super::state::{Rays, Throughput};
use crate::accel::packet::{lanes, LaneMask};
use crate::bsdf::{Bsdf, TransportMode};
use crate::material::Material;
use crate::math::Frame;
use crate::scene::Scene;
use crate::shading::sample_bsdf;
use crate::spectrum::{Carrier, Lambdas, SampledSpectrum};
use glam::{Vec2, Vec3};

/// Lane `i` of the hits `h` in `scene`.
type Lane<'a, const N: usize, const M: usize> = (&'a Scene, &'a Hits<N, M>, usize);

/// Lane `i`'s BSDF at the hit of `h` for a path carrying `lambda`, its frame and the local
/// direction back along the ray: the opaque glTF BRDF, or the rough dielectric of the
/// lane's η where the material transmits ([`crate::shading::bsdf_at`]: η from the volume
/// against air, the kernel's volumes being disjoint). A glossy material is untextured
/// ([`super::features`]).
#[inline]
fn lobe<C: Carrier, const N: usize, const M: usize>(
    (scene, h, i): Lane<N, M>,
    lambda: &C::Lambda,
) -> (Bsdf<C>, Frame, Vec3) {
    let m: &Material = &scene.materials()[h.material[i] as usize];
    let sp = m.untextured().expect("a glossy material is untextured");
    let frame = Frame::from_normal(Vec3::new(h.ns[0][i], h.ns[1][i], h.ns[2][i]));
    let wo = frame.to_local(Vec3::new(h.wo[0][i], h.wo[1][i], h.wo[2][i]));
    let bsdf = if sp.transmission > 0.0 {
        m.transmission_bsdf::<C>(sp, Some(h.eta[i]), lambda)
    } else {
        m.opaque_bsdf::<C>(sp, lambda)
    };
    (bsdf, frame, wo)
}

/// f (in `M` channels) toward the unit world direction `wi` and the density with which
/// the lobe's sampling picks it, at lane `at`.
#[inline]
fn eval_in<C: Carrier, const N: usize, const M: usize>(
    at: Lane<N, M>,
    lambda: &C::Lambda,
    wi: Vec3,
) -> ([f32; M], f32) {
    let (b, frame, wo) = lobe::<C, N, M>(at, lambda);
    let wi = frame.to_local(wi);
    let mode = TransportMode::Radiance;
    (take(b.eval(wo, wi, mode).to_lanes()), b.pdf(wo, wi, mode))
}

/// f (in `M` channels at the lane's wavelengths `lam`) toward the unit world direction
/// `wi` and the lobe's density of sampling it, at glossy lane `i` of `h`.
#[inline]
pub fn eval<const N: usize, const M: usize>(
    scene: &Scene,
    h: &Hits<N, M>,
    (i, lam): (usize, &Lambdas),
    wi: [f32; 3],
) -> ([f32; M], f32) {
    let wi = Vec3::from_array(wi);
    if spectral::<M>() {
        eval_in::<SampledSpectrum, N, M>((scene, h, i), lam, wi)
    } else {
        eval_in::<Vec3, N, M>((scene, h, i), &(), wi)
    }
}

/// A sample of the lobe taken at a lane (world space).
struct Sampled<X> {
    /// The direction.
    wi: [f32; 3],
    /// f·|cos θi|/pdf in the lane's channels.
    weight: X,
    /// The sample's density.
    pdf: f32,
    /// It crossed the surface: from outside (`wo` on the normal's side) into the volume,
    /// or out of it.
    crossed: Option<bool>,
}

/// A sample of the lobe at lane `i` with the numbers `uc` (lobe) and `u` (direction);
/// `None` when the lobe gives none the path can use ([`sample_bsdf`]).
#[inline]
fn sample_in<C: Carrier, const N: usize, const M: usize>(
    at: Lane<N, M>,
    lambda: &C::Lambda,
    (uc, u): (f32, Vec2),
) -> Option<Sampled<[f32; M]>> {
    let (b, frame, wo) = lobe::<C, N, M>(at, lambda);
    let bs = sample_bsdf(&b, wo, uc, u, TransportMode::Radiance)?;
    Some(Sampled {
        wi: frame.to_world(bs.wi).to_array(),
        weight: take((bs.f * (bs.wi.z.abs() / bs.pdf)).to_lanes()),
        pdf: bs.pdf,
        crossed: bs.transmission.then_some(wo.z > 0.0),
    })
}

/// [`sample_in`] at the lane's wavelengths `lam`.
#[inline]
fn sample<const N: usize, const M: usize>(
    scene: &Scene,
    h: &Hits<N, M>,
    (i, lam): (usize, &Lambdas),
    u: (f32, Vec2),
) -> Option<Sampled<[f32; M]>> {
    if spectral::<M>() {
        sample_in::<SampledSpectrum, N, M>((scene, h, i), lam, u)
    } else {
        sample_in::<Vec3, N, M>((scene, h, i), &(), u)
    }
}

/// The glossy bounce at the lanes `on` of `h` (in `scene`, at the lanes' wavelengths
/// `lam`) with the numbers `u` (lobe, direction, roulette): β times the sample's weight,
/// the bounce limit and roulette, the MIS record; the next ray into `next`. Returns the
/// lanes whose path ends here and those that played the roulette.
#[inline(always)]
pub fn bounce<const N: usize, const M: usize>(
    (scene, h, lam): (&Scene, &Hits<N, M>, &[Lambdas; N]),
    on: LaneMask,
    u: &Draws<N>,
    max_depth: u32,
    (st, next): (&mut Throughput<N, M>, &mut Rays<N>),
) -> (LaneMask, LaneMask) {
    let (mut ends, mut played): (LaneMask, LaneMask) = (0, 0);
    for i in lanes(on) {
        let ud = Vec2::new(u.direction[0][i], u.direction[1][i]);
        let Some(s) = sample::<N, M>(scene, h, (i, &lam[i]), (u.lobe[i], ud)) else {
            ends |= 1 << i;
            continue;
        };
        (0..M).for_each(|c| st.beta[c][i] *= s.weight[c]);
        if let Some(entered) = s.crossed {
            // Radiance across the interface: η'² into the η scale roulette reads.
            let etap = if entered { h.eta[i] } else { 1.0 / h.eta[i] };
            st.eta_scale[i] *= etap * etap;
            st.medium[i] = if entered { h.material[i] + 1 } else { 0 };
        }
        let (end, play) = survive(true, i, u.roulette[i], max_depth, st);
        ends |= u32::from(end) << i;
        played |= u32::from(play) << i;
        st.bounced(true, h, i, (s.pdf, false));
        spawn(true, h, i, s.wi, next);
    }
    (ends, played)
}
