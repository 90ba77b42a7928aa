//! `iris merge` refuses what does not fit and says why, writing nothing; shards that die
//! leave nothing it would accept (issue 19 items 2 and 5). Through the CLI binary, on
//! `assets/paper/fig4_4_1_prism.glb` at 32×24.

use crate::common;

use common::{entries, iris, scratch_dir, stderr};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn scene() -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/paper/fig4_4_1_prism.glb");
    p.to_string_lossy().into_owned()
}

/// `iris render SCENE --size 32x24 --method path --spp 6 --seed 1 -q --shard I/N -o OUT`,
/// with `extra` flag/value pairs replacing those values or added; panics unless it
/// succeeds.
fn shard(dir: &Path, out: &str, i_n: &str, extra: &[&str]) -> PathBuf {
    let scene = scene();
    let mut flags = vec![
        ("--size", "32x24"),
        ("--method", "path"),
        ("--spp", "6"),
        ("--seed", "1"),
    ];
    for pair in extra.chunks(2) {
        match flags.iter_mut().find(|(f, _)| *f == pair[0]) {
            Some(f) => f.1 = pair[1],
            None => flags.push((pair[0], pair[1])),
        }
    }
    let mut args = vec!["render", &scene, "-q", "--shard", i_n, "-o", out];
    args.extend(flags.iter().flat_map(|(f, v)| [*f, *v]));
    let o = iris(&args, dir);
    assert!(o.status.success(), "shard {i_n} {extra:?}: {}", stderr(&o));
    dir.join(out)
}

/// Runs `iris merge ARGS… -o OUT` and asserts it fails, writes nothing, and says each of
/// `says`; returns the message.
fn refused(dir: &Path, args: &[&str], says: &[&str]) -> String {
    let before = entries(dir);
    let mut all = vec!["merge"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", "merged.exr"]);
    let o = iris(&all, dir);
    let msg = stderr(&o);
    assert!(!o.status.success(), "{args:?} was accepted: {msg}");
    for s in says {
        assert!(msg.contains(s), "{args:?}: {msg:?} does not say {s:?}");
    }
    assert_eq!(entries(dir), before, "{args:?} wrote something");
    msg
}

#[test]
fn merge_refuses_parts_of_other_renders() {
    let dir = scratch_dir("merge-refusals");
    shard(&dir, "p1.exr", "1/3", &[]);
    shard(&dir, "p2.exr", "2/3", &[]);
    shard(&dir, "p3.exr", "3/3", &[]);
    let cases: &[(&[&str], &str, &str)] = &[
        (
            &["--seed", "2"],
            "seed.exr",
            "different seeds: 1 in p1.exr, 2 in seed.exr",
        ),
        (
            &["--size", "16x12"],
            "size.exr",
            "different sizes: 32x24 in p1.exr, 16x12",
        ),
        (
            &["--method", "whitted"],
            "method.exr",
            "different methods: path in p1.exr",
        ),
        (
            &["--max-depth", "5"],
            "depth.exr",
            "different --max-depth values",
        ),
        (&["--spp", "9"], "total.exr", "different totals"),
        (&["--alpha", "0.5"], "alpha.exr", "different --alpha values"),
        (&["--view", "front"], "view.exr", "different cameras"),
        // Options that change the image without changing the scene file or the counts.
        (
            &["--polarizer", "30"],
            "polarizer.exr",
            // A polarizer turns polarized (hence spectral) transport on.
            "different transports (spectral): false in p1.exr, true",
        ),
        (
            &["--fog", "density=0.3"],
            "fog.exr",
            "different --fog values",
        ),
        (
            &["--radius", "0.01"],
            "radius.exr",
            "different --radius values",
        ),
    ];
    for (extra, out, says) in cases {
        shard(&dir, out, "2/3", extra);
        refused(&dir, &["p1.exr", out, "p3.exr"], &[says, out]);
    }
    // Pairs of shards that differ in one image-changing option, neither the default.
    let pairs: &[(&[&str], &[&str], &str)] = &[
        (
            &["--polarizer", "0"],
            &["--polarizer", "90"],
            "--polarizer values",
        ),
        (
            &["--fog", "density=0.3"],
            &["--fog", "density=0.6"],
            "--fog values",
        ),
        (
            &["--fog", "density=0.3"],
            &["--fog", "density=0.3,g=0.5"],
            "--fog values",
        ),
        (
            &["--stone", "ruby"],
            &["--stone", "diamond"],
            "--stone/--metal values",
        ),
    ];
    for (i, (one, two, says)) in pairs.iter().enumerate() {
        let (a, b) = (format!("pa{i}.exr"), format!("pb{i}.exr"));
        shard(&dir, &a, "1/2", one);
        shard(&dir, &b, "2/2", two);
        refused(&dir, &[&a, &b], &[says, &a, &b]);
    }
    // `--fog none` against the file's own `iris_fog`.
    let hazy = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/hazy_prism.glb");
    for (i_n, out, fog) in [
        ("1/2", "hazy1.exr", None),
        ("2/2", "hazy2.exr", Some("none")),
    ] {
        let mut args = vec![
            "render",
            hazy.to_str().unwrap(),
            "--size",
            "16x12",
            "--method",
            "path",
            "--spp",
            "2",
            "-q",
            "--shard",
            i_n,
            "-o",
            out,
        ];
        args.extend(fog.iter().flat_map(|f| ["--fog", *f]));
        let o = iris(&args, &dir);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    refused(
        &dir,
        &["hazy1.exr", "hazy2.exr"],
        &["different --fog values: None in hazy1.exr, Some(None) in hazy2.exr"],
    );
    // Another scene file.
    let other = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/paper/fig7_2_bubble.glb");
    let o = iris(
        &[
            "render",
            other.to_str().unwrap(),
            "--size",
            "32x24",
            "--method",
            "path",
            "--spp",
            "6",
            "--seed",
            "1",
            "-q",
            "--shard",
            "2/3",
            "-o",
            "scene.exr",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    refused(
        &dir,
        &["p1.exr", "scene.exr", "p3.exr"],
        &["different scene files"],
    );
    // Another shard count.
    shard(&dir, "half.exr", "2/2", &[]);
    refused(
        &dir,
        &["p1.exr", "half.exr"],
        &["different shard counts: 3 in p1.exr, 2"],
    );
    // The same shard twice (or a copy of it).
    std::fs::copy(dir.join("p2.exr"), dir.join("p2-copy.exr")).unwrap();
    refused(
        &dir,
        &["p1.exr", "p2.exr", "p3.exr", "p2-copy.exr"],
        &[
            "p2.exr (shard 2/3, samples 2..4)",
            "p2-copy.exr (shard 2/3, samples 2..4)",
            "overlap",
        ],
    );
    // Not a partial image: a plain EXR, a PNG, a missing file.
    let o = iris(
        &[
            "render",
            &scene(),
            "--size",
            "32x24",
            "--spp",
            "1",
            "--method",
            "path",
            "-q",
            "-o",
            "plain.exr",
        ],
        &dir,
    );
    assert!(o.status.success());
    refused(
        &dir,
        &["p1.exr", "plain.exr"],
        &["plain.exr", "not an Iris partial image"],
    );
    std::fs::write(dir.join("fake.exr"), b"not an exr at all").unwrap();
    refused(&dir, &["fake.exr", "p1.exr"], &["fake.exr"]);
    refused(&dir, &["p1.exr", "absent.exr"], &["absent.exr"]);
    // A temporary file of a write that never finished: refused by its name.
    std::fs::copy(dir.join("p3.exr"), dir.join(".p3.exr.tmp-4242-0")).unwrap();
    refused(
        &dir,
        &["p1.exr", "p2.exr", ".p3.exr.tmp-4242-0"],
        &["temporary file", "rerun"],
    );
    // All three merge.
    let o = iris(
        &["merge", "p3.exr", "p1.exr", "p2.exr", "-o", "merged.png"],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("6 samples per pixel"), "{}", stderr(&o));
    assert!(dir.join("merged.png").is_file());
}

#[test]
fn missing_shards_are_named_and_allow_partial_reports_counts() {
    let dir = scratch_dir("merge-missing");
    shard(&dir, "p1.exr", "1/3", &[]);
    shard(&dir, "p3.exr", "3/3", &[]);
    refused(
        &dir,
        &["p1.exr", "p3.exr"],
        &[
            "samples 2..4 of 6 are missing (shard 2/3)",
            "--allow-partial",
        ],
    );
    let o = iris(
        &[
            "merge",
            "p1.exr",
            "p3.exr",
            "--allow-partial",
            "--report",
            "r.csv",
            "-o",
            "some.exr",
        ],
        &dir,
    );
    let msg = stderr(&o);
    assert!(o.status.success(), "{msg}");
    assert!(msg.contains("merged 2 of 3 shards of 6 samples"), "{msg}");
    assert!(msg.contains("4 samples per pixel"), "{msg}");
    assert!(
        msg.contains("samples 2..4 of 6 are missing (shard 2/3)"),
        "{msg}"
    );
    let csv = std::fs::read_to_string(dir.join("r.csv")).unwrap();
    let row = csv.lines().nth(1).expect("a merge row");
    assert!(row.starts_with("path,merge,"), "{row}");
    assert_eq!(row.split(',').nth(3), Some("4"), "{row}");
    // Shards that stopped at their time limit before their count leave a gap too; each
    // pixel's count is then the sum of what the shards took.
    let big = ["--spp", "1000000", "--time", "0.2"];
    let t1 = shard(&dir, "t1.exr", "1/2", &big);
    let t2 = shard(&dir, "t2.exr", "2/2", &big);
    refused(
        &dir,
        &["t1.exr", "t2.exr"],
        &[
            "stopped at its time limit",
            "of 1000000 are missing (shard 1/2",
        ],
    );
    let o = iris(
        &[
            "merge",
            "t1.exr",
            "t2.exr",
            "--allow-partial",
            "-o",
            "t.exr",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let done = |p: &Path| {
        let e = iris::output::partial::read(p).unwrap().exact;
        e.unit_span().0
    };
    let n = done(&t1) + done(&t2);
    assert!(
        stderr(&o).contains(&format!("{n} samples per pixel")),
        "{}",
        stderr(&o)
    );
}

#[test]
fn shard_flags_are_checked_before_rendering() {
    let dir = scratch_dir("merge-shard-flags");
    let scene = scene();
    let base = ["render", &scene, "--size", "32x24", "-q"];
    let bad: &[(&[&str], &str)] = &[
        (
            &["--spp", "6", "--shard", "0/3", "-o", "a.exr"],
            "counted from 1",
        ),
        (
            &["--spp", "6", "--shard", "4/3", "-o", "a.exr"],
            "I must be 1 to N = 3",
        ),
        (
            &["--spp", "6", "--shard", "3", "-o", "a.exr"],
            "expected I/N",
        ),
        (
            &["--spp", "6", "--shard", "7/7", "-o", "a.exr"],
            "at most 6 shards",
        ),
        (
            &[
                "--passes", "2", "--method", "sppm", "--shard", "3/3", "-o", "a.exr",
            ],
            "at most 2 shards",
        ),
        (
            &["--spp", "6", "--shard", "1/3", "-o", "a.png"],
            "must be .exr",
        ),
        (
            &[
                "--spp",
                "6",
                "--shard",
                "1/3",
                "--checkpoint",
                "2",
                "-o",
                "a.exr",
            ],
            "--checkpoint",
        ),
        (
            &[
                "--spp",
                "6",
                "--shard",
                "1/3",
                "--background",
                "white",
                "-o",
                "a.exr",
            ],
            "--background",
        ),
    ];
    for (extra, says) in bad {
        let mut args = base.to_vec();
        if !extra.contains(&"--method") {
            args.extend(["--method", "path"]);
        }
        args.extend_from_slice(extra);
        let o = iris(&args, &dir);
        assert!(!o.status.success(), "{extra:?} accepted");
        assert!(stderr(&o).contains(says), "{extra:?}: {}", stderr(&o));
        assert!(
            entries(&dir).is_empty(),
            "{extra:?} wrote {:?}",
            entries(&dir)
        );
    }
}

/// Spawns `iris render … --shard I/3 --time 600 --explain` (an open budget far beyond the
/// test) and returns it once the plan is printed, i.e. once rendering starts.
fn spawn_long_shard(dir: &Path, i_n: &str, out: &str) -> std::process::Child {
    let mut child = Command::new(env!("CARGO_BIN_EXE_iris"))
        .args([
            "render",
            &scene(),
            "--size",
            "32x24",
            "--method",
            "path",
            "--seed",
            "1",
            "--time",
            "600",
            "--explain",
            "-q",
            "--shard",
            i_n,
            "-o",
            out,
        ])
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn iris");
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    // The plan's last stage is `denoise`, followed by its cost line.
    for line in lines.by_ref() {
        if line.expect("stderr").starts_with("  denoise") {
            break;
        }
    }
    let _ = lines.next();
    // Keep draining stderr so the child never blocks on a full pipe.
    std::thread::spawn(move || lines.for_each(drop));
    std::thread::sleep(std::time::Duration::from_millis(300));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the shard ended before it was stopped"
    );
    child
}

/// The open-budget shards 1/3 and 3/3 of [`spawn_long_shard`]'s render, for 0.2 s each.
fn quick_open_shard(dir: &Path, i_n: &str, out: &str) {
    let o = iris(
        &[
            "render",
            &scene(),
            "--size",
            "32x24",
            "--method",
            "path",
            "--seed",
            "1",
            "--time",
            "0.2",
            "-q",
            "--shard",
            i_n,
            "-o",
            out,
        ],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_killed_shard_leaves_nothing_and_rerunning_it_fixes_the_merge() {
    let dir = scratch_dir("merge-killed");
    quick_open_shard(&dir, "1/3", "p1.exr");
    quick_open_shard(&dir, "3/3", "p3.exr");
    let mut child = spawn_long_shard(&dir, "2/3", "p2.exr");
    child.kill().expect("kill -9");
    let status = child.wait().unwrap();
    assert!(!status.success());
    assert_eq!(
        entries(&dir),
        ["p1.exr", "p3.exr"],
        "the killed shard left a file"
    );
    refused(
        &dir,
        &["p1.exr", "p3.exr"],
        &["shard 2/3 is missing (samples 349525..699050 of the open budget's block)"],
    );
    // Rerunning that index (here with a shorter time: not part of the render's identity).
    quick_open_shard(&dir, "2/3", "p2.exr");
    let o = iris(
        &["merge", "p1.exr", "p2.exr", "p3.exr", "-o", "all.exr"],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("merged 3 of 3 shards of an open budget"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn an_interrupted_shard_is_merged_only_with_allow_partial() {
    let dir = scratch_dir("merge-interrupted");
    quick_open_shard(&dir, "1/3", "p1.exr");
    quick_open_shard(&dir, "3/3", "p3.exr");
    let mut child = spawn_long_shard(&dir, "2/3", "p2.exr");
    let term = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("kill -TERM");
    assert!(term.success());
    let status = child.wait().unwrap();
    assert_eq!(
        status.code(),
        Some(130),
        "SIGTERM: the image so far, exit 130"
    );
    assert!(
        dir.join("p2.exr").is_file(),
        "an interrupted shard writes what it has"
    );
    refused(
        &dir,
        &["p1.exr", "p2.exr", "p3.exr"],
        &["p2.exr: shard 2/3 was interrupted", "--allow-partial"],
    );
    let o = iris(
        &[
            "merge",
            "p1.exr",
            "p2.exr",
            "p3.exr",
            "--allow-partial",
            "-o",
            "all.exr",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
}
