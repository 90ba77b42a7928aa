//! The radius sequence of progressive photon passes (SPPM, the hybrid's caustic and volume
//! maps, VCM's merges): Knaus & Zwicker 2011 ("Progressive Photon Mapping: A Probabilistic
//! Approach", eq. 20 with the per-pass form of Hachisuka & Jensen 2009's radius reduction),
//! r²ᵢ₊₁ = r²ᵢ · (i + α)/(i + 1) for pass i ≥ 1 (1-based), α ∈ (0, 1), so that
//! r²ₚ = r₀² · Πᵢ₌₁..ₚ (i + α)/(i + 1) for pass p (0-based) ([`radius2_factor`]).
//!
//! Units: radii in scene units (metres), r² kept in f64 so that the product over many
//! passes does not drift. Shards: the radius of pass p depends on r₀ and p alone, so a
//! shard starting at pass k replays the factors of passes 0..k in the same order
//! ([`RadiusSequence::replay`]) and reaches bit for bit the radius one render has there.
//!
//! The first radius, unless given, is [`first_radius`]: 2 pixel footprints
//! ([`pixel_footprint`]) at the median camera distance of the first pass's points (visible
//! points for SPPM, photons for the maps, light vertices for VCM).

use crate::camera::Camera;
use crate::render::RenderSettings;
use crate::scene::Scene;
use glam::{Vec2, Vec3};

/// The radius-sequence factor of pass `i` (1-based): r²ᵢ₊₁ / r²ᵢ = (i + α)/(i + 1)
/// (Knaus & Zwicker 2011).
pub fn radius2_factor(i: u32, alpha: f32) -> f64 {
    (i as f64 + alpha as f64) / (i as f64 + 1.0)
}

/// The radius of the passes of one render: r² of the current pass (none until the first is
/// chosen) and α. Pass p's radius is r₀² · Πᵢ₌₁..ₚ (i + α)/(i + 1) (module docs).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RadiusSequence {
    r2: Option<f64>,
    alpha: f32,
}

impl RadiusSequence {
    /// The sequence starting at `first` (`None`: chosen on the first pass,
    /// [`Self::or_first`]) with α `alpha`.
    pub fn new(first: Option<f32>, alpha: f32) -> RadiusSequence {
        RadiusSequence {
            r2: first.map(|r| f64::from(r) * f64::from(r)),
            alpha,
        }
    }

    /// Whether the first radius is known.
    pub fn is_chosen(&self) -> bool {
        self.r2.is_some()
    }

    /// The current radius, choosing the first as `first()` when none is known yet (it must
    /// be finite and positive, else 1 mm).
    pub fn or_first(&mut self, first: impl FnOnce() -> f32) -> f32 {
        if self.r2.is_none() {
            let r = first();
            let r = if r.is_finite() && r > 0.0 { r } else { 1e-3 };
            self.r2 = Some(f64::from(r) * f64::from(r));
        }
        self.radius()
    }

    /// The current radius (0 before the first is chosen).
    pub fn radius(&self) -> f32 {
        self.r2.map_or(0.0, f64::sqrt) as f32
    }

    /// The current r² (0 before the first is chosen).
    pub fn r2(&self) -> f64 {
        self.r2.unwrap_or(0.0)
    }

    /// Ends pass `pass` (0-based): r² ← r² · (i + α)/(i + 1) with i = pass + 1.
    pub fn end_pass(&mut self, pass: u32) {
        let factor = radius2_factor(pass + 1, self.alpha);
        self.r2 = self.r2.map(|r2| r2 * factor);
    }

    /// Ends passes 0..`first` in order: a shard starting at pass `first` then has the
    /// radius one render has at that pass.
    pub fn replay(&mut self, first: u64) {
        for p in 0..first {
            self.end_pass(p as u32);
        }
    }

    /// The sequence after [`Self::replay`]ing passes 0..`pass`.
    pub fn at_pass(mut self, pass: u32) -> RadiusSequence {
        self.replay(u64::from(pass));
        self
    }
}

/// The pixel footprint (world size of one pixel) at distance `d` from the camera, from two
/// neighbouring rays at the image centre.
pub fn pixel_footprint(camera: &Camera, settings: &RenderSettings, d: f32) -> f32 {
    let c = Vec2::new(settings.width as f32, settings.height as f32) * 0.5;
    let a = camera.generate_ray(c);
    let b = camera.generate_ray(c + Vec2::X);
    let (da, db) = (a.dir.normalize(), b.dir.normalize());
    (a.origin + da * d).distance(b.origin + db * d)
}

/// The first radius of a progressive pass sequence: 2 pixel footprints at the median
/// distance of `points` from the camera (1 % of the scene's diagonal without any).
pub fn first_radius(
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    points: impl Iterator<Item = Vec3>,
) -> f32 {
    let (w, h) = (settings.width as f32, settings.height as f32);
    let o = camera.generate_ray(Vec2::new(w, h) * 0.5).origin;
    let mut d: Vec<f32> = points.map(|p| p.distance(o)).collect();
    if d.is_empty() {
        return 0.01 * (scene.bounds().1 - scene.bounds().0).length();
    }
    let mid = d.len() / 2;
    let (_, m, _) = d.select_nth_unstable_by(mid, f32::total_cmp);
    2.0 * pixel_footprint(camera, settings, *m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// For α = 1 the radius stays r₀; for any α, r²ₚ is the closed form
    /// r₀² · Πᵢ₌₁..ₚ (i + α) / Πᵢ₌₁..ₚ (i + 1) (computed here with the other grouping), and
    /// it falls as p^(α−1).
    #[test]
    fn the_sequence_follows_knaus_zwicker() {
        let r0 = 0.05f32;
        let alpha = 2.0 / 3.0;
        assert_eq!(RadiusSequence::new(Some(r0), 1.0).at_pass(500).radius(), r0);
        for p in [0u32, 1, 2, 7, 100, 150] {
            let num: f64 = (1..=p).map(|i| f64::from(i) + f64::from(alpha)).product();
            let den: f64 = (1..=p).map(|i| f64::from(i) + 1.0).product();
            let want = f64::from(r0) * f64::from(r0) * num / den;
            let got = RadiusSequence::new(Some(r0), alpha).at_pass(p).r2();
            assert!(
                (got / want - 1.0).abs() < 1e-12,
                "pass {p}: {got} vs {want}"
            );
        }
        // Asymptotically r² ∝ p^(α−1) (Knaus & Zwicker 2011, §4.3).
        let a = RadiusSequence::new(Some(1.0), alpha).at_pass(10_000).r2();
        let b = RadiusSequence::new(Some(1.0), alpha).at_pass(20_000).r2();
        let slope = (b / a).ln() / 2f64.ln();
        assert!((slope - (f64::from(alpha) - 1.0)).abs() < 1e-3, "{slope}");
    }

    /// A shard starting at pass k replays the sequence: its radius at k and every later
    /// pass is bit for bit the one render's, whether the first radius was given or chosen.
    #[test]
    fn a_shard_replays_the_whole_renders_radius() {
        let alpha = 0.7;
        for first in [Some(0.013f32), None] {
            let mut whole = RadiusSequence::new(first, alpha);
            let mut radii = Vec::new();
            for pass in 0..64u32 {
                radii.push(whole.or_first(|| 0.02).to_bits());
                whole.end_pass(pass);
            }
            for k in [1u64, 5, 17, 63] {
                let mut shard = RadiusSequence::new(first, alpha);
                shard.or_first(|| 0.02);
                shard.replay(k);
                for (pass, want) in radii.iter().enumerate().skip(k as usize) {
                    assert_eq!(shard.radius().to_bits(), *want, "shard {k}, pass {pass}");
                    shard.end_pass(pass as u32);
                }
            }
        }
    }

    /// A first radius that is not finite and positive falls back to 1 mm; before any the
    /// radius is 0, and a given one is kept.
    #[test]
    fn the_first_radius_is_chosen_once() {
        let mut s = RadiusSequence::new(None, 0.5);
        assert!(!s.is_chosen());
        assert_eq!((s.radius(), s.r2()), (0.0, 0.0));
        assert_eq!(s.or_first(|| f32::NAN), 1e-3);
        assert_eq!(s.or_first(|| 5.0), 1e-3);
        let mut given = RadiusSequence::new(Some(0.25), 0.5);
        assert_eq!(given.or_first(|| 5.0), 0.25);
    }
}
