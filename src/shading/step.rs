//! The per-hit step every loop takes — the path tracer's camera paths, the Whitted tracer,
//! photon paths and photon mapping's final gather — written once, in two phases:
//!
//! 1. [`arrive`]: trace the ray to the next surface (one ray counted), take the
//!    Beer–Lambert transmittance of the segment in the current medium, find the surface
//!    really met ([`meet`]: coincident faces of touching objects) and evaluate its material
//!    there ([`Arrival`]). `None` when the ray escapes.
//! 2. [`Arrival::event`]: glTF BLEND coverage (stochastic: the surface is there with
//!    probability α, otherwise the path passes straight through, unchanged), then the BSDF
//!    at the hit ([`bsdf_at`], η from the path's media), keeping only the hero wavelength
//!    past a dispersive interface (or, for the path tracer at a rough one, all 4 with
//!    spectral MIS: [`Arrival::event_lanes`], [`spectral_mis`]), and the shading frame
//!    ([`Surface`]).
//!
//! What differs between the loops stays in them: what they do on arrival (emission with
//! MIS for camera paths, the light's range window for photons, Whitted's deterministic
//! branching, which uses phase 1 only), the transport mode they sample in, next-event
//! estimation and their termination rules.
//!
//! Frames: world space, except `wo` and sampled directions, which are in the local frame of
//! the outward shading normal (the BSDF's frame). Transmittance is per unit radiance or
//! flux (dimensionless).

use super::material_bsdf::{bsdf_at, lane_etas, sample_bsdf};
use super::spectral_mis;
use crate::bsdf::{Bsdf, BsdfSample, TransportMode};
use crate::interaction::{CoincidentFaces, SurfaceHit};
use crate::material::AlphaMode;
use crate::material::{Material, ShadingPoint};
use crate::math::{Frame, Ray, Rng};
use crate::medium_stack::MediumStack;
use crate::sampler::Bounce;
use crate::scene::{Scene, Triangle};
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

/// The surface a path really meets at `hit`, for touching objects (the intersection layer's
/// [`Scene::coincident`], probed only at volume boundaries): a non-volumetric face lying
/// on the boundary wins — water filling an opaque mug meets the mug's wall, still in the
/// water — and otherwise the coincident volume faces are returned to be crossed as one
/// interface. Either way rays leave from the returned hit, which clears all of them.
pub fn meet(scene: &Scene, hit: SurfaceHit) -> (SurfaceHit, CoincidentFaces) {
    let touches = scene.triangle(hit.prim).has(Triangle::TOUCHES);
    if !touches || !scene.materials()[hit.material as usize].is_volume() {
        return (hit, CoincidentFaces::default());
    }
    let (merged, set) = scene.coincident(&hit);
    let solid = set
        .iter()
        .find(|c| !scene.materials()[c.material as usize].is_volume());
    match solid {
        Some(solid) => (solid, CoincidentFaces::default()),
        None => (merged, set.faces()),
    }
}

/// A ray arrived at a surface: phase 1 of the step.
#[derive(Debug, Clone, Copy)]
pub struct Arrival<'s, C: Carrier> {
    /// The surface really met ([`meet`]); rays leave from it.
    pub hit: SurfaceHit,
    /// Coincident volume faces crossed with it as one interface.
    pub coincident: CoincidentFaces,
    /// Its material.
    pub mat: &'s Material,
    /// The material at the hit (textures evaluated).
    pub sp: ShadingPoint,
    /// Beer–Lambert transmittance of the segment just travelled, in the medium the ray was
    /// in ([`crate::medium_stack::segment_medium`]; one outside every medium).
    pub transmittance: C,
}

/// Traces `ray` (one ray added to `rays`) to the surface it meets, inside `media` at the
/// wavelengths `lambda`: `None` if it escapes the scene.
pub fn arrive<'s, C: Carrier>(
    scene: &'s Scene,
    ray: &Ray,
    media: &MediumStack,
    lambda: &C::Lambda,
    rays: &mut u64,
) -> Option<Arrival<'s, C>> {
    *rays += 1;
    arrival(scene, ray, scene.intersect(ray), media, lambda)
}

/// [`arrive`] for `ray` already traced ([`Scene::intersect`] or a lane of
/// [`Scene::intersect_packet`]) to `hit`. The Beer–Lambert segment starts where the ray
/// really starts ([`Ray::skipped`] before its origin).
#[inline]
pub fn arrival<'s, C: Carrier>(
    scene: &'s Scene,
    ray: &Ray,
    hit: Option<SurfaceHit>,
    media: &MediumStack,
    lambda: &C::Lambda,
) -> Option<Arrival<'s, C>> {
    let hit = hit?;
    let transmittance = match crate::medium_stack::segment_medium(scene, media, &hit) {
        Some(m) => {
            let x = hit.t + ray.skipped;
            scene.materials()[m as usize].transmittance_at::<C>(x, lambda)
        }
        None => C::ONE,
    };
    let (hit, coincident) = meet(scene, hit);
    let mat = &scene.materials()[hit.material as usize];
    let sp = mat.shade(&scene.textures_at(hit.uv));
    Some(Arrival {
        hit,
        coincident,
        mat,
        sp,
        transmittance,
    })
}

/// What a path does at an [`Arrival`]: phase 2 of the step.
// Returned by value and matched at once on every hit: boxing the large variant would cost
// an allocation per hit.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy)]
pub enum Event<C: Carrier> {
    /// The uncovered part of an alpha-BLEND surface: the path continues along this ray
    /// with its throughput, media and wavelengths unchanged.
    PassThrough(Ray),
    /// The path scatters at the surface.
    Scatter(Surface<C>),
}

/// A surface a path scatters at: its BSDF in the shading frame.
#[derive(Debug, Clone, Copy)]
pub struct Surface<C: Carrier> {
    /// The hit (rays leave from it).
    pub hit: SurfaceHit,
    /// The BSDF (one lobe chosen by the transmission weight).
    pub bsdf: Bsdf<C>,
    /// Frame of the outward shading normal (the BSDF's frame).
    pub frame: Frame,
    /// Direction back along the incoming ray, in `frame`.
    pub wo: Vec3,
    /// The media the path is in on arrival.
    media: MediumStack,
    /// The media on the far side of a refraction (equal to `media` unless a volume is
    /// entered or left).
    beyond: MediumStack,
    /// At a rough dispersive dielectric met by [`Arrival::event_lanes`]: the BSDF's η for
    /// each of the 4 lanes (lane 0 = the hero's, in `bsdf`), for spectral MIS
    /// ([`spectral_mis`]); `None` otherwise.
    lanes: Option<[f32; 4]>,
}

impl<C: Carrier> Arrival<'_, C> {
    /// Phase 2 of the step for a path inside `media`: BLEND coverage with one random number
    /// (only for BLEND materials), then the BSDF with another (the lobe choice); past a
    /// dispersive interface the path keeps only its hero wavelength: `beta` and `lambda`
    /// are updated ([`Carrier::keep_hero`], pbrt-v4 `TerminateSecondary`).
    pub fn event(
        &self,
        scene: &Scene,
        media: MediumStack,
        beta: &mut C,
        lambda: &mut C::Lambda,
        u: &mut impl StepNumbers,
    ) -> Event<C> {
        self.step(scene, media, beta, lambda, u, false)
    }

    /// [`Arrival::event`], except that at a ROUGH dispersive dielectric the path keeps its
    /// 4 lanes: the surface gets per-lane indices and its [`Surface::sample_mis`] and
    /// [`Surface::eval_mis`] weight the lanes by spectral MIS ([`spectral_mis`]). Smooth
    /// dispersive interfaces still keep the hero only. For the path tracer's camera paths.
    pub fn event_lanes(
        &self,
        scene: &Scene,
        media: MediumStack,
        beta: &mut C,
        lambda: &mut C::Lambda,
        u: &mut impl StepNumbers,
    ) -> Event<C> {
        self.step(scene, media, beta, lambda, u, true)
    }

    fn step(
        &self,
        scene: &Scene,
        media: MediumStack,
        beta: &mut C,
        lambda: &mut C::Lambda,
        u: &mut impl StepNumbers,
        keep_lanes: bool,
    ) -> Event<C> {
        // glTF BLEND: stochastic coverage; the uncovered part continues straight on.
        if matches!(self.mat.desc.alpha_mode, AlphaMode::Blend) && u.alpha() >= self.sp.alpha {
            return Event::PassThrough(self.hit.spawn_ray(-self.hit.wo));
        }
        // The layer number decides only between a partial transmission and the rest.
        let u_layer = if self.sp.transmission > 0.0 && self.sp.transmission < 1.0 {
            u.layer()
        } else {
            u.skip_layer();
            0.0
        };
        let (bsdf, beyond, dispersive) = bsdf_at::<C>(
            scene,
            &self.hit,
            &self.coincident,
            &self.sp,
            media,
            u_layer,
            lambda,
        );
        let mut lanes = None;
        if dispersive {
            let rough = bsdf.interface_eta().is_some() && !bsdf.is_delta();
            match C::lanes_nm(lambda) {
                Some(nm) if keep_lanes && rough && !C::is_hero_only(lambda) => {
                    lanes = Some(lane_etas(scene, &self.hit, &self.coincident, media, nm));
                }
                _ => *beta = beta.keep_hero(lambda),
            }
        }
        let frame = super::frame::shading_frame(scene, &self.hit, &self.sp.anisotropy);
        Event::Scatter(Surface {
            hit: self.hit,
            bsdf,
            frame,
            wo: frame.to_local(self.hit.wo),
            media,
            beyond,
            lanes,
        })
    }
}

/// Where the step's two random numbers come from: BLEND coverage (drawn only at BLEND
/// materials) and the material layer, in that order. A plain [`Rng`] draws both from its
/// stream (photon paths); a camera path's [`Bounce`] draws the layer from its scheduled
/// dimension.
pub trait StepNumbers {
    /// The number compared with a BLEND material's α.
    fn alpha(&mut self) -> f32;
    /// The number choosing the material layer.
    fn layer(&mut self) -> f32;
    /// Passes over the layer number where only one layer can be chosen.
    fn skip_layer(&mut self);
}

impl StepNumbers for Rng {
    fn alpha(&mut self) -> f32 {
        self.next_f32()
    }
    fn layer(&mut self) -> f32 {
        self.next_f32()
    }
    fn skip_layer(&mut self) {
        self.next_f32();
    }
}

impl StepNumbers for Bounce<'_> {
    fn alpha(&mut self) -> f32 {
        Bounce::alpha(self)
    }
    fn layer(&mut self) -> f32 {
        Bounce::layer(self)
    }
    fn skip_layer(&mut self) {
        Bounce::skip_layer(self)
    }
}

impl<C: Carrier> Surface<C> {
    /// A BSDF sample at `wo` ([`sample_bsdf`]).
    pub fn sample(&self, uc: f32, u: Vec2, mode: TransportMode) -> Option<BsdfSample<C>> {
        sample_bsdf(&self.bsdf, self.wo, uc, u, mode)
    }

    /// A BSDF sample for a path carrying `lambda`: at a rough dispersive dielectric
    /// ([`Arrival::event_lanes`]) f per lane and the hero-marginal pdf, updating the hero
    /// weights ([`spectral_mis::sample`]); elsewhere [`Surface::sample`].
    pub fn sample_mis(
        &self,
        uc: f32,
        u: Vec2,
        mode: TransportMode,
        lambda: &mut C::Lambda,
    ) -> Option<BsdfSample<C>> {
        match &self.lanes {
            Some(etas) => spectral_mis::sample(&self.bsdf, etas, self.wo, uc, u, mode, lambda),
            None => self.sample(uc, u, mode),
        }
    }

    /// f(wo, wi) and the pdf BSDF sampling ([`Surface::sample_mis`]) has for the local
    /// `wi`: per lane and hero-marginal at a rough dispersive dielectric
    /// ([`spectral_mis::eval`]), the BSDF's eval and pdf elsewhere.
    pub fn eval_mis(&self, wi: Vec3, mode: TransportMode, lambda: &C::Lambda) -> (C, f32) {
        match &self.lanes {
            Some(etas) => spectral_mis::eval(&self.bsdf, etas, self.wo, wi, mode, lambda),
            None => (
                self.bsdf.eval(self.wo, wi, mode),
                self.bsdf.pdf(self.wo, wi, mode),
            ),
        }
    }

    /// The per-lane η at a rough dispersive dielectric met by [`Arrival::event_lanes`]
    /// (lane 0 = the hero's, in `bsdf`); `None` elsewhere.
    pub fn lane_etas(&self) -> Option<[f32; 4]> {
        self.lanes
    }

    /// The same surface for the path's lanes rotated by `k` ([`Carrier::lanes_rotated`]):
    /// at a rough dispersive dielectric the BSDF takes lane `k`'s η as the hero's and its
    /// tint and the per-lane η rotate with the lanes (each lane's value depends on its own
    /// wavelength only, so the rotation is exact); elsewhere the surface is returned as is.
    pub fn with_hero_lane(&self, k: usize) -> Surface<C> {
        let Some(etas) = self.lanes else {
            return *self;
        };
        let etas = crate::spectrum::rotate_lanes(etas, k);
        let Some(bsdf) = self.bsdf.with_lane(etas[0], k) else {
            return *self;
        };
        Surface {
            bsdf,
            lanes: Some(etas),
            ..*self
        }
    }

    /// The media after leaving along a sampled direction: those beyond the surface if the
    /// sample is a transmission, the arrival's otherwise.
    pub fn media_after(&self, transmission: bool) -> MediumStack {
        if transmission {
            self.beyond
        } else {
            self.media
        }
    }

    /// The ray leaving the surface along the local direction `wi`.
    pub fn spawn(&self, wi: Vec3) -> Ray {
        self.hit.spawn_ray(self.frame.to_world(wi))
    }
}
