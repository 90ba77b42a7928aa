//! The live view's render thread and the state the web server shares with it.
//!
//! One thread renders; the server's handlers only change [`Shared`] and wake it:
//! - **A change** of the controls ([`Shared::change`]) is checked by the command line's
//!   parser first (a bad value is refused, nothing restarts), then bumps the generation and
//!   cancels the running render ([`crate::render::guard::Cancel`]: it stops before its next
//!   tile); the thread starts the new generation's render at once. A preset, Reset and a
//!   double-click's pick prepare the scene first ([`super::aim`]), outside the lock; a
//!   change of the orbit's pivot alone restarts nothing.
//! - **Frames.** The render shows its image after every unit ([`crate::app::live`]); the
//!   thread encodes one as PNG at most every [`FRAME_INTERVAL`] (always the first and every
//!   denoised one), keeps the last [`KEPT_FRAMES`] by id and announces each on the event
//!   channel, which every connected page reads: all pages get the same frames.
//! - **Rest.** A render that reaches [`CONVERGED`] display error or [`MAX_UNITS`] units
//!   stops and waits for the next change (the CPU idles).
//! - **The final render** ([`Shared::final_render`]) cancels the preview, runs `iris render`
//!   through [`crate::app::render_command`] with the arguments it reports (so the printed
//!   command reproduces it), keeps the PNG, then resumes the preview.

use super::controls::Controls;
use crate::app::live::LiveFrame;
use crate::app::{RenderJob, RenderOptions};
use crate::render::guard::Cancel;
use serde_json::{json, Value};
use std::collections::VecDeque;
use std::path::PathBuf;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};
use tokio::sync::broadcast;

/// Shortest time between two encoded frames (the first and denoised ones always go out).
pub const FRAME_INTERVAL: Duration = Duration::from_millis(100);
/// Frames kept for pages to fetch by id.
pub const KEPT_FRAMES: usize = 8;
/// The preview stops refining at this estimated display error of the raw picture (half an
/// 8-bit level, [`crate::output::display`]) …
pub const CONVERGED: f64 = 0.5 / 255.0;
/// … or after this many units.
pub const MAX_UNITS: u64 = 1 << 16;
/// The error at which the page calls the picture clean: `iris render`'s default target for
/// a PNG, compared with the display error of the picture shown (the denoised one once
/// resting).
pub const CLEAN: f64 = crate::app::budget::DEFAULT_DISPLAY_TARGET;
/// Seconds without a change after which frames are denoised.
pub const REST: Duration = Duration::from_millis(1500);

/// A message for every connected page: an SSE event name and its JSON.
#[derive(Debug, Clone)]
pub struct Event {
    /// `state`, `controls`, `frame`, `status`, `final` or `bye` (the server is stopping);
    /// `end`, after `bye`, ends the streams.
    pub kind: &'static str,
    /// JSON text.
    pub data: String,
}

/// An encoded frame.
pub struct Frame {
    /// Its id (increasing over the session).
    pub id: u64,
    /// PNG bytes.
    pub png: Arc<Vec<u8>>,
}

/// A final render asked for by a page.
pub struct FinalRequest {
    /// Image width and height.
    pub size: (u32, u32),
    /// Samples per pixel (passes for SPPM).
    pub units: u32,
    /// Where the answer goes: the JSON the page shows, or the error.
    pub reply: tokio::sync::oneshot::Sender<Result<Value, String>>,
}

/// What the view was started with.
pub struct Setup {
    /// The scene as given on the command line.
    pub scene: String,
    /// The live image's size.
    pub preview_size: (u32, u32),
    /// Worker threads (0: all).
    pub threads: usize,
    /// Where final renders are written.
    pub out_dir: PathBuf,
    /// The scene's subject as the page reads it ([`super::aim::home`]): what the view
    /// orbits and what the Stone control changes.
    pub subject: Value,
}

/// The state the server and the render thread share (module docs).
pub struct Shared {
    /// What the view was started with.
    pub setup: Setup,
    inner: Mutex<Inner>,
    wake: Condvar,
    events: broadcast::Sender<Event>,
}

struct Inner {
    controls: Controls,
    generation: u64,
    running: Option<Cancel>,
    status: Value,
    frames: VecDeque<Frame>,
    next_frame: u64,
    finals: VecDeque<(u64, Arc<Vec<u8>>)>,
    final_job: Option<FinalRequest>,
    shutdown: bool,
    restarts: u64,
    /// The newest frame's event (samples, estimate, time to clean), for a page that
    /// connects.
    last_frame: Value,
}

impl Shared {
    /// The shared state for `setup`, starting from `controls`.
    pub fn new(setup: Setup, controls: Controls) -> Arc<Shared> {
        let (events, _) = broadcast::channel(256);
        Arc::new(Shared {
            setup,
            inner: Mutex::new(Inner {
                controls,
                generation: 1,
                running: None,
                status: json!({"state": "starting"}),
                frames: VecDeque::new(),
                next_frame: 1,
                finals: VecDeque::new(),
                final_job: None,
                shutdown: false,
                restarts: 0,
                last_frame: Value::Null,
            }),
            wake: Condvar::new(),
            events,
        })
    }

    fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// A receiver of every event from now on.
    pub fn subscribe(&self) -> broadcast::Receiver<Event> {
        self.events.subscribe()
    }

    fn send(&self, kind: &'static str, data: Value) {
        // No page connected is not an error.
        let _ = self.events.send(Event {
            kind,
            data: data.to_string(),
        });
    }

    /// The controls, the status and the newest frame, for a page that connects.
    pub fn snapshot(&self) -> Value {
        let inner = self.lock();
        let (w, h) = self.setup.preview_size;
        json!({
            "scene": self.setup.scene,
            "controls": inner.controls.to_json(),
            "status": inner.status,
            "frame": inner.frames.back().map(|f| f.id),
            "last_frame": inner.last_frame,
            "generation": inner.generation,
            "restarts": inner.restarts,
            "subject": self.setup.subject,
            "preview_size": [w, h],
        })
    }

    /// The PNG of frame `id`, while it is kept.
    pub fn frame(&self, id: u64) -> Option<Arc<Vec<u8>>> {
        let inner = self.lock();
        inner
            .frames
            .iter()
            .find(|f| f.id == id)
            .map(|f| f.png.clone())
    }

    /// The PNG of final render `id`.
    pub fn final_png(&self, id: u64) -> Option<Arc<Vec<u8>>> {
        let inner = self.lock();
        inner.finals.iter().find(|f| f.0 == id).map(|f| f.1.clone())
    }

    /// Applies a change from a page (module docs): the controls' keys, and `view` (a
    /// preset), `reset` (the home camera) or `pick` (`[x, y]`: the pivot under that point
    /// of the image), which set the camera or the pivot ([`super::aim`]). A change of the
    /// pivot alone restarts nothing. Returns the generation and the controls, or the error
    /// naming the control or flag.
    pub fn change(&self, change: &Value) -> Result<(u64, Value), String> {
        let scene = &self.setup.scene;
        let mut change = change.clone();
        let current = self.lock().controls.clone();
        let mut aim = None;
        if let Some(map) = change.as_object_mut() {
            if let Some(view) = map.remove("view") {
                let name = view.as_str().ok_or("view: expected a view name")?;
                aim = Some(super::aim::preset(scene, name, current.turn)?);
            }
            if let Some(reset) = map.remove("reset") {
                if reset != Value::Bool(true) {
                    return Err("reset: expected true".into());
                }
                let width = self.setup.preview_size.0;
                let home = super::aim::home(scene, current.turn, width);
                aim = Some(home.map_err(|e| e.to_string())?.0);
            }
            if let Some(at) = map.remove("pick") {
                let xy = at
                    .as_array()
                    .filter(|a| a.len() == 2)
                    .and_then(|a| Some((a[0].as_f64()?, a[1].as_f64()?)))
                    .ok_or("pick: expected [x, y]")?;
                let pivot = super::aim::pick(scene, &current, xy)?;
                aim = Some(super::aim::Aim {
                    camera: current.camera,
                    pivot,
                });
            }
        }
        let mut inner = self.lock();
        let mut next = inner.controls.clone();
        if let Some(a) = aim {
            (next.camera, next.pivot) = (a.camera, a.pivot);
        }
        next.merge(&change)?;
        let args = next.args(scene, &[]);
        crate::cli::parse_render(&args).map_err(|e| e.to_string())?;
        let restart = args != inner.controls.args(scene, &[]);
        let changed = next != inner.controls;
        if changed {
            inner.controls = next;
            if restart {
                inner.generation += 1;
                inner.restarts += 1;
                if let Some(c) = &inner.running {
                    c.cancel();
                }
                self.wake.notify_all();
            }
        }
        let (generation, controls) = (inner.generation, inner.controls.to_json());
        drop(inner);
        if changed {
            self.send("controls", controls.clone());
        }
        Ok((generation, controls))
    }

    /// Queues a final render (the thread answers on the request's channel).
    pub fn final_render(&self, request: FinalRequest) -> Result<(), FinalRequest> {
        let mut inner = self.lock();
        if inner.final_job.is_some() {
            return Err(request);
        }
        inner.final_job = Some(request);
        if let Some(c) = &inner.running {
            c.cancel();
        }
        self.wake.notify_all();
        Ok(())
    }

    /// Stops the thread (after the tile in flight) and tells the pages.
    pub fn shut_down(&self) {
        let mut inner = self.lock();
        inner.shutdown = true;
        if let Some(c) = &inner.running {
            c.cancel();
        }
        self.wake.notify_all();
        drop(inner);
        self.send("bye", json!({}));
        // Ends every event stream right after its `bye` (never sent to a page).
        self.send("end", json!({}));
    }

    /// The render thread's loop: one preview per generation, final renders in between.
    pub fn run(self: Arc<Shared>) {
        let mut done_generation = 0;
        loop {
            let (generation, controls, final_job) = {
                let mut inner = self.lock();
                while !inner.shutdown
                    && inner.final_job.is_none()
                    && inner.generation == done_generation
                {
                    inner = self.wake.wait(inner).unwrap_or_else(|p| p.into_inner());
                }
                if inner.shutdown {
                    return;
                }
                (
                    inner.generation,
                    inner.controls.clone(),
                    inner.final_job.take(),
                )
            };
            if let Some(job) = final_job {
                let answer = self.run_final(&controls, job.size, job.units);
                let _ = job.reply.send(answer);
                done_generation = 0; // resume the preview
                continue;
            }
            self.preview(generation, &controls);
            done_generation = generation;
        }
    }

    /// The preview's arguments (size, threads, quiet) after the controls'.
    fn preview_options(&self, controls: &Controls) -> crate::Result<RenderOptions> {
        let (w, h) = self.setup.preview_size;
        let mut extra = vec!["--size".to_string(), format!("{w}x{h}"), "--quiet".into()];
        if self.setup.threads > 0 {
            extra.extend(["--threads".to_string(), self.setup.threads.to_string()]);
        }
        crate::cli::parse_render(&controls.args(&self.setup.scene, &extra))
    }

    /// Renders generation `generation` until it is cancelled or converged.
    fn preview(&self, generation: u64, controls: &Controls) {
        let cancel = Cancel::new();
        {
            let mut inner = self.lock();
            if inner.generation != generation {
                return;
            }
            inner.running = Some(cancel.clone());
        }
        let started = Instant::now();
        let result = self
            .preview_options(controls)
            .and_then(|opts| self.preview_job(generation, &opts, &cancel, started));
        let state = match &result {
            Ok(s) => s.to_string(),
            Err(e) => {
                self.status(
                    generation,
                    json!({"state": "error", "error": e.to_string()}),
                );
                String::new()
            }
        };
        let mut inner = self.lock();
        inner.running = None;
        if !state.is_empty() && inner.generation == generation {
            let mut status = inner.status.clone();
            status["state"] = json!(state);
            inner.status = status.clone();
            drop(inner);
            self.send("status", status);
        }
    }

    fn preview_job(
        &self,
        generation: u64,
        opts: &RenderOptions,
        cancel: &Cancel,
        started: Instant,
    ) -> crate::Result<&'static str> {
        let job = RenderJob::new(opts)?;
        let prepare_ms = started.elapsed().as_millis() as u64;
        self.status(generation, super::status::rendering(&job, prepare_ms));
        let display = opts.display;
        let mut last_sent: Option<Instant> = None;
        let mut converged = false;
        job.live(cancel, REST, |f: &LiveFrame| {
            let due = last_sent.is_none_or(|t| t.elapsed() >= FRAME_INTERVAL) || f.denoised;
            if let (Some(image), true) = (f.image, due) {
                let png = super::encode::png(image, display);
                last_sent = Some(Instant::now());
                self.publish(generation, png, f, started);
            }
            converged = f.units >= MAX_UNITS || f.estimate.is_some_and(|e| e <= CONVERGED);
            !converged
        })?;
        Ok(if cancel.is_cancelled() {
            "cancelled"
        } else if converged {
            "converged"
        } else {
            "done"
        })
    }

    /// Keeps frame `png` of `generation` and announces it.
    fn publish(&self, generation: u64, png: Vec<u8>, f: &LiveFrame, started: Instant) {
        let mut inner = self.lock();
        if inner.generation != generation {
            return;
        }
        let id = inner.next_frame;
        inner.next_frame += 1;
        inner.frames.push_back(Frame {
            id,
            png: Arc::new(png),
        });
        while inner.frames.len() > KEPT_FRAMES {
            inner.frames.pop_front();
        }
        // The preview stops at the error target or at MAX_UNITS, whichever comes first.
        let left = (MAX_UNITS as f64 / f.units.max(1) as f64 - 1.0).max(0.0);
        let by_units = Duration::try_from_secs_f64(f.elapsed.as_secs_f64() * left).ok();
        // The picture shown is clean by the command's standard: its own estimate (the
        // denoised picture's, for a denoised frame) at `iris render`'s default target.
        let shown = f.denoised_estimate.or(f.estimate);
        let clean = super::status::time_to_clean(shown, f.elapsed, CLEAN)
            .map(|d| by_units.map_or(d, |u| d.min(u)));
        let event = json!({"id": id, "generation": generation, "units": f.units,
                   "elapsed_ms": f.elapsed.as_millis() as u64,
                   "since_change_ms": started.elapsed().as_millis() as u64,
                   "estimate": shown, "raw_estimate": f.estimate, "target": CLEAN,
                   "denoised": f.denoised,
                   "clean_in_ms": clean.map(|d| d.as_millis() as u64)});
        inner.last_frame = event.clone();
        drop(inner);
        self.send("frame", event);
    }

    /// Replaces the status of `generation` (if still current) and announces it.
    fn status(&self, generation: u64, mut status: Value) {
        let mut inner = self.lock();
        if inner.generation != generation {
            return;
        }
        status["generation"] = json!(generation);
        inner.status = status.clone();
        drop(inner);
        self.send("status", status);
    }

    /// The final render (module docs): the JSON with the command line, the output and the
    /// image's id.
    fn run_final(
        &self,
        controls: &Controls,
        size: (u32, u32),
        units: u32,
    ) -> Result<Value, String> {
        self.send(
            "final",
            json!({"state": "rendering", "size": [size.0, size.1], "units": units}),
        );
        let output = super::encode::free_output(&self.setup.out_dir, &self.setup.scene)
            .map_err(|e| e.to_string())?;
        let probe = crate::cli::parse_render(&controls.args(&self.setup.scene, &[]))
            .and_then(|o| RenderJob::new(&o).map(|j| j.plan.method))
            .map_err(|e| e.to_string())?;
        let budget = probe.caps().units.flag();
        let mut extra = vec![
            "--size".to_string(),
            format!("{}x{}", size.0, size.1),
            budget.to_string(),
            units.to_string(),
            "-o".to_string(),
            output.display().to_string(),
        ];
        if self.setup.threads > 0 {
            extra.extend(["--threads".to_string(), self.setup.threads.to_string()]);
        }
        let args = controls.args(&self.setup.scene, &extra);
        let started = Instant::now();
        let opts = crate::cli::parse_render(&args).map_err(|e| e.to_string())?;
        let summary = crate::app::render_command(&opts).map_err(|e| e.to_string())?;
        let png = crate::fileio::input::read(&output, crate::fileio::Input::Image)
            .map_err(|e| format!("{}: {e}", output.display()))?;
        let mut inner = self.lock();
        let id = inner.finals.back().map_or(1, |f| f.0 + 1);
        inner.finals.push_back((id, Arc::new(png)));
        while inner.finals.len() > 4 {
            inner.finals.pop_front();
        }
        drop(inner);
        let command = super::encode::command_line(&args);
        let answer = json!({"state": "done", "id": id, "command": command, "args": args,
                            "output": output.display().to_string(),
                            "seconds": started.elapsed().as_secs_f64(),
                            "method": summary.method.name()});
        self.send("final", answer.clone());
        Ok(answer)
    }
}
