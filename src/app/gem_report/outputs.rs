//! The gem report's files: every picture ([`super::pictures`]) as a PNG and the pages
//! (report.md, report.html, report.json) into the output directory, each atomically, after
//! everything is rendered and measured. PNGs are written without tone mapping (exposure 0,
//! clamped), so an instrument's colours stay its colours.

use super::pictures::{direction_picture, fire_picture, Images};
use super::{json, page, Figures, GemReport, GemReportOptions};
use crate::error::{Error, Result};
use crate::image::ImageRgb;
use crate::output::{DisplayOptions, Exposure, ToneMap};
use std::path::PathBuf;

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
