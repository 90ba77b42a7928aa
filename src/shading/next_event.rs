//! Next-event estimation, written once for the path tracer (surfaces and media), VCM's
//! camera subpaths and the Whitted tracer's direct light ([`super::direct`]): choose a
//! light, sample it toward the vertex, evaluate the vertex's scattering toward it, weight
//! the sample, and leave or trace its shadow ray.
//!
//! What differs between the tracers is the [`Receiver`]: how the vertex scatters toward
//! the light (a BSDF, per lane at a rough dispersive interface, or a phase function; a
//! viewer-side test), the MIS weight (the power heuristic, VCM's balance over all its
//! strategies, or 1), and the throughput the value starts from. Which lights are sampled
//! is [`one`] (one light of the scene's light sampler, numbers drawn as the schedule says)
//! or [`every`] (each light once, weight 1: the Whitted tracer's); whether the shadow ray
//! is traced now ([`Estimate::resolve`]) or by the caller (the path tracer defers it) is
//! the caller's.
//!
//! Units: the value is throughput × f · incident / pmf · |cos| · w (radiance; incident as
//! [`lights::LightSample::incident`]); directions in world space unless said local.
//! Floating-point order: throughput · f, then · incident, then · (|cos| · w).

use super::lights::{self, LightSample};
use crate::interaction::SurfaceHit;
use crate::light::LightId;
use crate::math::Ray;
use crate::sampler::Bounce;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use glam::{Vec2, Vec3};

/// A light chosen for a vertex and its sample toward the vertex.
#[derive(Debug, Clone, Copy)]
pub struct Chosen<'a> {
    /// The light.
    pub light: LightId,
    /// The probability with which it was chosen (1 when every light is sampled).
    pub pmf: f32,
    /// Its sample toward the vertex.
    pub sample: LightSample<'a>,
}

impl Chosen<'_> {
    /// The solid-angle density of the sample's direction including the light's choice
    /// (`None` for a delta light); [`lights::area_pdf`] and [`lights::environment_pdf`]
    /// give the same for a BSDF-sampled direction.
    pub fn pdf(&self) -> Option<f32> {
        self.sample.pdf.map(|p| p * self.pmf)
    }
}

/// A vertex's scattering toward a light direction.
#[derive(Debug, Clone, Copy)]
pub struct Eval<C> {
    /// The BSDF (or phase function) value.
    pub f: C,
    /// |cos θ| toward the light (1 in a medium).
    pub cos: f32,
    /// The density with which the vertex's own sampling picks the direction (0 where no
    /// weight reads it).
    pub pdf: f32,
}

/// A vertex receiving next-event estimation: what differs between the tracers.
pub trait Receiver<C: Carrier> {
    /// The point the light is sampled toward.
    fn hit(&self) -> &SurfaceHit;

    /// The vertex's scattering toward the world direction `wi`; `None` when no light
    /// arrives that way (a zero f is refused by the estimator).
    fn eval(&self, wi: Vec3, lambda: &C::Lambda) -> Option<Eval<C>>;

    /// The MIS weight of the light sample `chosen` given `eval`; `None` when it is not
    /// counted (no shadow ray is traced).
    fn weight(&self, chosen: &Chosen<'_>, eval: &Eval<C>) -> Option<f32>;

    /// The throughput the value starts from (`None`: per unit throughput).
    fn throughput(&self) -> Option<C> {
        None
    }
}

/// A weighted light sample whose shadow ray decides it: `value` counts if nothing blocks
/// `shadow`.
#[derive(Debug, Clone, Copy)]
pub struct Estimate<C> {
    /// The shadow ray.
    pub shadow: Ray,
    /// The unit direction toward the light (world).
    pub wi: Vec3,
    /// The contribution if unblocked.
    pub value: C,
}

impl<C: Carrier> Estimate<C> {
    /// The value after tracing the shadow ray (zero when blocked; the ray was counted when
    /// the estimate was made).
    pub fn resolve(self, scene: &Scene) -> C {
        if scene.occluded(&self.shadow) {
            C::ZERO
        } else {
            self.value
        }
    }
}

/// Next-event estimation at `r` with one light chosen by the scene's light sampler
/// ([`Scene::light_sampler`]): the light choice, the position on the light and the member
/// of the emissive group from `u`, numbers the light does not read skipped
/// ([`lights::numbers_read`], [`Bounce::skip_light_choice`]: nothing drawn without
/// lights). The shadow ray is counted in `rays` and left to the caller.
pub fn one<C: Carrier>(
    scene: &Scene,
    r: &impl Receiver<C>,
    lambda: &C::Lambda,
    u: &mut Bounce<'_>,
    rays: &mut u64,
) -> Option<Estimate<C>> {
    let sampler = scene.light_sampler();
    if sampler.is_empty() {
        return None;
    }
    let u_choice = if sampler.lights().len() > 1 {
        u.light_choice()
    } else {
        u.skip_light_choice();
        0.0
    };
    let choice = sampler.sample(u_choice)?;
    let (reads_position, reads_member) = lights::numbers_read(choice.light);
    let up = if reads_position {
        u.light_position()
    } else {
        u.skip_light_position();
        Vec2::ZERO
    };
    let uc = if reads_member {
        u.light_member()
    } else {
        u.skip_light_member();
        0.0
    };
    let sample = lights::sample(scene, r.hit(), choice.light, uc, up)?;
    let chosen = Chosen {
        light: choice.light,
        pmf: choice.pmf,
        sample,
    };
    estimate(r, &chosen, lambda, rays)
}

/// Next-event estimation at `r` from every light of the scene's light sampler, each with
/// weight 1 and its shadow ray traced: each punctual light, one sample of the emissive
/// triangles (the vertex's light member and position numbers, drawn at every vertex) and
/// one of the environment (its BSDF-direction numbers, drawn only where there is one).
pub fn every<C: Carrier>(
    scene: &Scene,
    r: &impl Receiver<C>,
    lambda: &C::Lambda,
    u: &mut Bounce<'_>,
    rays: &mut u64,
) -> C {
    let hit = r.hit();
    let uc = u.light_member();
    let up = u.light_position();
    let mut sum = C::ZERO;
    for &light in scene.light_sampler().lights() {
        let sample = match light {
            LightId::Punctual(_) | LightId::Area => lights::sample(scene, hit, light, uc, up),
            LightId::Environment => lights::environment(scene, hit, u.bsdf_direction()),
        };
        let Some(sample) = sample else {
            continue;
        };
        let chosen = Chosen {
            light,
            pmf: 1.0,
            sample,
        };
        if let Some(e) = estimate(r, &chosen, lambda, rays) {
            sum += e.resolve(scene);
        }
    }
    sum
}

/// The weighted estimate of one chosen light sample at `r`, its shadow ray counted in
/// `rays`; `None` when the vertex does not scatter toward the light or the weight refuses
/// the sample.
fn estimate<C: Carrier>(
    r: &impl Receiver<C>,
    chosen: &Chosen<'_>,
    lambda: &C::Lambda,
    rays: &mut u64,
) -> Option<Estimate<C>> {
    let ls = &chosen.sample;
    let ev = r.eval(ls.wi, lambda)?;
    if ev.f == C::ZERO {
        return None;
    }
    let w = r.weight(chosen, &ev)?;
    *rays += 1;
    let incident = C::emitted(ls.incident / chosen.pmf, ls.shape, lambda);
    let f = match r.throughput() {
        Some(beta) => beta * ev.f,
        None => ev.f,
    };
    Some(Estimate {
        shadow: ls.shadow,
        wi: ls.wi,
        value: f * incident * (ev.cos * w),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::Backend;
    use crate::light::env::Environment;
    use crate::light::Light;
    use crate::material::MaterialDesc;
    use crate::sampler::{PixelSampler, SamplerKind};
    use crate::scene::desc::{MeshDesc, SceneDesc};

    /// A quad of half-size `h` at height `y`, facing down (a lamp) or up (the floor).
    fn quad(y: f32, h: f32, down: bool, material: usize) -> MeshDesc {
        let p = [(-h, -h), (h, -h), (h, h), (-h, h)].map(|(x, z)| Vec3::new(x, y, z));
        let indices = if down {
            vec![[0, 1, 2], [0, 2, 3]]
        } else {
            vec![[0, 2, 1], [0, 3, 2]]
        };
        MeshDesc {
            name: format!("quad {y}"),
            positions: p.to_vec(),
            indices,
            material: Some(material),
            ..Default::default()
        }
    }

    /// A floor, an emissive quad above it, a point light and a uniform environment: a
    /// light of every kind.
    fn scene() -> Scene {
        let floor = MaterialDesc {
            name: "floor".into(),
            metallic: 0.0,
            ..Default::default()
        };
        let lamp = MaterialDesc {
            name: "lamp".into(),
            base_color: glam::Vec4::new(0.0, 0.0, 0.0, 1.0),
            metallic: 0.0,
            emissive: Vec3::new(4.0, 3.0, 2.0),
            ..Default::default()
        };
        let desc = SceneDesc {
            source: "next event".into(),
            meshes: vec![quad(0.0, 4.0, false, 0), quad(2.0, 0.5, true, 1)],
            materials: vec![floor, lamp],
            environment_light: Some(Environment::Uniform {
                radiance: Vec3::new(0.2, 0.3, 0.4),
            }),
            ..Default::default()
        };
        let desc = crate::scene::validate::validate(desc).expect("valid");
        let point = Light::Point {
            position: Vec3::new(1.0, 1.5, -0.5),
            intensity: Vec3::splat(2.0),
            range: None,
        };
        Scene::build_with_lights(desc, Backend::Bvh, vec![point]).expect("build")
    }

    /// A Lambertian floor point (albedo 0.5, normal +Y) with a fixed weight, or refusing
    /// every sample, and an optional throughput.
    struct Floor {
        hit: SurfaceHit,
        weight: Option<f32>,
        throughput: Option<Vec3>,
    }

    impl Receiver<Vec3> for Floor {
        fn hit(&self) -> &SurfaceHit {
            &self.hit
        }

        fn eval(&self, wi: Vec3, _: &()) -> Option<Eval<Vec3>> {
            let cos = wi.y;
            (cos > 0.0).then(|| Eval {
                f: Vec3::splat(0.5 * std::f32::consts::FRAC_1_PI),
                cos,
                pdf: cos * std::f32::consts::FRAC_1_PI,
            })
        }

        fn weight(&self, _: &Chosen<'_>, _: &Eval<Vec3>) -> Option<f32> {
            self.weight
        }

        fn throughput(&self) -> Option<Vec3> {
            self.throughput
        }
    }

    fn floor_at(scene: &Scene, x: f32, z: f32) -> SurfaceHit {
        let down = Ray::new(Vec3::new(x, 5.0, z), Vec3::NEG_Y);
        let hit = scene.intersect(&down).expect("the floor");
        assert_eq!(hit.material, 0);
        hit
    }

    /// One light chosen with its pmf and divided by it is unbiased for the sum over every
    /// light: the mean of [`one`] over many samples matches the mean of [`every`] (both
    /// with weight 1; 3σ of the two means' difference, from their sample variances).
    #[test]
    fn one_light_by_its_pmf_estimates_every_light() {
        let scene = scene();
        assert_eq!(scene.light_sampler().lights().len(), 3);
        let r = Floor {
            hit: floor_at(&scene, 1.3, -0.9),
            weight: Some(1.0),
            throughput: None,
        };
        let sampler = PixelSampler::new(SamplerKind::Independent, 1, (1, 1), 11);
        let n = 40_000;
        let (mut one_sum, mut one_sq, mut all_sum, mut all_sq) = (0.0f64, 0.0, 0.0, 0.0);
        let mut rays = 0;
        for k in 0..n {
            let mut stream = sampler.start(0, 0, k);
            let mut u = stream.bounce(0);
            let x = f64::from(
                one(&scene, &r, &(), &mut u, &mut rays).map_or(0.0, |e| e.resolve(&scene).x),
            );
            let mut stream = sampler.start(0, 0, k + n);
            let y = f64::from(every(&scene, &r, &(), &mut stream.bounce(0), &mut rays).x);
            (one_sum, one_sq, all_sum, all_sq) =
                (one_sum + x, one_sq + x * x, all_sum + y, all_sq + y * y);
        }
        let nf = n as f64;
        let (m1, m2) = (one_sum / nf, all_sum / nf);
        let var = (one_sq / nf - m1 * m1) / nf + (all_sq / nf - m2 * m2) / nf;
        assert!(m2 > 0.0);
        assert!(
            (m1 - m2).abs() < 3.0 * var.sqrt(),
            "{m1} vs {m2} (σ {})",
            var.sqrt()
        );
    }

    /// The value is throughput · f, then · incident / pmf, then · (|cos| · w); a refused
    /// weight or a light behind the vertex traces no shadow ray.
    #[test]
    fn the_estimate_is_weighted_and_counted_once() {
        let scene = scene();
        let hit = floor_at(&scene, -0.4, 0.6);
        let sampler = PixelSampler::new(SamplerKind::Independent, 1, (1, 1), 3);
        let estimate = |r: &Floor, k: u64, rays: &mut u64| {
            let mut stream = sampler.start(0, 0, k);
            one(&scene, r, &(), &mut stream.bounce(0), rays)
        };
        let (mut plain, mut halved, mut doubled, mut refused) = (0, 0, 0, 0);
        let r = |weight, throughput| Floor {
            hit,
            weight,
            throughput,
        };
        for k in 0..64 {
            let a = estimate(&r(Some(1.0), None), k, &mut plain);
            let b = estimate(&r(Some(0.5), None), k, &mut halved);
            let c = estimate(&r(Some(1.0), Some(Vec3::splat(2.0))), k, &mut doubled);
            assert!(estimate(&r(None, None), k, &mut refused).is_none());
            let (Some(a), Some(b), Some(c)) = (a, b, c) else {
                assert!(a.is_none() && b.is_none() && c.is_none());
                continue;
            };
            assert_eq!(a.value * 0.5, b.value);
            assert_eq!(a.value * 2.0, c.value);
            assert_eq!(a.shadow.dir, b.shadow.dir);
            assert!(a.wi.y > 0.0);
        }
        assert_eq!(refused, 0);
        assert!(plain > 32 && plain == halved && plain == doubled, "{plain}");
    }
}
