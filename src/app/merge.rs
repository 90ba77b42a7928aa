//! `iris merge PART.exr… -o OUT.(exr|png)`: adds the partial images of a render's shards
//! ([`super::shard`]) into the image of the whole render.
//!
//! ## Checks (all before anything is written; an error names the files)
//! - every part is an Iris partial image ([`crate::output::partial`]), not the temporary
//!   file of an unfinished write (`.NAME.tmp-PID-N`, what a killed shard may leave);
//! - every part has the first one's identity ([`super::shard_id`]: scene and its content,
//!   method, seed, size, options, …) and the same shard count N;
//! - no unit (sample or pass) is in two parts: overlapping parts (the same shard twice)
//!   are an error naming both;
//! - with a fixed total, every unit is there: a missing shard, or one that stopped early
//!   (`--time`, Ctrl-C), is named with its missing range ("samples 12..18 of 24 are missing
//!   (shard 3/4)"); with an open budget, every shard is there. An interrupted part is
//!   refused too. `--allow-partial` merges what is there instead, and the summary gives
//!   the samples per pixel (fewest and most).
//!
//! ## The image
//! The parts' exact sums are added ([`crate::image::ExactImage::add`]) and divided by the
//! pixel's units: for a fixed total the sums, and so the image, are bit for bit those of
//! one `iris render` of all the units (the same formula, [`crate::image::fixed`]). The
//! output is written atomically, an EXR as `iris render` writes it, a PNG through the same
//! exposure and tone map (`--exposure`, `--tonemap`); the merge does not denoise (it has
//! no scene for the auxiliary pass). The half-buffer error estimate is printed, and
//! `--report` writes one `merge` row with `iris render`'s columns (`--reference`: the
//! error against it).

use super::shard::{Shard, ShardHeader, ShardState};
use crate::error::{Error, Result};
use crate::image::metrics::{compare, half_buffer_estimate, ErrorMetrics};
use crate::image::{ExactImage, ImageRgb};
use crate::measure::report::{write_csv, ReportRow};
use crate::output::{self, partial, DisplayOptions};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Everything `iris merge` needs.
#[derive(Debug, Clone)]
pub struct MergeOptions {
    /// The partial images (`iris render --shard I/N -o PART.exr`).
    pub parts: Vec<PathBuf>,
    /// The merged image (.exr or .png).
    pub output: PathBuf,
    /// `--report`: a CSV with one `merge` row.
    pub report: Option<PathBuf>,
    /// `--reference`: an EXR of the same size to measure the merged image against.
    pub reference: Option<PathBuf>,
    /// `--allow-partial`: merge what is there instead of refusing missing units.
    pub allow_partial: bool,
    /// PNG display options.
    pub display: DisplayOptions,
}

/// What a merge did.
#[derive(Debug, Clone)]
pub struct MergeSummary {
    /// Where the image went.
    pub output: PathBuf,
    /// The merged linear image.
    pub image: ImageRgb,
    /// The method that rendered the parts.
    pub method: String,
    /// "samples" or "passes".
    pub unit: String,
    /// The whole render's units (`None`: an open budget).
    pub total: Option<u64>,
    /// Shard count N.
    pub shards: u32,
    /// Parts merged.
    pub parts: usize,
    /// Fewest and most units (samples or passes) a pixel holds.
    pub units_per_pixel: (u64, u64),
    /// The missing ranges, in words (only with `--allow-partial`).
    pub missing: Vec<String>,
    /// The half-buffer error estimate (when every pixel has both halves).
    pub estimate: Option<ErrorMetrics>,
    /// The error against `--reference`.
    pub error: Option<ErrorMetrics>,
    /// Rays, photons and bad samples over the parts.
    pub counts: (u64, u64, u64),
}

/// A part read: its file, header and exact sums.
struct Part {
    path: PathBuf,
    header: ShardHeader,
    exact: ExactImage,
}

/// Whether `path` names a temporary file of [`crate::output::atomic`] (`.NAME.tmp-PID-N`).
fn is_temporary(path: &Path) -> bool {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    name.is_some_and(|n| n.starts_with('.') && n.contains(".tmp-"))
}

/// Reads one part, refusing temporary files and inconsistent sizes.
fn read_part(path: &Path) -> Result<Part> {
    if is_temporary(path) {
        return Err(Error::Usage(format!(
            "{}: the temporary file of an unfinished write (its shard was killed before it \
             finished): rerun that shard",
            path.display()
        )));
    }
    let p = partial::read(path)?;
    let header = ShardHeader::from_entries(path, &p.entries)?;
    let size = format!("{}x{}", p.exact.width, p.exact.height);
    if header.get("size") != Some(size.as_str()) {
        return Err(Error::Usage(format!(
            "{}: the header says size {:?} but the image is {size}",
            path.display(),
            header.get("size").unwrap_or("none")
        )));
    }
    Ok(Part {
        path: path.to_path_buf(),
        header,
        exact: p.exact,
    })
}

/// The outputs (`-o`, `--report`) checked before any part is read
/// ([`crate::fileio::output`]): writable, distinct, and none of them a part or the
/// `--reference`.
fn check_outputs(opts: &MergeOptions) -> Result<()> {
    use crate::fileio::output::{check_distinct, check_file};
    let mut outputs = vec![("-o", opts.output.as_path())];
    outputs.extend(opts.report.as_deref().map(|p| ("--report", p)));
    for (_, path) in &outputs {
        check_file(path)?;
    }
    let mut inputs: Vec<(&str, &Path)> = opts.parts.iter().map(|p| ("part", p.as_path())).collect();
    inputs.extend(opts.reference.as_deref().map(|p| ("--reference", p)));
    check_distinct(&outputs, &inputs)
}

/// Refuses `b` unless it belongs to the same render as `a` (identity and shard count).
fn check_same_render(a: &Part, b: &Part) -> Result<()> {
    let differ = |what: &str, va: &str, vb: &str| {
        let values = if va.len() + vb.len() <= 600 {
            format!(
                ": {va} in {}, {vb} in {}",
                a.path.display(),
                b.path.display()
            )
        } else {
            String::new()
        };
        Err(Error::Usage(format!(
            "{} and {} are parts of different renders: different {what}{values}",
            a.path.display(),
            b.path.display()
        )))
    };
    // The readable entries first (seed, size, method, …), then the options as given
    // (named by their flag), then the hashes and the integrator's settings.
    let keys: Vec<&String> = (a.header.identity.iter().chain(&b.header.identity))
        .map(|(k, _)| k)
        .collect();
    let compare = |readable: bool| {
        for key in &keys {
            if super::shard_id::is_readable(key) != readable {
                continue;
            }
            let (va, vb) = (a.header.get(key), b.header.get(key));
            if va != vb {
                let what = super::shard_id::describe(key);
                return differ(what, va.unwrap_or("none"), vb.unwrap_or("none"));
            }
        }
        Ok(())
    };
    compare(true)?;
    if let Some((what, va, vb)) =
        super::shard_id::option_difference(a.header.get("options"), b.header.get("options"))
    {
        return differ(&what, &va, &vb);
    }
    compare(false)?;
    if a.header.shard.count != b.header.shard.count {
        let (na, nb) = (a.header.shard.count, b.header.shard.count);
        return differ("shard counts", &na.to_string(), &nb.to_string());
    }
    Ok(())
}

/// "samples 12..18" (`unit` "samples" or "passes").
fn units_text(unit: &str, r: &Range<u64>) -> String {
    format!("{unit} {}..{}", r.start, r.end)
}

/// The missing units of a render of `total` (`None`: open) cut into `n` shards, given the
/// parts sorted by their first unit; in words, one entry per gap.
fn missing(parts: &[Part], n: u32, total: Option<u64>, unit: &str) -> Result<Vec<String>> {
    let mut out = Vec::new();
    for index in 1..=n {
        let shard = Shard { index, count: n };
        let part = parts.iter().find(|p| p.header.shard.index == index);
        let Some(total) = total else {
            if part.is_none() {
                let r = shard.range(crate::render::OPEN_UNITS, unit)?;
                out.push(format!(
                    "shard {shard} is missing ({} of the open budget's block)",
                    units_text(unit, &r)
                ));
            }
            continue;
        };
        let planned = shard.range(total, unit)?;
        match part {
            None => out.push(format!(
                "{} of {total} are missing (shard {shard})",
                units_text(unit, &planned)
            )),
            Some(p) if p.header.done < planned.end - planned.start => {
                let gap = planned.start + p.header.done..planned.end;
                let why = match p.header.state {
                    ShardState::Interrupted => "was interrupted",
                    ShardState::Complete if p.header.end == "time" => "stopped at its time limit",
                    ShardState::Complete => "stopped at its error target",
                };
                out.push(format!(
                    "{} of {total} are missing (shard {shard} {why} after {} of {} {unit}, in {})",
                    units_text(unit, &gap),
                    p.header.done,
                    planned.end - planned.start,
                    p.path.display()
                ));
            }
            Some(_) => {}
        }
    }
    Ok(out)
}

/// `iris merge`: checks the parts (module docs), adds them, writes the image and the
/// report; nothing is written when a check fails.
pub fn merge_command(opts: &MergeOptions) -> Result<MergeSummary> {
    let start = Instant::now();
    output::check_extension(&opts.output)?;
    check_outputs(opts)?;
    let parts = read_parts(opts)?;
    let first = &parts[0].header;
    let (unit, total, n) = (first.unit().to_string(), first.total(), first.shard.count);
    let method = first.get("method").unwrap_or("unknown").to_string();
    let missing = check_complete(opts, &parts, (&unit, total, n))?;
    let reference = opts
        .reference
        .as_deref()
        .map(crate::measure::read_reference_file)
        .transpose()?;
    let (w, h) = (parts[0].exact.width, parts[0].exact.height);
    if let (Some(r), Some(path)) = (&reference, &opts.reference) {
        crate::measure::check_reference_size(r, path, w, h, "the merged image")?;
    }
    let mut sum = ExactImage::new(w, h);
    for p in &parts {
        sum.add(&p.exact);
    }
    let image = sum.mean();
    let (a, b) = sum.halves();
    let units_per_pixel = sum.unit_span();
    let estimate = (units_per_pixel.0 >= 2)
        .then(|| half_buffer_estimate(&a, &b))
        .transpose()?;
    let error = reference.as_ref().map(|r| compare(&image, r)).transpose()?;
    output::write_image(&opts.output, &image, &opts.display)?;
    let counts = parts.iter().fold((0, 0, 0), |c, p| {
        let hd = &p.header;
        (c.0 + hd.rays, c.1 + hd.photons, c.2 + hd.bad_samples)
    });
    if let Some(path) = &opts.report {
        let row = ReportRow {
            run: method.clone(),
            stage: "merge".into(),
            wall_s: start.elapsed().as_secs_f64(),
            samples: units_per_pixel.0,
            passes: if unit == "passes" {
                units_per_pixel.0 as u32
            } else {
                1
            },
            rays: counts.0,
            photons: counts.1,
            error,
            estimate,
            denoised: None,
            denoise_s: None,
            display_estimate: None,
            display_error: None,
        };
        write_csv(path, &[row])?;
    }
    Ok(MergeSummary {
        output: opts.output.clone(),
        image,
        method,
        unit,
        total,
        shards: n,
        parts: parts.len(),
        units_per_pixel,
        missing: if opts.allow_partial {
            missing
        } else {
            Vec::new()
        },
        estimate,
        error,
        counts,
    })
}

/// Reads the parts (at least one), refusing one that the output would replace, one of
/// another render, and two holding the same unit; returns them sorted by their first unit.
fn read_parts(opts: &MergeOptions) -> Result<Vec<Part>> {
    if opts.parts.is_empty() {
        return Err(Error::Usage("iris merge: no partial images given".into()));
    }
    let mut parts = opts
        .parts
        .iter()
        .map(|p| read_part(p))
        .collect::<Result<Vec<_>>>()?;
    for p in &parts {
        if opts.output == p.path {
            return Err(Error::Usage(format!(
                "-o {}: the output would replace one of the parts",
                opts.output.display()
            )));
        }
        check_same_render(&parts[0], p)?;
    }
    parts.sort_by_key(|p| (p.header.planned.start, p.header.shard.index));
    for w in parts.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if a.header.planned.end > b.header.planned.start {
            return Err(Error::Usage(format!(
                "{} (shard {}, {}) and {} (shard {}, {}) overlap: a unit merged twice would \
                 count twice",
                a.path.display(),
                a.header.shard,
                units_text(a.header.unit(), &a.header.planned),
                b.path.display(),
                b.header.shard,
                units_text(b.header.unit(), &b.header.planned)
            )));
        }
    }
    Ok(parts)
}

/// Refuses an interrupted part and missing units unless `--allow-partial`; returns the
/// missing units in words ([`missing`]) of a render of `total` units in `n` shards.
fn check_complete(
    opts: &MergeOptions,
    parts: &[Part],
    (unit, total, n): (&str, Option<u64>, u32),
) -> Result<Vec<String>> {
    if !opts.allow_partial {
        if let Some(p) = parts
            .iter()
            .find(|p| p.header.state == ShardState::Interrupted)
        {
            return Err(Error::Usage(format!(
                "{}: shard {} was interrupted (Ctrl-C or SIGTERM) after {} of its {} {unit}: \
                 rerun it, or merge what is there with --allow-partial",
                p.path.display(),
                p.header.shard,
                p.header.done,
                p.header.planned.end - p.header.planned.start
            )));
        }
    }
    let missing = missing(parts, n, total, unit)?;
    if !missing.is_empty() && !opts.allow_partial {
        return Err(Error::Usage(format!(
            "cannot merge: {}; render the missing shards, or merge what is there with \
             --allow-partial",
            missing.join("; ")
        )));
    }
    Ok(missing)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporary_files_are_recognised_by_name() {
        assert!(is_temporary(Path::new("/x/.part3.exr.tmp-4242-0")));
        assert!(!is_temporary(Path::new("/x/part3.exr")));
        assert!(!is_temporary(Path::new(".hidden.exr")));
        let e = read_part(Path::new("/nowhere/.p.exr.tmp-1-2"))
            .err()
            .unwrap();
        assert!(e.to_string().contains("rerun that shard"), "{e}");
    }
}
