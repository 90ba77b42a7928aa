//! Photons aimed at what makes caustics: bounding spheres around the specular and
//! transmissive triangles ("caustic makers"), and the exact densities of directions (from a
//! point light or a point on an emitter) and of disc points (for distant light) that hit
//! them. [`super::emit`] mixes these with its usual emission and divides each photon's flux by
//! the full mixture density, so the estimate stays unbiased for any aim fraction.
//!
//! The idea is Jensen's projection maps (Jensen 2001, "Realistic Image Synthesis Using
//! Photon Mapping", §7.2: emit photons only toward the specular objects); here the map is a
//! few bounding spheres, whose cones and projected discs have closed-form densities, rather
//! than a grid of direction cells.
//!
//! ## Caustic makers
//! A triangle whose material is transmissive (`transmission > 0`, metallic < 1) or fully
//! metallic (`metallic ≥ 1`): what can start an L S+ D path (the tracer's `caustic` flag, which
//! also requires low roughness, so rough ones are included conservatively). The triangles are
//! grouped into at most [`MAX_TARGETS`] spheres: one sphere around all of them, then the
//! largest sphere is split at the median centroid along its longest axis while the two halves'
//! projected areas sum to less than [`SPLIT_GAIN`] of the parent's.
//!
//! ## Densities (world space, metres, steradians)
//! - From a point `p`, sphere `j` (centre c, radius R, distance d) subtends the cone of half
//!   angle θ_j with sin²θ_j = R²/d² and solid angle Ω_j = 2π(1 − cos θ_j) (pbrt-v4 §6.2.4,
//!   `Sphere::Sample` with a reference point); a point inside the sphere sees the whole
//!   sphere of directions (Ω_j = 4π). The sphere is chosen with probability Ω_j/ΣΩ and the
//!   direction uniformly in its cone, so the aimed density of a direction ω is
//!   (number of cones containing ω) / ΣΩ.
//! - Across the disc of distant light (⟂ the travel direction), sphere `j` projects to a disc
//!   of radius R_j; it is chosen with probability R_j²/ΣR², the point uniformly in its disc,
//!   so the aimed density of a point x is (number of discs containing x) / (π ΣR²).
//!
//! A direction lies in cone `j` iff the ray along it hits the sphere: d·ω > 0 and
//! |d × ω|² ≤ R² (exact for tiny cones, unlike a cos θ comparison near 1). The cone (or
//! disc) the sample was drawn from is always counted, so rounding at a cone's rim never
//! leaves a sampled direction with a density that misses its own term.

use crate::material::Material;
use crate::math::Frame;
use crate::scene::Scene;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Most bounding spheres (each photon tests all of them).
pub const MAX_TARGETS: usize = 8;
/// A sphere is split when its halves' R² sum to less than this fraction of its own.
pub const SPLIT_GAIN: f32 = 0.8;
/// The aim fraction the renderers use (`Aim::Mixture(DEFAULT_AIM_FRACTION)`).
pub const DEFAULT_AIM_FRACTION: f32 = 0.5;

/// How photons are aimed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Aim {
    /// The usual emission only.
    #[default]
    Off,
    /// With probability `a` (clamped to [0, 1]) an aimed sample, else the usual one; the
    /// power is divided by the mixture density (unbiased for every path).
    Mixture(f32),
    /// Aimed samples only, the power divided by the aimed density alone: unbiased for the
    /// photons whose first segment points at a target (a sphere cone or projected disc), and
    /// no photon starts anywhere else. For a caustic map (L S+ D) this loses nothing when the
    /// spheres bound every caustic maker, since such a path's first segment hits a caustic
    /// maker; photons reaching a caustic maker after a diffuse bounce (L D S D) are no
    /// caustic paths anyway. The mean power is then the flux toward the targets, not
    /// [`super::emit::PhotonEmitter::total_power`]. A light that sees no target emits nothing.
    Only,
}

/// The default aim of the renderers: `Mixture(DEFAULT_AIM_FRACTION)`.
pub const DEFAULT_AIM: Aim = Aim::Mixture(DEFAULT_AIM_FRACTION);

impl Aim {
    /// The probability of an aimed sample: 0, `a` clamped to [0, 1] (NaN → 0), or 1.
    pub fn fraction(self) -> f32 {
        match self {
            Aim::Off => 0.0,
            Aim::Mixture(a) if a.is_nan() => 0.0,
            Aim::Mixture(a) => a.clamp(0.0, 1.0),
            Aim::Only => 1.0,
        }
    }
}

/// A bounding sphere of caustic makers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// Centre (world).
    pub centre: Vec3,
    /// Radius (> 0).
    pub radius: f32,
}

/// The cone of directions from a point toward one sphere.
#[derive(Debug, Clone, Copy)]
struct Cone {
    /// Unit axis toward the centre (+Z for a point inside the sphere).
    axis: Vec3,
    /// 1 − cos θ (2 for a point inside: the whole sphere).
    one_minus_cos: f32,
}

impl Cone {
    fn solid_angle(&self) -> f32 {
        2.0 * PI * self.one_minus_cos
    }
}

/// The cones toward every sphere from one point, with their total solid angle.
#[derive(Debug, Clone, Copy)]
pub struct ConesFrom {
    p: Vec3,
    cones: [Option<Cone>; MAX_TARGETS],
    total: f32,
}

/// The caustic makers' bounding spheres (see the module docs).
#[derive(Debug, Clone, Default)]
pub struct Targets {
    spheres: Vec<Sphere>,
}

/// Whether a material can start an L S+ D path (transmissive or fully metallic).
pub fn is_caustic_maker(m: &Material) -> bool {
    m.is_transmissive() || m.desc.metallic >= 1.0
}

/// The bounding sphere of `tris`' vertices: box centre, largest vertex distance.
fn bound(tris: &[[Vec3; 3]]) -> Sphere {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for v in tris.iter().flatten() {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    let centre = 0.5 * (lo + hi);
    let radius = tris
        .iter()
        .flatten()
        .map(|v| v.distance(centre))
        .fold(0.0f32, f32::max);
    Sphere { centre, radius }
}

/// Splits `tris` at the median centroid along the centroids' longest axis.
fn split(mut tris: Vec<[Vec3; 3]>) -> (Vec<[Vec3; 3]>, Vec<[Vec3; 3]>) {
    let c = |t: &[Vec3; 3]| (t[0] + t[1] + t[2]) / 3.0;
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for t in &tris {
        lo = lo.min(c(t));
        hi = hi.max(c(t));
    }
    let e = hi - lo;
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = tris.len() / 2;
    tris.select_nth_unstable_by(mid, |a, b| c(a)[axis].total_cmp(&c(b)[axis]));
    let right = tris.split_off(mid);
    (tris, right)
}

impl Targets {
    /// The bounding spheres of `scene`'s caustic makers (none when there are none).
    pub fn new(scene: &Scene) -> Targets {
        let makers: Vec<bool> = scene.materials().iter().map(is_caustic_maker).collect();
        let tris: Vec<[Vec3; 3]> = scene
            .triangles()
            .iter()
            .filter(|t| makers.get(t.material() as usize).copied().unwrap_or(false))
            .filter(|t| t.p.iter().all(|v| v.is_finite()))
            .map(|t| t.p)
            .collect();
        Targets::from_triangles(tris)
    }

    /// The spheres around `tris` (world-space triangles), split as the module docs say.
    pub fn from_triangles(tris: Vec<[Vec3; 3]>) -> Targets {
        if tris.is_empty() {
            return Targets::default();
        }
        // (triangles, sphere, may still be split)
        let mut clusters = vec![(bound(&tris), tris, true)];
        while clusters.len() < MAX_TARGETS {
            let Some(k) = (0..clusters.len())
                .filter(|&k| clusters[k].2 && clusters[k].1.len() > 1)
                .max_by(|&a, &b| clusters[a].0.radius.total_cmp(&clusters[b].0.radius))
            else {
                break;
            };
            let (parent, tris, _) = clusters.swap_remove(k);
            let (a, b) = split(tris.clone());
            let (sa, sb) = (bound(&a), bound(&b));
            if sa.radius.powi(2) + sb.radius.powi(2) < SPLIT_GAIN * parent.radius.powi(2) {
                clusters.push((sa, a, true));
                clusters.push((sb, b, true));
            } else {
                clusters.push((parent, tris, false));
            }
        }
        let spheres = clusters
            .into_iter()
            .map(|c| c.0)
            .filter(|s| s.radius > 0.0 && s.radius.is_finite() && s.centre.is_finite())
            .collect();
        Targets { spheres }
    }

    /// The spheres (at most [`MAX_TARGETS`]).
    pub fn spheres(&self) -> &[Sphere] {
        &self.spheres
    }

    /// No caustic maker.
    pub fn is_empty(&self) -> bool {
        self.spheres.is_empty()
    }

    /// The cones from `p` (total solid angle 0 when there is no sphere).
    pub fn cones_from(&self, p: Vec3) -> ConesFrom {
        let mut cones = [None; MAX_TARGETS];
        let mut total = 0.0;
        for (slot, s) in cones.iter_mut().zip(&self.spheres) {
            let d = s.centre - p;
            let d2 = d.length_squared();
            let r2 = s.radius * s.radius;
            let cone = if d2 <= r2 {
                Cone {
                    axis: Vec3::Z,
                    one_minus_cos: 2.0,
                }
            } else {
                let sin2 = r2 / d2;
                let cos = (1.0 - sin2).max(0.0).sqrt();
                Cone {
                    axis: d / d2.sqrt(),
                    one_minus_cos: sin2 / (1.0 + cos),
                }
            };
            let omega = cone.solid_angle();
            if omega > 0.0 && omega.is_finite() && cone.axis.is_finite() {
                *slot = Some(cone);
                total += omega;
            }
        }
        ConesFrom { p, cones, total }
    }

    /// Whether the ray from `p` along unit `dir` meets sphere `s` (or `p` is inside it).
    fn in_cone(s: &Sphere, p: Vec3, dir: Vec3) -> bool {
        let d = s.centre - p;
        let r2 = s.radius * s.radius;
        d.length_squared() <= r2 || (d.dot(dir) > 0.0 && d.cross(dir).length_squared() <= r2)
    }

    /// An aimed direction from `cones.p`: `u.x` chooses a sphere by solid angle and, rescaled
    /// within the sphere's share, with `u.y` the direction uniformly in its cone. Returns the
    /// unit direction and the sphere's index, `None` when no sphere subtends a positive solid
    /// angle.
    pub fn sample_direction(&self, cones: &ConesFrom, u: Vec2) -> Option<(Vec3, usize)> {
        if cones.total <= 0.0 {
            return None;
        }
        let weights = cones.cones.map(|c| c.map_or(0.0, |c| c.solid_angle()));
        let (j, u_cone) = pick(&weights[..self.spheres.len()], u.x * cones.total)?;
        let cone = cones.cones[j]?;
        // Uniform in the cone: 1 − cos θ = u·(1 − cos θmax), sin²θ = x(2 − x).
        let omc = u_cone * cone.one_minus_cos;
        let cos = 1.0 - omc;
        let sin = (omc * (2.0 - omc)).max(0.0).sqrt();
        let (sp, cp) = (2.0 * PI * u.y).sin_cos();
        let dir = Frame::from_normal(cone.axis)
            .to_world(Vec3::new(sin * cp, sin * sp, cos))
            .normalize();
        dir.is_finite().then_some((dir, j))
    }

    /// The aimed density (per steradian) of unit `dir` from `cones.p`: the number of cones
    /// containing it over ΣΩ; `sampled` (the sphere the direction came from) always counts.
    pub fn direction_pdf(&self, cones: &ConesFrom, dir: Vec3, sampled: Option<usize>) -> f32 {
        if cones.total <= 0.0 {
            return 0.0;
        }
        let n = cones
            .cones
            .iter()
            .zip(&self.spheres)
            .enumerate()
            .filter(|(j, (c, s))| {
                c.is_some() && (sampled == Some(*j) || Targets::in_cone(s, cones.p, dir))
            })
            .count();
        n as f32 / cones.total
    }

    /// Σ R² of the spheres (their projected discs' area over π).
    fn projected_r2(&self) -> f32 {
        self.spheres.iter().map(|s| s.radius * s.radius).sum()
    }

    /// The centre of sphere `s` projected onto the plane ⟂ `frame.n` through `centre`, in
    /// (s, t) coordinates.
    fn projected(s: &Sphere, frame: &Frame, centre: Vec3) -> Vec2 {
        let d = s.centre - centre;
        Vec2::new(d.dot(frame.s), d.dot(frame.t))
    }

    /// An aimed point on the plane ⟂ `frame.n` (travel direction) through `centre`, in
    /// (s, t) coordinates: `u.x` chooses a sphere by projected area and, rescaled within its
    /// share, with `u.y` the point uniformly in its projected disc. Returns the point and the
    /// sphere's index.
    pub fn sample_across(&self, frame: &Frame, centre: Vec3, u: Vec2) -> Option<(Vec2, usize)> {
        let total = self.projected_r2();
        if total <= 0.0 || !total.is_finite() {
            return None;
        }
        let mut weights = [0.0; MAX_TARGETS];
        for (w, s) in weights.iter_mut().zip(&self.spheres) {
            *w = s.radius * s.radius;
        }
        let (j, u_r) = pick(&weights[..self.spheres.len()], u.x * total)?;
        let s = &self.spheres[j];
        let r = u_r.sqrt() * s.radius;
        let (sp, cp) = (2.0 * PI * u.y).sin_cos();
        Some((
            Targets::projected(s, frame, centre) + Vec2::new(r * cp, r * sp),
            j,
        ))
    }

    /// The aimed density (per m²) of point `x` of [`Targets::sample_across`]'s plane: the
    /// number of projected discs containing it over π ΣR²; `sampled` always counts.
    pub fn across_pdf(&self, frame: &Frame, centre: Vec3, x: Vec2, sampled: Option<usize>) -> f32 {
        let total = self.projected_r2();
        if total <= 0.0 || !total.is_finite() {
            return 0.0;
        }
        let n = self
            .spheres
            .iter()
            .enumerate()
            .filter(|(j, s)| {
                sampled == Some(*j)
                    || (x - Targets::projected(s, frame, centre)).length_squared()
                        <= s.radius * s.radius
            })
            .count();
        n as f32 / (PI * total)
    }
}

impl ConesFrom {
    /// Σ of the cones' solid angles (0: nothing to aim at from here).
    pub fn total(&self) -> f32 {
        self.total
    }
}

/// The index whose share of the running sum of `weights` contains `x` (in [0, Σ)), and `x`
/// rescaled to [0, 1) within that share; zero weights are never picked.
fn pick(weights: &[f32], x: f32) -> Option<(usize, f32)> {
    const BELOW_ONE: f32 = 1.0 - f32::EPSILON / 2.0;
    let mut acc = 0.0;
    let mut last = None;
    for (j, &w) in weights.iter().enumerate() {
        if w <= 0.0 {
            continue;
        }
        last = Some((j, acc, w));
        if x < acc + w {
            break;
        }
        acc += w;
    }
    let (j, lo, w) = last?;
    Some((j, ((x - lo) / w).clamp(0.0, BELOW_ONE)))
}

/// Splits `u` at `a`: `(true, u/a)` below it, `(false, (u − a)/(1 − a))` above, both kept
/// below 1.
pub fn split_choice(u: f32, a: f32) -> (bool, f32) {
    const BELOW_ONE: f32 = 1.0 - f32::EPSILON / 2.0;
    if u < a {
        (true, (u / a).min(BELOW_ONE))
    } else {
        (false, ((u - a) / (1.0 - a)).clamp(0.0, BELOW_ONE))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri_at(c: Vec3, s: f32) -> [Vec3; 3] {
        [c, c + Vec3::X * s, c + Vec3::Y * s]
    }

    #[test]
    fn far_apart_groups_get_their_own_spheres() {
        let mut tris = Vec::new();
        for c in [Vec3::ZERO, Vec3::new(10.0, 0.0, 0.0)] {
            for k in 0..4 {
                tris.push(tri_at(c + Vec3::Z * (k as f32 * 0.01), 0.1));
            }
        }
        let t = Targets::from_triangles(tris);
        assert_eq!(t.spheres().len(), 2, "{:?}", t.spheres());
        assert!(t.spheres().iter().all(|s| s.radius < 0.2));
    }

    #[test]
    fn cone_samples_hit_the_sphere_and_pdf_integrates() {
        let t = Targets::from_triangles(vec![tri_at(Vec3::new(0.0, 0.0, 3.0), 0.5)]);
        let p = Vec3::ZERO;
        let cones = t.cones_from(p);
        let s = t.spheres()[0];
        for i in 0..100 {
            let u = Vec2::new((i as f32 + 0.5) / 100.0, (i * 37 % 100) as f32 / 100.0);
            let (dir, j) = t.sample_direction(&cones, u).unwrap();
            assert!(Targets::in_cone(&s, p, dir), "{dir}");
            let pdf = t.direction_pdf(&cones, dir, Some(j));
            assert!((pdf * cones.total() - 1.0).abs() < 1e-6);
        }
        // Ω = 2π(1 − cos θ) with sin θ = R/d.
        let sin = s.radius / s.centre.length();
        let want = 2.0 * PI * (1.0 - (1.0 - sin * sin).sqrt());
        assert!((cones.total() - want).abs() < 1e-5 * want);
        assert_eq!(t.direction_pdf(&cones, -Vec3::Z, None), 0.0);
    }

    #[test]
    fn split_choice_rescales_both_sides() {
        assert_eq!(split_choice(0.25, 0.5), (true, 0.5));
        assert_eq!(split_choice(0.75, 0.5), (false, 0.5));
        assert!(!split_choice(0.0, 0.0).0);
        assert!(split_choice(0.999, 1.0).0);
    }
}
