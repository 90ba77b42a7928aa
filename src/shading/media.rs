//! Scattering media along a path's rays ([`crate::volume`]), for the path tracer: which
//! medium a ray segment crosses ([`segment`]: the current volume's, or the fog's part of a
//! segment in air), free flight through it ([`fly`]), boundaries that change only the
//! medium ([`cross_matched`]), and the transmittance of a shadow ray ([`shadow`]), which
//! crosses such boundaries and multiplies the exact transmittance of every medium on its
//! way.
//!
//! Units: distances along unit-direction rays in scene units; transmittance per unit
//! radiance. The random numbers of free flight (RGB's channel choice, the distance) come
//! from the sample's independent stream, outside the dimension schedule, so scenes
//! without media draw exactly the numbers they drew before media existed.

use super::material_bsdf::interface;
use super::step::meet;
use crate::interaction::{CoincidentFaces, SurfaceHit};
use crate::math::{Ray, Rng};
use crate::medium::MediumStack;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use crate::volume::track::{self, Track};
use crate::volume::{Medium, Phase};
use glam::Vec3;

/// Most medium-only boundaries a shadow ray crosses before it is taken as blocked.
const MAX_SHADOW_CROSSINGS: u32 = 32;

/// The part of a ray that crosses a scattering medium.
#[derive(Debug, Clone, Copy)]
pub struct Segment<'s> {
    /// The medium.
    pub medium: &'s Medium,
    /// Where the medium starts and ends along the ray (distances, `end` may be +∞).
    pub start: f32,
    /// See `start`.
    pub end: f32,
}

/// The scattering medium the unit-direction `ray` of a path inside `media` crosses before
/// the distance `t_hit` (+∞ if it escapes): the current volume's medium, or in air the
/// fog's box; `None` where nothing scatters (absorbing volumes keep their Beer–Lambert
/// factor, [`crate::material::Material::transmittance_at`]).
pub fn segment<'s>(
    scene: &'s Scene,
    ray: &Ray,
    t_hit: f32,
    media: &MediumStack,
) -> Option<Segment<'s>> {
    match media.current() {
        Some(m) => scene.material(m).medium().map(|medium| Segment {
            medium,
            start: 0.0,
            end: t_hit,
        }),
        None => {
            let fog = scene.fog()?;
            let (start, end) = fog.clip(ray.origin, ray.dir, t_hit)?;
            Some(Segment {
                medium: &fog.medium,
                start,
                end,
            })
        }
    }
}

/// A scattering event on a path's ray: where, and the phase function there.
#[derive(Debug, Clone, Copy)]
pub struct Scattered {
    /// The point (world space).
    pub p: Vec3,
    /// The medium's phase function.
    pub phase: Phase,
}

/// Free flight of a path inside `media` along the unit-direction `ray` up to `t_hit`:
/// multiplies `beta` by the flight's weight ([`crate::volume::track`], which also updates
/// the hero weights of `lambda`) and returns the scattering event, if one happens before
/// the surface. Nothing happens outside scattering media.
pub fn fly<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    t_hit: f32,
    media: &MediumStack,
    (beta, lambda): (&mut C, &mut C::Lambda),
    rng: &mut Rng,
) -> Option<Scattered> {
    let seg = segment(scene, ray, t_hit, media)?;
    let c = seg.medium.coeffs::<C>(lambda);
    let u_lane = if C::SPECTRAL { 0.0 } else { rng.next_f32() };
    match track::sample(&c, seg.end - seg.start, lambda, u_lane, rng.next_f32()) {
        Track::Pass { weight } => {
            *beta *= weight;
            None
        }
        Track::Scatter { t, weight } => {
            *beta *= weight;
            Some(Scattered {
                p: ray.origin + ray.dir * (seg.start + t),
                phase: seg.medium.phase,
            })
        }
    }
}

/// Past the start of a chromatic scattering medium (σ_t or σ_s differing between the path's
/// lanes), a spectral path keeps only its hero wavelength ([`Carrier::keep_hero`], as at a
/// dispersive interface): its free-flight weights are then the hero's own f / p, unbiased
/// whichever lane is the hero. Estimators that pair a camera path with photons sharing the
/// pass's hero (the hybrid's caustic maps) need this; the plain path tracer keeps the 4
/// lanes with spectral MIS instead ([`fly`]). Grey media and RGB transport change nothing.
pub fn keep_hero_in<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    t_hit: f32,
    media: &MediumStack,
    (beta, lambda): (&mut C, &mut C::Lambda),
) {
    if !C::SPECTRAL || C::is_hero_only(lambda) {
        return;
    }
    let Some(seg) = segment(scene, ray, t_hit, media) else {
        return;
    };
    let c = seg.medium.coeffs::<C>(lambda);
    let grey = |v: C| {
        let l = v.to_lanes();
        l.iter().all(|&x| x == l[0])
    };
    if !(grey(c.sigma_t) && grey(c.sigma_s)) {
        *beta = beta.keep_hero(lambda);
    }
}

/// The media beyond `hit` (with its `coincident` faces) for a path inside `media`, if the
/// surface changes nothing else: an index-matched material
/// ([`crate::material::Material::is_index_matched`]) between equal indices. Paths cross it
/// without a bounce and shadow rays see through it ([`shadow`]).
pub fn cross_matched<C: Carrier>(
    scene: &Scene,
    hit: &SurfaceHit,
    coincident: &CoincidentFaces,
    media: MediumStack,
    l: &C::Lambda,
) -> Option<MediumStack> {
    let matched = |m: u32| scene.material(m).is_index_matched();
    if !matched(hit.material) || coincident.iter().any(|c| !matched(c.material)) {
        return None;
    }
    let (n_i, n_t, after, _) = interface::<C>(scene, hit, coincident, media, l);
    (n_i == n_t).then_some(after)
}

/// The exact transmittance per lane of a path inside `media` over `[0, length]` of the
/// unit-direction `ray`: e^(−σ_t d) for the scattering medium it crosses, times the
/// Beer–Lambert factor of an absorbing volume.
fn segment_transmittance<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    length: f32,
    media: &MediumStack,
    l: &C::Lambda,
) -> C {
    let absorbed = match media.current() {
        Some(m) => scene.material(m).transmittance_at::<C>(length, l),
        None => C::ONE,
    };
    match segment(scene, ray, length, media) {
        Some(seg) => {
            absorbed * track::transmittance(&seg.medium.coeffs::<C>(l), seg.end - seg.start)
        }
        None => absorbed,
    }
}

/// The transmittance of the shadow ray `ray` (from [`SurfaceHit::spawn_ray`] or
/// [`SurfaceHit::spawn_ray_to`]) leaving a vertex inside `media`: zero if a surface
/// blocks it, else the product of every medium's transmittance along it, crossing
/// index-matched boundaries ([`cross_matched`]). The caller counted the first ray; each
/// segment beyond a crossing adds one to `rays`.
pub fn shadow<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    mut media: MediumStack,
    l: &C::Lambda,
    rays: &mut u64,
) -> C {
    let scale = ray.dir.length();
    if !(scale > 0.0 && scale.is_finite()) {
        return C::ZERO;
    }
    let dir = ray.dir / scale;
    let mut left = ray.t_max * scale;
    let mut r = Ray {
        origin: ray.origin,
        dir,
        t_max: left,
    };
    let mut t = C::ONE;
    for _ in 0..MAX_SHADOW_CROSSINGS {
        let Some(hit) = scene.intersect(&r) else {
            return t * segment_transmittance::<C>(scene, &r, left, &media, l);
        };
        let (hit, coincident) = meet(scene, hit);
        let Some(after) = cross_matched::<C>(scene, &hit, &coincident, media, l) else {
            return C::ZERO;
        };
        t *= segment_transmittance::<C>(scene, &r, hit.t, &media, l);
        media = after;
        left -= hit.t;
        r = Ray {
            t_max: left,
            ..hit.spawn_ray(dir)
        };
        *rays += 1;
    }
    C::ZERO
}

/// What scatters in `scene`, for messages and the plan: each material holding a scattering
/// medium and the fog, with its coefficients (at most three materials, then a count).
pub fn summary(scene: &Scene) -> String {
    let mut parts: Vec<String> = scene
        .materials()
        .iter()
        .filter_map(|m| {
            m.medium()
                .map(|med| format!("{}: {}", m.desc.name, med.describe()))
        })
        .collect();
    let n = parts.len();
    if n > 3 {
        parts.truncate(3);
        parts.push(format!("and {} more", n - 3));
    }
    if let Some(fog) = scene.fog() {
        parts.push(format!("fog: {}", fog.medium.describe()));
    }
    parts.join("; ")
}
