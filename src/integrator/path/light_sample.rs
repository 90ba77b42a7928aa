//! Next-event estimation of a camera path's vertex ([`next_event`], the shared estimator
//! [`crate::shading::next_event`] with the path's [`Receiver`]): one light chosen by the
//! scene's light sampler, from a surface (its BSDF, per lane at a rough dispersive
//! interface) or from a scattering event in a medium (its phase function), MIS-weighted
//! against the vertex's own sampling (power heuristic). The shadow ray is left to the
//! caller ([`super::walk::Pending`]), with the media it starts in when the scene has
//! media, for its transmittance.
//!
//! Units: the light sample's value is f · incident · |cos| (radiance per unit throughput);
//! directions in world space unless said local.

use crate::bsdf::TransportMode;
use crate::interaction::SurfaceHit;
use crate::math::Ray;
use crate::medium_stack::MediumStack;
use crate::sampler::Bounce;
use crate::scene::Scene;
use crate::shading::media::Through;
use crate::shading::next_event::{self, Chosen, Eval, Receiver};
use crate::shading::Surface;
use crate::spectrum::Carrier;
use crate::volume::Phase;
use glam::Vec3;

/// A vertex's next-event record: the contribution of a light sample (the shading layer's
/// [`crate::shading::lights::LightSample`], weighted and carried) and the shadow ray that decides it:
/// `value` counts if nothing blocks `shadow` (times the shadow ray's transmittance through
/// the media it starts in, `through`, in a scene with media); with no shadow ray, `value`
/// is zero.
pub(super) struct NextEvent<C: Carrier> {
    pub shadow: Option<Ray>,
    /// The direction toward the light (world, unit; zero without a sample).
    pub wi: Vec3,
    pub value: C,
    pub through: Option<Through>,
}

impl<C: Carrier> NextEvent<C> {
    const NONE: Self = NextEvent {
        shadow: None,
        wi: Vec3::ZERO,
        value: C::ZERO,
        through: None,
    };
}

/// Where next-event estimation starts: a surface, or a point in a medium.
#[derive(Clone, Copy)]
pub(super) enum Scatterer<'a, C: Carrier> {
    /// A surface vertex.
    Surface(&'a Surface<C>),
    /// A scattering event in a medium: the point ([`SurfaceHit::in_medium`]), its phase
    /// function and the media the path is in there.
    Medium {
        hit: SurfaceHit,
        phase: Phase,
        media: MediumStack,
    },
}

impl<C: Carrier> Scatterer<'_, C> {
    fn hit(&self) -> &SurfaceHit {
        match self {
            Scatterer::Surface(s) => &s.hit,
            Scatterer::Medium { hit, .. } => hit,
        }
    }

    /// f and |cos θ| (the phase function's value and 1 in a medium) toward the world
    /// direction `wi`, and the density with which the vertex's own sampling picks `wi` (the
    /// hero-marginal one at a rough dispersive interface).
    fn eval(&self, wi: Vec3, lambda: &C::Lambda) -> (C, f32, f32) {
        match self {
            Scatterer::Surface(s) => {
                let wi_local = s.frame.to_local(wi);
                let (f, pdf) = s.eval_mis(wi_local, TransportMode::Radiance, lambda);
                (f, wi_local.z.abs(), pdf)
            }
            Scatterer::Medium { hit, phase, .. } => {
                let p = phase.eval(hit.wo, wi);
                (C::splat(p), 1.0, p)
            }
        }
    }

    /// Where a shadow ray leaving toward `wi` starts: the media beyond or before a
    /// surface, or a medium's point at the fine scale (its walk's scale and band are the
    /// caller's, [`super::in_medium`]).
    fn through(&self, wi: Vec3) -> Through {
        match self {
            Scatterer::Surface(s) => {
                let wi_local = s.frame.to_local(wi);
                Through::surface(s.media_after(wi_local.z * s.wo.z < 0.0))
            }
            Scatterer::Medium { media, .. } => Through {
                from_point: true,
                ..Through::surface(*media)
            },
        }
    }
}

/// The path's side of the shared estimator ([`shading::next_event`]): the scatterer's f,
/// |cos| and density, and the power heuristic against the vertex's own sampling (weight 1
/// without MIS or for a delta light).
struct PathReceiver<'a, 'b, C: Carrier> {
    at: &'a Scatterer<'b, C>,
    use_mis: bool,
}

impl<C: Carrier> Receiver<C> for PathReceiver<'_, '_, C> {
    fn hit(&self) -> &SurfaceHit {
        self.at.hit()
    }

    fn eval(&self, wi: Vec3, lambda: &C::Lambda) -> Option<Eval<C>> {
        let (f, cos, pdf) = self.at.eval(wi, lambda);
        Some(Eval { f, cos, pdf })
    }

    fn weight(&self, chosen: &Chosen<'_>, eval: &Eval<C>) -> Option<f32> {
        Some(match chosen.pdf() {
            Some(lp) if self.use_mis => mis(lp, eval.pdf),
            _ => 1.0,
        })
    }
}

/// Next-event estimation at `at` ([`next_event::one`]): one light, chosen by the scene's
/// light sampler ([`Scene::light_sampler`](crate::scene::Scene)), with the shadow ray left
/// to the caller (counted in `rays` here). With `use_mis` false the light sample gets the
/// full weight (the path stops here, so BSDF sampling will not find the light). In a scene
/// with media the shadow ray carries the media it starts in, for its transmittance.
pub(super) fn next_event<C: Carrier>(
    scene: &Scene,
    at: &Scatterer<'_, C>,
    lambda: &C::Lambda,
    use_mis: bool,
    u: &mut Bounce<'_>,
    rays: &mut u64,
) -> NextEvent<C> {
    let r = PathReceiver { at, use_mis };
    let Some(e) = next_event::one(scene, &r, lambda, u, rays) else {
        return NextEvent::NONE;
    };
    NextEvent {
        shadow: Some(e.shadow),
        wi: e.wi,
        value: e.value,
        through: scene.has_media().then(|| at.through(e.wi)),
    }
}

/// Power heuristic with β = 2.
pub(super) fn mis(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 {
        a2 / (a2 + b2)
    } else {
        0.0
    }
}
