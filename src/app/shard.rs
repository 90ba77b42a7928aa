//! `iris render SCENE --shard I/N -o PART.exr`: one machine's share of a render (issue
//! 19), written as a partial image ([`crate::output::partial`]) that `iris merge` adds
//! exactly to the others ([`super::merge`]).
//!
//! ## Which units a shard takes
//! Units are samples per pixel (SPPM: passes; the hybrid: passes of one sample), by
//! absolute index: unit k of a shard is unit k of the whole render (its sampler index, its
//! half k mod 2, SPPM's and the hybrid's radius and wavelengths of pass k), so the film's
//! exact sums ([`crate::image::fixed`]) of the shards add up to one render's.
//! - A fixed count T (`--spp T`, SPPM `--passes T`): shard I of N (1 ≤ I ≤ N ≤ T, 1-based
//!   like Slurm's array indices) takes the contiguous units ⌊(I−1)T/N⌋ .. ⌊I·T/N⌋. The
//!   merge of all N is bit for bit the render of T units.
//! - An open budget (no `--spp`/`--passes`: `--time`, `--target-error` or the defaults,
//!   each per shard): shard I starts at (I−1)·⌊2²⁰/N⌋ of the pixel's 2²⁰-sample Sobol'
//!   block ([`crate::render::OPEN_UNITS`]) and runs until its own limit (at most to the
//!   next shard's start), its stop test on its own halves. The merge is then not a prefix
//!   of one render: it is the average of disjoint segments of the block, each sample still
//!   a uniformly scrambled Sobol' point, so an unbiased estimate of the same image.
//!
//! ## What a shard writes
//! Only at its end, atomically (temporary name, then rename): a shard that is killed
//! leaves no file under its name (at most a `.NAME.tmp-PID-N` file, which `iris merge`
//! refuses by name and by content), and rerunning that index replaces nothing but its own
//! file. There are no checkpoint writes (`--checkpoint` is refused). A shard stopped by
//! Ctrl-C or SIGTERM (Slurm's time limit) writes what it has, marked `interrupted`: `iris
//! merge` takes it only with `--allow-partial`. The header ([`ShardHeader`]) holds the
//! render's identity ([`super::shard_id`]), the shard, the units planned and done, how it
//! ended and its counts; no times, so the same shard rendered twice gives the same bytes.
//!
//! Not with `--shard`: a PNG output, `--background` other than `env`, `--denoise on` (the
//! merge writes the picture; it does not denoise, having no scene for the auxiliary pass).

use crate::error::{Error, LoadError, LoadErrorKind, Result};
use crate::render::{EndReason, RenderStats, OPEN_UNITS};
use std::ops::Range;
use std::path::Path;

/// Most shards a render may be cut into.
pub const MAX_SHARDS: u32 = 1 << 16;

/// `--shard I/N`: shard `index` (1-based) of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 1 ≤ index ≤ count.
    pub index: u32,
    /// 1 ≤ count ≤ [`MAX_SHARDS`].
    pub count: u32,
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// Parses `I/N` with 1 ≤ I ≤ N ≤ [`MAX_SHARDS`].
    pub fn parse(s: &str) -> Result<Shard> {
        let bad = |why: &str| Error::Usage(format!("--shard {s:?}: {why}"));
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| bad("expected I/N, e.g. 3/8 (shard 3 of 8, counted from 1)"))?;
        let num = |t: &str, what: &str| {
            t.trim()
                .parse::<u32>()
                .map_err(|_| bad(&format!("{what} {t:?} is not a whole number")))
        };
        let (index, count) = (num(i, "I")?, num(n, "N")?);
        if count == 0 || count > MAX_SHARDS {
            return Err(bad(&format!("N must be 1 to {MAX_SHARDS}")));
        }
        if index == 0 || index > count {
            return Err(bad(&format!(
                "I must be 1 to N = {count} (shards are counted from 1, like Slurm array indices)"
            )));
        }
        Ok(Shard { index, count })
    }

    /// The units this shard takes of a render of `total` units (open when `total` ≥
    /// [`OPEN_UNITS`]; see the module docs); an error when a shard would get none (more
    /// shards than units).
    pub fn range(self, total: u64, unit: &str) -> Result<Range<u64>> {
        let (i, n) = (u64::from(self.index), u64::from(self.count));
        if total >= OPEN_UNITS {
            let seg = total / n;
            return Ok((i - 1) * seg..i * seg);
        }
        if n > total {
            return Err(Error::Usage(format!(
                "--shard {self}: {n} shards of {total} {unit} leave some shards nothing to \
                 render (at most {total} shards)"
            )));
        }
        Ok((i - 1) * total / n..i * total / n)
    }
}

/// How a shard's render ended, as its partial image says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShardState {
    /// It ran to its count, its time limit or its error target.
    Complete,
    /// Ctrl-C or SIGTERM stopped it: `iris merge` needs `--allow-partial`.
    Interrupted,
}

/// A shard's header: the render's identity and the shard's own facts (see the module
/// docs). Stored as `key=value` entries in that order.
#[derive(Debug, Clone, PartialEq)]
pub struct ShardHeader {
    /// The render's identity ([`super::shard_id::identity`]): equal in every part.
    pub identity: Vec<(String, String)>,
    /// The scene file as named on the command line (informative only).
    pub scene: String,
    /// Which shard.
    pub shard: Shard,
    /// The units planned (absolute indices).
    pub planned: Range<u64>,
    /// Units every pixel has, from `planned.start`.
    pub done: u64,
    /// How it ended.
    pub state: ShardState,
    /// What ended it: `samples`, `target`, `time` or `interrupted`.
    pub end: String,
    /// Rays traced.
    pub rays: u64,
    /// Photons emitted.
    pub photons: u64,
    /// Samples left out as NaN, infinite or out of range.
    pub bad_samples: u64,
}

/// "a..b".
fn range_text(r: &Range<u64>) -> String {
    format!("{}..{}", r.start, r.end)
}

impl ShardHeader {
    /// The header of a shard rendered with `stats` over `planned`, every pixel having
    /// `done` units.
    pub fn new(
        identity: Vec<(String, String)>,
        scene: &Path,
        shard: Shard,
        (planned, done): (Range<u64>, u64),
        stats: &RenderStats,
    ) -> ShardHeader {
        let (state, end) = match stats.end {
            EndReason::Interrupted => (ShardState::Interrupted, "interrupted"),
            EndReason::Samples => (ShardState::Complete, "samples"),
            EndReason::Target => (ShardState::Complete, "target"),
            EndReason::TimeLimit => (ShardState::Complete, "time"),
        };
        ShardHeader {
            identity,
            scene: scene.display().to_string(),
            shard,
            planned,
            done,
            state,
            end: end.into(),
            rays: stats.rays,
            photons: stats.photons,
            bad_samples: stats.bad_samples,
        }
    }

    /// The entries in file order.
    pub fn entries(&self) -> Vec<(String, String)> {
        let mut e = self.identity.clone();
        let state = match self.state {
            ShardState::Complete => "complete",
            ShardState::Interrupted => "interrupted",
        };
        let own = [
            ("scene", self.scene.clone()),
            ("shard", self.shard.to_string()),
            ("planned", range_text(&self.planned)),
            ("done", self.done.to_string()),
            ("state", state.into()),
            ("end", self.end.clone()),
            ("rays", self.rays.to_string()),
            ("photons", self.photons.to_string()),
            ("bad_samples", self.bad_samples.to_string()),
        ];
        e.extend(own.into_iter().map(|(k, v)| (k.to_string(), v)));
        e
    }

    /// The header of `path`'s `entries`; an error names the file and the key.
    pub fn from_entries(
        path: &Path,
        entries: &[(String, String)],
    ) -> std::result::Result<ShardHeader, LoadError> {
        let own = [
            "scene",
            "shard",
            "planned",
            "done",
            "state",
            "end",
            "rays",
            "photons",
            "bad_samples",
        ];
        let bad = |key: &str, why: String| {
            let element = format!(
                "attribute {} entry {key}",
                crate::output::partial::ATTRIBUTE
            );
            LoadError::new(path, element, LoadErrorKind::Parse, why)
        };
        let get = |key: &str| {
            entries
                .iter()
                .find(|(k, _)| k == key)
                .map(|(_, v)| v.as_str())
                .ok_or_else(|| bad(key, "missing".into()))
        };
        let num = |key: &str| -> std::result::Result<u64, LoadError> {
            let v = get(key)?;
            v.parse()
                .map_err(|_| bad(key, format!("{v:?} is not a count")))
        };
        let planned = get("planned")?;
        let planned = planned
            .split_once("..")
            .and_then(|(a, b)| Some(a.parse().ok()?..b.parse().ok()?))
            .filter(|r: &Range<u64>| r.start < r.end)
            .ok_or_else(|| bad("planned", format!("{planned:?} is not a range a..b")))?;
        let shard = Shard::parse(get("shard")?).map_err(|e| bad("shard", e.to_string()))?;
        let state = match get("state")? {
            "complete" => ShardState::Complete,
            "interrupted" => ShardState::Interrupted,
            other => return Err(bad("state", format!("unknown state {other:?}"))),
        };
        let identity = entries
            .iter()
            .filter(|(k, _)| !own.contains(&k.as_str()))
            .cloned()
            .collect();
        Ok(ShardHeader {
            identity,
            scene: get("scene")?.into(),
            shard,
            planned,
            done: num("done")?,
            state,
            end: get("end")?.into(),
            rays: num("rays")?,
            photons: num("photons")?,
            bad_samples: num("bad_samples")?,
        })
    }

    /// The identity value of `key`, if present.
    pub fn get(&self, key: &str) -> Option<&str> {
        self.identity
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// The whole render's units (`None`: an open budget, or unreadable).
    pub fn total(&self) -> Option<u64> {
        self.get("total").and_then(|t| t.parse().ok())
    }

    /// "samples" or "passes".
    pub fn unit(&self) -> &str {
        self.get("unit").unwrap_or("samples")
    }
}

/// Refuses the flags a shard cannot honour (see the module docs), before anything is
/// rendered.
pub fn check_flags(opts: &super::RenderOptions, output: &Path) -> Result<()> {
    let Some(shard) = opts.shard else {
        return Ok(());
    };
    let is_exr = output
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    let refuse = |why: String| Err(Error::Usage(format!("--shard {shard}: {why}")));
    if !is_exr {
        return refuse(format!(
            "the output {} must be .exr (a partial image for iris merge)",
            output.display()
        ));
    }
    if opts.checkpoint.is_some() {
        return refuse("--checkpoint: a shard writes its partial image only at its end".into());
    }
    if opts.preview.background != crate::output::Background::Environment {
        return refuse("--background: give it to the merged image's render instead".into());
    }
    if opts.denoise == crate::denoise::DenoiseMode::On {
        return refuse("--denoise on: a partial image is not denoised".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shard_flags_parse_one_based() {
        assert_eq!(Shard::parse("3/8").unwrap(), Shard { index: 3, count: 8 });
        assert_eq!(
            Shard::parse(" 1 / 1 ").unwrap(),
            Shard { index: 1, count: 1 }
        );
        for bad in ["0/4", "5/4", "1/0", "a/2", "2", "1/2/3", "-1/2", "1/70000"] {
            let e = Shard::parse(bad).unwrap_err().to_string();
            assert!(e.contains("--shard"), "{bad}: {e}");
        }
    }

    #[test]
    fn fixed_ranges_tile_the_units() {
        for total in [1u64, 5, 24, 25, 1000] {
            for n in 1..=total.min(9) as u32 {
                let mut next = 0;
                for i in 1..=n {
                    let r = Shard { index: i, count: n }.range(total, "spp").unwrap();
                    assert_eq!(r.start, next);
                    assert!(r.end > r.start, "{i}/{n} of {total}");
                    next = r.end;
                }
                assert_eq!(next, total);
            }
        }
        assert_eq!(
            Shard { index: 3, count: 7 }.range(25, "spp").unwrap(),
            7..10
        );
        let e = Shard { index: 1, count: 3 }.range(2, "passes").unwrap_err();
        assert!(e.to_string().contains("at most 2 shards"), "{e}");
    }

    #[test]
    fn open_ranges_are_disjoint_segments_of_the_block() {
        let s = |i| {
            Shard { index: i, count: 3 }
                .range(OPEN_UNITS, "spp")
                .unwrap()
        };
        let seg = OPEN_UNITS / 3;
        assert_eq!((s(1), s(2), s(3)), (0..seg, seg..2 * seg, 2 * seg..3 * seg));
    }
}
