//! One fixed chunk of a caustic pass's photons ([`super::CausticMap::trace_pass`]): each
//! photon traced ([`crate::photon::trace`], or [`crate::photon::polarized`] for the
//! polarized hybrid) and its caustic-origin vertices kept, in photon order (the split is
//! [`super`]'s module docs). Units as there: world space, metres; a stored photon's power
//! is its flux over the photons emitted in the pass.

use super::photon_basis;
use crate::integrator::light_trace::{Splat, Splatter};
use crate::math::Rng;
use crate::photon::emit::EmittedPhoton;
use crate::photon::store::Photon;
use crate::photon::trace::{self, MediumVertex, TraceSettings};
use crate::polar::stokes::Light;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use std::cell::Cell;
use std::ops::ControlFlow;

/// How far a caustic photon is followed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Walk {
    /// Until nothing more of it can be stored: it ends at its first medium event or at a
    /// first non-delta surface event that is not caustic-origin (the render's passes).
    /// Each photon's numbers are its own stream ([`super::CausticMap::trace_pass`]), so the
    /// photons stored are those of the full walk; only the rays traced fall.
    #[default]
    UntilStored,
    /// To its end by roulette and depth (the photon budget's pilot: its rays per photon,
    /// and so the count it chooses, are those of the full walk).
    Full,
}

impl Walk {
    /// What the tracer does after an event (`Break` ends the photon,
    /// [`trace::trace_in_media`]); `stored_all`: nothing more of the photon can be stored.
    fn after(self, stored_all: bool) -> ControlFlow<()> {
        if stored_all && self == Walk::UntilStored {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

/// What one fixed chunk of a pass's photons leaves: surface photons, light tracing's
/// splats, rays traced and volume photons, in photon order.
#[derive(Default)]
pub(super) struct Chunk {
    pub(super) surface: Vec<Photon>,
    pub(super) splats: Vec<Splat>,
    pub(super) rays: u64,
    pub(super) volume: Vec<Photon>,
    /// Polarized photons: each surface photon's normalized (s₁, s₂, s₃) ([`CausticMap::stokes`]).
    pub(super) stokes: Vec<[f32; 3]>,
}

impl Chunk {
    /// Traces the photon `ph` and keeps its caustic-origin vertices. The tracer calls back
    /// at every non-delta event, surface or (in media) scattering; the first decides the
    /// photon's origin: after ≥ 1 bounce (L S+ D or L S+ M) it is stored at every non-delta
    /// surface vertex before its first scattering event in a medium (the surface map) and,
    /// if its first event scattered in a medium, there alone (the volume map: L S+ M only,
    /// [`super::volume_map`] gives the split); any other photon is not stored. Without media
    /// this is the caustic map of the module docs. The first surface vertex is flagged
    /// CAUSTIC, the later ones not ([`CausticMap::density`] can leave it to light tracing);
    /// with a `splatter`, kept surface vertices are also connected to the camera.
    ///
    /// How far the photon is followed is `walk`'s ([`Walk`]); the vertices kept are the
    /// same either way.
    pub(super) fn trace_one<C: Carrier>(
        &mut self,
        (scene, settings, splatter, walk): (&Scene, &TraceSettings, Option<&Splatter>, Walk),
        ph: &EmittedPhoton<'_>,
        lambda: C::Lambda,
        inv_n: f32,
        rng: &mut Rng,
    ) {
        let origin: Cell<Option<bool>> = Cell::new(None);
        let decide = |bounces: u32| decide_origin(&origin, bounces);
        let hero = hero_flag::<C>;
        let mut camera_rays = 0;
        let (surface, splats, volume) = (&mut self.surface, &mut self.splats, &mut self.volume);
        let scattered = Cell::new(false);
        // Nothing more of the photon is stored after a medium event (the volume map keeps
        // its first event only, the surface map no vertex after one), nor after a first
        // non-delta event that is not caustic-origin.
        let keep_volume = |v: &MediumVertex, power: C, l: &C::Lambda| {
            scattered.set(true);
            let (first, caustic_origin) = decide(v.bounces);
            if first && caustic_origin && power != C::ZERO {
                volume.push(Photon::new(v.p, v.wi, (power * inv_n).to_lanes(), hero(l)));
            }
            walk.after(true)
        };
        let keep_surface = |v: &trace::PhotonVertex<C>, l: &C::Lambda| {
            let (first, caustic_origin) = decide(v.bounces);
            if !caustic_origin {
                return walk.after(true);
            }
            if !scattered.get() && v.power != C::ZERO {
                let power = v.power * inv_n;
                if let Some(sp) = splatter.filter(|sp| first || sp.every_vertex()) {
                    splats.extend(sp.connect(v, power, l, &mut camera_rays));
                }
                let caustic = if first { Photon::CAUSTIC } else { 0 };
                surface.push(Photon::new(v.p, v.wi, power.to_lanes(), hero(l) | caustic));
            }
            ControlFlow::Continue(())
        };
        self.rays +=
            trace::trace_in_media::<C>(scene, ph, lambda, settings, rng, keep_surface, keep_volume);
        self.rays += camera_rays;
    }

    /// [`Self::trace_one`] for the polarized hybrid: the photon traced with its Stokes
    /// vector ([`crate::photon::polarized`]; no media, no light tracing: the plan and
    /// [`super::hybrid`] refuse them), each kept surface photon with its polarization in the
    /// basis [`photon_basis`] of its stored direction.
    pub(super) fn trace_polarized<C: Carrier>(
        &mut self,
        (scene, max_depth): (&Scene, u32),
        ph: &EmittedPhoton<'_>,
        lambda: C::Lambda,
        inv_n: f32,
        rng: &mut Rng,
    ) {
        let origin = Cell::new(None);
        let (surface, stokes) = (&mut self.surface, &mut self.stokes);
        let keep = |v: &trace::PhotonVertex<C>, light: &Light, l: &C::Lambda| {
            let (first, caustic_origin) = decide_origin(&origin, v.bounces);
            if !caustic_origin || v.power == C::ZERO {
                return;
            }
            let flags = hero_flag::<C>(l) | if first { Photon::CAUSTIC } else { 0 };
            let p = Photon::new(v.p, v.wi, (v.power * inv_n).to_lanes(), flags);
            let s = light.in_basis(photon_basis(&p));
            surface.push(p);
            stokes.push([s[1], s[2], s[3]]);
        };
        self.rays += crate::photon::polarized::trace::<C>(scene, ph, lambda, max_depth, rng, keep);
    }
}

/// At a photon's non-delta event after `bounces` bounces: whether it is the first (which
/// decides the photon's origin, kept in `origin`) and whether the photon is caustic-origin
/// (its first non-delta event came after ≥ 1 bounce).
pub(super) fn decide_origin(origin: &Cell<Option<bool>>, bounces: u32) -> (bool, bool) {
    let first = origin.get().is_none();
    let o = origin.get().unwrap_or(bounces > 0);
    origin.set(Some(o));
    (first, o)
}

/// [`Photon::HERO_ONLY`] for a photon that kept its hero wavelength alone, else 0.
pub(super) fn hero_flag<C: Carrier>(l: &C::Lambda) -> u32 {
    if C::is_hero_only(l) {
        Photon::HERO_ONLY
    } else {
        0
    }
}
