//! The gem report's images: the rendered shots by role ([`Images`]) and the pictures made
//! from them (the fire picture: the spot dome's C, d and F renders as red, green and blue;
//! the direction map), written by [`super::outputs`].

use super::shots::Shot;
use crate::image::ImageRgb;
use glam::Vec3;

/// The rendered images by role.
pub(super) struct Images<'a> {
    /// (tilt, ASET, Ideal-Scope), face-up first.
    pub tilts: Vec<(f32, &'a ImageRgb, &'a ImageRgb)>,
    /// The overcast sky.
    pub overcast: &'a ImageRgb,
    /// Direction code at F, d, C.
    pub code: [&'a ImageRgb; 3],
    /// Spot dome at C, d, F.
    pub spots: [&'a ImageRgb; 3],
}

impl<'a> Images<'a> {
    /// Picks the images of [`super::shots::shots`]`(tilts)` by position.
    pub fn new(list: &[Shot], images: &'a [ImageRgb], tilts: &[f32]) -> Images<'a> {
        let n = 2 * tilts.len();
        debug_assert_eq!(list.len(), n + 7);
        Images {
            tilts: tilts
                .iter()
                .enumerate()
                .map(|(k, &t)| (t, &images[2 * k], &images[2 * k + 1]))
                .collect(),
            overcast: &images[n],
            code: [&images[n + 1], &images[n + 2], &images[n + 3]],
            spots: [&images[n + 4], &images[n + 5], &images[n + 6]],
        }
    }
}

/// The direction map at the d line, contrast stretched: red and blue (0.5 + d.x, 0.5 +
/// d.z) tell the azimuth, green d.y = sin e the elevation (0 at the horizon, 1 overhead),
/// for a pixel whose light all comes from one direction d above the girdle plane (code
/// (d + 1)/2); mixtures and leakage are darker.
pub(super) fn direction_picture(code: &ImageRgb) -> ImageRgb {
    ImageRgb {
        width: code.width,
        height: code.height,
        data: code
            .data
            .iter()
            .map(|&c| {
                let d = 2.0 * c - Vec3::ONE;
                Vec3::new(0.5 + d.x, d.y, 0.5 + d.z).clamp(Vec3::ZERO, Vec3::ONE)
            })
            .collect(),
    }
}

/// The fire picture: the spot-lit face at the C, d and F lines as red, green and blue.
pub(super) fn fire_picture(spots: &[&ImageRgb; 3]) -> ImageRgb {
    let [c, d, f] = spots;
    ImageRgb {
        width: c.width,
        height: c.height,
        data: c
            .data
            .iter()
            .zip(&d.data)
            .zip(&f.data)
            .map(|((r, g), b)| Vec3::new(r.x, g.y, b.z))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::studio::instrument::Instrument;

    #[test]
    fn shots_cover_every_tilt_and_line() {
        let list = super::super::shots::shots(&[0.0, 10.0]);
        assert_eq!(list.len(), 2 * 2 + 7);
        let images: Vec<ImageRgb> = (0..list.len())
            .map(|k| ImageRgb {
                width: 1,
                height: 1,
                data: vec![Vec3::splat(k as f32)],
            })
            .collect();
        let set = Images::new(&list, &images, &[0.0, 10.0]);
        assert_eq!(set.tilts[1].0, 10.0);
        assert_eq!(set.tilts[1].1.data[0].x, 2.0);
        assert_eq!(list[2].instrument, Instrument::Aset);
        assert_eq!(set.overcast.data[0].x, 4.0);
        assert_eq!(list[4].instrument, Instrument::Overcast);
        assert_eq!(list[5].instrument, Instrument::Directions);
        assert!(matches!(list[8].instrument, Instrument::Spots));
        assert_eq!(set.spots[2].data[0].x, 10.0);
    }
}
