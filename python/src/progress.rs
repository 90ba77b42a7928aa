//! A render run from Python: the render on a worker thread, the calling thread waiting
//! for it with the GIL released and, every [`POLL`], checking for signals (Ctrl-C: the
//! render is cancelled, the worker joined, and `KeyboardInterrupt` raised within a tile
//! per core) and calling the progress callback, so the callback runs on the calling
//! thread too: at every checkpoint (the worker waits for its answer), and between
//! checkpoints at least every [`TICK`] (`checkpoint: False`, the figures of the last
//! checkpoint with the time now).

use iris::app::{RenderJob, RenderSummary, RunHooks};
use iris::render::guard::Cancel;
use iris::render::{EndReason, Progress};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// How often the calling thread checks for signals.
const POLL: Duration = Duration::from_millis(50);
/// The longest the progress callback waits between two calls.
const TICK: Duration = Duration::from_secs(1);

/// A checkpoint's figures, as the callback's dict has them.
#[derive(Debug, Clone, Copy, Default)]
struct Snapshot {
    units: u64,
    passes: u32,
    seconds: f64,
    rays: u64,
    photons: u64,
    done: bool,
    estimate: Option<f64>,
}

impl Snapshot {
    fn of(p: &Progress) -> Snapshot {
        let estimate = (p.samples >= 2)
            .then(|| iris::render::relative_error_estimate(p.halves.0, p.halves.1))
            .flatten();
        Snapshot {
            units: p.samples,
            passes: p.passes,
            seconds: p.elapsed.as_secs_f64(),
            rays: p.rays,
            photons: p.photons,
            done: p.done,
            estimate,
        }
    }

    /// The dict the callback gets; `checkpoint` False for a call on time.
    fn dict<'py>(&self, py: Python<'py>, checkpoint: bool) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("units", self.units)?;
        d.set_item("passes", self.passes)?;
        d.set_item("seconds", self.seconds)?;
        d.set_item("rays", self.rays)?;
        d.set_item("photons", self.photons)?;
        d.set_item("done", self.done)?;
        d.set_item("estimate", self.estimate)?;
        d.set_item("checkpoint", checkpoint)?;
        Ok(d)
    }
}

/// What the worker tells the calling thread.
enum Event {
    /// The job is prepared; the render starts.
    Started,
    /// A checkpoint; the worker waits for the answer (go on?).
    Checkpoint(Snapshot),
    /// The render's end.
    Finished(Box<iris::Result<RenderSummary>>),
}

/// A finished render: the summary, whether the callback stopped it, and the half-buffer
/// error estimate of its image.
pub struct Outcome {
    pub summary: RenderSummary,
    pub stopped: bool,
    pub estimate: Option<f64>,
}

impl Outcome {
    /// The summary's `end`.
    pub fn end(&self) -> &'static str {
        match self.summary.stats.end {
            _ if self.stopped => "progress",
            EndReason::Samples => "samples",
            EndReason::Target => "target",
            EndReason::TimeLimit => "time limit",
            EndReason::Interrupted => "interrupted",
        }
    }
}

/// The calling thread's side of a render: the callback, the last checkpoint, and why the
/// render must stop (an exception to raise, or the callback's answer).
struct Caller {
    callback: Option<PyObject>,
    last: Option<(Snapshot, Instant)>,
    started: Option<Instant>,
    called: Instant,
    failure: Option<PyErr>,
    stopped: bool,
}

impl Caller {
    /// Calls the callback with `d`; whether the render goes on.
    fn call(&mut self, py: Python<'_>, d: PyResult<Bound<'_, PyDict>>) -> bool {
        self.called = Instant::now();
        let Some(callback) = &self.callback else {
            return true;
        };
        match d.and_then(|d| callback.call1(py, (d,))) {
            Ok(a) if a.is_none(py) => true,
            Ok(a) => match a.is_truthy(py) {
                Ok(true) => true,
                Ok(false) => {
                    self.stopped = true;
                    false
                }
                Err(e) => self.fail(e),
            },
            Err(e) => self.fail(e),
        }
    }

    fn fail(&mut self, e: PyErr) -> bool {
        self.failure.get_or_insert(e);
        false
    }

    /// Whether the render should stop.
    fn stopping(&self) -> bool {
        self.failure.is_some() || self.stopped
    }

    /// A checkpoint: the callback's answer (not called again once stopping).
    fn checkpoint(&mut self, py: Python<'_>, s: Snapshot) -> bool {
        self.last = Some((s, Instant::now()));
        !self.stopping() && self.call(py, s.dict(py, true))
    }

    /// Between checkpoints: calls the callback when [`TICK`] has passed since the last
    /// call; whether the render goes on.
    fn tick(&mut self, py: Python<'_>) -> bool {
        let Some(started) = self.started else {
            return true;
        };
        if self.callback.is_none() || self.stopping() || self.called.elapsed() < TICK {
            return true;
        }
        let mut s = self.last.map_or(Snapshot::default(), |l| l.0);
        s.seconds = match self.last {
            Some((l, at)) => l.seconds + at.elapsed().as_secs_f64(),
            None => started.elapsed().as_secs_f64(),
        };
        (s.done, s.estimate) = (false, None);
        self.call(py, s.dict(py, false))
    }
}

/// Checks that `progress` is None or callable (`TypeError` now, not at the first
/// checkpoint).
pub fn check_callback(py: Python<'_>, progress: Option<&PyObject>) -> PyResult<()> {
    match progress {
        Some(p) if !p.bind(py).is_callable() => Err(PyTypeError::new_err(format!(
            "progress must be callable (a function of one dict), not {}",
            p.bind(py).get_type().name()?
        ))),
        _ => Ok(()),
    }
}

/// Runs the job `make` builds (on a worker thread: the preparation too) as the module docs
/// say, with the optional `progress` callback; writes the image only with `write_image`.
pub fn run<'o>(
    py: Python<'_>,
    make: impl FnOnce() -> iris::Result<RenderJob<'o>> + Send,
    progress: Option<PyObject>,
    write_image: bool,
) -> PyResult<Outcome> {
    check_callback(py, progress.as_ref())?;
    let cancel = Cancel::new();
    let (tx, rx) = mpsc::channel::<Event>();
    let (reply_tx, reply_rx) = mpsc::channel::<bool>();
    let rx = Mutex::new(rx);
    let mut caller = Caller {
        callback: progress,
        last: None,
        started: None,
        called: Instant::now(),
        failure: None,
        stopped: false,
    };
    let worker_cancel = cancel.clone();
    let result = std::thread::scope(|scope| {
        scope.spawn(move || {
            let result = make().and_then(|job| {
                let _ = tx.send(Event::Started);
                let events = tx.clone();
                let mut hook = move |p: &Progress| {
                    events.send(Event::Checkpoint(Snapshot::of(p))).is_ok()
                        && reply_rx.recv().unwrap_or(false)
                };
                job.run_with(RunHooks {
                    write_image,
                    progress: Some(&mut hook),
                    cancel: worker_cancel,
                })
            });
            let _ = tx.send(Event::Finished(Box::new(result)));
        });
        wait(py, &rx, &reply_tx, &cancel, &mut caller)
    });
    if let Some(e) = caller.failure {
        return Err(e);
    }
    let summary = result.map_err(crate::py_err)?;
    let estimate = match summary.stats.end {
        EndReason::Target if !caller.stopped => summary.target_estimate,
        _ => caller.last.and_then(|l| l.0.estimate),
    };
    Ok(Outcome {
        estimate: estimate.or(summary.target_estimate),
        summary,
        stopped: caller.stopped,
    })
}

/// The calling thread until the worker's render ends: events, signals, calls on time.
fn wait(
    py: Python<'_>,
    rx: &Mutex<mpsc::Receiver<Event>>,
    reply: &mpsc::Sender<bool>,
    cancel: &Cancel,
    caller: &mut Caller,
) -> iris::Result<RenderSummary> {
    loop {
        let event = py.allow_threads(|| match rx.lock() {
            Ok(rx) => rx.recv_timeout(POLL),
            Err(_) => Err(RecvTimeoutError::Disconnected),
        });
        match event {
            Ok(Event::Finished(result)) => return *result,
            Ok(Event::Started) => caller.started = Some(Instant::now()),
            Ok(Event::Checkpoint(s)) => {
                // A stop asked before the first checkpoint stops the render here.
                let _ = reply.send(caller.checkpoint(py, s));
            }
            // Stopped between checkpoints after the first: cancelled (the render returns
            // the samples taken so far); before the first, the first checkpoint stops it.
            Err(RecvTimeoutError::Timeout) => {
                if !caller.tick(py) && caller.last.is_some() {
                    cancel.cancel();
                }
            }
            // The worker panicked; joining it raises the panic.
            Err(RecvTimeoutError::Disconnected) => {
                return Err(iris::Error::Usage("the render thread ended early".into()))
            }
        }
        if caller.failure.is_none() {
            if let Err(e) = py.check_signals() {
                caller.failure = Some(e);
            }
        }
        if caller.failure.is_some() {
            cancel.cancel();
        }
    }
}
