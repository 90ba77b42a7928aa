//! Light tracing of the hybrid's caustic paths onto the image (`--caustics light|mixed`):
//! caustic-origin photon vertices the map stores ([`super::caustic`]) are
//! also connected to the camera and splatted onto the pixel they project to (the t = 1
//! strategy of bidirectional path tracing, Veach 1997 §10.2; pbrt-v4 `ConnectBDPT` with
//! `t == 1`; LuxCore's "hybrid back/forward"). It is strong where the caustic is seen
//! directly: no kernel blur, every photon lands in its own pixel.
//!
//! ## The split with the map (Heckbert's notation; S = delta bounce, D = non-delta)
//! A caustic-origin path is a full path whose light end starts L S+ D; its light subpath's
//! non-delta vertices are y₁ (the L S+ D vertex, flagged
//! [`crate::photon::store::Photon::CAUSTIC`] in the map)
//! and the later y₂, y₃, …, all stored in the map. The camera path reaches its first
//! non-delta vertex D₁ either *through* ≥ 1 delta bounce or BLEND pass-through
//! (C (S|P)+ D₁) or *directly* (C D₁); D₁ is one of the yₖ. Per mode:
//! - D₁ through delta (every mode): D₁ gathers the whole map, as `--caustics map` does
//!   everywhere — no connection to a camera seen only through a delta chain is possible.
//! - D₁ seen directly, `light`: D₁ gathers nothing; every yₖ is connected to the pinhole.
//! - D₁ seen directly, `mixed`: y₁ is connected (the caustic proper, L S+ y₁ C); D₁ gathers only the map's later photons (k ≥ 2, no
//!   `CAUSTIC` flag), whose kernel blur is harmless on smooth indirect light and which
//!   light tracing would splat sparsely.
//! - Every other path (light end not L S+ D) is the path tracer's, unchanged (emission after
//!   D S+ L dropped in every mode).
//!
//! A connection from yₖ counts iff the segment yₖ→eye is unoccluded and yₖ projects into
//! the image, i.e. iff a camera ray reaches yₖ directly as its D₁ (a BLEND surface
//! occludes the connection; its 1 − α share is the map's by the pass-through rule). So
//! each caustic-origin path, having exactly one D₁ = yₖ, seen directly or not, and one k,
//! is counted by exactly one estimator: never twice, never lost. The camera-side depth rule
//! (D₁ gathers only if its bounce would be followed: `max_depth` ≥ 2) holds for the
//! connections too: no splats below `max_depth` 2.
//!
//! ## The splat (units: radiance, linear RGB)
//! Iris's pixel j is the box-filtered radiance I_j = (1/a) ∫_{pixel j} L(ω) / cos³θ dω,
//! where a is the pixel's area on the image plane at unit distance (pixels are uniform
//! over their square in raster space, `render::primary_ray`; the plane's area element is
//! dω / cos³θ). With dω = |cos θ_y,g| dA_y / d² this is pinhole importance
//! W_e = 1/(a cos⁴θ) times the connection's cos θ / d², i.e. pbrt-v4
//! `PerspectiveCamera::We` = 1/(A cos⁴θ) with the whole film area A (and lens area 1 for
//! a pinhole) times `SampleWi`'s cos θ / d², with the film's 1/A replaced by the pixel's
//! 1/a because Iris's film holds per-pixel radiance. A photon of flux Φ (already divided
//! by the photons emitted in the pass) arriving at y from w_l contributes
//! Φ · f(w_c, w_l) · |w_l·n_s| |w_c·n_g| / |w_l·n_g| · 1/(a d² cos³θ)
//! to its pixel, where w_c points to the eye: the adjoint BSDF in importance mode
//! f*(w_l, w_c) = f(w_c, w_l) in radiance mode (Veach 1997 §5.3; as the map's gather), and
//! |w_l·n_s| |w_c·n_g| / |w_l·n_g| is pbrt-v4's `CorrectShadingNormal` (bdpt.cpp) times
//! the connection's |w_c·n_s|. Summed over the pass's photons, that is an unbiased
//! per-pixel estimate of the caustic paths' share of I_j, added to the pass's camera
//! sample. The splat is that pixel's box and nothing wider (no reconstruction filter
//! spreads it to the neighbours): the footprint of the camera's jittered rays, so a sharp
//! caustic seen directly keeps its peak (tests/photon/light_trace_pixels.rs checks every pixel
//! against an analytic caustic).
//!
//! Spectral: the photons carry the pass's shared wavelengths; a photon that kept only its
//! hero (4× its lane, the others 0) converts with the same wavelengths and needs no other
//! factor (the camera side brings no second 4×, unlike the map's gather).
//!
//! Limits: an orthographic camera cannot be connected to (no pinhole): it keeps the map
//! everywhere ([`Splatter::new`] is `None`). The pinhole's solid-angle factors assume a
//! rigid camera transform (as [`Camera::generate_ray`]'s normalised directions do). Iris cameras are in air: a photon vertex
//! inside a volume is reached only through its boundary (a surface, which occludes), so
//! the connection carries no Beer–Lambert factor.
//!
//! Determinism: splats are made in the caustic map's fixed photon chunks and added to the
//! pass's splat image in chunk order ([`splat_image`]).

use crate::bsdf::TransportMode;
use crate::camera::{Camera, Projected};
use crate::photon::trace::PhotonVertex;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::Vec3;

/// One splat: the pixel index (y · width + x) and the radiance added to it (linear RGB).
pub type Splat = (u32, Vec3);

/// Connects photon vertices to a perspective camera ([`Splatter::connect`]).
#[derive(Clone, Copy)]
pub struct Splatter<'a> {
    scene: &'a Scene,
    camera: &'a Camera,
    width: u32,
    height: u32,
    every_vertex: bool,
}

impl<'a> Splatter<'a> {
    /// A splatter onto a `width × height` image of `camera` (the size it was built for),
    /// of every caustic-origin vertex (`every_vertex`, `--caustics light`) or of the first
    /// ones only (`mixed`); `None` when no connection can count: an orthographic camera,
    /// or `max_depth` < 2 (the camera path would not follow D₁'s bounce, see the module
    /// docs).
    pub fn new(
        scene: &'a Scene,
        camera: &'a Camera,
        (width, height): (u32, u32),
        max_depth: u32,
        every_vertex: bool,
    ) -> Option<Splatter<'a>> {
        (camera.is_perspective() && max_depth >= 2).then_some(Splatter {
            scene,
            camera,
            width,
            height,
            every_vertex,
        })
    }

    /// Whether every caustic-origin vertex is splatted (else only the first, L S+ D).
    pub fn every_vertex(&self) -> bool {
        self.every_vertex
    }

    /// A splatter for vertex connection and merging: every vertex, any `max_depth`
    /// (its weights decide what counts); `None` for an orthographic camera.
    pub fn every(
        scene: &'a Scene,
        camera: &'a Camera,
        (width, height): (u32, u32),
    ) -> Option<Splatter<'a>> {
        camera.is_perspective().then_some(Splatter {
            scene,
            camera,
            width,
            height,
            every_vertex: true,
        })
    }

    /// The splat of photon vertex `v` carrying flux `power` at wavelengths `lambda`
    /// (see the module docs for the formula); `None` if it projects outside the image, is
    /// occluded from the eye or contributes nothing. Counts the visibility ray in `rays`.
    pub fn connect<C: Carrier>(
        &self,
        v: &PhotonVertex<C>,
        power: C,
        lambda: &C::Lambda,
        rays: &mut u64,
    ) -> Option<Splat> {
        self.connect_weighted(v, power, lambda, rays, |_, _, _| 1.0)
    }

    /// [`Splatter::connect`] times `weight(projection, unit direction to the eye (world),
    /// squared distance to the eye)`, asked only for a connection that may count (before
    /// its visibility ray).
    pub fn connect_weighted<C: Carrier>(
        &self,
        v: &PhotonVertex<C>,
        power: C,
        lambda: &C::Lambda,
        rays: &mut u64,
        weight: impl FnOnce(&Projected, Vec3, f32) -> f32,
    ) -> Option<Splat> {
        let s = v.surface;
        let pr = self.camera.project(s.hit.p)?;
        let (x, y) = (pr.raster.x as u32, pr.raster.y as u32);
        if x >= self.width || y >= self.height {
            return None;
        }
        let to_eye = pr.eye - s.hit.p;
        let d2 = to_eye.length_squared();
        let w_c = to_eye / d2.sqrt();
        let (wo, wi) = (s.frame.to_local(w_c), s.frame.to_local(v.wi));
        let f = s.bsdf.eval(wo, wi, TransportMode::Radiance);
        if f == C::ZERO {
            return None;
        }
        // pbrt-v4 CorrectShadingNormal × |w_c·n_s|, and W_e · cos θ / d² for the pixel.
        let ng = s.hit.ng;
        let cos3 = pr.cos_theta * pr.cos_theta * pr.cos_theta;
        let g = wi.z.abs() * w_c.dot(ng).abs() / (v.wi.dot(ng).abs() * pr.pixel_area * d2 * cos3);
        let g = g * weight(&pr, w_c, d2);
        if !(g.is_finite() && g > 0.0) {
            return None;
        }
        *rays += 1;
        if self.scene.occluded(&s.hit.spawn_ray_to(pr.eye)) {
            return None;
        }
        let rgb = (f * power * g).to_rgb(lambda);
        rgb.is_finite().then_some((y * self.width + x, rgb))
    }
}

/// The pass's splat image (`pixels` entries, row-major): `chunks` added in order (a fixed
/// order whatever the thread count, so the image is bit-identical).
pub fn splat_image<S: AsRef<[Splat]>>(chunks: &[S], pixels: usize) -> Vec<Vec3> {
    let mut img = vec![Vec3::ZERO; pixels];
    for &(i, rgb) in chunks.iter().flat_map(|c| c.as_ref()) {
        if let Some(p) = img.get_mut(i as usize) {
            *p += rgb;
        }
    }
    img
}
