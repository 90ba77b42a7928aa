//! Scattering media along a path's rays ([`crate::volume`]), for the path tracer: which
//! medium a ray segment crosses ([`segment`]: the current volume's, or the fog's part of a
//! segment in air), free flight through it ([`fly`]), how rays leave a scattering event
//! ([`Scattered::leave`]), boundaries that change only the medium ([`cross_matched`]), and
//! the transmittance of a shadow ray ([`shadow`]), which crosses such boundaries and
//! multiplies the exact transmittance of every medium on its way.
//!
//! Offsets never skip a medium: a segment starts where its ray really starts, the part of
//! its line the intersection layer's offset skipped included ([`Ray::skipped`]), and a
//! scattering event within a surface's offset of it is kept in the surface's band
//! ([`BandPoint`]), so rays leaving it start on its side of the surface (a medium whose mean
//! free path is shorter than the offset scatters there). Long walks are coarse-grained
//! ([`crate::volume::coarse`]): flights and the first segment of a shadow ray take the
//! walk's [`Scale`].
//!
//! Units: distances along unit-direction rays in scene units; transmittance per unit
//! radiance. The random numbers of free flight (RGB's channel choice, the distance) come
//! from the sample's independent stream, outside the dimension schedule, so scenes
//! without media draw exactly the numbers they drew before media existed.

use super::material_bsdf::interface;
use super::step::meet;
use crate::interaction::{BandPoint, CoincidentFaces, Leave, SurfaceHit};
use crate::math::{Ray, Rng};
use crate::medium_stack::MediumStack;
use crate::scene::Scene;
use crate::spectrum::Carrier;
use crate::volume::coarse::Scale;
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
/// the distance `t_hit` (+∞ if it escapes), from where the ray really starts (its
/// [`Ray::skipped`] part before the origin included, as negative distances): the current
/// volume's medium, or in air the fog's box; `None` where nothing scatters (absorbing
/// volumes keep their Beer–Lambert factor, [`crate::material::Material::transmittance_at`]).
pub fn segment<'s>(
    scene: &'s Scene,
    ray: &Ray,
    t_hit: f32,
    media: &MediumStack,
) -> Option<Segment<'s>> {
    match media.current() {
        Some(m) => scene.material(m).medium().map(|medium| Segment {
            medium,
            start: -ray.skipped,
            end: t_hit,
        }),
        None => {
            let fog = scene.fog()?;
            let (start, end) = fog.clip(ray.origin, ray.dir, (-ray.skipped, t_hit))?;
            Some(Segment {
                medium: &fog.medium,
                start,
                end,
            })
        }
    }
}

/// A scattering event on a path's ray: where, the phase function there, and the band of a
/// surface it lies in, if any.
#[derive(Debug, Clone, Copy)]
pub struct Scattered {
    /// The point (world space).
    pub p: Vec3,
    /// The medium's phase function.
    pub phase: Phase,
    /// The surface band it lies in ([`BandPoint`]); `None`: a free point.
    pub band: Option<BandPoint>,
}

impl Scattered {
    /// How a ray in the unit direction `dir` leaves it: from the point itself, or as its
    /// band says.
    pub fn leave(&self, dir: Vec3) -> Leave {
        match &self.band {
            Some(b) => b.leave(dir),
            None => Leave::Ray(Ray::new(self.p, dir)),
        }
    }
}

/// The surfaces at the ends of a path's ray: the one it was spawned from (its origin offset
/// from it by [`Ray::skipped`]; `None` for the camera, a point in a medium, or unknown) and
/// the one it meets (`None` if it escapes).
#[derive(Debug, Clone, Copy)]
pub struct Ends<'a> {
    /// The surface the ray left.
    pub from: Option<&'a SurfaceHit>,
    /// The surface it meets.
    pub meets: Option<&'a SurfaceHit>,
}

/// Free flight of a path inside `media` along the unit-direction `ray` between its `ends`,
/// in the walk's coarse-grained media of `scale`: multiplies `beta` by the flight's weight
/// ([`crate::volume::track`], which also updates the hero weights of `lambda`; a coarse
/// event's extra absorption, [`Scale::event_weight`]) and returns the scattering event, if
/// one happens before the surface. Nothing happens outside scattering media.
pub fn fly<C: Carrier>(
    scene: &Scene,
    (ray, ends): (&Ray, Ends<'_>),
    media: &MediumStack,
    scale: Scale,
    (beta, lambda): (&mut C, &mut C::Lambda),
    rng: &mut Rng,
) -> Option<Scattered> {
    let t_hit = ends.meets.map_or(f32::INFINITY, |h| h.t);
    let seg = segment(scene, ray, t_hit, media)?;
    let c = seg.medium.coeffs::<C>(lambda);
    let u_lane = if C::SPECTRAL { 0.0 } else { rng.next_f32() };
    let coarse = scale.coeffs(c);
    match track::sample(&coarse, seg.end - seg.start, lambda, u_lane, rng.next_f32()) {
        Track::Pass { weight } => {
            *beta *= weight;
            None
        }
        Track::Scatter { t, weight } => {
            *beta *= weight * scale.event_weight(&c);
            let t = seg.start + t;
            let band = if t < 0.0 {
                ends.from.and_then(|h| h.band_behind(ray, t))
            } else {
                ends.meets.and_then(|h| h.band_before(t_hit - t))
            };
            Some(Scattered {
                p: band.map_or_else(|| ray.at(t), |b| b.position()),
                phase: seg.medium.phase,
                band,
            })
        }
    }
}

/// The media a ray leaving a point of a medium (no surface, no band) really starts in,
/// given the surface it meets (with its coincident faces; `None`: it escapes): the path's
/// `media`, unless the point lies outside its current volume by rounding, which shows as a
/// ray that meets no surface from inside a closed volume, or that meets the volume's own
/// surface from outside within that surface's offset. The volume is then left.
pub fn starting(
    scene: &Scene,
    media: MediumStack,
    meets: Option<(&SurfaceHit, &CoincidentFaces)>,
) -> MediumStack {
    let Some(m) = media
        .current()
        .filter(|&m| scene.material(m).medium().is_some())
    else {
        return media;
    };
    let outside = match meets {
        None => true,
        Some((hit, coincident)) => {
            hit.material == m
                && hit.front_face
                && hit.is_within_band()
                && !coincident.iter().any(|f| f.material == m && !f.front_face)
        }
    };
    if outside {
        media.left(m)
    } else {
        media
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

/// The exact transmittance per lane of a path inside `media` along the unit-direction `ray`
/// up to `length` (from where it really starts, [`Ray::skipped`] included), in the media
/// coarse-grained by `scale`: e^(−σ_t d / k) for the scattering medium it crosses, times the
/// Beer–Lambert factor of an absorbing volume.
fn segment_transmittance<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    length: f32,
    (media, scale): (&MediumStack, Scale),
    l: &C::Lambda,
) -> C {
    let absorbed = match media.current() {
        Some(m) => scene
            .material(m)
            .transmittance_at::<C>(length + ray.skipped, l),
        None => C::ONE,
    };
    match segment(scene, ray, length, media) {
        Some(seg) => {
            let c = scale.coeffs(seg.medium.coeffs::<C>(l));
            absorbed * track::transmittance(&c, seg.end - seg.start)
        }
        None => absorbed,
    }
}

/// Where a shadow ray starts: the media, the coarse scale of the walk there (its first
/// segment's, up to the first surface), and whether it leaves a point of a medium (no
/// surface, no band: its media are checked with [`starting`]).
#[derive(Debug, Clone, Copy)]
pub struct Through {
    /// The media it starts in.
    pub media: MediumStack,
    /// The walk's scale.
    pub scale: Scale,
    /// It leaves a free point of a medium.
    pub from_point: bool,
}

impl Default for Through {
    /// A shadow ray leaving a surface in air.
    fn default() -> Through {
        Through::surface(MediumStack::new())
    }
}

impl Through {
    /// A shadow ray leaving a surface into `media`.
    pub fn surface(media: MediumStack) -> Through {
        Through {
            media,
            scale: Scale::FINE,
            from_point: false,
        }
    }
}

/// The transmittance of the shadow ray `ray` (from [`SurfaceHit::spawn_ray`] or
/// [`SurfaceHit::spawn_ray_to`], or leaving a scattering event) starting `through`: zero if
/// a surface blocks it, else the product of every medium's transmittance along it, crossing
/// index-matched boundaries ([`cross_matched`]). The caller counted the first ray; each
/// segment beyond a crossing adds one to `rays`.
pub fn shadow<C: Carrier>(
    scene: &Scene,
    ray: &Ray,
    through: Through,
    l: &C::Lambda,
    rays: &mut u64,
) -> C {
    let len = ray.dir.length();
    if !(len > 0.0 && len.is_finite()) {
        return C::ZERO;
    }
    let dir = ray.dir / len;
    let mut left = ray.t_max * len;
    let mut r = Ray {
        dir,
        t_max: left,
        ..*ray
    };
    let (mut media, mut scale) = (through.media, through.scale);
    let mut t = C::ONE;
    for k in 0..MAX_SHADOW_CROSSINGS {
        let found = scene.intersect(&r).map(|h| meet(scene, h));
        if k == 0 && through.from_point {
            media = starting(scene, media, found.as_ref().map(|(h, c)| (h, c)));
        }
        let Some((hit, coincident)) = found else {
            return t * segment_transmittance::<C>(scene, &r, left, (&media, scale), l);
        };
        let Some(after) = cross_matched::<C>(scene, &hit, &coincident, media, l) else {
            return C::ZERO;
        };
        t *= segment_transmittance::<C>(scene, &r, hit.t, (&media, scale), l);
        if t == C::ZERO {
            return t;
        }
        (media, scale) = (after, Scale::FINE);
        left -= hit.t;
        r = Ray {
            t_max: left,
            ..hit.spawn_ray(dir)
        };
        *rays += 1;
    }
    C::ZERO
}

/// The shadow ray `shadow` of next-event estimation at the scattering event `sc` (as
/// [`crate::shading::lights::sample`] spawned it from the event's point: toward a point
/// when `t_max` is finite, else along a direction) for a walk `through`: from a band point
/// ([`Scattered::band`]) as the band lets it leave ([`Leave`]). Returns the ray to trace,
/// where it starts, and the transmittance of the band it crossed before (toward its
/// surface: the distance left to the surface, then the surface crossed if it changes only
/// the medium; zero if it does more).
pub fn shadow_from<C: Carrier>(
    scene: &Scene,
    sc: &Scattered,
    shadow: Ray,
    through: Through,
    l: &C::Lambda,
) -> (Ray, Through, C) {
    let Some(band) = &sc.band else {
        return (shadow, through, C::ONE);
    };
    let finite = shadow.t_max.is_finite();
    let target = shadow.origin + shadow.dir;
    let dir = shadow.dir.normalize_or_zero();
    let leave = if finite {
        band.leave_to(target)
    } else {
        band.leave(dir)
    };
    let surface = Through::surface(through.media);
    match leave {
        Leave::Ray(r) => (
            r,
            Through {
                from_point: false,
                ..through
            },
            C::ONE,
        ),
        Leave::Meets { hit, distance } => {
            let inside = Ray {
                t_max: distance,
                ..Ray::new(sc.p, dir)
            };
            let media = (&through.media, through.scale);
            let tr = segment_transmittance::<C>(scene, &inside, distance, media, l);
            let (hit, coincident) = meet(scene, hit);
            let next = if finite {
                hit.spawn_ray_to(target)
            } else {
                hit.spawn_ray(dir)
            };
            match cross_matched::<C>(scene, &hit, &coincident, through.media, l) {
                Some(after) => (next, Through::surface(after), tr),
                None => (next, surface, C::ZERO),
            }
        }
    }
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
