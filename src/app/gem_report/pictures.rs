//! The gem report's images: the rendered shots by role ([`Images`]), the pictures made
//! from them (the fire picture: the spot dome's C, d and F renders as red, green and blue;
//! the direction map), and the writing of every file into the output directory, each
//! atomically, after everything is rendered and measured. PNGs are written without tone
//! mapping (exposure 0, clamped), so an instrument's colours stay its colours.

use super::shots::Shot;
use super::{json, page, Figures, GemReport, GemReportOptions};
use crate::error::{Error, Result};
use crate::image::ImageRgb;
use crate::output::{DisplayOptions, Exposure, ToneMap};
use glam::Vec3;
use std::path::PathBuf;

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

/// Writes the images and pages into the output directory; returns the paths written.
pub(super) fn write_outputs(
    opts: &GemReportOptions,
    set: &Images,
    report: &GemReport,
    figs: &Figures,
) -> Result<Vec<PathBuf>> {
    let dir = &opts.out_dir;
    std::fs::create_dir_all(dir).map_err(|e| Error::Output {
        path: dir.clone(),
        reason: e.to_string(),
    })?;
    let display = DisplayOptions {
        exposure: Exposure::Ev(0.0),
        tonemap: ToneMap::Clamp,
    };
    let mut pictures: Vec<(String, ImageRgb)> = Vec::new();
    for &(t, a, s) in &set.tilts {
        let (aset, scope) = if t == 0.0 {
            ("aset.png".to_string(), "ideal-scope.png".to_string())
        } else {
            (
                format!("tilt-{}.png", tilt_name(t)),
                format!("tilt-{}-ideal-scope.png", tilt_name(t)),
            )
        };
        pictures.push((aset, a.clone()));
        pictures.push((scope, s.clone()));
    }
    pictures.push(("face-up.png".into(), set.overcast.clone()));
    pictures.push(("fire.png".into(), fire_picture(&set.spots)));
    pictures.push(("directions.png".into(), direction_picture(set.code[1])));
    let mut written = Vec::new();
    for (name, image) in &pictures {
        let path = dir.join(name);
        crate::output::write_image(&path, image, &display)?;
        written.push(path);
    }
    let names: Vec<&str> = pictures.iter().map(|(n, _)| n.as_str()).collect();
    for (name, text) in [
        ("report.md", page::markdown(opts, report, figs, &names)),
        ("report.html", page::html(opts, report, figs, &names)),
        ("report.json", json::json(opts, report, figs)?),
    ] {
        let path = dir.join(name);
        crate::output::atomic::write_file_atomic(&path, text.as_bytes())?;
        written.push(path);
    }
    Ok(written)
}

/// A tilt in a file name: `10`, `-5`, `12.5`.
fn tilt_name(t: f32) -> String {
    format!("{t}")
}

/// The direction map at the d line, contrast stretched: red and blue (0.5 + d.x, 0.5 +
/// d.z) tell the azimuth, green d.y = sin e the elevation (0 at the horizon, 1 overhead),
/// for a pixel whose light all comes from one direction d above the girdle plane (code
/// (d + 1)/2); mixtures and leakage are darker.
fn direction_picture(code: &ImageRgb) -> ImageRgb {
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
fn fire_picture(spots: &[&ImageRgb; 3]) -> ImageRgb {
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
