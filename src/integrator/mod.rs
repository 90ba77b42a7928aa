//! Integrators: how radiance along camera rays is estimated. A closed enum; each variant's
//! maths lives in its own module, and per-hit shading shared between them lives in
//! [`shading`].

pub mod lights;
pub mod path;
pub mod shading;
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
}

impl Integrator {
    /// Radiance arriving along `ray` at the sample's wavelengths `lambda` (linear RGB when
    /// `C` is [`Vec3`]).
    pub fn radiance<C: Carrier>(
        &self,
        scene: &Scene,
        ray: &Ray,
        lambda: C::Lambda,
        ctx: &mut Context,
    ) -> C {
        match self.method {
            Method::Whitted => whitted::radiance(scene, ray, self.max_depth, lambda, ctx),
            Method::Path => path::radiance(scene, ray, self.max_depth, lambda, ctx),
        }
    }
}
