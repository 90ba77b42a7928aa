//! Stable-toolchain companion of the cargo-fuzz targets in `fuzz/` (see FUZZING.md).
//!
//! 1. Replays the committed inputs (`fuzz/seeds/<target>/`, `fuzz/regressions/<target>/`)
//!    through the same entry points as the fuzzers (`iris::load::fuzz_entry`).
//! 2. Runs a deterministic mutation pass (seeded xorshift: bit flips, byte sets,
//!    truncations, chunk duplication, JSON numbers replaced with huge, negative or
//!    non-finite values): a fixed number of mutants per target ([`MUTANTS`]) over those
//!    seeds and the repo's `assets/`, and a second fixed-count pass ([`SHARED_MUTANTS`]) over
//!    `../shared/assets` (which skips, saying so, where that folder is absent).
//! 3. Runs the exporter pass ([`exporters`]): the Draco and meshopt files real exporters
//!    made, mutated inside their compressed streams (byte flips, truncations, duplicated
//!    runs, 32-bit field overwrites; [`glb`] rebuilds the GLB around the mutated stream).
//!
//! Which mutants run is a function of the seed files and the RNG seed alone, never of the
//! clock: the same checkout tries the same inputs on any machine under any load. The only
//! clock in this file is [`PER_INPUT`], a guard against hangs.
//!
//! Every input must end in `Ok` or an `Err` that names the input file (or its MTL) and
//! says what is wrong; it must not panic (nor make a decoder panic inside the loaders'
//! panic net, `iris::load::panic_net`), take longer than [`PER_INPUT`], or grow the
//! heap by more than [`PEAK_LIMIT`] (counting global allocator below). A failing input is
//! written to `target/tmp/fuzz-replay-failures/` and named in the failure message, for
//! `cargo +nightly fuzz run <target> <file>`.

use iris::load::{fuzz_entry, panic_net};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::common;
mod exporters;
mod glb;

/// Most heap growth one input may cause. The loaders' own limits (2^22 zero-filled
/// accessor elements, 2^26-texel textures, 2^26-texel environment maps) allow a few
/// hundred MiB at most; the inputs here are ≤ 512 KiB, so 1 GiB means a missing bound.
const PEAK_LIMIT: usize = 1 << 30;

/// Longest one input may take. The slowest seeds load in tens of milliseconds in
/// release; 10 s (the fuzzers' `-timeout`) means a hang or a quadratic blow-up.
const PER_INPUT: Duration = Duration::from_secs(10);

/// Mutants per target in the pass over the repo's seeds. A count, not a time budget (see
/// the module docs), sized so the three targets take about 8 s in release on this
/// project's 2-core machines (BENCHMARKS.md, "Test suite").
const MUTANTS: usize = 8000;

/// Mutants per target in the pass over `../shared/assets`, whose larger glTF seeds load
/// about 10× slower (about 7 s for the three targets).
const SHARED_MUTANTS: usize = 1000;

/// Largest seed used (bigger shared assets would make each mutant slow to load).
const MAX_SEED: u64 = 512 << 10;

/// The allocation counters are the process's: the tests run one at a time.
use crate::common::alloc::SERIAL;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Target {
    Gltf,
    Obj,
    Image,
}

impl Target {
    const ALL: [Target; 3] = [Target::Gltf, Target::Obj, Target::Image];

    fn name(self) -> &'static str {
        match self {
            Target::Gltf => "gltf",
            Target::Obj => "obj",
            Target::Image => "image",
        }
    }

    /// Runs the input; `Err` describes a violated contract (not a load error).
    fn run(self, data: &[u8]) -> Result<(), String> {
        match self {
            Target::Gltf => check_load(
                fuzz_entry::load_gltf_bytes(data),
                &[Names::Exactly("fuzz-input.gl")],
            ),
            Target::Obj => check_load(
                fuzz_entry::load_obj_mtl_bytes(data),
                &[Names::Exactly("fuzz-input.obj"), Names::Extension("mtl")],
            ),
            Target::Image => {
                let out = fuzz_entry::decode_image_bytes(data);
                if let Err((_, detail)) = &out.texture {
                    if detail.trim().is_empty() {
                        return Err("texture error without a message".into());
                    }
                }
                match out.environment {
                    Some(Err(iris::Error::Load(e))) => {
                        check_load::<()>(Err(e), &[Names::Exactly("iris-fuzz-env")])
                    }
                    Some(Err(e)) => Err(format!("environment map: unexpected error kind: {e}")),
                    _ => Ok(()),
                }
            }
        }
    }
}

/// Files an error may name: the input itself, or the MTL its `mtllib` asks for.
#[derive(Clone, Copy)]
enum Names {
    /// The error's file contains this name.
    Exactly(&'static str),
    /// The error's file has this extension, in any case: the OBJ loader names the MTL
    /// file as the OBJ's `mtllib` spells it (`seed.Mtl` after a bit flip), which is the
    /// name it opened, so that is the right name to report.
    Extension(&'static str),
}

impl Names {
    fn matches(self, file: &Path) -> bool {
        match self {
            Names::Exactly(name) => file.to_string_lossy().contains(name),
            Names::Extension(ext) => file
                .extension()
                .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case(ext)),
        }
    }
}

/// A load error must name the input (`file` matches one of `files`) and say what is wrong.
fn check_load<T>(r: Result<T, iris::LoadError>, files: &[Names]) -> Result<(), String> {
    match r {
        Ok(_) => Ok(()),
        Err(e) => {
            if !files.iter().any(|f| f.matches(&e.file)) {
                return Err(format!("error does not name the input: {e}"));
            }
            if e.detail.trim().is_empty() {
                return Err(format!("error without details: {e}"));
            }
            Ok(())
        }
    }
}

/// Runs one input on a worker thread under `catch_unwind`, checking time and heap.
fn run_guarded(target: Target, data: &[u8]) -> Result<(), String> {
    let owned = data.to_vec();
    guarded(move || target.run(&owned)).0
}

/// Runs `work` on a worker thread under `catch_unwind`; a panic (escaped, or caught by
/// the loaders' panic net), more than [`PER_INPUT`] or a heap growth over [`PEAK_LIMIT`]
/// is an `Err`. Also returns the heap growth.
fn guarded<T: Send + 'static>(
    work: impl FnOnce() -> Result<T, String> + Send + 'static,
) -> (Result<T, String>, usize) {
    let (tx, rx) = mpsc::channel();
    let base = common::alloc::start_peak();
    let start = Instant::now();
    std::thread::spawn(move || {
        let caught = panic_net::caught_count();
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work))
            .unwrap_or_else(|p| Err(format!("panic: {}", panic_text(&p))));
        // A panic the loaders' net caught is a decoder bug too (the tests run serially).
        let r = match r {
            Ok(_) if panic_net::caught_count() != caught => Err(
                "a decoder panicked (caught by the panic net; `iris info --verbose` on the saved input names it)".into(),
            ),
            r => r,
        };
        let _ = tx.send(r);
    });
    let r = match rx.recv_timeout(PER_INPUT) {
        Ok(r) => r,
        Err(_) => return (Err(format!("no result after {PER_INPUT:?} (hang)")), 0),
    };
    let peak = common::alloc::peak_growth(base);
    if peak > PEAK_LIMIT {
        return (Err(format!("heap grew by {peak} bytes")), peak);
    }
    let took = start.elapsed();
    if took > PER_INPUT {
        return (Err(format!("took {took:?}")), peak);
    }
    (r, peak)
}

fn panic_text(p: &Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "non-string payload".into())
}

/// Saves a failing input and returns a line for the failure report.
fn record_failure(target: Target, data: &[u8], why: &str) -> String {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz-replay-failures");
    let _ = std::fs::create_dir_all(&dir);
    let hash = data.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
    });
    let path = dir.join(format!("{}-{hash:016x}", target.name()));
    let _ = std::fs::write(&path, data);
    format!(
        "{}: {why} (input saved to {})",
        target.name(),
        path.display()
    )
}

fn files_in(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    v.retain(|p| p.is_file());
    v.sort();
    v
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The committed inputs of `target`: seeds and minimized crash reproducers.
fn committed(target: Target) -> Vec<PathBuf> {
    let mut v = files_in(&repo().join("fuzz/seeds").join(target.name()));
    v.extend(files_in(
        &repo().join("fuzz/regressions").join(target.name()),
    ));
    v
}

#[test]
fn committed_corpus_replays_cleanly() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut failures = Vec::new();
    let mut count = 0;
    for target in Target::ALL {
        let inputs = committed(target);
        assert!(!inputs.is_empty(), "no committed {} inputs", target.name());
        for path in inputs {
            let data = std::fs::read(&path).unwrap();
            count += 1;
            if let Err(why) = run_guarded(target, &data) {
                failures.push(format!(
                    "{}: {}",
                    path.display(),
                    record_failure(target, &data, &why)
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {count} inputs failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    eprintln!("replayed {count} committed inputs");
}

/// Seeds from the repo for the mutation pass: committed inputs and `assets/`.
fn repo_seeds(target: Target) -> Vec<Vec<u8>> {
    let mut paths = committed(target);
    paths.extend(seed_files(&repo().join("assets"), target));
    read_seeds(target, &paths)
}

/// Seed files of `target` under `root`, sorted, at most [`MAX_SEED`] bytes each.
fn seed_files(root: &Path, target: Target) -> Vec<PathBuf> {
    let wanted: &[&str] = match target {
        Target::Gltf => &["glb", "gltf"],
        Target::Obj => &["obj"],
        Target::Image => &["png", "jpg", "jpeg", "hdr", "exr"],
    };
    common::files_with_ext(root, wanted)
        .into_iter()
        .filter(|p| std::fs::metadata(p).is_ok_and(|m| m.len() <= MAX_SEED))
        .collect()
}

fn read_seeds(target: Target, paths: &[PathBuf]) -> Vec<Vec<u8>> {
    paths
        .iter()
        .filter_map(|p| {
            let bytes = std::fs::read(p).ok()?;
            if target == Target::Obj && p.extension().is_some_and(|e| e == "obj") {
                // Pair an OBJ with the first MTL next to it, as the `obj` fuzzer expects.
                let mtl = files_in(p.parent()?)
                    .into_iter()
                    .find(|m| m.extension().is_some_and(|e| e == "mtl"))
                    .and_then(|m| std::fs::read(m).ok())
                    .unwrap_or_default();
                let mut joined = bytes;
                joined.extend_from_slice(fuzz_entry::OBJ_MTL_SEPARATOR);
                joined.extend_from_slice(&mtl);
                return Some(joined);
            }
            Some(bytes)
        })
        .collect()
}

/// xorshift64* (Vigna 2016), deterministic per seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Values that break naive count and size arithmetic.
const NASTY_NUMBERS: &[&str] = &[
    "4294967295",
    "4294967296",
    "2147483648",
    "18446744073709551615",
    "-1",
    "-2147483649",
    "0",
    "1e309",
    "-1e309",
    "NaN",
    "1e-320",
    "999999999999",
];

/// Applies 1–4 random mutations to `data`.
fn mutate(rng: &mut Rng, data: &[u8]) -> Vec<u8> {
    let mut d = data.to_vec();
    for _ in 0..1 + rng.below(4) {
        if d.is_empty() {
            d.push(rng.next() as u8);
        }
        match rng.below(6) {
            0 => {
                let i = rng.below(d.len());
                d[i] ^= 1 << rng.below(8);
            }
            1 => {
                let i = rng.below(d.len());
                d[i] = [0u8, 0xff, 0x7f, 0x80, rng.next() as u8][rng.below(5)];
            }
            2 => {
                let keep = rng.below(d.len());
                d.truncate(keep);
            }
            3 => {
                let a = rng.below(d.len());
                let len = rng.below((d.len() - a).min(4096)) + 1;
                let chunk = d[a..a + len].to_vec();
                let at = rng.below(d.len());
                d.splice(
                    at..at,
                    chunk.iter().copied().cycle().take(len * (1 + rng.below(4))),
                );
            }
            4 => {
                // Four little-endian bytes set to a nasty 32-bit value (GLB/EXR/PNG fields).
                if d.len() >= 4 {
                    let i = rng.below(d.len() - 3);
                    let v = [u32::MAX, 0x8000_0000, 0x7fff_ffff, 0, 0x0100_0000][rng.below(5)];
                    d[i..i + 4].copy_from_slice(&v.to_le_bytes());
                }
            }
            _ => replace_number(rng, &mut d),
        }
    }
    d
}

/// Replaces one run of ASCII digits (a JSON/OBJ/MTL number) with a nasty value.
fn replace_number(rng: &mut Rng, d: &mut Vec<u8>) {
    let starts: Vec<usize> = (0..d.len())
        .filter(|&i| d[i].is_ascii_digit() && (i == 0 || !d[i - 1].is_ascii_digit()))
        .collect();
    if starts.is_empty() {
        return;
    }
    let s = starts[rng.below(starts.len())];
    let e = (s..d.len())
        .find(|&i| !d[i].is_ascii_digit())
        .unwrap_or(d.len());
    let value = NASTY_NUMBERS[rng.below(NASTY_NUMBERS.len())].as_bytes();
    d.splice(s..e, value.iter().copied());
}

/// Runs `mutants` mutants per target over `seeds` (the RNG stream of target `k` starts from
/// `salt`) and fails listing the failing mutants (each input saved, see [`record_failure`]).
fn mutation_pass(label: &str, mutants: usize, salt: u64, seeds: impl Fn(Target) -> Vec<Vec<u8>>) {
    let mut failures = Vec::new();
    for (k, target) in Target::ALL.into_iter().enumerate() {
        let seeds = seeds(target);
        assert!(!seeds.is_empty(), "{label}: no {} seeds", target.name());
        assert!(
            mutants >= seeds.len(),
            "{label}: {mutants} mutants do not cover the {} {} seeds once",
            seeds.len(),
            target.name()
        );
        let mut rng = Rng(salt ^ (k as u64 + 1));
        let start = Instant::now();
        for i in 0..mutants {
            let input = mutate(&mut rng, &seeds[i % seeds.len()]);
            if let Err(why) = run_guarded(target, &input) {
                failures.push(format!(
                    "mutant {i}: {}",
                    record_failure(target, &input, &why)
                ));
            }
            if failures.len() >= 10 {
                break; // enough to act on; the pass is deterministic, so rerun to see more
            }
        }
        // Printed for BENCHMARKS.md's sizing of MUTANTS; asserted nowhere.
        eprintln!(
            "{label} {}: {mutants} mutants of {} seeds in {:.1} s",
            target.name(),
            seeds.len(),
            start.elapsed().as_secs_f64()
        );
    }
    assert!(
        failures.is_empty(),
        "{label}: {} mutants failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn bounded_mutation_pass() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    mutation_pass("repo", MUTANTS, 0x9e37_79b9_7f4a_7c15, repo_seeds);
}

/// The same fixed-count pass over `../shared/assets` (third-party files), a separate test
/// so that the repo pass above tries the same mutants with or without that folder.
#[test]
fn bounded_mutation_pass_over_shared_assets() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    mutation_pass("shared", SHARED_MUTANTS, 0x6a09_e667_f3bc_c909, |t| {
        read_seeds(t, &seed_files(&shared, t))
    });
}

/// Issue 15: a bit flip turned `mtllib seed.mtl` into `seed.Mtl`. The loader names the MTL
/// file as the OBJ spells it (the name it opened), and the replay's contract accepts any
/// case of the `.mtl` extension.
#[test]
fn an_mtl_error_names_the_mtl_as_the_obj_spells_it() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let data = std::fs::read(repo().join("fuzz/regressions/obj/mtllib_case_flip.objmtl"))
        .expect("committed regression input");
    let e = fuzz_entry::load_obj_mtl_bytes(&data).expect_err("newmtl without a name");
    assert_eq!(e.file, Path::new("seed.Mtl"), "{e}");
    assert!(e.to_string().contains("newmtl"), "{e}");
    assert_eq!(Target::Obj.run(&data), Ok(()));
}
