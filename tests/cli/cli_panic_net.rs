//! The panic net under the Draco decoder, as a user of the `iris` binary meets it
//! (`iris::load::panic_net`): a decoder panic is the clear error "the Draco decoder
//! panicked on this data" naming the file and the primitive, with a non-zero exit code,
//! and the panic's own message (`panicked at …`, `assertion failed …`, a backtrace under
//! `RUST_BACKTRACE=1`) never reaches the terminal, except with `--verbose`, which adds
//! the message and its location to the error.
//!
//! No known input makes the vendored decoder panic any more (its IRIS-PATCHES.md P6–P8
//! fixed the three the exporter campaign found), so the panic is forced inside the net
//! with [`iris::load::panic_net::FORCE_PANIC_ENV`]; the regression inputs of those three
//! panics are checked here too, as clean errors.

use crate::common;

use iris::load::panic_net::FORCE_PANIC_ENV;
use std::path::PathBuf;
use std::process::{Command, Output};

fn repo(rel: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(rel)
        .to_string_lossy()
        .into_owned()
}

/// `iris ARGS` with `RUST_BACKTRACE=1` (so a printed panic would bring its backtrace),
/// and the forced decoder panic if `force`.
fn iris(args: &[&str], force: bool) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_iris"));
    cmd.args(args).env("RUST_BACKTRACE", "1");
    if force {
        cmd.env(FORCE_PANIC_ENV, "1");
    } else {
        cmd.env_remove(FORCE_PANIC_ENV);
    }
    cmd.output().expect("run iris")
}

/// Text of a printed panic or backtrace.
const PANIC_TEXT: [&str; 4] = [
    "panicked at",
    "assertion failed",
    "stack backtrace",
    "RUST_BACKTRACE",
];

const DRACO: &str = "tests/data/compressed/round_diamond_draco.glb";

#[test]
fn the_file_loads_without_the_forced_panic() {
    let o = iris(&["info", &repo(DRACO)], false);
    assert!(o.status.success(), "{}", common::stderr(&o));
}

#[test]
fn a_caught_panic_is_a_clear_error_and_prints_nothing_else() {
    let o = iris(&["info", &repo(DRACO)], true);
    let err = common::stderr(&o);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("the Draco decoder panicked on this data"),
        "{err}"
    );
    assert!(err.contains("round_diamond_draco.glb"), "{err}");
    assert!(err.contains("primitive 0"), "{err}");
    for text in PANIC_TEXT {
        assert!(!err.contains(text), "{text:?} in:\n{err}");
    }
    assert!(!err.contains("(panic:"), "{err}");
}

#[test]
fn verbose_adds_the_panic_message_and_location() {
    // `--verbose` is global: before or after the subcommand.
    for args in [
        ["--verbose", "info", &repo(DRACO)],
        ["info", &repo(DRACO), "--verbose"],
    ] {
        let o = iris(&args, true);
        let err = common::stderr(&o);
        assert!(!o.status.success(), "{err}");
        assert!(
            err.contains(&format!(
                "the Draco decoder panicked on this data (panic: forced by {FORCE_PANIC_ENV} at src/load/panic_net.rs:"
            )),
            "{err}"
        );
        // The message is in the error line, not printed by the panic hook.
        assert!(!err.contains("panicked at"), "{err}");
        assert!(!err.contains("stack backtrace"), "{err}");
    }
}

/// The inputs of the three decoder panics the exporter campaign found (FUZZING.md) are now
/// clean errors from the decoder, through `iris render` too.
#[test]
fn the_former_panics_are_clean_decoder_errors() {
    let dir = common::scratch_dir("cli_panic_net");
    for name in [
        "draco_wrap_bounds_inverted.glb",
        "draco_octahedral_transform_3d.glb",
        "draco_symbol_stream_short.glb",
    ] {
        let out = dir.join("out.png");
        let o = iris(
            &[
                "render",
                &repo(&format!("fuzz/regressions/gltf/{name}")),
                "--size",
                "16x16",
                "--spp",
                "1",
                "--quiet",
                "-o",
                &out.to_string_lossy(),
            ],
            false,
        );
        let err = common::stderr(&o);
        assert!(!o.status.success(), "{name}: {err}");
        assert!(err.contains(name), "{err}");
        assert!(err.contains("invalid Draco data: "), "{name}: {err}");
        for text in PANIC_TEXT {
            assert!(!err.contains(text), "{name}: {text:?} in:\n{err}");
        }
        assert!(!out.exists(), "{name}: an output was written");
    }
}
