//! The lighting of the gemologist's instruments (`iris gem-report`): the surroundings a
//! stone sees, face-up under a viewer, as equirectangular [`EnvMap`]s built in memory.
//!
//! ## Frame and units
//! - The instrument's axis is world +Y: the viewer looks straight down it at a stone whose
//!   table faces +Y ([`crate::prepare::stage`]). A direction's **elevation** e is its angle
//!   above the horizontal plane (the girdle plane of a face-up stone), e = asin(y); its
//!   **azimuth** φ = atan2(x, −z), the map convention of [`crate::light::env::mapping`].
//! - Radiance is linear RGB, dimensionless: 1 is the brightest zone of each instrument,
//!   so a pixel's value is the fraction of that radiance the stone returns.
//! - Maps are [`WIDTH`]×[`HEIGHT`] texels of 0.25°: every band edge below (0°, 45°, 75°) is
//!   a texel edge, so the nearest-texel lookup of [`EnvMap`] puts each direction in the
//!   right band exactly. Band maps hold the value at each texel's centre; the spots of
//!   [`Instrument::Spots`] are anti-aliased (the fraction of a 4×4 grid of sub-directions
//!   inside a spot).
//!
//! ## The instruments
//! | instrument | e < 0° (below the girdle plane) | 0° ≤ e < 45° | 45° ≤ e < 75° | e ≥ 75° |
//! |---|---|---|---|---|
//! | [`Instrument::Aset`] | black (leakage) | green | red | blue (observer) |
//! | [`Instrument::IdealScope`] | white (leakage) | red | red | black (observer) |
//! | [`Instrument::Overcast`] | black | (1 + 2 sin e)/3 grey | (1 + 2 sin e)/3 grey | black (observer's head) |
//! | [`Instrument::Spots`] | black | small white discs on black | discs | black |
//! | [`Instrument::Directions`] | black | (d + 1)/2 | (d + 1)/2 | (d + 1)/2 |
//!
//! - **ASET**, the Angular Spectrum Evaluation Tool of the American Gem Society
//!   Laboratories: the stone seen through a hole at the top of a hemisphere whose inside is
//!   coloured by elevation: red for light from 45°–75° above the girdle plane (the
//!   brightest light), green for 0°–45° (less bright, low angles), blue for 75°–90°, the
//!   region the observer's own head obscures, and black (a lit base shows white) where the
//!   stone shows what is below it, i.e. leaks. Bands as published by AGS Laboratories and
//!   used by Sasian, Quick, Sheffield, Caudill & Yantzer, "Evaluation of brilliance, fire,
//!   and scintillation in round brilliant gemstones", Opt. Eng. 46(9) 093604 (2007).
//! - **Ideal-Scope** (Garry Holloway, after K. Okuda's FireScope of the 1970s): a red
//!   reflector round the stone, a black viewing lens over it; light returned from the red
//!   surround shows red, light from under the stone (leakage) shows white or clear, the
//!   viewer's obscuration black. The obscured cone is taken as ASET's (75°–90°), so the
//!   two images differ only in how they colour the same three regions (Ideal-Scope merges
//!   ASET's red and green and separates leakage, which ASET paints black like nothing).
//! - **Overcast**: the CIE standard overcast sky (Moon & Spencer 1942; CIE S 011/E:2003,
//!   sky type 1), luminance (1 + 2 sin e)/3 of the zenith's, with the observer's head
//!   cone (e ≥ 75°) dark and a black floor: diffuse room light for the face-up picture and
//!   the brilliance figure.
//! - **Spots**: small white discs (angular radius [`SPOT_RADIUS_DEG`]) on black, in rings
//!   at the elevations [`SPOT_ELEVATIONS`] (10°–70°), [`SPOT_SPACING_DEG`] apart along each
//!   ring (⌊360° cos e / spacing⌉ spots, odd rings offset by half a spacing, every ring by
//!   [`SPOT_OFFSET_DEG`] so no spot sits on a round brilliant's mirror plane), none in the
//!   observer's cone: the directed lighting of a jeweller's ceiling of spots, which shows
//!   fire and sparkle (GIA's fire metric uses spot lighting, Reinitz et al., Gems &
//!   Gemology 37(3), 2001; Moscow State University's "Brill" model uses 60 small sources).
//! - **Directions**: not an instrument but a measuring light: the radiance from unit
//!   direction d above the girdle plane is (d + 1)/2 (each component in [0, 1]), so a
//!   pixel's value tells from which direction (averaged over its Fresnel branches, weighted
//!   by their share) the viewer receives the light the stone returns. Nearest texel: the
//!   direction is known to the texel's 0.25°.

use crate::error::Result;
use crate::image::ImageRgb;
use crate::light::env::{uv_to_dir, EnvMap, Environment};
use glam::{Vec2, Vec3};
use std::path::Path;

/// Map width, texels (0.25° each).
pub const WIDTH: u32 = 1440;
/// Map height, texels (0.25° each).
pub const HEIGHT: u32 = 720;
/// Elevation above which the observer's head obscures the light (ASET blue), degrees.
pub const OBSCURED_DEG: f32 = 75.0;
/// Elevation dividing ASET's low (green) from its high (red) band, degrees.
pub const LOW_HIGH_DEG: f32 = 45.0;
/// Angular radius of each spot, degrees.
pub const SPOT_RADIUS_DEG: f32 = 1.0;
/// Elevations of the rings of spots, degrees: 10° to 70° every 5°.
pub const SPOT_ELEVATIONS: [f32; 13] = [
    10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0, 50.0, 55.0, 60.0, 65.0, 70.0,
];
/// Angle between neighbouring spots of a ring, degrees (measured along the ring).
pub const SPOT_SPACING_DEG: f32 = 5.0;
/// Azimuth of the first spot of every even ring, degrees.
pub const SPOT_OFFSET_DEG: f32 = 3.0;

/// A lighting set-up round a face-up stone (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Instrument {
    /// AGS's Angular Spectrum Evaluation Tool: red, green, blue by elevation.
    Aset,
    /// Holloway's Ideal-Scope: red surround, white leakage, black observer.
    IdealScope,
    /// The CIE overcast sky with the observer's head cone dark.
    Overcast,
    /// Rings of small white spots.
    Spots,
    /// Radiance (d + 1)/2 from each direction d above the girdle plane.
    Directions,
}

impl Instrument {
    /// Short name for messages and file names.
    pub fn name(self) -> &'static str {
        match self {
            Instrument::Aset => "ASET",
            Instrument::IdealScope => "Ideal-Scope",
            Instrument::Overcast => "overcast dome",
            Instrument::Spots => "spot dome",
            Instrument::Directions => "direction code",
        }
    }

    /// Whether the instrument codes angles in its colour channels (ASET, Ideal-Scope, the
    /// direction code), so a stone's body colour would corrupt its reading.
    pub fn codes_by_channel(self) -> bool {
        matches!(
            self,
            Instrument::Aset | Instrument::IdealScope | Instrument::Directions
        )
    }

    /// Radiance arriving from elevation `e` (degrees) in the band instruments; `None` for
    /// the spots and the direction code, which depend on the azimuth too.
    pub fn band(self, e: f32) -> Option<Vec3> {
        let (below, low, high, top) = match self {
            Instrument::Aset => (Vec3::ZERO, Vec3::Y, Vec3::X, Vec3::Z),
            Instrument::IdealScope => (Vec3::ONE, Vec3::X, Vec3::X, Vec3::ZERO),
            Instrument::Overcast => {
                let sky = Vec3::splat((1.0 + 2.0 * e.to_radians().sin()) / 3.0);
                (Vec3::ZERO, sky, sky, Vec3::ZERO)
            }
            Instrument::Spots | Instrument::Directions => return None,
        };
        Some(if e < 0.0 {
            below
        } else if e < LOW_HIGH_DEG {
            low
        } else if e < OBSCURED_DEG {
            high
        } else {
            top
        })
    }

    /// The instrument as an environment light.
    pub fn environment(self) -> Result<Environment> {
        let (w, h) = (WIDTH as usize, HEIGHT as usize);
        let data = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f32, (i / w) as f32);
                let centre = Vec2::new((x + 0.5) / w as f32, (y + 0.5) / h as f32);
                match (self, self.band(90.0 - 180.0 * centre.y)) {
                    (_, Some(c)) => c,
                    (Instrument::Directions, None) => direction_code(uv_to_dir(centre)),
                    _ => Vec3::splat(spot_coverage(x, y)),
                }
            })
            .collect();
        let image = ImageRgb {
            width: WIDTH,
            height: HEIGHT,
            data,
        };
        let name = format!("<{} lighting>", self.name());
        Ok(Environment::Map(EnvMap::from_image(
            image,
            Path::new(&name),
        )?))
    }
}

/// The radiance of [`Instrument::Directions`] from unit direction `d`: (d + 1)/2 above the
/// girdle plane (y ≥ 0), black below.
pub fn direction_code(d: Vec3) -> Vec3 {
    if d.y >= 0.0 {
        (d + Vec3::ONE) * 0.5
    } else {
        Vec3::ZERO
    }
}

/// One ring of spots: elevation, count, azimuth of the first spot and step, degrees.
#[derive(Debug, Clone, Copy)]
struct Ring {
    elevation: f32,
    count: u32,
    first: f32,
    step: f32,
}

impl Ring {
    /// The rings of the module docs.
    fn all() -> impl Iterator<Item = Ring> {
        SPOT_ELEVATIONS.iter().enumerate().map(|(k, &elevation)| {
            let count = (360.0 * elevation.to_radians().cos() / SPOT_SPACING_DEG)
                .round()
                .max(1.0) as u32;
            let step = 360.0 / count as f32;
            let first = SPOT_OFFSET_DEG + if k % 2 == 1 { 0.5 * step } else { 0.0 };
            Ring {
                elevation,
                count,
                first,
                step,
            }
        })
    }

    /// The centre of spot `k`.
    fn spot(&self, k: i64) -> Vec3 {
        let phi = (self.first + self.step * k as f32).to_radians();
        let (se, ce) = self.elevation.to_radians().sin_cos();
        Vec3::new(ce * phi.sin(), se, -ce * phi.cos())
    }
}

/// The unit directions of the spots' centres (see the module docs).
pub fn spot_directions() -> Vec<Vec3> {
    Ring::all()
        .flat_map(|r| (0..i64::from(r.count)).map(move |k| r.spot(k)))
        .collect()
}

/// The spots within 2° of unit direction `d`: the nearest two of each ring within
/// 2° of its elevation (a spot is 1° in radius, a texel at most 0.25° across).
fn spots_near(d: Vec3) -> Vec<Vec3> {
    let e = d.y.clamp(-1.0, 1.0).asin().to_degrees();
    let phi = d.x.atan2(-d.z).to_degrees();
    Ring::all()
        .filter(|r| (r.elevation - e).abs() <= SPOT_RADIUS_DEG + 1.0)
        .flat_map(|r| {
            let k = ((phi - r.first) / r.step).floor() as i64;
            [r.spot(k), r.spot(k + 1)]
        })
        .collect()
}

/// Sub-directions per texel side when a texel touches a spot.
const SUPERSAMPLE: u32 = 4;

/// The fraction of texel (x, y) covered by spots.
fn spot_coverage(x: f32, y: f32) -> f32 {
    let (w, h) = (WIDTH as f32, HEIGHT as f32);
    let centre = uv_to_dir(Vec2::new((x + 0.5) / w, (y + 0.5) / h));
    let cos_in = SPOT_RADIUS_DEG.to_radians().cos();
    // A texel is at most 0.25° square: skip the spots farther than radius + 0.5°.
    let near = (SPOT_RADIUS_DEG + 0.5).to_radians().cos();
    let close: Vec<Vec3> = spots_near(centre)
        .into_iter()
        .filter(|s| s.dot(centre) > near)
        .collect();
    if close.is_empty() {
        return 0.0;
    }
    let n = SUPERSAMPLE;
    let mut inside = 0;
    for j in 0..n {
        for i in 0..n {
            let u = (x + (i as f32 + 0.5) / n as f32) / w;
            let v = (y + (j as f32 + 0.5) / n as f32) / h;
            let d = uv_to_dir(Vec2::new(u, v));
            if close.iter().any(|s| s.dot(d) >= cos_in) {
                inside += 1;
            }
        }
    }
    inside as f32 / (n * n) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aset_bands_follow_the_published_angles() {
        let a = Instrument::Aset;
        assert_eq!(a.band(-1.0), Some(Vec3::ZERO));
        assert_eq!(a.band(10.0), Some(Vec3::Y));
        assert_eq!(a.band(44.9), Some(Vec3::Y));
        assert_eq!(a.band(45.0), Some(Vec3::X));
        assert_eq!(a.band(74.9), Some(Vec3::X));
        assert_eq!(a.band(75.0), Some(Vec3::Z));
        assert_eq!(a.band(90.0), Some(Vec3::Z));
    }

    #[test]
    fn ideal_scope_shows_leakage_white_and_the_observer_black() {
        let s = Instrument::IdealScope;
        assert_eq!(s.band(-10.0), Some(Vec3::ONE));
        assert_eq!(s.band(30.0), Some(Vec3::X));
        assert_eq!(s.band(60.0), Some(Vec3::X));
        assert_eq!(s.band(80.0), Some(Vec3::ZERO));
    }

    #[test]
    fn overcast_sky_is_a_third_at_the_horizon() {
        let o = Instrument::Overcast;
        assert!((o.band(0.0).unwrap().x - 1.0 / 3.0).abs() < 1e-6);
        let at_60 = (1.0 + 2.0 * 60f32.to_radians().sin()) / 3.0;
        assert!((o.band(60.0).unwrap().x - at_60).abs() < 1e-6);
        assert_eq!(o.band(80.0), Some(Vec3::ZERO));
    }

    #[test]
    fn band_edges_fall_on_texel_edges_of_the_map() {
        // Rows are 180°/HEIGHT tall; 15°, 45° and 75° are whole numbers of rows.
        let row = 180.0 / HEIGHT as f32;
        for e in [0.0f32, 45.0, 75.0] {
            let rows = (90.0 - e) / row;
            assert!((rows - rows.round()).abs() < 1e-4, "{e}° is {rows} rows");
        }
        let map = match Instrument::Aset.environment().unwrap() {
            Environment::Map(m) => m,
            _ => unreachable!(),
        };
        // Just above and below 45° elevation along −Z.
        let dir = |e: f32| {
            let (s, c) = e.to_radians().sin_cos();
            Vec3::new(0.0, s, -c)
        };
        assert_eq!(map.eval(dir(45.1)), Vec3::X);
        assert_eq!(map.eval(dir(44.9)), Vec3::Y);
        assert_eq!(map.eval(dir(-0.1)), Vec3::ZERO);
        assert_eq!(map.eval(dir(75.1)), Vec3::Z);
    }

    #[test]
    fn spots_light_their_centres_only() {
        let spots = spot_directions();
        // ⌊72 cos e⌉ spots a ring, e = 10°, 15°, …, 70°.
        let expected: u32 = SPOT_ELEVATIONS
            .iter()
            .map(|e| (72.0 * e.to_radians().cos()).round() as u32)
            .sum();
        assert_eq!(spots.len() as u32, expected);
        assert!(spots.len() > 600, "{}", spots.len());
        let env = Instrument::Spots.environment().unwrap();
        for s in &spots {
            assert_eq!(env.eval(*s), Vec3::ONE);
            assert!(s.y < OBSCURED_DEG.to_radians().sin());
        }
        // Half-way between two spots of the first ring, and between rings: dark.
        let (s, c) = 10f32.to_radians().sin_cos();
        let n = (72.0 * c).round();
        let phi = (SPOT_OFFSET_DEG + 0.5 * 360.0 / n).to_radians();
        assert_eq!(
            env.eval(Vec3::new(c * phi.sin(), s, -c * phi.cos())),
            Vec3::ZERO
        );
        let (s, c) = 12.5f32.to_radians().sin_cos();
        assert_eq!(env.eval(Vec3::new(0.0, s, -c)), Vec3::ZERO);
        // A spot's edge is anti-aliased: some texel near the rim is partly lit.
        let rim = spots[0] + 0.98 * SPOT_RADIUS_DEG.to_radians() * Vec3::Y;
        assert!(env.eval(rim.normalize()).x > 0.0);
        assert_eq!(env.eval(Vec3::Y), Vec3::ZERO);
    }

    #[test]
    fn direction_code_recovers_the_direction_to_a_texel() {
        let env = Instrument::Directions.environment().unwrap();
        for d in [
            Vec3::new(0.3, 0.8, -0.2),
            Vec3::new(-0.9, 0.1, 0.4),
            Vec3::Y,
        ] {
            let d = d.normalize();
            let back = env.eval(d) * 2.0 - Vec3::ONE;
            // Within half a texel's diagonal: 0.18° ≈ 0.0031 rad.
            assert!((back - d).length() < 0.0035, "{d} -> {back}");
        }
        assert_eq!(env.eval(Vec3::new(0.0, -0.5, 0.8).normalize()), Vec3::ZERO);
    }
}
