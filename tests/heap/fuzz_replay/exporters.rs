//! The exporter pass: the Draco and meshopt files real exporters made
//! (tests/data/compressed: Blender 5.0.1's Draco, gltfpack's and glTF-Transform's meshopt),
//! mutated with byte flips, truncations, duplications (a run of bytes repeated) and 32-bit
//! field overwrites ([`Kind`]), mostly inside their compressed streams (the GLB rebuilt
//! around the mutated stream, so the mutant reaches the decoder) and partly anywhere in
//! the file.
//!
//! Every mutant must end in `Ok` or a clean error (the replay's contract, see
//! [`super::guarded`]) **and** catch no panic: a panic the loader's net turned into
//! "the Draco decoder panicked on this data" ([`iris::load::panic_net::caught_count`]) is a
//! decoder bug as much as one that escaped.
//!
//! - [`exporter_mutation_pass`] runs in every test run: [`PASS_STREAM`] and [`PASS_FILE`]
//!   mutants per seed and kind, a fixed count (deterministic, seconds in release).
//! - [`exporter_campaign`] (ignored) is the long campaign behind FUZZING.md's numbers:
//!   `IRIS_CAMPAIGN_STREAM` and `IRIS_CAMPAIGN_FILE` mutants per seed and kind (another RNG
//!   stream with `IRIS_CAMPAIGN_SALT`, only some seeds with `IRIS_CAMPAIGN_ONLY`), a table of
//!   outcomes and of findings by cause, and the first inputs of each cause saved under
//!   `target/tmp/exporter-campaign/`.

use super::glb::{Glb, Kind, Region};
use super::{check_load, guarded, Names, Rng, Target, SERIAL};
use iris::load::{fuzz_entry, panic_net};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Mutants per seed and kind inside the compressed streams, in every test run.
const PASS_STREAM: usize = 100;

/// Mutants per seed and kind anywhere in the file, in every test run.
const PASS_FILE: usize = 25;

/// The exporter-made files that hold a compressed stream, sorted, with their bytes.
fn exporter_seeds() -> Vec<(String, Vec<u8>, Glb)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/compressed");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/data/compressed")
        .filter_map(|e| Some(e.ok()?.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "glb"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .filter_map(|p| {
            let bytes = std::fs::read(&p).ok()?;
            let glb = Glb::parse(&bytes)?;
            let name = p.file_stem()?.to_string_lossy().into_owned();
            (!glb.streams().is_empty()).then_some((name, bytes, glb))
        })
        .collect()
}

/// What one mutant did.
enum Outcome {
    Loaded,
    Refused,
    /// A broken contract: the cause (panic message and location, hang, heap growth).
    Finding(String),
}

/// Runs `input` through the glTF fuzz entry point under the replay's guard, and checks
/// that no panic was caught on the way. Returns the outcome and the heap growth.
fn run_mutant(input: &[u8]) -> (Outcome, usize) {
    let owned = input.to_vec();
    let (result, peak) = guarded(move || {
        let caught = panic_net::caught_count();
        let r = fuzz_entry::load_gltf_bytes(&owned).map(|_| ());
        if panic_net::caught_count() != caught {
            // The tests turn `show_caught_panics` on, so the detail names the panic.
            let detail = r.err().map_or("the file loaded".into(), |e| e.detail);
            return Err(format!("caught: {detail}"));
        }
        let loaded = r.is_ok();
        check_load(r, &[Names::Exactly("fuzz-input.gl")]).map(|()| loaded)
    });
    let outcome = match result {
        Err(why) => Outcome::Finding(why),
        Ok(true) => Outcome::Loaded,
        Ok(false) => Outcome::Refused,
    };
    (outcome, peak)
}

/// The RNG stream of one seed, kind and region (`salt` 0 in the test pass).
fn rng_for(seed: usize, kind: Kind, region: Region, salt: u64) -> Rng {
    let k = Kind::ALL.iter().position(|&x| x == kind).unwrap_or(0) as u64;
    let r = u64::from(region == Region::File);
    let stream = ((seed as u64) << 8 | k << 2 | r).wrapping_mul(0x9e37_79b9);
    Rng(0x243f_6a88_85a3_08d3 ^ stream ^ salt.wrapping_mul(0xff51_afd7_ed55_8ccd))
}

/// Counts of one (seed, kind, region) run.
#[derive(Default)]
struct Tally {
    runs: usize,
    loaded: usize,
    refused: usize,
    findings: BTreeMap<String, usize>,
    peak: usize,
}

/// Runs `count` mutants of seed `s` for `kind` in `region`; `on_finding` sees each
/// failing input.
fn run_class(
    s: usize,
    seed: &(String, Vec<u8>, Glb),
    kind: Kind,
    region: Region,
    (count, salt): (usize, u64),
    mut on_finding: impl FnMut(&str, &[u8]),
) -> Tally {
    let (_, file, glb) = seed;
    let mut rng = rng_for(s, kind, region, salt);
    let mut tally = Tally::default();
    for _ in 0..count {
        let input = glb.mutant(file, &mut rng, kind, region);
        let (outcome, peak) = run_mutant(&input);
        tally.runs += 1;
        tally.peak = tally.peak.max(peak);
        match outcome {
            Outcome::Loaded => tally.loaded += 1,
            Outcome::Refused => tally.refused += 1,
            Outcome::Finding(cause) => {
                on_finding(&cause, &input);
                *tally.findings.entry(cause).or_default() += 1;
            }
        }
    }
    tally
}

#[test]
fn exporter_mutation_pass() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    panic_net::show_caught_panics(true);
    let seeds = exporter_seeds();
    // 3 Blender Draco files, 6 meshopt files (gltfpack, glTF-Transform).
    assert_eq!(seeds.len(), 9, "exporter seeds with compressed streams");
    let start = Instant::now();
    let mut failures = Vec::new();
    let (mut runs, mut loaded, mut refused) = (0, 0, 0);
    for (s, seed) in seeds.iter().enumerate() {
        for kind in Kind::ALL {
            for (region, count) in [(Region::Stream, PASS_STREAM), (Region::File, PASS_FILE)] {
                let tally = run_class(s, seed, kind, region, (count, 0), |cause, input| {
                    failures.push(super::record_failure(Target::Gltf, input, cause));
                });
                runs += tally.runs;
                loaded += tally.loaded;
                refused += tally.refused;
            }
        }
    }
    eprintln!(
        "exporter pass: {runs} mutants of {} seeds ({loaded} loaded, {refused} refused) in {:.1} s",
        seeds.len(),
        start.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{} exporter mutants failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    // The pass must reach both ends: mutants the decoders accept and mutants they refuse.
    assert!(
        loaded > 0 && refused > 0,
        "{loaded} loaded, {refused} refused"
    );
}

/// A cause without what varies between inputs (numbers), for grouping.
fn cause_key(cause: &str) -> String {
    let mut out = String::new();
    let mut last_digit = false;
    for c in cause.chars() {
        if c.is_ascii_digit() {
            if !last_digit {
                out.push('N');
            }
            last_digit = true;
        } else {
            out.push(c);
            last_digit = false;
        }
    }
    out
}

/// The long campaign (see the module docs):
/// `IRIS_CAMPAIGN_STREAM=20000 IRIS_CAMPAIGN_FILE=5000 cargo test --release --test
/// heap -- --ignored exporter_campaign --nocapture`.
#[test]
#[ignore = "long; run by hand for FUZZING.md"]
fn exporter_campaign() {
    let count = |var: &str, default: usize| {
        std::env::var(var)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let stream = count("IRIS_CAMPAIGN_STREAM", 2000);
    let file = count("IRIS_CAMPAIGN_FILE", 500);
    // Another RNG stream than the test pass's (0), and the seeds whose name contains
    // `IRIS_CAMPAIGN_ONLY`.
    let salt = count("IRIS_CAMPAIGN_SALT", 0) as u64;
    let only = std::env::var("IRIS_CAMPAIGN_ONLY").unwrap_or_default();
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    panic_net::show_caught_panics(true);
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("exporter-campaign");
    let _ = std::fs::create_dir_all(&out_dir);
    // Cause → (its number, how many inputs, the first inputs saved).
    let mut by_cause: BTreeMap<String, (usize, usize, Vec<String>)> = BTreeMap::new();
    let start = Instant::now();
    println!("seed\tkind\tregion\tmutants\tloaded\trefused\tfindings\tpeak_MiB\tseconds");
    for (s, seed) in exporter_seeds().iter().enumerate() {
        if !seed.0.contains(&only) {
            continue;
        }
        for kind in Kind::ALL {
            for (region, n) in [(Region::Stream, stream), (Region::File, file)] {
                let t0 = Instant::now();
                let tally = run_class(s, seed, kind, region, (n, salt), |cause, input| {
                    let id = by_cause.len();
                    let entry = by_cause
                        .entry(cause_key(cause))
                        .or_insert_with(|| (id, 0, Vec::new()));
                    entry.1 += 1;
                    if entry.2.len() < 3 {
                        // `cause<id>-<seed>-<kind>-<region>-<n>.glb`
                        let name = format!(
                            "cause{}-{}-{kind:?}-{region:?}-{}.glb",
                            entry.0, seed.0, entry.1
                        );
                        let _ = std::fs::write(out_dir.join(&name), input);
                        entry.2.push(name);
                    }
                });
                println!(
                    "{}\t{kind:?}\t{region:?}\t{}\t{}\t{}\t{}\t{:.1}\t{:.1}",
                    seed.0,
                    tally.runs,
                    tally.loaded,
                    tally.refused,
                    tally.findings.values().sum::<usize>(),
                    tally.peak as f64 / (1 << 20) as f64,
                    t0.elapsed().as_secs_f64()
                );
            }
        }
    }
    println!(
        "findings by cause ({:.0} s):",
        start.elapsed().as_secs_f64()
    );
    for (cause, (id, n, files)) in &by_cause {
        println!("cause{id}\t{n}\t{cause}\t{}", files.join(" "));
    }
    assert!(by_cause.is_empty(), "{} causes", by_cause.len());
}
