//! Shards and merges (issue 19 items 1 and 2): a render cut into N shards
//! (`--shard I/N`) and merged (`iris merge`) is bit for bit the render of all its units,
//! for every method (the film's sums are exact, `src/image/fixed.rs`; SPPM and the hybrid
//! rebuild the radius sequence, `src/integrator/sppm.rs`); a shard is deterministic; an
//! open budget's shards merge into an average of disjoint segments and report its counts.
//! Library calls on the repository's own small scenes at 32×24.

use crate::common;
mod identity_flags;

use iris::app::merge::{merge_command, MergeOptions, MergeSummary};
use iris::app::shard::Shard;
use iris::app::{render_command, RenderOptions};
use iris::integrator::Method;
use std::path::{Path, PathBuf};
use std::time::Duration;

fn asset(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets")
        .join(rel)
}

/// `iris render SCENE --size 32x24 --method M --spp/--passes UNITS --seed 5 -q -o OUT`
/// (hybrid and SPPM with 3000 photons a pass, photon mapping 20 000 in all).
fn opts(scene: &Path, out: &Path, method: Method, units: u32) -> RenderOptions {
    let mut o = RenderOptions::new(scene, Some(out));
    o.size = Some((32, 24));
    o.method = method;
    o.seed = 5;
    o.quiet = true;
    o.threads = 2;
    o.spp = units;
    o.photon.passes = units;
    o.photon.photons = if method == Method::Photon {
        20_000
    } else {
        3000
    };
    o
}

/// Renders every shard of `n` (in the order `order` gives, 1-based) to `dir/part-I.exr`.
fn render_shards(base: &RenderOptions, dir: &Path, n: u32, order: &[u32]) -> Vec<PathBuf> {
    order
        .iter()
        .map(|&i| {
            let out = dir.join(format!("part-{i}-of-{n}.exr"));
            let o = RenderOptions {
                output: Some(out.clone()),
                shard: Some(Shard::parse(&format!("{i}/{n}")).unwrap()),
                ..base.clone()
            };
            render_command(&o).unwrap_or_else(|e| panic!("shard {i}/{n}: {e}"));
            out
        })
        .collect()
}

fn merge(parts: &[PathBuf], out: &Path, allow_partial: bool) -> iris::Result<MergeSummary> {
    merge_command(&MergeOptions {
        parts: parts.to_vec(),
        output: out.to_path_buf(),
        report: None,
        reference: None,
        allow_partial,
        display: Default::default(),
    })
}

/// The merge of `n` shards (rendered in a scrambled order) against one render of all the
/// units: the same EXR bytes and pixels.
fn assert_merge_is_exact(scene: &Path, method: Method, units: u32, n: u32, dir: &Path) {
    let whole_path = dir.join("whole.exr");
    assert_options_merge_exactly(&opts(scene, &whole_path, method, units), n, dir);
}

/// [`assert_merge_is_exact`] of the render `base` describes (its output is the whole
/// render's).
fn assert_options_merge_exactly(base: &RenderOptions, n: u32, dir: &Path) {
    let whole_path = base.output.clone().unwrap();
    let whole = render_command(base).expect("whole render");
    let order: Vec<u32> = (1..=n).rev().collect();
    let parts = render_shards(base, dir, n, &order);
    let merged_path = dir.join(format!("merged-{n}.exr"));
    let m = merge(&parts, &merged_path, false).expect("merge");
    let units = if base.method == Method::Sppm {
        base.photon.passes
    } else {
        base.spp
    };
    let what = format!("{} {units} units in {n} shards", base.method.name());
    assert_eq!(
        m.units_per_pixel,
        (u64::from(units), u64::from(units)),
        "{what}"
    );
    let differ = (m.image.data.iter())
        .zip(&whole.image.data)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(differ, 0, "{what}: pixels differ from the whole render");
    let (a, b) = (
        std::fs::read(&merged_path).unwrap(),
        std::fs::read(&whole_path).unwrap(),
    );
    assert!(a == b, "{what}: the EXR files differ");
    assert_eq!(m.parts, n as usize);
    // A noisy image: an exact merge of images that were all alike would prove little.
    let distinct = whole
        .image
        .data
        .iter()
        .map(|p| p.x.to_bits())
        .collect::<std::collections::HashSet<_>>();
    assert!(
        distinct.len() > 50,
        "{what}: {} distinct values",
        distinct.len()
    );
}

/// The methods whose merges the tests below check: every method whose declaration takes
/// shards must be one of them (a new method comes with its merge test).
#[test]
fn every_method_declaring_shards_has_a_merge_test() {
    let merged = [
        Method::Path,
        Method::Whitted,
        Method::Sppm,
        Method::Hybrid,
        Method::Vcm,
        Method::Bpt,
        Method::Photon,
    ];
    for m in Method::ALL {
        if m != Method::Auto && m.caps().shards.is_yes() {
            assert!(
                merged.contains(&m),
                "--method {} has no merge test",
                m.name()
            );
        }
    }
}

#[test]
fn path_and_whitted_merges_are_bit_identical_to_one_render() {
    let scene = asset("paper/fig4_4_1_prism.glb");
    // 11 samples: not divisible by 2, 3 or 7.
    for method in [Method::Path, Method::Whitted] {
        for n in [1, 2, 3, 7] {
            let dir = common::scratch_dir(&format!("shards-{}-{n}", method.name()));
            assert_merge_is_exact(&scene, method, 11, n, &dir);
        }
    }
}

#[test]
fn spectral_path_merge_is_bit_identical() {
    // A dispersive prism under a sky map: spectral transport, hero wavelengths stratified
    // over the block.
    let dir = common::scratch_dir("shards-spectral-path");
    assert_merge_is_exact(&asset("scenes/prism_sky.glb"), Method::Path, 10, 3, &dir);
}

#[test]
fn sppm_and_hybrid_merges_are_bit_identical_to_one_render() {
    // Spectral SPPM and hybrid on a caustic scene: shards after the first rebuild the
    // radius sequence from pass 0.
    let scene = asset("scenes/gem_caustics.glb");
    for (method, n) in [(Method::Sppm, 2), (Method::Sppm, 3), (Method::Hybrid, 3)] {
        let dir = common::scratch_dir(&format!("shards-{}-{n}", method.name()));
        assert_merge_is_exact(&scene, method, 7, n, &dir);
    }
    // An explicit --radius skips pass 0's radius choice; the merge stays exact.
    let dir = common::scratch_dir("shards-sppm-radius");
    let mut o = opts(&scene, &dir.join("whole.exr"), Method::Sppm, 5);
    o.photon.radius = Some(0.002);
    assert_options_merge_exactly(&o, 2, &dir);
    // The pilot's photon budget (no --photons, the map only): every shard runs the same
    // pilot and makes the same choice.
    let dir = common::scratch_dir("shards-hybrid-pilot");
    let mut o = opts(&scene, &dir.join("whole.exr"), Method::Hybrid, 5);
    o.photon.photons = 0;
    o.photon.caustic_mode = iris::integrator::CausticMode::Map;
    assert_options_merge_exactly(&o, 3, &dir);
    // The hybrid's light-traced caustics (splats made per pass) merge exactly too.
    let dir = common::scratch_dir("shards-hybrid-mixed");
    let mut o = opts(&scene, &dir.join("whole.exr"), Method::Hybrid, 5);
    o.photon.caustic_mode = iris::integrator::CausticMode::Mixed;
    assert_options_merge_exactly(&o, 2, &dir);
}

/// The polarized hybrid on the calcite rhomb (a crystal: `--polarization auto` turns it on):
/// shards after the first replay pass 0's polarized photons for the radius, and merge
/// exactly.
#[test]
fn polarized_hybrid_merges_are_bit_identical_to_one_render() {
    let scene = asset("scenes/calcite_rhomb.glb");
    let dir = common::scratch_dir("shards-hybrid-polarized");
    assert_merge_is_exact(&scene, Method::Hybrid, 5, 3, &dir);
    // It was polarized: the same render with the mode off is another image.
    let mut off = opts(&scene, &dir.join("off.exr"), Method::Hybrid, 5);
    off.polarization = iris::plan::PolarizationMode::Off;
    let off = render_command(&off).expect("unpolarized render");
    let on = iris::output::read_exr(&dir.join("whole.exr"));
    assert!(on.is_ok(), "the whole render is readable");
    assert!(
        off.image.data != on.unwrap().data,
        "polarized and unpolarized hybrids gave the same image"
    );
}

/// The hybrid with scattering media: shards after the first replay the surface and the
/// volume map's radius sequences from pass 0, with the pilot's photon budget (the volume
/// map's first radius comes from pass 0's photons, as many as one render's pass 0
/// traces) and with a fixed count; the path tracer through a medium merges exactly too.
#[test]
fn media_merges_are_bit_identical_to_one_render() {
    for (scene, method, photons) in [
        ("scenes/milky_tank.glb", Method::Hybrid, 0),
        ("scenes/hazy_prism.glb", Method::Hybrid, 3000),
        ("scenes/opal.glb", Method::Path, 3000),
    ] {
        let name = format!("shards-media-{}-{photons}", method.name());
        let dir = common::scratch_dir(&format!("{name}-{}", scene.len()));
        let mut o = opts(&asset(scene), &dir.join("whole.exr"), method, 6);
        o.photon.photons = photons;
        assert_options_merge_exactly(&o, 3, &dir);
    }
}

/// VCM and BPT (spectral, on a caustic scene): shards after the first take VCM's first
/// radius from pass 0's light subpaths, as one render does.
#[test]
fn vcm_and_bpt_merges_are_bit_identical_to_one_render() {
    let scene = asset("scenes/gem_caustics.glb");
    for (method, n) in [(Method::Vcm, 3), (Method::Bpt, 2)] {
        let dir = common::scratch_dir(&format!("shards-{}-{n}", method.name()));
        assert_merge_is_exact(&scene, method, 5, n, &dir);
    }
}

#[test]
fn photon_mapping_merge_is_bit_identical() {
    // Every shard builds the same maps (a function of the seed) and takes its samples.
    let dir = common::scratch_dir("shards-photon");
    assert_merge_is_exact(
        &asset("paper/fig4_4_1_prism.glb"),
        Method::Photon,
        5,
        2,
        &dir,
    );
}

#[test]
fn a_shard_is_deterministic_whatever_the_threads() {
    let dir = common::scratch_dir("shards-determinism");
    let scene = asset("paper/fig4_4_1_prism.glb");
    let mut bytes = Vec::new();
    for (k, threads) in [(0, 1), (1, 2), (2, 2)] {
        let out = dir.join(format!("p{k}.exr"));
        let mut o = opts(&scene, &out, Method::Path, 9);
        o.threads = threads;
        o.shard = Some(Shard { index: 2, count: 3 });
        render_command(&o).unwrap();
        bytes.push(std::fs::read(&out).unwrap());
    }
    assert!(
        bytes[0] == bytes[1] && bytes[1] == bytes[2],
        "a shard's bytes differ between runs"
    );
}

#[test]
fn open_budget_shards_merge_as_disjoint_segments_and_report_counts() {
    let dir = common::scratch_dir("shards-open");
    let scene = asset("paper/fig4_4_1_prism.glb");
    let budget = iris::app::BudgetFlags {
        method: Some(Method::Path),
        time: Some(Duration::from_millis(200)),
        ..Default::default()
    }
    .resolve();
    let base = opts(&scene, &dir.join("x.exr"), Method::Path, 1).with_budget(&budget);
    let parts = render_shards(&base, &dir, 3, &[1, 2, 3]);
    let mut done = 0;
    for (i, p) in parts.iter().enumerate() {
        let partial = iris::output::partial::read(p).unwrap();
        let h = iris::app::shard::ShardHeader::from_entries(p, &partial.entries).unwrap();
        // Shard I starts at (I−1)·⌊2²⁰/3⌋ of the block and stopped at its own time limit.
        let seg = iris::render::OPEN_UNITS / 3;
        assert_eq!(h.planned, i as u64 * seg..(i as u64 + 1) * seg);
        assert_eq!(h.end, "time");
        assert!(h.done >= 1 && h.done < seg);
        assert_eq!(partial.exact.unit_span(), (h.done, h.done));
        done += h.done;
    }
    let m = merge(&parts, &dir.join("open.exr"), false).expect("merge");
    assert_eq!(m.total, None);
    assert_eq!(m.units_per_pixel, (done, done));
    assert!(m.image.data.iter().all(|p| p.is_finite()));
    // The mean of the merge is the sample-weighted mean of the parts.
    let means: Vec<_> = parts
        .iter()
        .map(|p| iris::output::partial::read(p).unwrap().exact)
        .collect();
    let px = 32 * 12 + 16;
    let weighted: f64 = means
        .iter()
        .map(|e| e.mean().data[px].x as f64 * e.unit_span().0 as f64)
        .sum::<f64>()
        / done as f64;
    assert!((m.image.data[px].x as f64 - weighted).abs() <= 1e-5 * weighted.abs().max(1e-3));
    // Without a shard it is refused: the open budget's segments are named by shard.
    let e = merge(&parts[..2], &dir.join("two.exr"), false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("shard 3/3 is missing"), "{e}");
}
