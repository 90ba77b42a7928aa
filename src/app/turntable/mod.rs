//! `iris turntable SCENE --frames N -o DIR` as a library call: N frames of the model
//! turning once about the vertical axis under fixed lights and a fixed camera (why the
//! model turns: [`crate::prepare::turntable`]), written as `DIR/frame_0000.png` …, then an
//! animated preview ([`assemble`]).
//!
//! - **Frames are numbered from 0**: frame F shows the model turned by 360°·F/N, F = 0 …
//!   N − 1 (a Slurm array `--array=0-35` for N = 36). Frame 0 is the file as it is.
//! - **Each frame is an `iris render`** through [`RenderJob`] with the frame's turn
//!   ([`RenderOptions::spin`]): every render flag applies per frame (method, budget, size,
//!   studio, stones, denoise …). The **seed is the same for every frame** (`--seed`, as
//!   Blender Cycles' default): the noise pattern stays put instead of crawling from frame
//!   to frame, and the same frame rendered twice with a count budget (`--spp`, `--passes`)
//!   gives the same bytes. `--method auto` is resolved **once, on frame 0's scene** (every
//!   job prepares frame 0's scene for it), and every frame renders with that method, so
//!   the frames never switch between path tracer, hybrid and SPPM.
//! - **One exposure for the whole turn**: `--exposure auto` is locked from probe renders
//!   at quarter turns, the same in every job ([`exposure`]); `--exposure EV` as given.
//! - **Frames appear whole or not at all**: a frame renders to `frame_0007.partial.png`
//!   (rewritten at checkpoints, so it can be watched) and is renamed to `frame_0007.png`
//!   only when its render ends other than by interruption (the `.exr` of `--exr` first,
//!   the `.png` last: the PNG marks the frame done). Ctrl-C or SIGTERM removes the partial
//!   frame, stops the sequence and writes no animation.
//! - Without `--frame`: every frame in order, then the animation. `--frame F`: only frame
//!   F. `--assemble`: only the animation, from the frames on disk ([`assemble`]: it names
//!   the missing frames and writes nothing when one is missing).
//! - `--reference`, `--report` and `--plot` are per-image measurements and are refused
//!   (render one frame with `iris render` for them).

pub mod assemble;
pub mod exposure;

use super::render::{RenderJob, RenderSummary};
use super::render_options::RenderOptions;
use crate::error::{Error, Result};
use crate::integrator::Method;
use crate::prepare::turntable::Spin;
use crate::render::EndReason;
pub use assemble::{assemble, Assembled};
use std::path::{Path, PathBuf};

/// Which part of the turntable to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    /// Every frame, then the animation.
    All,
    /// Only this frame (`--frame F`).
    Frame(u32),
    /// Only the animation, from the frames on disk (`--assemble`).
    Assemble,
}

/// Everything `iris turntable` needs.
#[derive(Debug, Clone)]
pub struct TurntableOptions {
    /// The render flags of every frame (`output` and `spin` are set per frame).
    pub render: RenderOptions,
    /// The output directory (`-o DIR`).
    pub dir: PathBuf,
    /// Frames in the whole turn, 1 to [`crate::prepare::turntable::MAX_FRAMES`].
    pub frames: u32,
    /// What to do.
    pub step: Step,
    /// Frames per second of the animation, 1 to [`crate::output::animation::MAX_FPS`].
    pub fps: u32,
    /// Also write each frame as linear EXR (`frame_0000.exr`).
    pub exr: bool,
    /// Also write the animation as GIF (`turntable.gif`).
    pub gif: bool,
}

/// `DIR/frame_0007.png` (`ext` = `png` or `exr`; `partial` adds `.partial` before it).
pub fn frame_path(dir: &Path, frame: u32, ext: &str, partial: bool) -> PathBuf {
    let part = if partial { ".partial" } else { "" };
    dir.join(format!("frame_{frame:04}{part}.{ext}"))
}

/// What happens as the turntable goes, for the caller to print.
pub enum Event<'a> {
    /// A decision for every frame (the method, the exposure), before the first frame.
    Note(&'a str),
    /// A frame is about to render (`degrees` of turn); `plan` is its plan text when
    /// `--explain` asked for it (the first frame only).
    Starting {
        /// The frame.
        frame: u32,
        /// Its turn in degrees.
        degrees: f64,
        /// The plan with costs, under `--explain`, for the first frame rendered.
        plan: Option<String>,
    },
    /// A frame is done and in place (`output`).
    Done {
        /// The frame.
        frame: u32,
        /// Where it is.
        output: &'a Path,
        /// Its render.
        summary: &'a RenderSummary,
    },
}

/// What `iris turntable` did.
#[derive(Debug, Clone, Default)]
pub struct TurntableSummary {
    /// Frames rendered and in place, in order.
    pub rendered: Vec<u32>,
    /// The frame a Ctrl-C or SIGTERM interrupted (removed; nothing assembled).
    pub interrupted: Option<u32>,
    /// `--method auto`'s choice on frame 0 and its reason, when it was resolved here.
    pub method_note: Option<String>,
    /// How `--exposure auto` was locked for the whole turn ([`exposure`]).
    pub exposure_note: Option<String>,
    /// The animation, when assembled.
    pub assembled: Option<Assembled>,
}

/// Checks every turntable flag before anything renders or is written: the frame count,
/// `--frame`, `--fps`, the refused measurement flags, and (unless only assembling) that
/// `DIR` can be created and written.
pub fn check(opts: &TurntableOptions) -> Result<()> {
    Spin::new(0, opts.frames)?;
    if let Step::Frame(f) = opts.step {
        if f >= opts.frames {
            return Err(Error::Usage(format!(
                "--frame {f}: out of range for --frames {} (frames are numbered 0 to {})",
                opts.frames,
                opts.frames - 1
            )));
        }
    }
    let fps = opts.fps;
    if !(1..=crate::output::animation::MAX_FPS).contains(&fps) {
        return Err(Error::Usage(format!(
            "--fps {fps}: frames per second must be 1 to {}",
            crate::output::animation::MAX_FPS
        )));
    }
    let m = &opts.render.measure;
    if m.reference.is_some() || m.report.is_some() || m.plot.is_some() {
        return Err(Error::Usage(
            "--reference, --report and --plot measure one image: not with iris turntable \
             (render a frame with iris render for them)"
                .into(),
        ));
    }
    match opts.step {
        Step::Assemble => Ok(()),
        Step::All => prepare_dir(&opts.dir, "all"),
        Step::Frame(f) => prepare_dir(&opts.dir, &f.to_string()),
    }
}

/// Creates `dir` and proves it writable with a probe file named after `job` (frame jobs
/// of one array may share the directory, on several machines), removed again.
fn prepare_dir(dir: &Path, job: &str) -> Result<()> {
    let fail = |e: std::io::Error| Error::Output {
        path: dir.to_path_buf(),
        reason: format!("-o: cannot write the turntable's frames in this directory: {e}"),
    };
    if dir.exists() && !dir.is_dir() {
        return Err(Error::Output {
            path: dir.to_path_buf(),
            reason: "-o: not a directory (iris turntable writes its frames into a directory)"
                .into(),
        });
    }
    std::fs::create_dir_all(dir).map_err(fail)?;
    let probe = dir.join(format!(
        ".iris-turntable-probe-{job}-{}",
        std::process::id()
    ));
    std::fs::write(&probe, b"").map_err(fail)?;
    match std::fs::remove_file(&probe) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(fail(e)),
        _ => Ok(()),
    }
}

/// `iris turntable`: checks the flags ([`check`]), renders the frames the step asks for,
/// in order, telling `on_event` as it goes, then assembles the animation (not after
/// `--frame`, nor after an interruption).
pub fn turntable_command(
    opts: &TurntableOptions,
    mut on_event: impl FnMut(Event<'_>),
) -> Result<TurntableSummary> {
    check(opts)?;
    let mut summary = TurntableSummary::default();
    let frames: Vec<u32> = match opts.step {
        Step::All => (0..opts.frames).collect(),
        Step::Frame(f) => vec![f],
        Step::Assemble => Vec::new(),
    };
    // `--method auto`: frame 0's choice for every frame; `--exposure auto`: one exposure
    // for the whole turn ([`exposure`]).
    let mut render = opts.render.clone();
    if !frames.is_empty() {
        if render.method == Method::Auto {
            let (m, note) = frame_zero_method(opts)?;
            render.method = m;
            summary.method_note =
                note.map(|n| format!("{n}; chosen on frame 0's scene, for every frame"));
        }
        let (e, note) = exposure::locked(opts, render.method)?;
        render.display.exposure = e;
        summary.exposure_note = note;
        let notes = [&summary.method_note, &summary.exposure_note];
        for n in notes.into_iter().flatten() {
            on_event(Event::Note(n));
        }
    }
    let opts = &TurntableOptions {
        render,
        ..opts.clone()
    };
    // A signal stops the frame in flight, which is removed ([`TurntableSummary::interrupted`]).
    let _honour = crate::interrupt::Honour::begin();
    for &frame in &frames {
        let ro = frame_options(opts, frame)?;
        let job = RenderJob::new(&ro)?;
        let explain = (opts.render.explain && summary.rendered.is_empty())
            .then(|| job.plan.text_with_costs());
        on_event(Event::Starting {
            frame,
            degrees: Spin::new(frame, opts.frames)?.degrees(),
            plan: explain,
        });
        let partials = partial_paths(opts, frame);
        let done = job.run().and_then(|s| {
            if s.end() == EndReason::Interrupted || crate::render::guard::stop_requested() {
                return Ok((s, false));
            }
            put_in_place(opts, frame)?;
            Ok((s, true))
        });
        match done {
            Ok((s, true)) => {
                let output = frame_path(&opts.dir, frame, "png", false);
                on_event(Event::Done {
                    frame,
                    output: &output,
                    summary: &s,
                });
                summary.rendered.push(frame);
            }
            Ok((_, false)) => {
                remove_all(&partials);
                summary.interrupted = Some(frame);
                return Ok(summary);
            }
            Err(e) => {
                remove_all(&partials);
                return Err(e);
            }
        }
    }
    if !matches!(opts.step, Step::Frame(_)) {
        summary.assembled = Some(assemble(&opts.dir, opts.frames, opts.fps, opts.gif)?);
    }
    Ok(summary)
}

/// The render options of frame `frame`: the flags, the frame's turn and its partial
/// outputs.
fn frame_options(opts: &TurntableOptions, frame: u32) -> Result<RenderOptions> {
    Ok(RenderOptions {
        output: Some(frame_path(&opts.dir, frame, "png", true)),
        exr_copy: opts.exr.then(|| frame_path(&opts.dir, frame, "exr", true)),
        spin: Some(Spin::new(frame, opts.frames)?),
        ..opts.render.clone()
    })
}

/// `--method auto` resolved on frame 0's scene (the one preparation, with frame 0's turn),
/// with its reason.
fn frame_zero_method(opts: &TurntableOptions) -> Result<(Method, Option<String>)> {
    let ro = frame_options(opts, 0)?;
    let prepared = crate::prepare::prepare(&ro.scene, &ro.prepare_options(None))?;
    Ok(crate::plan::resolve_method(
        Method::Auto,
        &prepared.scene,
        &prepared.camera.projection,
    ))
}

/// The partial outputs of `frame`.
fn partial_paths(opts: &TurntableOptions, frame: u32) -> Vec<PathBuf> {
    let mut v = vec![frame_path(&opts.dir, frame, "png", true)];
    if opts.exr {
        v.push(frame_path(&opts.dir, frame, "exr", true));
    }
    v
}

/// Renames the finished frame's partial files to their final names, the EXR first: the
/// PNG's presence marks the frame done.
fn put_in_place(opts: &TurntableOptions, frame: u32) -> Result<()> {
    let mut exts = Vec::new();
    if opts.exr {
        exts.push("exr");
    }
    exts.push("png");
    for ext in exts {
        let (from, to) = (
            frame_path(&opts.dir, frame, ext, true),
            frame_path(&opts.dir, frame, ext, false),
        );
        std::fs::rename(&from, &to).map_err(|e| Error::Output {
            path: to.clone(),
            reason: format!(
                "cannot move the finished frame {} here: {e}",
                from.display()
            ),
        })?;
    }
    Ok(())
}

/// Removes `paths` that exist (best effort: a partial frame left behind is never taken
/// for a finished one).
fn remove_all(paths: &[PathBuf]) {
    for p in paths {
        let _ = std::fs::remove_file(p);
    }
}
