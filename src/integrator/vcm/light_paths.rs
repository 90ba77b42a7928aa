//! The light subpaths of one pass of vertex connection and merging: one per pixel, each
//! from the scene's photon emitter (light chosen by power, aimed at the caustic makers as
//! the photon methods aim, [`crate::photon::emit`]) and followed with the shared per-hit
//! step in importance mode ([`crate::shading::step`], as photons are). Every non-delta
//! vertex is kept, with its throughput and MIS partial sums ([`super::mis`]), for the camera
//! subpaths to connect to and merge with, and is connected to the camera (light tracing,
//! the splat of [`crate::integrator::light_trace`] with its MIS weight).
//!
//! Units: `beta` is the flux the light subpath carries to the vertex (the emitted photon's
//! power, not divided by the number of light subpaths), per lane of the pass's wavelengths
//! (linear RGB for [`glam::Vec3`]); splats are radiance.
//!
//! Depth: a full path counts its non-delta vertices between the light and the camera
//! (delta bounces are free up to [`crate::shading::MAX_DELTA_BOUNCES`], as for the other methods); a
//! light vertex at `depth` d is kept while d ≤ `max_depth`, so every strategy sees the
//! same paths.
//!
//! Determinism: light subpath `i` of pass `p` is a pure function of the seed, `p` and `i`
//! (Halton emission numbers over the index p·n + i, a stream for its bounces); subpaths
//! are traced in fixed chunks, kept in chunk order.

use super::mis::{LightEnd, Partials, Pass};
use crate::bsdf::TransportMode;
use crate::integrator::light_trace::{Splat, Splatter};
use crate::math::Rng;
use crate::medium_stack::MediumStack;
use crate::photon::emit::{Aim, EmittedPhoton, PhotonEmitter, PhotonNumbers, Source};
use crate::photon::trace::PhotonVertex;
use crate::scene::Scene;
use crate::shading::termination::{delta_bounce, throughput_roulette};
use crate::shading::{self, Event, Surface};
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Light subpaths traced together (a fixed chunk, so the order never depends on threads).
const CHUNK: usize = 1024;
/// The aim light subpaths are emitted with.
pub const AIM: Aim = crate::photon::emit::DEFAULT_AIM;

/// One non-delta vertex of a light subpath.
#[derive(Clone, Copy)]
pub struct LightVertex<C: Carrier> {
    /// The surface there (its `wo` points back along the light subpath).
    pub surface: Surface<C>,
    /// Flux arriving (see the module docs).
    pub beta: C,
    /// The subpath's wavelengths there (the hero only past a dispersive interface).
    pub lambda: C::Lambda,
    /// MIS partial sums on arrival.
    pub partials: Partials,
    /// Non-delta vertices of the light subpath up to and including this one.
    pub depth: u32,
}

/// What a pass's light subpaths leave: their vertices in the chunks they were traced in
/// (kept apart, so the pass holds its vertices once: a light vertex takes about 0.5 kB),
/// where each subpath starts, and the splats of light tracing.
pub struct LightPaths<C: Carrier> {
    chunks: Vec<Chunk<C>>,
    /// Light subpaths traced.
    count: usize,
    pub rays: u64,
}

/// The subpaths `k·CHUNK ..` of one chunk.
struct Chunk<C: Carrier> {
    vertices: Vec<LightVertex<C>>,
    /// Subpath `k·CHUNK + j`'s vertices are `vertices[starts[j]..starts[j + 1]]`.
    starts: Vec<u32>,
    splats: Vec<Splat>,
}

impl<C: Carrier> LightPaths<C> {
    /// The light subpaths traced.
    pub fn count(&self) -> usize {
        self.count
    }

    /// The vertices of light subpath `i` (empty past the last).
    pub fn path(&self, i: usize) -> &[LightVertex<C>] {
        let Some(c) = self.chunks.get(i / CHUNK) else {
            return &[];
        };
        let j = i % CHUNK;
        match (c.starts.get(j), c.starts.get(j + 1)) {
            (Some(&a), Some(&b)) => &c.vertices[a as usize..b as usize],
            _ => &[],
        }
    }

    /// All light vertices of the pass.
    pub fn len(&self) -> usize {
        self.chunks.iter().map(|c| c.vertices.len()).sum()
    }

    /// Every light vertex, in chunk order, then subpath order.
    pub fn vertices(&self) -> impl Iterator<Item = &LightVertex<C>> + '_ {
        self.chunks.iter().flat_map(|c| c.vertices.iter())
    }

    /// The light-tracing splats, in chunk order (for [`crate::integrator::light_trace::splat_image`]).
    pub fn splats(&self) -> Vec<&[Splat]> {
        self.chunks.iter().map(|c| c.splats.as_slice()).collect()
    }
}

/// What tracing a pass's light subpaths needs.
pub struct LightKit<'a> {
    pub scene: &'a Scene,
    pub emitter: &'a PhotonEmitter,
    pub numbers: &'a PhotonNumbers,
    /// Light tracing onto the image (`None`: no connection to the camera can count).
    pub splatter: Option<Splatter<'a>>,
    pub max_depth: u32,
    pub seed: u64,
}

impl LightKit<'_> {
    /// Traces light subpaths `0..n` of pass `pass` at the wavelengths `lambda`.
    pub fn trace<C: Carrier>(
        &self,
        pass: u32,
        n: usize,
        lambda: C::Lambda,
        mis: &Pass,
    ) -> LightPaths<C> {
        let chunks: Vec<(Chunk<C>, u64)> = (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let (mut vs, mut starts, mut splats, mut rays) =
                    (Vec::new(), vec![0u32], Vec::new(), 0);
                for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                    let index = u64::from(pass) * n as u64 + i as u64;
                    self.path(index, lambda, mis, (&mut vs, &mut splats), &mut rays);
                    starts.push(vs.len() as u32);
                }
                let chunk = Chunk {
                    vertices: vs,
                    starts,
                    splats,
                };
                (chunk, rays)
            })
            .collect();
        LightPaths {
            count: n,
            rays: chunks.iter().map(|(_, r)| r).sum(),
            chunks: chunks.into_iter().map(|(c, _)| c).collect(),
        }
    }

    /// The densities of the photon's start ([`PhotonEmitter::densities`]); for an
    /// emissive triangle at the point on the triangle the ray was offset from.
    fn start(&self, ph: &EmittedPhoton) -> LightEnd {
        let mut point = ph.ray.origin;
        if let Source::Area(prim) = ph.source {
            if let Some((_, n)) = self.scene.area_lights().point_pdf(prim) {
                let t = self.scene.triangle(prim);
                point -= n * (point - t.p[0]).dot(n);
            }
        }
        self.emitter
            .densities(self.scene, ph.source, point, ph.ray.dir, AIM)
    }

    /// Light subpath `index` (absolute over the render): its vertices and splats.
    fn path<C: Carrier>(
        &self,
        index: u64,
        mut lambda: C::Lambda,
        mis: &Pass,
        (vertices, splats): (&mut Vec<LightVertex<C>>, &mut Vec<Splat>),
        rays: &mut u64,
    ) {
        let scene = self.scene;
        let Some(ph) = self.emitter.emit_index(scene, self.numbers, index, AIM) else {
            return;
        };
        let end = self.start(&ph);
        if !(end.emit > 0.0 && end.emit.is_finite()) {
            return;
        }
        let mut rng = Rng::new(&[self.seed, index, 0x7C_4D_11]);
        let mut part = Partials::light(&end, mis);
        let mut beta = C::emitted(ph.power, ph.shape, &lambda);
        let (mut ray, mut media, mut prev) = (ph.ray, MediumStack::new(), ph.ray.origin);
        let (mut depth, mut deltas, mut first) = (0u32, 0u32, true);
        while let Some(at) = shading::arrive::<C>(scene, &ray, &media, &lambda, rays) {
            if first && ph.range.is_some() {
                beta *= crate::light::range_window(at.hit.t, ph.range);
            }
            beta *= at.transmittance;
            if beta == C::ZERO {
                break;
            }
            let ev = at.event(scene, media, &mut beta, &mut lambda, &mut rng);
            let s = match &ev {
                Event::PassThrough(next) => {
                    ray = *next;
                    continue;
                }
                Event::Scatter(s) => s,
            };
            part.arrive(
                s.hit.p.distance_squared(prev),
                s.wo.z.abs(),
                !first || end.finite,
            );
            first = false;
            if !s.bsdf.is_delta() {
                depth += 1;
                let v = LightVertex {
                    surface: *s,
                    beta,
                    lambda,
                    partials: part,
                    depth,
                };
                if let Some(sp) = self.to_camera(&v, mis, rays) {
                    splats.push(sp);
                }
                vertices.push(v);
                if depth >= self.max_depth {
                    break;
                }
            }
            let uc = rng.next_f32();
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            let Some(bs) = s.sample(uc, u, TransportMode::Importance) else {
                break;
            };
            let pdf_rev = if bs.delta {
                0.0
            } else {
                s.bsdf.pdf(bs.wi, s.wo, TransportMode::Importance)
            };
            part.scatter(bs.delta, bs.wi.z.abs(), bs.pdf, pdf_rev, mis);
            // Roulette on the throughput's change; survivors keep their flux (as photons).
            let next = beta * bs.f * (bs.wi.z.abs() / bs.pdf);
            let Some(next) = throughput_roulette(beta, next, || rng.next_f32()) else {
                break;
            };
            beta = next;
            if !beta.is_finite() {
                break;
            }
            if bs.delta && !delta_bounce(&mut deltas) {
                break;
            }
            media = s.media_after(bs.transmission);
            prev = s.hit.p;
            ray = s.spawn(bs.wi);
        }
    }

    /// Light tracing: vertex `v` connected to the camera, weighted against the camera
    /// subpaths' strategies ([`Partials::to_camera`]); the splat divided by the light
    /// subpaths of the pass.
    fn to_camera<C: Carrier>(
        &self,
        v: &LightVertex<C>,
        mis: &Pass,
        rays: &mut u64,
    ) -> Option<Splat> {
        let splatter = self.splatter.as_ref()?;
        let s = &v.surface;
        let pv = PhotonVertex {
            p: s.hit.p,
            wi: s.hit.wo,
            power: v.beta,
            bounces: v.depth,
            caustic: false,
            surface: s,
        };
        splatter.connect_weighted(&pv, v.beta, &v.lambda, rays, |pr, w_c, d2| {
            // The camera's density per m² of generating this vertex through its pixel:
            // the pixel's solid-angle density 1/(a cos³θ) times |cos|/d² at the vertex.
            let wc = s.frame.to_local(w_c);
            let cos3 = pr.cos_theta * pr.cos_theta * pr.cos_theta;
            let camera_pdf_a = wc.z.abs() / (pr.pixel_area * cos3 * d2);
            let pdf_rev = s.bsdf.pdf(wc, s.wo, TransportMode::Radiance);
            v.partials.to_camera(camera_pdf_a, pdf_rev, mis) / mis.n_light
        })
    }
}

/// A point's position for the merging grid.
pub fn position<C: Carrier>(v: &LightVertex<C>) -> Vec3 {
    v.surface.hit.p
}
