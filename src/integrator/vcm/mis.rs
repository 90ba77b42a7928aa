//! The multiple-importance weights of vertex connection and merging, computed from three
//! partial sums carried along each subpath (Georgiev, Křivánek, Davidovič, Slusallek 2012,
//! "Light Transport Simulation with Vertex Connection and Merging", §5; the recursive form
//! of the accompanying tech report "Implementing Vertex Connection and Merging", eqs.
//! 28–42, which SmallVCM's `vertexcm.hxx` implements). Balance heuristic.
//!
//! Notation: a subpath's vertex i carries `d_vcm`, `d_vc`, `d_vm` (the report's dVCM, dVC,
//! dVM): sums over the other strategies' densities up to this vertex, divided by this
//! subpath's own density, in a form that needs only the densities at the current vertex
//! to be extended. Densities are per steradian for directions and per m² for positions;
//! the conversion between them (cos / distance²) is applied as a vertex is reached
//! ([`Partials::arrive`]). Cosines are taken with the shading normal at every vertex, the
//! same in every strategy, so the weights of one full path sum to one whatever generated
//! it. Russian roulette is left out of the densities (the weights stay a partition of
//! unity; the estimators divide by the true survival probabilities).
//!
//! `n_light` is the number of light subpaths a pass traces (one per pixel); `r` the
//! pass's merging radius: merging's density relative to connection is η = π r² n_light
//! (the report's eq. 15).

/// Balance heuristic: the density itself.
#[inline]
fn mis(p: f32) -> f32 {
    p
}

/// The pass's constants: η_VCM = π r² n_light for merging against connecting (0 without
/// merging) and its inverse for connecting against merging (0 without connection).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pass {
    /// mis(η): the merging weight factor (the report's `mMisVmWeightFactor`).
    pub vm: f32,
    /// mis(1/η): the connection weight factor (`mMisVcWeightFactor`).
    pub vc: f32,
    /// 1 / η: the normalisation of a merged contribution (`mVmNormalization`).
    pub merge_norm: f32,
    /// Light subpaths per pass.
    pub n_light: f32,
}

impl Pass {
    /// The constants for radius `r` and `n_light` light subpaths; `merge` false leaves
    /// merging out (bidirectional path tracing, Veach 1997's estimator with the balance
    /// heuristic).
    pub fn new(r: f32, n_light: f32, merge: bool) -> Pass {
        let eta = std::f32::consts::PI * r * r * n_light;
        let ok = merge && eta.is_finite() && eta > 0.0;
        Pass {
            vm: if ok { mis(eta) } else { 0.0 },
            vc: if ok { mis(1.0 / eta) } else { 0.0 },
            merge_norm: if ok { 1.0 / eta } else { 0.0 },
            n_light,
        }
    }

    /// Whether the pass merges.
    pub fn merges(&self) -> bool {
        self.merge_norm > 0.0
    }
}

/// The three partial sums of one subpath at its current vertex.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Partials {
    /// The report's dVCM.
    pub d_vcm: f32,
    /// The report's dVC (connection).
    pub d_vc: f32,
    /// The report's dVM (merging).
    pub d_vm: f32,
}

/// The densities of one light point ([`crate::photon::emit::Densities`]): emission,
/// next-event estimation, |cos| at the light, delta, finite.
pub use crate::photon::emit::Densities as LightEnd;

impl Partials {
    /// A camera subpath leaving through a pixel whose ray has the solid-angle density
    /// `camera_pdf` (report eq. 31).
    pub fn camera(camera_pdf: f32, pass: &Pass) -> Partials {
        Partials {
            d_vcm: mis(pass.n_light / camera_pdf),
            d_vc: 0.0,
            d_vm: 0.0,
        }
    }

    /// A light subpath leaving its light (report eqs. 28–30).
    pub fn light(end: &LightEnd, pass: &Pass) -> Partials {
        let d_vc = if end.delta {
            0.0
        } else {
            let cos = if end.finite { end.cos } else { 1.0 };
            mis(cos / end.emit)
        };
        Partials {
            d_vcm: mis(end.direct / end.emit),
            d_vc,
            d_vm: d_vc * pass.vc,
        }
    }

    /// The subpath reaches its next vertex at distance² `dist2` with |cos| `cos` there;
    /// `scale_dist` false for the first vertex of a light subpath from distant light, whose
    /// densities are already per m² of the receiver (report eqs. 32–34).
    pub fn arrive(&mut self, dist2: f32, cos: f32, scale_dist: bool) {
        if scale_dist {
            self.d_vcm *= mis(dist2);
        }
        let c = mis(cos);
        self.d_vcm /= c;
        self.d_vc /= c;
        self.d_vm /= c;
    }

    /// The subpath scatters: a delta lobe (`pdf_fwd` and `pdf_rev` then unused), or a
    /// direction sampled with density `pdf_fwd` whose reverse density is `pdf_rev`, |cos|
    /// `cos_out` at the vertex (report eqs. 35–37; a delta lobe's forward and reverse
    /// probabilities are equal and cancel).
    pub fn scatter(&mut self, delta: bool, cos_out: f32, pdf_fwd: f32, pdf_rev: f32, pass: &Pass) {
        if delta {
            self.d_vcm = 0.0;
            self.d_vc *= mis(cos_out);
            self.d_vm *= mis(cos_out);
            return;
        }
        let g = mis(cos_out / pdf_fwd);
        self.d_vc = g * (self.d_vc * mis(pdf_rev) + self.d_vcm + pass.vm);
        self.d_vm = g * (self.d_vm * mis(pdf_rev) + self.d_vcm * pass.vc + 1.0);
        self.d_vcm = mis(1.0 / pdf_fwd);
    }

    /// The weight of a camera subpath's vertex hitting an emitter (or escaping to the
    /// environment) whose densities are `end`, for emission read there: the camera
    /// subpath against next-event estimation and the light subpaths (report eq. 43).
    pub fn hit_light(&self, end: &LightEnd) -> f32 {
        let others = mis(end.direct) * self.d_vcm + mis(end.emit) * self.d_vc;
        1.0 / (1.0 + others)
    }

    /// The weight of next-event estimation at a camera vertex: the light sample's
    /// solid-angle density `light_pdf` (with its choice), the BSDF's density `pdf_fwd` of
    /// that direction and `pdf_rev` of the camera side's direction given it, |cos| at the
    /// vertex `cos_here` (report eq. 44).
    pub fn next_event(
        &self,
        end: &LightEnd,
        light_pdf: f32,
        (pdf_fwd, pdf_rev): (f32, f32),
        cos_here: f32,
        pass: &Pass,
    ) -> f32 {
        let w_light = if end.delta {
            0.0
        } else {
            mis(pdf_fwd / light_pdf)
        };
        let ratio = end.emit * cos_here / (light_pdf * end.cos);
        let w_camera = mis(ratio) * (pass.vm + self.d_vcm + self.d_vc * mis(pdf_rev));
        1.0 / (w_light + 1.0 + w_camera)
    }

    /// The weight of connecting a camera vertex to a light vertex: `cam` and `light` are
    /// each side's (forward, reverse) BSDF densities of the connection, `cos` each side's
    /// |cos| toward the other, `dist2` the squared distance (report eqs. 45–46).
    pub fn connect(
        &self,
        light_side: &Partials,
        (cam, light): ((f32, f32), (f32, f32)),
        (cos_cam, cos_light): (f32, f32),
        dist2: f32,
        pass: &Pass,
    ) -> f32 {
        let cam_to_light_a = cam.0 * cos_light / dist2;
        let light_to_cam_a = light.0 * cos_cam / dist2;
        let w_light =
            mis(cam_to_light_a) * (pass.vm + light_side.d_vcm + light_side.d_vc * mis(light.1));
        let w_camera = mis(light_to_cam_a) * (pass.vm + self.d_vcm + self.d_vc * mis(cam.1));
        1.0 / (w_light + 1.0 + w_camera)
    }

    /// The weight of merging a light vertex (partials `light_side`) at this camera vertex,
    /// the camera BSDF's forward density `pdf_fwd` of the light vertex's incoming direction
    /// and `pdf_rev` of its own (report eqs. 47–48).
    pub fn merge(&self, light_side: &Partials, (pdf_fwd, pdf_rev): (f32, f32), pass: &Pass) -> f32 {
        let w_light = light_side.d_vcm * pass.vc + light_side.d_vm * mis(pdf_fwd);
        let w_camera = self.d_vcm * pass.vc + self.d_vm * mis(pdf_rev);
        1.0 / (w_light + 1.0 + w_camera)
    }

    /// The weight of a light vertex connected to the camera (light tracing): `camera_pdf_a`
    /// the camera's density per m² of generating the vertex through its pixel, `pdf_rev` the
    /// light vertex's BSDF density of its incoming direction given the camera's (report
    /// eq. 46 with the camera as the other end).
    pub fn to_camera(&self, camera_pdf_a: f32, pdf_rev: f32, pass: &Pass) -> f32 {
        let w_light =
            mis(camera_pdf_a / pass.n_light) * (pass.vm + self.d_vcm + self.d_vc * mis(pdf_rev));
        1.0 / (w_light + 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without merging the merging factors vanish, so the partial dVM plays no part.
    #[test]
    fn no_merging_leaves_the_merge_factors_out() {
        let p = Pass::new(0.01, 1000.0, false);
        assert_eq!((p.vm, p.vc, p.merge_norm), (0.0, 0.0, 0.0));
        let q = Pass::new(0.01, 1000.0, true);
        let eta = std::f32::consts::PI * 1e-4 * 1000.0;
        assert!((q.vm - eta).abs() < 1e-6 && (q.vc * eta - 1.0).abs() < 1e-6);
    }

    /// A diffuse receiver lit by an area light: the weights of emission hit, next-event
    /// estimation and light tracing for the path camera → x → light sum to one when each
    /// is computed from its own subpath (the invariant the partial sums exist for).
    #[test]
    fn the_three_strategies_of_a_direct_path_sum_to_one() {
        let pass = Pass::new(0.0, 50.0, false);
        // Geometry: camera at distance 2 from x (cos 0.8 at x toward the camera), light
        // point at distance 1.5 (cos 0.6 at x, 0.9 at the light).
        let (d_cx2, cos_x_cam, d_xl2, cos_x_l, cos_l) = (4.0f32, 0.8f32, 2.25f32, 0.6f32, 0.9f32);
        let camera_pdf = 3.0e4f32; // the pixel's solid-angle density
        let bsdf = |cos: f32| cos / std::f32::consts::PI; // cosine-weighted sampling
        let (pdf_a_light, emit_dir) = (0.25f32, bsdf(cos_l)); // point density, cos-weighted emission
        let end = LightEnd {
            emit: pdf_a_light * emit_dir,
            direct: pdf_a_light,
            cos: cos_l,
            delta: false,
            finite: true,
        };
        // Camera subpath: the camera vertex x, then a BSDF sample toward the light.
        let mut cam = Partials::camera(camera_pdf, &pass);
        cam.arrive(d_cx2, cos_x_cam, true);
        // Next-event estimation at x: the light's solid-angle density.
        let light_pdf_w = pdf_a_light * d_xl2 / cos_l;
        let w_nee = cam.next_event(
            &end,
            light_pdf_w,
            (bsdf(cos_x_l), bsdf(cos_x_cam)),
            cos_x_l,
            &pass,
        );
        // BSDF sampling reaches the light.
        let mut hit = cam;
        hit.scatter(false, cos_x_l, bsdf(cos_x_l), bsdf(cos_x_cam), &pass);
        hit.arrive(d_xl2, cos_l, true);
        let w_hit = hit.hit_light(&end);
        // Light tracing: the light subpath reaches x and is connected to the camera.
        let mut light = Partials::light(&end, &pass);
        light.arrive(d_xl2, cos_x_l, true);
        let camera_pdf_a = camera_pdf * cos_x_cam / d_cx2;
        let w_lt = light.to_camera(camera_pdf_a, bsdf(cos_x_l), &pass);
        let sum = w_nee + w_hit + w_lt;
        assert!(
            (sum - 1.0).abs() < 1e-5,
            "{w_nee} + {w_hit} + {w_lt} = {sum}"
        );
    }

    /// Camera → x1 → x2 → area light, both vertices diffuse (cosine-weighted sampling):
    /// the six ways VCM samples it — emission hit, next-event estimation at x2, connecting
    /// x1 to x2, light tracing to the camera, merging at x1, merging at x2 — each weighted
    /// from its own subpaths, sum to one.
    #[test]
    fn the_six_strategies_of_a_two_bounce_path_sum_to_one() {
        let pass = Pass::new(0.02, 400.0, true);
        let pdf = |cos: f32| cos / std::f32::consts::PI;
        // Cosines: at x1 toward the camera and toward x2; at x2 toward x1 and toward the
        // light; at the light. Squared distances camera–x1, x1–x2, x2–light.
        let (c1c, c12, c21, c2l, cl) = (0.7f32, 0.5f32, 0.8f32, 0.6f32, 0.9f32);
        let (dc1, d12, d2l) = (9.0f32, 1.5f32, 2.0f32);
        let camera_pdf = 2.0e4f32;
        let pdf_a = 0.3f32;
        let end = LightEnd {
            emit: pdf_a * pdf(cl),
            direct: pdf_a,
            cos: cl,
            delta: false,
            finite: true,
        };
        // The camera subpath at x1 and at x2.
        let mut c1 = Partials::camera(camera_pdf, &pass);
        c1.arrive(dc1, c1c, true);
        let mut c2 = c1;
        c2.scatter(false, c12, pdf(c12), pdf(c1c), &pass);
        c2.arrive(d12, c21, true);
        // The light subpath at x2 and at x1.
        let mut l2 = Partials::light(&end, &pass);
        l2.arrive(d2l, c2l, true);
        let mut l1 = l2;
        l1.scatter(false, c21, pdf(c21), pdf(c2l), &pass);
        l1.arrive(d12, c12, true);
        // (a) emission hit after BSDF sampling at x2.
        let mut hit = c2;
        hit.scatter(false, c2l, pdf(c2l), pdf(c21), &pass);
        hit.arrive(d2l, cl, true);
        let a = hit.hit_light(&end);
        // (b) next-event estimation at x2.
        let b = c2.next_event(&end, pdf_a * d2l / cl, (pdf(c2l), pdf(c21)), c2l, &pass);
        // (c) x1 connected to the light vertex x2.
        let c = c1.connect(
            &l2,
            ((pdf(c12), pdf(c1c)), (pdf(c21), pdf(c2l))),
            (c12, c21),
            d12,
            &pass,
        );
        // (d) light tracing from x1.
        let d = l1.to_camera(camera_pdf * c1c / dc1, pdf(c12), &pass);
        // (e) merging at x1 (the light vertex arrived from x2), (f) at x2.
        let e = c1.merge(&l1, (pdf(c12), pdf(c1c)), &pass);
        let f = c2.merge(&l2, (pdf(c2l), pdf(c21)), &pass);
        let sum = a + b + c + d + e + f;
        assert!((sum - 1.0).abs() < 1e-4, "{a} {b} {c} {d} {e} {f}: {sum}");
    }
}
