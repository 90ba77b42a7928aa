//! Files Iris reads must be regular files within their kind's size bound (issue 48 item 2):
//! a symbolic link to `/dev/zero`, a FIFO or a directory given to `iris merge`, `iris
//! diff`, `--reference` or `--env` ends in an error naming the path and what it is, and an
//! oversized file in an error naming the bound, all before anything is read or rendered.
//!
//! Each command runs [`guarded`]: under an address-space limit, so a regression that reads
//! `/dev/zero` whole fails on allocation instead of exhausting the machine, and killed after
//! [`HANG`], so one that waits on a FIFO fails instead of hanging the suite.

use super::{asset, entries};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Longest wait for one command: a guard against hangs, not a speed test.
pub const HANG: Duration = Duration::from_secs(60);

/// The address-space limit of a guarded command, in KiB (`ulimit -v`): 6 GiB, far above
/// what these small commands use and below the files read whole by a regression.
const ADDRESS_SPACE_KIB: u64 = 6 << 20;

/// Runs `iris ARGS` in `dir` with [`ADDRESS_SPACE_KIB`] and [`HANG`] (module docs); returns
/// the exit code (`None`: killed by a signal) and the standard error. Panics after killing
/// a command that outlived [`HANG`].
pub fn guarded(args: &[&str], dir: &Path) -> (Option<i32>, String) {
    let log = dir.with_extension("stderr");
    let script = format!("ulimit -v {ADDRESS_SPACE_KIB} && exec \"$0\" \"$@\"");
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_iris"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(&log).expect("stderr log"))
        .spawn()
        .expect("start iris");
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break Some(s);
        }
        if start.elapsed() > HANG {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let err = std::fs::read_to_string(&log).unwrap_or_default();
    let Some(status) = status else {
        panic!("iris {args:?} still running after {HANG:?}, killed: {err}");
    };
    (status.code(), err)
}

/// Creates a FIFO at `path` (the `mkfifo` command: the test crate has no libc).
pub fn mkfifo(path: &Path) {
    let ok = Command::new("mkfifo").arg(path).status().expect("mkfifo");
    assert!(ok.success(), "mkfifo {}", path.display());
}

/// A small valid EXR image at `path`.
fn write_exr(path: &Path) {
    let img = iris::image::ImageRgb {
        width: 4,
        height: 3,
        data: vec![glam::Vec3::splat(0.5); 12],
    };
    iris::output::write_image(path, &img, &Default::default()).expect("write exr");
}

/// The special files of one test: (name in `dir`, what the error must call it).
fn special_files(dir: &Path) -> Vec<(PathBuf, &'static str)> {
    let zero = dir.join("zero.exr");
    std::os::unix::fs::symlink("/dev/zero", &zero).expect("symlink");
    let fifo = dir.join("fifo.exr");
    mkfifo(&fifo);
    let folder = dir.join("folder.exr");
    std::fs::create_dir(&folder).expect("mkdir");
    vec![
        (
            zero,
            "a symbolic link to /dev/zero, a character device, not a regular file",
        ),
        (fifo, "a FIFO (named pipe), not a regular file"),
        (folder, "a directory, not a file"),
    ]
}

/// Runs `args` and asserts it fails with exit code 1, saying each of `says`, and leaves
/// `dir` as it was.
fn refused(dir: &Path, args: &[&str], says: &[&str]) {
    let before = entries(dir);
    let (code, err) = guarded(args, dir);
    assert_eq!(code, Some(1), "{args:?}: {err}");
    for s in says {
        assert!(err.contains(s), "{args:?}: {err:?} does not say {s:?}");
    }
    assert_eq!(entries(dir), before, "{args:?} wrote something");
}

#[test]
fn special_files_are_refused_by_merge_diff_reference_and_env() {
    let dir = crate::common::scratch_dir("cli_special_inputs");
    let good = dir.join("good.exr");
    write_exr(&good);
    let good = good.to_str().unwrap();
    let scene = asset("fig4_4_1_prism.glb");
    for (path, what) in special_files(&dir) {
        let p = path.to_str().unwrap();
        let named = format!("{p}: cannot read: {what}");
        refused(&dir, &["merge", p, "-o", "out.exr"], &[&named]);
        refused(&dir, &["diff", p, good], &[&named]);
        refused(&dir, &["diff", good, p], &[&named]);
        let render = [
            "render", &scene, "--size", "4x3", "--spp", "1", "-o", "out.png",
        ];
        for flag in ["--reference", "--env"] {
            let args = [&render[..], &[flag, p]].concat();
            refused(&dir, &args, &[&named]);
        }
    }
}

#[test]
fn env_naming_a_directory_says_so() {
    let dir = crate::common::scratch_dir("cli_env_dir");
    std::fs::create_dir(dir.join("maps")).expect("mkdir");
    let scene = asset("fig4_4_1_prism.glb");
    let args = ["render", &scene, "--env", "maps", "-o", "out.png"];
    refused(&dir, &args, &["maps: cannot read: a directory, not a file"]);
}

#[test]
fn oversized_files_are_refused_naming_the_bound() {
    let dir = crate::common::scratch_dir("cli_oversized");
    // Sparse files: their sizes cost no disk.
    let big = |name: &str, len: u64| {
        let path = dir.join(name);
        let f = std::fs::File::create(&path).expect("create");
        f.set_len(len).expect("set_len");
        path.to_string_lossy().into_owned()
    };
    let exr = big("big.exr", iris::fileio::input::EXR_BYTES + 1);
    let glb = big("big.glb", iris::fileio::input::SCENE_BYTES + 1);
    let exr_says = format!(
        "{exr}: too large: {} bytes, over the bound of 8 GiB for EXR images",
        iris::fileio::input::EXR_BYTES + 1
    );
    refused(&dir, &["merge", &exr, "-o", "out.exr"], &[&exr_says]);
    refused(&dir, &["diff", &exr, &exr], &[&exr_says]);
    refused(
        &dir,
        &["render", &glb, "-o", "out.png"],
        &[&format!(
            "{glb}: too large: {} bytes, over the bound of 4 GiB for scene files and glTF buffers",
            iris::fileio::input::SCENE_BYTES + 1
        )],
    );
}
