//! Interrupting `iris render` (issue 7): SIGINT or SIGTERM during a long render writes the
//! image rendered so far (atomically: the output name holds a whole image, no temporary file
//! is left) and exits with 130; every method stops at its next safe point (per-sample
//! methods: after the tiles in flight; SPPM: after the pass). Outside a render, where nothing
//! would act on a stop request, a signal exits at once with 130 (issue 48).

use crate::common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Longest wait for anything in this file: a guard against hangs, not a speed test.
const HANG: Duration = Duration::from_secs(120);

/// Starts a render that would take hours (or its default budget's two minutes), waits
/// until it has written its first checkpoint (`--checkpoint 1`, or the default budget's
/// first write: the image at 1 sample or pass, so the signal handler is installed and the
/// render is under way, however fast or loaded the machine), sends `signal` (by the `kill`
/// command: the test crate has no libc) and returns its exit code and stderr.
fn interrupt(dir: &Path, extra: &[&str], signal: &str) -> (Option<i32>, String) {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/paper/fig4_5_1_caustics.glb");
    let child = Command::new(env!("CARGO_BIN_EXE_iris"))
        .arg("render")
        .arg(&scene)
        .args(["--size", "64x48", "-o", "out.png", "--threads", "2"])
        .args(extra)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start iris");
    let t = Instant::now();
    while !dir.join("out.png").is_file() {
        assert!(t.elapsed() < HANG, "no checkpoint written after {HANG:?}");
        std::thread::sleep(Duration::from_millis(20));
    }
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(status.success(), "kill {signal} failed");
    let t = Instant::now();
    let out = child.wait_with_output().expect("wait for iris");
    // A stop at the next safe point: one 64×48 tile round or one SPPM pass. The bound only
    // catches a render that ignores the signal (it would run for hours).
    assert!(t.elapsed() < HANG, "took {:?} to stop", t.elapsed());
    (out.status.code(), common::stderr(&out))
}

fn check_written(dir: &Path, stderr: &str) {
    // The summary says what ended the render.
    assert!(
        stderr.contains("iris: interrupted (Ctrl-C or SIGTERM): the image so far"),
        "{stderr}"
    );
    assert_eq!(common::entries(dir), ["out.png"], "{stderr}");
    let img = image::open(dir.join("out.png"))
        .expect("a whole PNG")
        .to_rgb8();
    assert_eq!(img.dimensions(), (64, 48));
    // The scene is lit: the image so far is not black.
    assert!(img.pixels().any(|p| p.0.iter().any(|&c| c > 0)));
}

#[test]
fn sigint_writes_the_path_traced_image_so_far() {
    let dir = common::scratch_dir("interrupt_path");
    let flags = ["--method", "path", "--spp", "1000000", "--checkpoint", "1"];
    let (code, err) = interrupt(&dir, &flags, "-INT");
    assert_eq!(code, Some(130), "{err}");
    check_written(&dir, &err);
}

#[test]
fn sigterm_writes_the_sppm_image_so_far() {
    let dir = common::scratch_dir("interrupt_sppm");
    let flags = [
        "--method",
        "sppm",
        "--passes",
        "10000000",
        "--checkpoint",
        "1",
    ];
    let (code, err) = interrupt(&dir, &flags, "-TERM");
    assert_eq!(code, Some(130), "{err}");
    check_written(&dir, &err);
}

#[test]
fn the_default_budget_writes_as_it_goes_and_sigint_keeps_the_image() {
    // No budget flag: the render would go on to the error target or two minutes, writing
    // the image as it improves (the first checkpoint at once, which `interrupt` waits for).
    let dir = common::scratch_dir("interrupt_default");
    let (code, err) = interrupt(&dir, &[], "-INT");
    assert_eq!(code, Some(130), "{err}");
    check_written(&dir, &err);
}

#[test]
fn an_uninterrupted_render_exits_zero_and_reports_no_bad_samples() {
    let dir = common::scratch_dir("interrupt_none");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/paper/fig4_5_1_caustics.glb");
    let out = common::iris(
        &[
            "render",
            scene.to_str().unwrap(),
            "--size",
            "32x24",
            "--spp",
            "2",
            "-o",
            "out.png",
        ],
        &dir,
    );
    let err = common::stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        !err.contains("interrupted") && !err.contains("NaN"),
        "{err}"
    );
}

#[test]
fn sigterm_outside_a_render_exits_at_once() {
    // `iris info` of a file with 20 000 objects prints about 0.6 MB on stdout at the end.
    // The test reads its first bytes (so the handler is installed and the scene loaded),
    // then stops reading: the child waits on the full pipe, as it would on any slow I/O,
    // with no render running that could act on a stop request. SIGTERM must end it with
    // 130 at once, not leave it waiting for a reader (it would wait forever: the bound
    // only catches that).
    let dir = common::scratch_dir("interrupt_info");
    let mut obj = String::new();
    for i in 0..20_000 {
        let x = i as f32;
        obj.push_str(&format!(
            "o part{i}\nv {x} 0 0\nv {} 0 0\nv {x} 1 0\nf -3 -2 -1\n",
            x + 0.5
        ));
    }
    std::fs::write(dir.join("many.obj"), obj).expect("write obj");
    let mut child = Command::new(env!("CARGO_BIN_EXE_iris"))
        .args(["info", "many.obj"])
        .current_dir(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start iris");
    let mut stdout = child.stdout.take().expect("stdout");
    let mut first = [0u8; 16];
    std::io::Read::read_exact(&mut stdout, &mut first).expect("the first bytes of info");
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(status.success(), "kill -TERM failed");
    let t = Instant::now();
    let code = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s.code();
        }
        if t.elapsed() > HANG {
            let _ = child.kill();
            let _ = child.wait();
            panic!("iris info still waiting on its output {HANG:?} after SIGTERM");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    drop(stdout);
    assert_eq!(code, Some(130));
}
