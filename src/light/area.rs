//! Emissive triangles as lights (glTF `emissiveFactor` × KHR_materials_emissive_strength, OBJ
//! `Ke`): the emitting triangles with their corners ([`Emitter`], copied from the scene so
//! the lights need nothing else), chosen in proportion to their power and sampled uniformly
//! by area, for next-event estimation and photon emission.
//!
//! Units: emission is radiance (nits when the file's lights are photometric). Emission leaves
//! the front side (along the outward normal) of single-sided materials and both sides of
//! double-sided ones. Power used for selection: luminance(Le) × area × π × sides.
//! Densities: `sample` returns the pdf with respect to **solid angle** at the receiving point:
//! p_ω = p_A · d² / |cos θ_light| with p_A = P(triangle) / area (pbrt-v4 §12.2).

use glam::{Vec2, Vec3};

/// Luminance of linear Rec.709 RGB.
fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// One emitting triangle.
#[derive(Debug, Clone, Copy)]
pub struct Emitter {
    /// Its index among the scene's triangles.
    pub prim: u32,
    /// Its corners, world space.
    pub p: [Vec3; 3],
    /// The probability that it is chosen.
    pub prob: f32,
}

/// The emitting triangles of a scene.
#[derive(Debug, Clone, Default)]
pub struct AreaLights {
    /// The emitters, in increasing triangle index.
    emitters: Vec<Emitter>,
    /// Cumulative selection probability (last entry 1).
    cdf: Vec<f32>,
    /// Total emitted power proxy (luminance·area·π·sides).
    total: f32,
}

/// A point sampled on an emitter, seen from a receiving point.
#[derive(Debug, Clone, Copy)]
pub struct AreaSample {
    /// The point on the light.
    pub point: Vec3,
    /// The light triangle's unit outward normal.
    pub normal: Vec3,
    /// Unit direction from the receiver toward the light point.
    pub wi: Vec3,
    /// Distance from the receiver to the light point.
    pub dist: f32,
    /// Triangle index of the emitter.
    pub prim: u32,
    /// Barycentric weights of the triangle's vertices 0, 1, 2 at `point`.
    pub bary: [f32; 3],
    /// Solid-angle pdf at the receiver.
    pub pdf: f32,
}

/// A point sampled on an emitter with no receiver (photon emission).
#[derive(Debug, Clone, Copy)]
pub struct EmitterPoint {
    /// Triangle index of the emitter.
    pub prim: u32,
    /// The point on the light.
    pub point: Vec3,
    /// Barycentric weights of the triangle's vertices 0, 1, 2 at `point`.
    pub bary: [f32; 3],
    /// The triangle's unit outward normal.
    pub normal: Vec3,
    /// The triangle's area.
    pub area: f32,
    /// Probability that this triangle was chosen (so the area density is `prob / area`).
    pub prob: f32,
}

impl AreaLights {
    /// Collects emitters from `tris` (triangle index, corners, material, in increasing
    /// index): `emission(material)` gives a material's emitted radiance (factor only;
    /// textures modulate it where a point is sampled) and whether it is double-sided.
    pub fn build(
        tris: impl IntoIterator<Item = (u32, [Vec3; 3], u32)>,
        emission: impl Fn(u32) -> (Vec3, bool),
    ) -> Self {
        let mut emitters = Vec::new();
        let mut weights = Vec::new();
        for (prim, p, material) in tris {
            let (le, two_sided) = emission(material);
            let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
            let w = luminance(le) * area * std::f32::consts::PI * if two_sided { 2.0 } else { 1.0 };
            if w > 0.0 && w.is_finite() {
                emitters.push(Emitter { prim, p, prob: 0.0 });
                weights.push(w);
            }
        }
        let total: f32 = weights.iter().sum();
        let mut cdf = Vec::with_capacity(weights.len());
        let mut acc = 0.0f64;
        for (e, w) in emitters.iter_mut().zip(&weights) {
            acc += *w as f64;
            cdf.push((acc / total as f64) as f32);
            e.prob = w / total;
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        AreaLights {
            emitters,
            cdf,
            total,
        }
    }

    /// Whether the scene has no emitting triangles.
    pub fn is_empty(&self) -> bool {
        self.emitters.is_empty()
    }

    /// Number of emitting triangles.
    pub fn len(&self) -> usize {
        self.emitters.len()
    }

    /// The emitting triangles, in increasing triangle index.
    pub fn emitters(&self) -> &[Emitter] {
        &self.emitters
    }

    /// Total power proxy.
    pub fn power(&self) -> f32 {
        self.total
    }

    /// Samples a point on an emitter, independent of any receiver: `u` picks the triangle
    /// (by power), `uv` the point (uniform by area, Turk 1990 square-root mapping). `None`
    /// if there is no emitter or the triangle is degenerate.
    pub fn sample_point(&self, u: f32, uv: Vec2) -> Option<EmitterPoint> {
        if self.emitters.is_empty() {
            return None;
        }
        let k = self
            .cdf
            .partition_point(|&c| c <= u)
            .min(self.emitters.len() - 1);
        let Emitter { prim, p, prob } = self.emitters[k];
        let su = uv.x.sqrt();
        let (b0, b1) = (1.0 - su, uv.y * su);
        let b2 = 1.0 - b0 - b1;
        let point = p[0] * b0 + p[1] * b1 + p[2] * b2;
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let area = 0.5 * n.length();
        if area.is_nan() || area <= 0.0 {
            return None;
        }
        Some(EmitterPoint {
            prim,
            point,
            bary: [b0, b1, b2],
            normal: n.normalize_or_zero(),
            area,
            prob,
        })
    }

    /// Samples a point on an emitter for the receiver at `p`: `u` picks the triangle,
    /// `uv` the point (uniform by area, Turk 1990 square-root mapping).
    pub fn sample(&self, p: Vec3, u: f32, uv: Vec2) -> Option<AreaSample> {
        let EmitterPoint {
            prim,
            point,
            bary,
            normal,
            area,
            prob,
        } = self.sample_point(u, uv)?;
        let v = point - p;
        let d2 = v.length_squared();
        if d2 <= 0.0 {
            return None;
        }
        let dist = d2.sqrt();
        let wi = v / dist;
        let cos_l = normal.dot(wi).abs();
        if cos_l <= 0.0 {
            return None;
        }
        Some(AreaSample {
            point,
            normal,
            wi,
            dist,
            prim,
            bary,
            pdf: prob / area * d2 / cos_l,
        })
    }

    /// The area density (per m²) with which [`AreaLights::sample_point`] (and so
    /// [`AreaLights::sample`]) picks a point of triangle `prim`, and the triangle's unit
    /// normal (outward front side); `None` if `prim` does not emit or is degenerate.
    pub fn point_pdf(&self, prim: u32) -> Option<(f32, Vec3)> {
        let k = self.emitters.binary_search_by_key(&prim, |e| e.prim).ok()?;
        let Emitter { p: t, prob, .. } = self.emitters[k];
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let area = 0.5 * n.length();
        (area > 0.0 && area.is_finite()).then(|| (prob / area, n / (2.0 * area)))
    }

    /// Solid-angle pdf that `sample` picks the point `q` on triangle `prim` from the
    /// receiver `p`; 0 if `prim` does not emit. For MIS.
    pub fn pdf(&self, prim: u32, p: Vec3, q: Vec3) -> f32 {
        let Ok(k) = self.emitters.binary_search_by_key(&prim, |e| e.prim) else {
            return 0.0;
        };
        let Emitter { p: t, prob, .. } = self.emitters[k];
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let area = 0.5 * n.length();
        let v = q - p;
        let d2 = v.length_squared();
        let cos_l = n.normalize_or_zero().dot(v.normalize_or_zero()).abs();
        if area <= 0.0 || cos_l <= 0.0 {
            return 0.0;
        }
        prob / area * d2 / cos_l
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rng;

    /// Two triangles (index, corners, material) from `first` on.
    fn quad(y: f32, half: f32, material: u32, first: u32) -> Vec<(u32, [Vec3; 3], u32)> {
        // Facing down (−Y): counter-clockwise seen from below.
        let a = Vec3::new(-half, y, -half);
        let b = Vec3::new(half, y, -half);
        let c = Vec3::new(half, y, half);
        let d = Vec3::new(-half, y, half);
        vec![
            (first, [a, b, c], material),
            (first + 1, [a, c, d], material),
        ]
    }

    #[test]
    fn irradiance_from_a_square_light_matches_the_closed_form() {
        // A uniform square emitter of radiance L, half-size h, at height H above the point
        // on its axis: E = 4·L·[x/√(1+x²)·atan(y/√(1+x²)) + y/√(1+y²)·atan(x/√(1+y²))]/2 with
        // x = y = h/H (view factor of a rectangle to a parallel differential area,
        // Howell's catalogue C-11, E = π·L·F).
        let (h, height, l) = (0.5f32, 1.0f32, 3.0f32);
        let mut tris = quad(height, h, 0, 0);
        tris.extend(quad(-5.0, 0.1, 1, 2)); // a dark triangle pair that must never be chosen
        let lights = AreaLights::build(tris, |m| {
            (if m == 0 { Vec3::splat(l) } else { Vec3::ZERO }, true)
        });
        assert_eq!(lights.len(), 2);
        let x = (h / height) as f64;
        let s = (1.0 + x * x).sqrt();
        let f = 2.0 / std::f64::consts::PI * (x / s * (x / s).atan() + x / s * (x / s).atan());
        let expected = std::f64::consts::PI * l as f64 * f;
        let mut rng = Rng::new(&[5]);
        let n = 400_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let u = rng.next_f32();
            let uv = Vec2::new(rng.next_f32(), rng.next_f32());
            let s = lights.sample(Vec3::ZERO, u, uv).unwrap();
            assert!(s.prim < 2);
            let pdf = lights.pdf(s.prim, Vec3::ZERO, s.point);
            assert!(
                (pdf - s.pdf).abs() <= 1e-3 * s.pdf,
                "pdf {pdf} vs {}",
                s.pdf
            );
            sum += (l * s.wi.y.max(0.0) / s.pdf) as f64;
        }
        let est = sum / n as f64;
        assert!(
            (est - expected).abs() < 0.01 * expected,
            "E {est} vs {expected}"
        );
    }
}
