//! The gem report's figures, measured on the shots' images ([`super::shots`]). Every figure
//! is a mean over the stone's **face**: the pixels weighted by their coverage α (the
//! fraction of the pixel's camera samples that hit the stone), A = Σ α. The instruments are
//! [`crate::studio::instrument`]'s; the definitions below are this report's computable
//! versions of the gemological ones, and say what they simplify.
//!
//! - **Light return, obscuration, leakage** (the angular spectrum of ASET; AGS
//!   Laboratories; Sasian et al., Opt. Eng. 46(9) 093604, 2007): with (r, g, b) the ASET
//!   image and (R, G, B) the Ideal-Scope image,
//!   high = Σ r / A (light from 45°–75°), low = Σ g / A (0°–45°),
//!   obscured = Σ b / A (75°–90°, the viewer's head),
//!   leakage = Σ (G − (1 − α)) / A (light from below the girdle plane: Ideal-Scope's white,
//!   minus the white background of the uncovered part of edge pixels),
//!   light return = high + low, other = 1 − light return − obscured − leakage (absorbed
//!   in a coloured stone; paths ended by the depth limit). Fractions of the light the
//!   viewer sees in the face, each in [0, 1] for a clear stone, summing to 1.
//! - **Zones**: the same on the face-up images, for the pixels whose centre lies at a
//!   distance ρ from the stone's axis with ρ / girdle radius in [0, 0.3) (centre),
//!   [0.3, 0.7) (middle), [0.7, ∞) (outer). A too-deep pavilion darkens the centre (the
//!   "nailhead": light from the viewer's own cone) and leaks near the girdle; a
//!   too-shallow one leaks in a ring round the table ("fish-eye").
//! - **Brilliance**: after GIA's weighted light return (Hemphill et al., Gems & Gemology
//!   34(3), 1998: light returned through the crown under diffuse light, the observer's
//!   head blocking some): the mean luminance of the face under the CIE overcast sky with
//!   the head cone dark, relative to the sky's zenith luminance, B = Σ Y / A. Simplified:
//!   one viewing direction, the sky's luminance instead of GIA's cosine weighting of
//!   the returned rays.
//! - **Fire**: after GIA's dispersed coloured light return (Reinitz et al., Gems &
//!   Gemology 37(3), 2001: the light returned with colour enough to be seen as fire, under
//!   spot lighting) and the angular spread of the spectrum in Sasian et al. 2007: with
//!   m_λ the direction-code image at the Fraunhofer line λ (the Fresnel-weighted mean of
//!   (d + 1)/2 over the directions d above the girdle plane the pixel's light comes from),
//!   the pixel's **spread** is θ = 2 asin(min(|m_C − m_F|, 1)), the angle between the
//!   directions red (656 nm) and blue (486 nm) light reach the viewer from (2 asin(|Δm|) is
//!   the angle between two unit directions whose codes differ by Δm; light from below the
//!   girdle plane counts 0). A light source of angular size s shows colour where θ ≳ s, so
//!   fire = Σ min(θ / s, 1) / A with s = [`FIRE_SOURCE_DEG`]: the share of the face that
//!   shows a 1° light source in colour (a ramp below 1°); with it the median spread of
//!   the pixels whose light comes from above the girdle plane. Simplified: two
//!   wavelengths, directions known to the direction map's 0.25° texels, one mean
//!   direction per pixel (branches of one pixel that split apart partly cancel),
//!   no threshold of visibility in luminance or chroma.
//! - **Scintillation**: after GIA's sparkle (Moses et al., Gems & Gemology 40(3), 2004:
//!   the bright flashes a face-up stone shows under spot lighting) and the virtual facets
//!   of Sasian et al. 2007: the number of **flashes** face-up under the spot dome at the d
//!   line: connected regions (4-neighbours) of pixels at least [`FLASH_LEVEL`] of a spot's
//!   radiance, of at least [`min_flash_pixels`] pixels; each is a virtual facet showing a
//!   spot, and the more and smaller they are, the more the stone sparkles as it, the light
//!   or the viewer moves. Also the lit share of the face. Simplified: one still view under
//!   one standard lighting (no motion, no flash timing); counted at the report's
//!   resolution.

use super::pictures::Images;
use crate::image::{Coverage, ImageRgb};
use glam::Vec3;

/// Angular size of the light source fire is measured for, degrees.
pub const FIRE_SOURCE_DEG: f64 = 1.0;

/// Brightness, as a fraction of a spot's radiance, from which a pixel counts as lit.
pub const FLASH_LEVEL: f32 = 0.25;

/// The zones' outer edges as fractions of the girdle radius (the last is unbounded).
pub const ZONES: [(&str, f32, f32); 3] = [
    ("centre", 0.0, 0.3),
    ("middle", 0.3, 0.7),
    ("outer", 0.7, f32::INFINITY),
];

/// Where the light the viewer sees in (part of) the face comes from, as fractions.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Returns {
    /// From 45°–75° above the girdle plane (ASET red).
    pub high: f64,
    /// From 0°–45° (ASET green).
    pub low: f64,
    /// From 75°–90°, where the viewer's head is (ASET blue).
    pub obscured: f64,
    /// From below the girdle plane (Ideal-Scope white).
    pub leakage: f64,
    /// The rest: absorbed, or lost at the depth limit.
    pub other: f64,
    /// The face area measured, pixels (Σ α).
    pub area: f64,
}

impl Returns {
    /// Light return: high + low.
    pub fn light_return(&self) -> f64 {
        self.high + self.low
    }
}

/// The pixel layout of the face: image centre on the stone's axis.
#[derive(Debug, Clone, Copy)]
pub struct Layout {
    /// Girdle radius in pixels.
    pub girdle_px: f32,
}

impl Layout {
    /// Distance of pixel (x, y)'s centre from the axis over the girdle radius.
    pub fn rho(&self, w: u32, h: u32, x: u32, y: u32) -> f32 {
        let dx = x as f32 + 0.5 - 0.5 * w as f32;
        let dy = y as f32 + 0.5 - 0.5 * h as f32;
        dx.hypot(dy) / self.girdle_px.max(f32::MIN_POSITIVE)
    }
}

/// [`Returns`] over the pixels `keep` accepts (see the module docs).
pub fn returns(
    aset: &ImageRgb,
    scope: &ImageRgb,
    cov: &Coverage,
    keep: impl Fn(u32, u32) -> bool,
) -> Returns {
    let (w, h) = (cov.width, cov.height);
    let (mut a, mut high, mut low, mut obs, mut leak) = (0.0f64, 0.0f64, 0.0, 0.0, 0.0);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            if !keep(x, y) {
                continue;
            }
            let (alpha, c, s) = (f64::from(cov.alpha[i]), aset.data[i], scope.data[i]);
            a += alpha;
            high += f64::from(c.x);
            low += f64::from(c.y);
            obs += f64::from(c.z);
            leak += f64::from(s.y) - (1.0 - alpha);
        }
    }
    if a <= 0.0 {
        return Returns::default();
    }
    let r = Returns {
        high: high / a,
        low: low / a,
        obscured: obs / a,
        leakage: (leak / a).max(0.0),
        other: 0.0,
        area: a,
    };
    Returns {
        other: 1.0 - r.light_return() - r.obscured - r.leakage,
        ..r
    }
}

/// [`Returns`] of each of the [`ZONES`] of the face-up images.
pub fn zones(
    aset: &ImageRgb,
    scope: &ImageRgb,
    cov: &Coverage,
    layout: Layout,
) -> Vec<(&'static str, Returns)> {
    let (w, h) = (cov.width, cov.height);
    ZONES
        .iter()
        .map(|&(name, lo, hi)| {
            let keep = |x, y| (lo..hi).contains(&layout.rho(w, h, x, y));
            (name, returns(aset, scope, cov, keep))
        })
        .collect()
}

/// The face's area, Σ α.
fn area(cov: &Coverage) -> f64 {
    cov.alpha.iter().map(|&a| f64::from(a)).sum()
}

/// Brilliance: the mean luminance of the face under the overcast sky (zenith 1).
pub fn brilliance(overcast: &ImageRgb, cov: &Coverage) -> f64 {
    let a = area(cov);
    if a <= 0.0 {
        return 0.0;
    }
    let y: f64 = overcast
        .data
        .iter()
        .map(|&c| f64::from(crate::output::tonemap::luminance(c)))
        .sum();
    y / a
}

/// The spread θ of one pixel, degrees, from its direction codes at the F and C lines.
pub fn spread_degrees(code_f: Vec3, code_c: Vec3) -> f64 {
    f64::from(2.0 * (code_c - code_f).length().min(1.0).asin()).to_degrees()
}

/// Fire: the share of the face that shows a [`FIRE_SOURCE_DEG`] source in colour.
pub fn fire(code_f: &ImageRgb, code_c: &ImageRgb, cov: &Coverage) -> f64 {
    let a = area(cov);
    if a <= 0.0 {
        return 0.0;
    }
    let sum: f64 = code_f
        .data
        .iter()
        .zip(&code_c.data)
        .map(|(&f, &c)| (spread_degrees(f, c) / FIRE_SOURCE_DEG).min(1.0))
        .sum();
    sum / a
}

/// The median spread, degrees, of the pixels fully on the face lit from above the girdle
/// plane at both lines (0 when there is none).
pub fn median_spread(code_f: &ImageRgb, code_c: &ImageRgb, cov: &Coverage) -> f64 {
    let mut spreads: Vec<f64> = code_f
        .data
        .iter()
        .zip(&code_c.data)
        .zip(&cov.alpha)
        .filter(|((f, c), &a)| a >= 1.0 && f.max_element() > 0.0 && c.max_element() > 0.0)
        .map(|((&f, &c), _)| spread_degrees(f, c))
        .collect();
    if spreads.is_empty() {
        return 0.0;
    }
    spreads.sort_by(f64::total_cmp);
    spreads[spreads.len() / 2]
}

/// Smallest region counted as a flash: 1/20 000 of the face, at least 2 pixels.
pub fn min_flash_pixels(face_pixels: f64) -> usize {
    ((face_pixels / 20_000.0) as usize).max(2)
}

/// Flashes under the spot dome: (count, lit share of the face).
pub fn flashes(spots: &ImageRgb, cov: &Coverage) -> (usize, f64) {
    let (w, h) = (spots.width as usize, spots.height as usize);
    let lit: Vec<bool> = spots
        .data
        .iter()
        .map(|&c| crate::output::tonemap::luminance(c) >= FLASH_LEVEL)
        .collect();
    let face = area(cov);
    let min = min_flash_pixels(face);
    let mut seen = vec![false; w * h];
    let mut stack = Vec::new();
    let mut count = 0;
    for start in 0..w * h {
        if !lit[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut size = 0usize;
        while let Some(i) = stack.pop() {
            size += 1;
            let (x, y) = (i % w, i / w);
            let neighbours = [
                (x > 0).then(|| i - 1),
                (x + 1 < w).then(|| i + 1),
                (y > 0).then(|| i - w),
                (y + 1 < h).then(|| i + w),
            ];
            for j in neighbours.into_iter().flatten() {
                if lit[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        if size >= min {
            count += 1;
        }
    }
    let lit_px = lit.iter().filter(|&&b| b).count() as f64;
    (count, if face > 0.0 { lit_px / face } else { 0.0 })
}

/// Every figure of a report.
#[derive(Debug, Clone)]
pub struct Figures {
    /// Face-up returns.
    pub face_up: Returns,
    /// Face-up returns by zone.
    pub zones: Vec<(&'static str, Returns)>,
    /// Returns at each tilt, face-up first.
    pub tilts: Vec<(f32, Returns)>,
    /// Brilliance, a fraction of the zenith luminance.
    pub brilliance: f64,
    /// Fire: the share of the face showing a 1° source in colour.
    pub fire: f64,
    /// Median spread between the C and F lines' directions, degrees.
    pub median_spread: f64,
    /// Scintillation: flashes counted face-up under the spot dome.
    pub flashes: usize,
    /// The lit share of the face under the spot dome.
    pub lit: f64,
}

/// Every figure from the images (see the module docs).
pub(super) fn measure(set: &Images, covers: &[Coverage], layout: Layout) -> Figures {
    let (_, aset, scope) = set.tilts[0];
    let face = &covers[0];
    let all = |_, _| true;
    let (flashes, lit) = flashes(set.spots[1], face);
    Figures {
        face_up: returns(aset, scope, face, all),
        zones: zones(aset, scope, face, layout),
        tilts: set
            .tilts
            .iter()
            .zip(covers)
            .map(|(&(t, a, s), c)| (t, returns(a, s, c, all)))
            .collect(),
        brilliance: brilliance(set.overcast, face),
        fire: fire(set.code[0], set.code[2], face),
        median_spread: median_spread(set.code[0], set.code[2], face),
        flashes,
        lit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: u32, h: u32, f: impl Fn(u32, u32) -> Vec3) -> ImageRgb {
        ImageRgb {
            width: w,
            height: h,
            data: (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| f(x, y))
                .collect(),
        }
    }

    fn full(w: u32, h: u32) -> Coverage {
        Coverage {
            width: w,
            height: h,
            alpha: vec![1.0; (w * h) as usize],
            escaped: vec![Vec3::ZERO; (w * h) as usize],
        }
    }

    #[test]
    fn returns_add_up_and_read_the_right_channels() {
        let aset = image(2, 1, |x, _| {
            if x == 0 {
                Vec3::new(0.5, 0.2, 0.1)
            } else {
                Vec3::new(0.1, 0.1, 0.0)
            }
        });
        let scope = image(2, 1, |x, _| {
            if x == 0 {
                Vec3::new(0.8, 0.2, 0.2)
            } else {
                Vec3::new(1.0, 0.8, 0.8)
            }
        });
        let r = returns(&aset, &scope, &full(2, 1), |_, _| true);
        assert!((r.high - 0.3).abs() < 1e-6 && (r.low - 0.15).abs() < 1e-6);
        assert!((r.obscured - 0.05).abs() < 1e-6 && (r.leakage - 0.5).abs() < 1e-6);
        let sum = r.light_return() + r.obscured + r.leakage + r.other;
        assert!((sum - 1.0).abs() < 1e-12);
        assert!((r.other - 0.0).abs() < 1e-6);
    }

    #[test]
    fn leakage_discounts_the_background_of_edge_pixels() {
        // Half covered, the stone part returning everything red: Ideal-Scope shows
        // 0.5 red + 0.5 white background.
        let aset = image(1, 1, |_, _| Vec3::new(0.5, 0.0, 0.0));
        let scope = image(1, 1, |_, _| Vec3::new(1.0, 0.5, 0.5));
        let mut cov = full(1, 1);
        cov.alpha[0] = 0.5;
        let r = returns(&aset, &scope, &cov, |_, _| true);
        assert!(
            (r.high - 1.0).abs() < 1e-6 && r.leakage.abs() < 1e-6,
            "{r:?}"
        );
    }

    #[test]
    fn zones_split_by_radius() {
        let layout = Layout { girdle_px: 10.0 };
        assert!(layout.rho(20, 20, 10, 10) < 0.1);
        assert!((layout.rho(20, 20, 19, 10) - 9.5f32.hypot(0.5) / 10.0).abs() < 1e-6);
        // Leakage only in the centre: the centre zone leaks, the outer does not.
        let aset = image(20, 20, |_, _| Vec3::ZERO);
        let scope = image(20, 20, |x, y| {
            if layout.rho(20, 20, x, y) < 0.3 {
                Vec3::ONE
            } else {
                Vec3::X
            }
        });
        let z = zones(&aset, &scope, &full(20, 20), layout);
        assert_eq!(z[0].0, "centre");
        assert!((z[0].1.leakage - 1.0).abs() < 1e-6);
        assert!(z[2].1.leakage.abs() < 1e-6);
    }

    #[test]
    fn fire_ramps_with_the_spread_up_to_the_source_size() {
        // Red light from straight up, blue `deg` away, in every pixel.
        let code = |deg: f32| {
            let (s, c) = deg.to_radians().sin_cos();
            (Vec3::new(s, c, 0.0) + Vec3::ONE) * 0.5
        };
        assert!((spread_degrees(code(0.3), code(0.0)) - 0.3).abs() < 1e-3);
        let c = image(4, 4, |_, _| code(0.0));
        let half = fire(&image(4, 4, |_, _| code(0.5)), &c, &full(4, 4));
        assert!((half - 0.5).abs() < 1e-3, "{half}");
        let wide = fire(&image(4, 4, |_, _| code(3.0)), &c, &full(4, 4));
        assert!((wide - 1.0).abs() < 1e-9, "{wide}");
        assert_eq!(fire(&c, &c, &full(4, 4)), 0.0);
    }

    #[test]
    fn flashes_are_lit_regions_big_enough() {
        // Two lit squares, one single lit pixel (below the minimum of 2), dim elsewhere.
        let spots = image(40, 40, |x, y| {
            let lit = (x < 5 && y < 5) || (x >= 30 && y >= 30) || (x == 20 && y == 20);
            Vec3::splat(if lit { 0.8 } else { 0.2 })
        });
        let (n, share) = flashes(&spots, &full(40, 40));
        assert_eq!(n, 2);
        assert!((share - 126.0 / 1600.0).abs() < 1e-9);
    }
}
