//! The camera subpaths of vertex connection and merging: one per pixel and pass, traced
//! with the shared per-hit step in radiance mode, its numbers from the pixel's sampler
//! (as the path tracer's). At every vertex the camera subpath reads emission (weighted
//! against next-event estimation and the light subpaths), and at every non-delta vertex it
//! samples a light (next-event estimation), connects to each vertex of the pass's light
//! subpath paired with its pixel, and merges with the light vertices within the pass's
//! radius; each contribution carries its weight from [`super::mis`].
//!
//! Units: radiance per lane of the pass's wavelengths (linear RGB for [`glam::Vec3`]).
//! Frames as in [`crate::shading::step`]. Connections run in one medium (a surface between
//! the two vertices occludes them): the segment takes that medium's Beer–Lambert
//! transmittance. Where both subpaths kept only the hero wavelength (a dispersive
//! interface on each side), their product carries 4× twice and is divided by 4 once
//! (as the photon gather's, [`crate::integrator::photon_pass::GatherLanes`]).

use super::light_paths::{LightPaths, LightVertex, AIM};
use super::mis::{Partials, Pass};
use crate::bsdf::TransportMode;
use crate::camera::Camera;
use crate::interaction::SurfaceHit;
use crate::light::LightId;
use crate::math::Ray;
use crate::medium_stack::MediumStack;
use crate::photon::emit::{PhotonEmitter, Source};
use crate::photon::grid::HashGrid;
use crate::render::Context;
use crate::sampler::Bounce;
use crate::scene::Scene;
use crate::shading::next_event::{self, Chosen, Eval, Receiver};
use crate::shading::termination::{delta_bounce, roulette, Draw};
use crate::shading::{self, Arrival, Event, Surface};
use crate::spectrum::Carrier;
use glam::Vec3;

/// Non-delta vertices after which camera subpaths play Russian roulette.
const ROULETTE_DEPTH: u32 = 3;

/// What a pass's camera subpaths read: the scene, its lights, the pass's light subpaths
/// and their grid.
pub struct CameraKit<'a, C: Carrier> {
    pub scene: &'a Scene,
    pub camera: &'a Camera,
    pub emitter: &'a PhotonEmitter,
    pub lights: &'a LightPaths<C>,
    /// The pass's light vertices by the index `grid` holds (empty without merging).
    pub merged: &'a [&'a LightVertex<C>],
    pub grid: &'a HashGrid,
    pub radius: f32,
    pub mis: Pass,
    pub max_depth: u32,
    /// The image's width in pixels (pixel (x, y) pairs with light subpath y·width + x).
    pub width: usize,
}

/// A camera subpath at its current vertex.
struct Walk<C: Carrier> {
    beta: C,
    lambda: C::Lambda,
    part: Partials,
    /// Non-delta vertices so far.
    depth: u32,
    /// The last vertex (the camera's pinhole at first).
    prev: Vec3,
    /// No vertex yet: what the ray meets is seen directly.
    first: bool,
}

impl<C: Carrier> CameraKit<'_, C> {
    /// The radiance of the camera subpath leaving along `ray` (the pixel's, from the
    /// pixel's sampler in `ctx`), paired with light subpath `pair`, at the pass's
    /// wavelengths `lambda`.
    pub fn radiance(&self, ray: Ray, pair: usize, lambda: C::Lambda, ctx: &mut Context) -> C {
        let scene = self.scene;
        let Some(pr) = self.camera.project(ray.origin + ray.dir) else {
            return C::ZERO;
        };
        let cos3 = pr.cos_theta * pr.cos_theta * pr.cos_theta;
        let mut w = Walk {
            beta: C::ONE,
            lambda,
            part: Partials::camera(1.0 / (pr.pixel_area * cos3), &self.mis),
            depth: 0,
            prev: ray.origin,
            first: true,
        };
        let (mut ray, mut media, mut l) = (ray, MediumStack::new(), C::ZERO);
        let (mut vertex, mut deltas) = (0u32, 0u32);
        loop {
            let Some(at) = shading::arrive::<C>(scene, &ray, &media, &w.lambda, &mut ctx.rays)
            else {
                l += self.escaped(&ray, &w);
                break;
            };
            w.beta *= at.transmittance;
            l += self.emitted(&at, &w);
            let mut u = ctx.sample.bounce(vertex);
            vertex += 1;
            let ev = at.event(scene, media, &mut w.beta, &mut w.lambda, &mut u);
            let s = match &ev {
                Event::PassThrough(next) => {
                    ray = *next;
                    continue;
                }
                Event::Scatter(s) => s,
            };
            let dist2 = s.hit.p.distance_squared(w.prev);
            w.part.arrive(dist2, s.wo.z.abs(), true);
            w.first = false;
            if !s.bsdf.is_delta() {
                w.depth += 1;
                if w.depth > self.max_depth {
                    break;
                }
                l += self.next_event(s, &w, &mut u, &mut ctx.rays);
                l += self.connect(s, &w, self.lights.path(pair), &mut ctx.rays);
                l += self.merge(s, &w);
            }
            let uc = u.bsdf_lobe();
            let ud = u.bsdf_direction_if(s.bsdf.samples_direction());
            let Some(bs) = s.sample(uc, ud, TransportMode::Radiance) else {
                break;
            };
            let pdf_rev = if bs.delta {
                0.0
            } else {
                s.bsdf.pdf(bs.wi, s.wo, TransportMode::Radiance)
            };
            w.part
                .scatter(bs.delta, bs.wi.z.abs(), bs.pdf, pdf_rev, &self.mis);
            w.beta *= bs.f * (bs.wi.z.abs() / bs.pdf);
            if w.depth >= ROULETTE_DEPTH && !bs.delta {
                let q = w.beta.max_element().min(1.0);
                let Some(q) = roulette(q, Draw::UnlessDead, || u.roulette()) else {
                    break;
                };
                w.beta *= C::splat(1.0 / q);
            }
            if !w.beta.is_finite() || w.beta == C::ZERO {
                break;
            }
            if bs.delta && !delta_bounce(&mut deltas) {
                break;
            }
            media = s.media_after(bs.transmission);
            w.prev = s.hit.p;
            ray = s.spawn(bs.wi);
        }
        l
    }

    /// The environment seen along an escaped ray, weighted against next-event estimation
    /// and light subpaths from the environment (weight 1 when seen directly).
    fn escaped(&self, ray: &Ray, w: &Walk<C>) -> C {
        let Some(env) = self.scene.environment() else {
            return C::ZERO;
        };
        let d = ray.dir.normalize();
        let le = w.beta * C::illuminant(env.eval(d), &w.lambda);
        if w.first {
            return le;
        }
        let dens = self
            .emitter
            .densities(self.scene, Source::Environment, w.prev, -d, AIM);
        le * w.part.hit_light(&dens)
    }

    /// Emission of the surface arrived at (its emitting side), weighted likewise.
    fn emitted(&self, at: &Arrival<'_, C>, w: &Walk<C>) -> C {
        let (hit, mat) = (&at.hit, at.mat);
        if at.sp.emissive == Vec3::ZERO || !(hit.front_face || mat.desc.double_sided) {
            return C::ZERO;
        }
        let le = w.beta * C::emitted(at.sp.emissive, mat.emitter_shape(), &w.lambda);
        if w.first {
            return le;
        }
        let dens = self
            .emitter
            .densities(self.scene, Source::Area(hit.prim), hit.p, hit.wo, AIM);
        let mut part = w.part;
        part.arrive(hit.p.distance_squared(w.prev), dens.cos, true);
        le * part.hit_light(&dens)
    }

    /// Next-event estimation at `s` ([`next_event::one`] with [`Nee`]): one light of the
    /// scene's light sampler, weighted against the camera subpath reaching it and light
    /// subpaths starting there.
    fn next_event(&self, s: &Surface<C>, w: &Walk<C>, u: &mut Bounce<'_>, rays: &mut u64) -> C {
        if self.scene.light_sampler().is_empty() {
            // Without lights the subpath still draws the light numbers of its vertex.
            let _ = (u.light_choice(), u.light_position(), u.light_member());
            return C::ZERO;
        }
        let r = Nee { kit: self, s, w };
        next_event::one(self.scene, &r, &w.lambda, u, rays)
            .map_or(C::ZERO, |e| e.resolve(self.scene))
    }

    /// Connections of `s` to the vertices of its paired light subpath.
    fn connect(&self, s: &Surface<C>, w: &Walk<C>, path: &[LightVertex<C>], rays: &mut u64) -> C {
        let mut sum = C::ZERO;
        for v in path.iter().filter(|v| w.depth + v.depth <= self.max_depth) {
            let y = &v.surface;
            let d = y.hit.p - s.hit.p;
            let d2 = d.length_squared();
            let dir = d / d2.sqrt();
            let (wc, wl) = (s.frame.to_local(dir), y.frame.to_local(-dir));
            let fc = s.bsdf.eval(s.wo, wc, TransportMode::Radiance);
            let fl = y.bsdf.eval(wl, y.wo, TransportMode::Radiance);
            if fc == C::ZERO || fl == C::ZERO || d2.is_nan() || d2 <= 0.0 {
                continue;
            }
            let cam = (
                s.bsdf.pdf(s.wo, wc, TransportMode::Radiance),
                s.bsdf.pdf(wc, s.wo, TransportMode::Radiance),
            );
            let light = (
                y.bsdf.pdf(y.wo, wl, TransportMode::Radiance),
                y.bsdf.pdf(wl, y.wo, TransportMode::Radiance),
            );
            let cos = (wc.z.abs(), wl.z.abs());
            let weight = w
                .part
                .connect(&v.partials, (cam, light), cos, d2, &self.mis);
            let g = cos.0 * cos.1 / d2 * weight;
            if !(g > 0.0 && g.is_finite()) {
                continue;
            }
            *rays += 1;
            if self.scene.occluded(&s.hit.spawn_ray_to(y.hit.p)) {
                continue;
            }
            let media = s.media_after(wc.z * s.wo.z < 0.0);
            let tr: C = segment(self.scene, &media, d2.sqrt(), &w.lambda);
            sum += hero_product(w.beta * fc * tr, &w.lambda, fl * v.beta, &v.lambda) * g;
        }
        sum
    }

    /// Merging at `s` with the light vertices within the pass's radius.
    fn merge(&self, s: &Surface<C>, w: &Walk<C>) -> C {
        if !self.mis.merges() {
            return C::ZERO;
        }
        let mut sum = C::ZERO;
        self.grid.for_each_within(s.hit.p, self.radius, |i, _| {
            let v = self.merged[i as usize];
            if w.depth + v.depth > self.max_depth + 1 {
                return;
            }
            if !crate::photon::grid::in_disc(s.hit.p, s.hit.ng, v.surface.hit.p, self.radius) {
                return;
            }
            let wi = s.frame.to_local(v.surface.hit.wo);
            let f = s.bsdf.eval(s.wo, wi, TransportMode::Radiance);
            if f == C::ZERO {
                return;
            }
            let pdfs = (
                s.bsdf.pdf(s.wo, wi, TransportMode::Radiance),
                s.bsdf.pdf(wi, s.wo, TransportMode::Radiance),
            );
            let weight = w.part.merge(&v.partials, pdfs, &self.mis);
            sum += hero_product(f, &w.lambda, v.beta, &v.lambda) * weight;
        });
        w.beta * sum * self.mis.merge_norm
    }
}

/// VCM's side of the shared next-event estimator: the BSDF toward the light, the weight
/// over all of VCM's strategies ([`Partials::next_event`], the light's densities from the
/// photon emitter), the camera subpath's throughput.
struct Nee<'a, 'k, C: Carrier> {
    kit: &'a CameraKit<'k, C>,
    s: &'a Surface<C>,
    w: &'a Walk<C>,
}

impl<C: Carrier> Receiver<C> for Nee<'_, '_, C> {
    fn hit(&self) -> &SurfaceHit {
        &self.s.hit
    }

    fn eval(&self, wi: Vec3, _: &C::Lambda) -> Option<Eval<C>> {
        let wi = self.s.frame.to_local(wi);
        let f = self.s.bsdf.eval(self.s.wo, wi, TransportMode::Radiance);
        Some(Eval {
            f,
            cos: wi.z.abs(),
            pdf: 0.0,
        })
    }

    /// `None` for an emissive-group sample without its triangle, or a weight that is not
    /// finite and positive.
    fn weight(&self, chosen: &Chosen<'_>, eval: &Eval<C>) -> Option<f32> {
        let (s, ls) = (self.s, &chosen.sample);
        let source = match (chosen.light, ls.prim) {
            (LightId::Punctual(k), _) => Source::Punctual(k),
            (LightId::Area, Some(prim)) => Source::Area(prim),
            (LightId::Area, None) => return None,
            (LightId::Environment, _) => Source::Environment,
        };
        let point = ls.position.unwrap_or(s.hit.p);
        let e = self
            .kit
            .emitter
            .densities(self.kit.scene, source, point, -ls.wi, AIM);
        // Next-event estimation's solid-angle density (with its light choice).
        let light_pdf = if e.finite {
            e.direct * point.distance_squared(s.hit.p) / e.cos
        } else {
            e.direct
        };
        let wi = s.frame.to_local(ls.wi);
        let pdfs = (
            s.bsdf.pdf(s.wo, wi, TransportMode::Radiance),
            s.bsdf.pdf(wi, s.wo, TransportMode::Radiance),
        );
        let weight = self
            .w
            .part
            .next_event(&e, light_pdf, pdfs, eval.cos, &self.kit.mis);
        (weight > 0.0 && weight.is_finite()).then_some(weight)
    }

    fn throughput(&self) -> Option<C> {
        Some(self.w.beta)
    }
}

/// The Beer–Lambert transmittance over `dist` in the current medium of `media`.
fn segment<C: Carrier>(scene: &Scene, media: &MediumStack, dist: f32, lambda: &C::Lambda) -> C {
    match media.current() {
        Some(m) => scene.materials()[m as usize].transmittance_at::<C>(dist, lambda),
        None => C::ONE,
    }
}

/// `a · b` for a camera side at `la` and a light side at `lb`, divided by 4 when both kept
/// only the hero (see the module docs).
fn hero_product<C: Carrier>(a: C, la: &C::Lambda, b: C, lb: &C::Lambda) -> C {
    if C::is_hero_only(la) && C::is_hero_only(lb) {
        a * b * 0.25
    } else {
        a * b
    }
}
