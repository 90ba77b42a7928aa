//! Integrators: how radiance along camera rays is estimated. A closed enum; each variant's
//! maths lives in its own module, and per-hit shading shared between them lives in
//! [`shading`].

pub mod lights;
pub mod path;
pub mod photon_map;
pub mod shading;
pub mod sppm;
pub mod whitted;

use crate::math::{Ray, Rng};
use crate::scene::Scene;
use crate::spectrum::Carrier;
#[allow(unused_imports)]
use glam::Vec3;

/// The rendering method (`--method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Recursive ray tracing after the seed paper §4: direct light from punctual lights,
    /// Fresnel-weighted reflection and refraction branches.
    Whitted,
    /// Unidirectional path tracing with next-event estimation and MIS.
    Path,
    /// Classic photon mapping (Jensen): direct light by shadow rays, a caustic map gathered
    /// at the first diffuse hit, a global map reached by final gathering.
    Photon,
    /// Stochastic progressive photon mapping in passes (Hachisuka & Jensen 2009, radius
    /// sequence of Knaus & Zwicker 2011).
    Sppm,
    /// `Sppm` when the scene has caustic paths, `Path` otherwise ([`Method::resolve`]); an
    /// unresolved `Auto` renders as `Path`.
    Auto,
}

impl Method {
    /// Resolves [`Method::Auto`] for `scene`: SPPM when light can reach a diffuse-like
    /// surface through specular ones (found by tracing a few thousand photons:
    /// [`crate::photon::trace::has_caustic_paths`]), the path tracer otherwise. Returns the
    /// method and the reason.
    pub fn resolve(self, scene: &Scene) -> (Method, Option<String>) {
        if self != Method::Auto {
            return (self, None);
        }
        let emitter = crate::photon::emit::PhotonEmitter::new(scene);
        if !emitter.is_empty() && crate::photon::trace::has_caustic_paths(scene, &emitter, 4096) {
            (
                Method::Sppm,
                Some("--method auto: light reaches diffuse surfaces through specular ones (caustics): SPPM".into()),
            )
        } else {
            (
                Method::Path,
                Some("--method auto: no caustic paths found: path tracer".into()),
            )
        }
    }
}

/// Photon-mapping settings (`--method photon` and `sppm`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhotonSettings {
    /// Photons per pass (SPPM) or in total (photon); 0 = one per pixel (SPPM) or 500 000.
    pub photons: u64,
    /// Initial (SPPM) or largest (photon) gather radius in scene units; `None` = from the
    /// pixel footprint at the visible points.
    pub radius: Option<f32>,
    /// SPPM radius-reduction parameter α ∈ (0, 1) (Knaus & Zwicker 2011: r²ᵢ₊₁ = r²ᵢ (i+α)/(i+1)).
    pub alpha: f32,
    /// SPPM passes.
    pub passes: u32,
    /// Photon Russian roulette rule.
    pub roulette: crate::photon::trace::Roulette,
    /// Photons in a caustic-map estimate (photon).
    pub k_caustic: usize,
    /// Photons in a global-map estimate (photon, at final-gather hits).
    pub k_global: usize,
}

impl Default for PhotonSettings {
    fn default() -> Self {
        PhotonSettings {
            photons: 0,
            radius: None,
            alpha: 2.0 / 3.0,
            passes: 64,
            roulette: crate::photon::trace::Roulette::Throughput,
            k_caustic: 64,
            k_global: 64,
        }
    }
}

/// Per-thread state an integrator carries along one camera sample.
pub struct Context {
    /// Random numbers for this pixel sample.
    pub rng: Rng,
    /// Rays traced so far (closest-hit and shadow).
    pub rays: u64,
}

/// Integrator settings.
#[derive(Debug, Clone, Copy)]
pub struct Integrator {
    /// Which method.
    pub method: Method,
    /// Maximum recursion depth (specular bounces count too).
    pub max_depth: u32,
    /// Photon-mapping settings (ignored by Whitted and path).
    pub photon: PhotonSettings,
}

impl Integrator {
    /// Radiance arriving along `ray` at the sample's wavelengths `lambda` (linear RGB when
    /// `C` is [`Vec3`]), for the per-sample methods; the photon methods need their maps or
    /// passes ([`crate::render`]) and fall back to the path tracer here.
    pub fn radiance<C: Carrier>(
        &self,
        scene: &Scene,
        ray: &Ray,
        lambda: C::Lambda,
        ctx: &mut Context,
    ) -> C {
        match self.method {
            Method::Whitted => whitted::radiance(scene, ray, self.max_depth, lambda, ctx),
            Method::Path | Method::Photon | Method::Sppm | Method::Auto => {
                path::radiance(scene, ray, self.max_depth, lambda, ctx)
            }
        }
    }
}
