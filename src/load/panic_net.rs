//! The net under third-party decoders: a panic inside one becomes an error, and its
//! message stays off the terminal.
//!
//! Iris runs decoders it does not own (the Draco decoder, the image decoders) on bytes
//! from files it did not write. The vendored Draco decoder is patched wherever fuzzing
//! found a panic (vendor/draco-oxide-decoder/IRIS-PATCHES.md), but a bug not yet found must
//! still end in a clean [`LoadError`](crate::LoadError), not a crash: [`catch`] runs the
//! decoder under [`std::panic::catch_unwind`] and the caller turns a [`Caught`] into its
//! error ("the Draco decoder panicked on this data").
//!
//! `catch_unwind` alone does not keep the panic quiet: the panic hook runs before the
//! unwinding starts, and the default hook prints `thread '…' panicked at …` (and, with
//! `RUST_BACKTRACE`, a backtrace) to stderr. So [`catch`] also installs, once per process,
//! a hook that wraps whichever hook was set before it:
//!
//! - On a thread that is inside [`catch`] (a thread-local depth counter), the hook records
//!   the panic's message and location for [`Caught`] and prints nothing.
//! - On every other thread, and outside [`catch`], it calls the previous hook unchanged:
//!   a panic in Iris itself, or on a render thread while another thread decodes, is
//!   reported as before.
//!
//! The hook is installed once and never removed. Swapping hooks per call (take, set,
//! restore) is not thread-safe: two threads decoding at once could each restore the other's
//! quiet hook and silence the process for good. A hook set later by someone else replaces
//! this one; a caught panic is then printed by that hook, and still caught.
//!
//! With [`show_caught_panics`]`(true)` (`iris --verbose`), [`Caught::describe`] appends the
//! recorded message and location to the error's sentence, so the user sees them in the
//! error line.

use std::cell::{Cell, RefCell};
use std::panic::{PanicHookInfo, UnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Once;

/// Whether [`Caught::describe`] includes the panic's message (`--verbose`).
static SHOW: AtomicBool = AtomicBool::new(false);

/// Panics [`catch`] has caught in this process.
static CAUGHT: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// How many [`catch`] calls this thread is inside (they may nest).
    static DEPTH: Cell<u32> = const { Cell::new(0) };
    /// The message of the last panic the hook kept quiet on this thread.
    static LAST: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Makes [`Caught::describe`] include the caught panic's message and location (`true`), or
/// not (`false`, the default). Process-wide: the command line sets it once, from `--verbose`.
pub fn show_caught_panics(show: bool) {
    SHOW.store(show, Ordering::Relaxed);
}

/// How many panics [`catch`] has caught in this process so far. A caught panic is still a
/// decoder bug: the fuzz target and the mutation passes (FUZZING.md) fail when it grows.
pub fn caught_count() -> u64 {
    CAUGHT.load(Ordering::Relaxed)
}

/// A panic [`catch`] caught.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Caught {
    /// The panic's message and source location (`assertion failed: … at src/x.rs:1:2`).
    pub message: String,
}

impl Caught {
    /// `sentence` for the error, followed by the panic's message when
    /// [`show_caught_panics`] is on.
    pub fn describe(&self, sentence: &str) -> String {
        if SHOW.load(Ordering::Relaxed) {
            format!("{sentence} (panic: {})", self.message)
        } else {
            sentence.to_string()
        }
    }
}

/// Set (to anything) in the environment, every [`catch`] panics inside the net before it
/// runs its work. For the command-line tests of the net (tests/cli/cli_panic_net.rs): no
/// known input makes a decoder panic any more, so they need another way in.
pub const FORCE_PANIC_ENV: &str = "IRIS_TEST_FORCE_DECODER_PANIC";

/// Runs `f`; a panic inside it is returned as [`Caught`] and not printed (see the module
/// docs for how the hook decides).
pub fn catch<R>(f: impl FnOnce() -> R + UnwindSafe) -> Result<R, Caught> {
    install_hook();
    let forced = std::env::var_os(FORCE_PANIC_ENV).is_some();
    DEPTH.with(|d| d.set(d.get() + 1));
    let result = std::panic::catch_unwind(move || {
        if forced {
            panic!("forced by {FORCE_PANIC_ENV}");
        }
        f()
    });
    DEPTH.with(|d| d.set(d.get() - 1));
    result.map_err(|payload| {
        CAUGHT.fetch_add(1, Ordering::Relaxed);
        let recorded = LAST.with(|last| last.borrow_mut().take());
        Caught {
            message: recorded.unwrap_or_else(|| payload_text(payload.as_ref())),
        }
    })
}

/// Installs the quiet hook on top of the current one, once per process.
fn install_hook() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            // `try_with`: a panic while this thread's locals are being destroyed goes to
            // the previous hook.
            let quiet = DEPTH.try_with(|d| d.get() > 0).unwrap_or(false);
            if quiet
                && LAST
                    .try_with(|last| *last.borrow_mut() = Some(describe(info)))
                    .is_ok()
            {
                return;
            }
            previous(info);
        }));
    });
}

/// `message at file:line:column`, as the default hook would print them.
fn describe(info: &PanicHookInfo<'_>) -> String {
    let message = payload_text(info.payload());
    match info.location() {
        Some(at) => format!("{message} at {}:{}:{}", at.file(), at.line(), at.column()),
        None => message,
    }
}

/// The text of a panic payload (`panic!` with a literal or with format arguments).
fn payload_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_is_caught_with_its_message_and_location() {
        let caught = catch(|| -> u32 { panic!("the decoder gave up on {}", 7) }).unwrap_err();
        assert!(
            caught.message.starts_with("the decoder gave up on 7 at "),
            "{}",
            caught.message
        );
        assert!(
            caught.message.contains("panic_net.rs:"),
            "{}",
            caught.message
        );
        assert_eq!(catch(|| 5), Ok(5));
        // Other tests may catch panics at the same time: the count only grows.
        let before = caught_count();
        let _ = catch(|| panic!("counted"));
        assert!(caught_count() > before);
    }

    #[test]
    fn nested_catches_keep_their_own_panics() {
        let outer = catch(|| {
            let inner = catch(|| panic!("inner"));
            assert!(inner.unwrap_err().message.starts_with("inner at "));
            panic!("outer")
        });
        assert!(outer.unwrap_err().message.starts_with("outer at "));
        // Back outside: the depth is 0 again.
        assert_eq!(DEPTH.with(Cell::get), 0);
    }

    #[test]
    fn the_verbose_sentence_carries_the_message() {
        let caught = Caught {
            message: "assertion failed: min <= max at x.rs:1:2".into(),
        };
        // `SHOW` is process-wide: only this test sets it, and restores it.
        show_caught_panics(true);
        let verbose = caught.describe("the decoder panicked");
        show_caught_panics(false);
        let quiet = caught.describe("the decoder panicked");
        assert_eq!(
            verbose,
            "the decoder panicked (panic: assertion failed: min <= max at x.rs:1:2)"
        );
        assert_eq!(quiet, "the decoder panicked");
    }
}
