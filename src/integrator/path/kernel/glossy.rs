//! The glTF BRDF with its specular or metal part at the kernel's lanes
//! ([`super::features::Shade::Glossy`]:
//! Lambert + GGX, KHR_materials_specular, metallic; untextured, isotropic, no layer or
//! film), and rough glass: the scalar BSDF itself per lane ([`Lobes`], built once a
//! vertex) — [`Material::opaque_bsdf`] or [`Material::transmission_bsdf`] at the
//! material's one shading point ([`Material::untextured`]) and the lane's wavelengths, its
//! eval, pdf and sample ([`crate::bsdf::Bsdf`], glTF 2.0 Appendix B) in the frame
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
use crate::material::{Material, ShadingPoint};
use crate::math::Frame;
use crate::scene::Scene;
use crate::shading::sample_bsdf;
use crate::spectrum::{Carrier, Lambdas, SampledSpectrum};
use glam::{Vec2, Vec3};

/// A lane's lobe in the carrier of its transport.
#[derive(Clone, Copy)]
enum Carried {
    Rgb(Bsdf<Vec3>),
    Spectral(Bsdf<SampledSpectrum>),
}

/// A glossy lane's BSDF at its hit, its frame and the local direction back along the ray.
#[derive(Clone, Copy)]
struct Lobe {
    bsdf: Carried,
    frame: Frame,
    wo: Vec3,
}

/// The BSDFs of one vertex's glossy lanes (`None` at the other lanes), built once for
/// next-event estimation ([`super::shade::Toward`]) and the bounce ([`bounce`]).
pub struct Lobes<const N: usize>([Option<Lobe>; N]);

impl<const N: usize> Lobes<N> {
    /// No glossy lane.
    pub fn none() -> Self {
        Lobes([None; N])
    }

    /// The BSDFs at the lanes `on` of `h` (in `scene`) for paths at the lanes' wavelengths
    /// `lam`: the opaque glTF BRDF, or the rough dielectric of the lane's η where the
    /// material transmits ([`crate::shading::bsdf_at`]: η from the volume against air, the
    /// kernel's volumes being disjoint), at the material's one shading point (a glossy
    /// material is untextured: [`super::features`]).
    #[inline]
    pub fn new<const M: usize>(
        scene: &Scene,
        h: &Hits<N, M>,
        lam: &[Lambdas; N],
        on: LaneMask,
    ) -> Self {
        let mut lobes = Lobes::none();
        for i in lanes(on) {
            let m: &Material = &scene.materials()[h.material[i] as usize];
            let sp = m.untextured().expect("a glossy material is untextured");
            let frame = Frame::from_normal(Vec3::new(h.ns[0][i], h.ns[1][i], h.ns[2][i]));
            let wo = frame.to_local(Vec3::new(h.wo[0][i], h.wo[1][i], h.wo[2][i]));
            let eta = (sp.transmission > 0.0).then_some(h.eta[i]);
            let bsdf = if spectral::<M>() {
                Carried::Spectral(at(m, sp, eta, &lam[i]))
            } else {
                Carried::Rgb(at(m, sp, eta, &()))
            };
            lobes.0[i] = Some(Lobe { bsdf, frame, wo });
        }
        lobes
    }

    /// f (in `M` channels) toward the unit world direction `wi` and the density with which
    /// the lobe's sampling picks it, at glossy lane `i` (`None` at another lane).
    #[inline]
    pub fn eval<const M: usize>(&self, i: usize, wi: [f32; 3]) -> Option<([f32; M], f32)> {
        let l = self.0[i].as_ref()?;
        let wi = l.frame.to_local(Vec3::from_array(wi));
        Some(match &l.bsdf {
            Carried::Rgb(b) => eval_in(b, l.wo, wi),
            Carried::Spectral(b) => eval_in(b, l.wo, wi),
        })
    }

    /// A sample of the lobe at glossy lane `i` with the numbers `u` (lobe, direction);
    /// `None` at another lane or when the lobe gives none the path can use
    /// ([`sample_bsdf`]).
    #[inline]
    fn sample<const M: usize>(&self, i: usize, u: (f32, Vec2)) -> Option<Sampled<[f32; M]>> {
        let l = self.0[i].as_ref()?;
        match &l.bsdf {
            Carried::Rgb(b) => sample_in(b, (&l.frame, l.wo), u),
            Carried::Spectral(b) => sample_in(b, (&l.frame, l.wo), u),
        }
    }
}

/// The BSDF of `m` at its point `sp` for a path carrying `lambda`: the rough dielectric of
/// η `eta` where given, else the opaque glTF BRDF.
#[inline]
fn at<C: Carrier>(
    m: &Material,
    sp: &ShadingPoint,
    eta: Option<f32>,
    lambda: &C::Lambda,
) -> Bsdf<C> {
    match eta {
        Some(eta) => m.transmission_bsdf::<C>(sp, Some(eta), lambda),
        None => m.opaque_bsdf::<C>(sp, lambda),
    }
}

/// f of `b` (in `M` channels) from the local `wo` toward the local `wi`, and its density of
/// sampling `wi`.
#[inline]
fn eval_in<C: Carrier, const M: usize>(b: &Bsdf<C>, wo: Vec3, wi: Vec3) -> ([f32; M], f32) {
    let mode = TransportMode::Radiance;
    (take(b.eval(wo, wi, mode).to_lanes()), b.pdf(wo, wi, mode))
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

/// A sample of `b` in the frame `frame` from the local `wo` with the numbers `uc` (lobe)
/// and `u` (direction).
#[inline]
fn sample_in<C: Carrier, const M: usize>(
    b: &Bsdf<C>,
    (frame, wo): (&Frame, Vec3),
    (uc, u): (f32, Vec2),
) -> Option<Sampled<[f32; M]>> {
    let bs = sample_bsdf(b, wo, uc, u, TransportMode::Radiance)?;
    Some(Sampled {
        wi: frame.to_world(bs.wi).to_array(),
        weight: take((bs.f * (bs.wi.z.abs() / bs.pdf)).to_lanes()),
        pdf: bs.pdf,
        crossed: bs.transmission.then_some(wo.z > 0.0),
    })
}

/// The glossy bounce at the lanes `on` of `h` with their BSDFs `lobes` and the numbers `u`
/// (lobe, direction, roulette): β times the sample's weight, the bounce limit and roulette,
/// the MIS record; the next ray into `next`. Returns the lanes whose path ends here and
/// those that played the roulette.
#[inline(always)]
pub fn bounce<const N: usize, const M: usize>(
    (lobes, h): (&Lobes<N>, &Hits<N, M>),
    on: LaneMask,
    u: &Draws<N>,
    max_depth: u32,
    (st, next): (&mut Throughput<N, M>, &mut Rays<N>),
) -> (LaneMask, LaneMask) {
    let (mut ends, mut played): (LaneMask, LaneMask) = (0, 0);
    for i in lanes(on) {
        let ud = Vec2::new(u.direction[0][i], u.direction[1][i]);
        let Some(s) = lobes.sample::<M>(i, (u.lobe[i], ud)) else {
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
