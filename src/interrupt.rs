//! What Ctrl-C (SIGINT) or SIGTERM does, decided by what the process is doing (the
//! handler is the binary's, `src/main.rs`; the library only keeps the state).
//!
//! - While a render that stops at a safe point is running ([`Honour`] held: `iris
//!   render`'s render and its outputs, `iris converge`'s renders, the loops of `iris
//!   gallery`, `turntable` and `gem-report`, the live view), a signal asks it to stop
//!   (`render::guard::request_stop`) and it writes what it has.
//! - Otherwise (loading a scene, reading, merging or comparing images, checking flags)
//!   nothing would act on that request, so the process exits at once ([`exit_now`]) with
//!   [`EXIT_INTERRUPTED`]. An atomic write in flight ([`Writing`], held by
//!   `output::atomic`) is finished or abandoned first, so neither a half-written
//!   output nor its temporary file is left behind; a write not yet begun is not begun.
//! - A second signal exits at once.
//!
//! Invariant: [`exit_now`] sets its flag before it reads the count of writes, and
//! [`Writing::begin`] counts itself before it reads the flag (both sequentially
//! consistent), so either the exit waits for the write or the write sees the exit and
//! does not start.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

/// The exit status of an interrupted run: 128 + SIGINT, for SIGTERM too.
pub const EXIT_INTERRUPTED: u8 = 130;

/// Holders of [`Honour`].
static HONOURING: AtomicUsize = AtomicUsize::new(0);
/// Atomic writes in flight.
static WRITES: AtomicUsize = AtomicUsize::new(0);
/// Set once [`exit_now`] is waiting for the writes in flight.
static EXITING: AtomicBool = AtomicBool::new(false);

/// While held, a signal asks the render to stop instead of ending the process.
#[derive(Debug)]
#[must_use = "the stop is honoured only while the token lives"]
pub struct Honour(());

impl Honour {
    /// Declares that a signal from now on should ask the render to stop.
    pub fn begin() -> Honour {
        HONOURING.fetch_add(1, Ordering::SeqCst);
        Honour(())
    }
}

impl Drop for Honour {
    fn drop(&mut self) {
        HONOURING.fetch_sub(1, Ordering::SeqCst);
    }
}

/// True while some [`Honour`] is held.
pub fn honoured() -> bool {
    HONOURING.load(Ordering::SeqCst) > 0
}

/// An atomic write in flight: [`exit_now`] waits until it is dropped.
#[derive(Debug)]
pub struct Writing(());

impl Writing {
    /// Starts a write, or `None` when the process is exiting on a signal (then the write
    /// must not start).
    pub fn begin() -> Option<Writing> {
        WRITES.fetch_add(1, Ordering::SeqCst);
        if EXITING.load(Ordering::SeqCst) {
            WRITES.fetch_sub(1, Ordering::SeqCst);
            return None;
        }
        Some(Writing(()))
    }
}

impl Drop for Writing {
    fn drop(&mut self) {
        WRITES.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Ends the process with [`EXIT_INTERRUPTED`] as soon as no atomic write is in flight.
pub fn exit_now() -> ! {
    EXITING.store(true, Ordering::SeqCst);
    while WRITES.load(Ordering::SeqCst) > 0 {
        std::thread::sleep(Duration::from_millis(1));
    }
    std::process::exit(EXIT_INTERRUPTED.into())
}
