//! The turntable's assemble step (`iris turntable SCENE --frames N -o DIR --assemble`, and
//! the end of a run without `--frame`): checks that every frame `DIR/frame_0000.png` …
//! `frame_{N−1}.png` is there, then writes the animated preview
//! ([`crate::output::animation`]): `DIR/turntable.png` (APNG, lossless) and with `--gif`
//! `DIR/turntable.gif`, each atomically.
//!
//! A missing frame is an error that names every missing frame (and says which exist only as
//! a partial render) and writes nothing; so does a frame that cannot be decoded or differs
//! in size or layout from frame 0 (frames of different renders). After a Slurm array of
//! `--frame F` jobs, this is the job that runs with `--dependency=afterok`.

use super::frame_path;
use crate::error::{Error, Result};
use crate::output::animation::{AnimationEncoder, Frame8};
use crate::output::atomic::write_file_atomic;
use crate::prepare::turntable::Spin;
use std::path::{Path, PathBuf};

/// The animation's file name in `DIR` (APNG keeps the `.png` extension, as its
/// specification recommends).
pub const APNG_NAME: &str = "turntable.png";
/// The GIF's file name in `DIR` (`--gif`).
pub const GIF_NAME: &str = "turntable.gif";

/// What the assemble step wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Assembled {
    /// The APNG.
    pub apng: PathBuf,
    /// The GIF, with `--gif`.
    pub gif: Option<PathBuf>,
    /// Frames in it.
    pub frames: u32,
    /// Frame width and height in pixels.
    pub size: (u32, u32),
    /// Frames per second.
    pub fps: u32,
}

/// Checks that the `frames` frames are in `dir` and writes the animation at `fps` (and a
/// GIF when `gif`); see the module docs.
pub fn assemble(dir: &Path, frames: u32, fps: u32, gif: bool) -> Result<Assembled> {
    Spin::new(0, frames)?;
    let apng_path = dir.join(APNG_NAME);
    let fail = |reason: String| Error::Output {
        path: apng_path.clone(),
        reason,
    };
    if !dir.is_dir() {
        return Err(fail(format!(
            "{} is not a directory of frames (render them first: iris turntable without \
             --assemble, or with --frame F)",
            dir.display()
        )));
    }
    let missing: Vec<u32> = (0..frames)
        .filter(|&f| !frame_path(dir, f, "png", false).is_file())
        .collect();
    if !missing.is_empty() {
        let partial: Vec<u32> = missing
            .iter()
            .copied()
            .filter(|&f| frame_path(dir, f, "png", true).is_file())
            .collect();
        let partial = if partial.is_empty() {
            String::new()
        } else {
            format!(
                "; only partly rendered (still running or interrupted): {}",
                ranges(&partial)
            )
        };
        return Err(fail(format!(
            "{} of the {frames} frames missing in {}: {} (frame_NNNN.png, numbered from \
             0){partial}; render them with --frame F; nothing written",
            missing.len(),
            dir.display(),
            ranges(&missing)
        )));
    }
    let first_path = frame_path(dir, 0, "png", false);
    let first = Frame8::read_png(&first_path)?;
    let mut apng = Vec::new();
    let mut gif_bytes = gif.then(Vec::new);
    let mut enc = AnimationEncoder::new(
        &first,
        &first_path,
        frames,
        fps,
        &mut apng,
        gif_bytes.as_mut(),
    )?;
    enc.push(&first, &first_path)?;
    for f in 1..frames {
        let path = frame_path(dir, f, "png", false);
        enc.push(&Frame8::read_png(&path)?, &path)?;
    }
    enc.finish()?;
    let gif_path = gif_bytes
        .map(|bytes| -> Result<PathBuf> {
            let path = dir.join(GIF_NAME);
            write_file_atomic(&path, &bytes)?;
            Ok(path)
        })
        .transpose()?;
    write_file_atomic(&apng_path, &apng)?;
    Ok(Assembled {
        apng: apng_path,
        gif: gif_path,
        frames,
        size: (first.width, first.height),
        fps,
    })
}

/// `0, 3–5, 9`: sorted frame numbers with runs collapsed.
fn ranges(frames: &[u32]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < frames.len() {
        let start = frames[i];
        let mut end = start;
        while i + 1 < frames.len() && frames[i + 1] == end + 1 {
            end += 1;
            i += 1;
        }
        parts.push(if end == start {
            start.to_string()
        } else {
            format!("{start}–{end}")
        });
        i += 1;
    }
    parts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_frames_are_listed_as_ranges() {
        assert_eq!(ranges(&[]), "");
        assert_eq!(ranges(&[4]), "4");
        assert_eq!(ranges(&[0, 3, 4, 5, 9, 11, 12]), "0, 3–5, 9, 11–12");
    }
}
