//! `iris gallery`: renders a fixed list of scenes ([`ENTRIES`]) into one directory
//! (`docs/gallery/` by default) as `<name>.png`, and writes a Markdown page
//! (`README.md` there) with one section per image: the image, the source file, the licence
//! of shared third-party files, the method chosen, the render plan, the render time and the
//! samples or passes taken.
//!
//! Each entry is rendered exactly as `iris render FILE --size WxH` would (with `--time T`
//! when the gallery is given one): the same app-level function
//! ([`crate::app::render_command`], called only from [`render_entry`]) and the CLI's
//! defaults for every other flag: the default budget ([`crate::app::budget`]: `--method
//! auto`, rendered until the estimated display error of the written picture, the
//! denoised PNG, is 0.01, or 120 s), one photon per pixel and pass, ACES tone map, automatic exposure, the
//! file's camera, lights and environment, else the drop-in preview's framing, studio
//! (jeweller for gems) and floor. So the plan, the `--method auto` choice and the stop
//! shown are what a user gets with no flags.
//!
//! Before/after pairs: an entry with a [`Entry::before`] caption whose `<name>_before.png`
//! is in the output directory (a committed image from an earlier Iris, never rewritten
//! here) is shown beside the new image.
//!
//! Paths: project entries are relative to the current directory, which must be the project
//! root (where `assets/` is); shared entries are relative to the shared asset folder
//! ([`shared_assets_dir`]: `IRIS_SHARED_ASSETS`, else `../shared/assets`). Their licence
//! and attribution are read from that folder's `MANIFEST.md` (the table row naming the
//! file). When the folder is absent the gallery says so on stderr and on the page, renders
//! the rest and succeeds, unless `IRIS_REQUIRE_SHARED=1`, which makes it an error (the
//! rule the tests follow in `tests/common`).
//!
//! Invariants: every image and the page are written atomically (temporary name + rename,
//! [`crate::output::atomic::write_file_atomic`]); a `--only` pattern that matches no entry
//! is an error before anything renders; the page lists the entries in [`ENTRIES`] order.
//! With `--only`, an existing page keeps its header and its other entries, the rendered
//! ones replacing theirs ([`splice`]).

use crate::app::budget::BudgetFlags;
use crate::app::{self, RenderOptions, RenderSummary};
use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Duration;

mod entries;
mod splice;
pub use entries::{Entry, Origin, ENTRIES};

/// What `iris gallery` was asked for.
#[derive(Debug, Clone)]
pub struct GalleryOptions {
    /// Output directory (created if missing).
    pub out: PathBuf,
    /// Image size, pixels.
    pub size: (u32, u32),
    /// Time limit of each entry's render (`--time`, the whole budget); `None`: the default
    /// budget of `iris render`.
    pub time: Option<Duration>,
    /// Keep the entries whose name contains one of these (case-insensitive); all if empty.
    pub only: Vec<String>,
    /// No progress output.
    pub quiet: bool,
    /// The command line, for the page header.
    pub command: String,
}

/// One rendered entry.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// The entry.
    pub entry: Entry,
    /// The scene file as opened.
    pub source: PathBuf,
    /// What the render did (image path, method, plan, stats).
    pub summary: RenderSummary,
}

/// What `iris gallery` did.
#[derive(Debug, Clone)]
pub struct GallerySummary {
    /// Rendered entries, in [`ENTRIES`] order.
    pub rendered: Vec<Rendered>,
    /// Why the shared entries were left out, if they were.
    pub shared_missing: Option<String>,
    /// The Markdown page.
    pub page: PathBuf,
}

/// The shared third-party asset folder: `IRIS_SHARED_ASSETS`, else `../shared/assets`
/// (relative to the current directory). The folder counts as present when it holds its
/// index, `MANIFEST.md` (an empty folder is absent: CI runs the suite once with
/// `IRIS_SHARED_ASSETS` pointing to one, to prove the skips). `Ok(None)` when absent,
/// unless `IRIS_REQUIRE_SHARED=1`, which makes that an [`Error::Usage`].
pub fn shared_assets_dir() -> Result<Option<PathBuf>> {
    shared_assets_dir_in(Path::new(""))
}

/// Where [`shared_assets_dir_in`] looks: `IRIS_SHARED_ASSETS`, else
/// `root/../shared/assets`.
pub fn shared_assets_candidate(root: &Path) -> PathBuf {
    std::env::var_os("IRIS_SHARED_ASSETS")
        .map_or_else(|| root.join("../shared/assets"), PathBuf::from)
}

/// [`shared_assets_dir`] for a project at `root` (the tests and benches pass their
/// manifest directory): `IRIS_SHARED_ASSETS`, else `root/../shared/assets`.
pub fn shared_assets_dir_in(root: &Path) -> Result<Option<PathBuf>> {
    let dir = shared_assets_candidate(root);
    if dir.join("MANIFEST.md").is_file() {
        return Ok(Some(dir));
    }
    if std::env::var("IRIS_REQUIRE_SHARED").is_ok_and(|v| v == "1") {
        return Err(Error::Usage(format!(
            "IRIS_REQUIRE_SHARED=1 but the shared test assets are missing at {}",
            dir.display()
        )));
    }
    Ok(None)
}

/// The entries `--only` keeps: those whose name contains a pattern (case-insensitive).
/// A pattern that matches nothing is an [`Error::Usage`] listing the names.
pub fn select(only: &[String]) -> Result<Vec<Entry>> {
    let hit = |e: &Entry, p: &str| e.name.contains(&p.to_ascii_lowercase());
    if let Some(p) = only.iter().find(|p| !ENTRIES.iter().any(|e| hit(e, p))) {
        let names: Vec<&str> = ENTRIES.iter().map(|e| e.name).collect();
        return Err(Error::Usage(format!(
            "--only {p:?} matches no gallery entry (entries: {})",
            names.join(", ")
        )));
    }
    Ok(ENTRIES
        .iter()
        .filter(|e| only.is_empty() || only.iter().any(|p| hit(e, p)))
        .copied()
        .collect())
}

/// Renders `scene` to `output` as `iris render SCENE --size WxH [--time T] -o OUTPUT`
/// would (every other flag at its CLI default, so the default budget and the drop-in
/// preview's studio, floor and framing apply). The one call of the app-level render in
/// this module.
fn render_entry(scene: &Path, output: &Path, opts: &GalleryOptions) -> Result<RenderSummary> {
    let budget = BudgetFlags {
        time: opts.time,
        ..BudgetFlags::default()
    }
    .resolve();
    let render = RenderOptions {
        size: Some(opts.size),
        quiet: opts.quiet,
        ..RenderOptions::new(scene, Some(output))
    }
    .with_budget(&budget);
    app::render_command(&render)
}

/// `iris gallery`: renders the selected entries into `opts.out` and writes the page.
pub fn run(opts: &GalleryOptions) -> Result<GallerySummary> {
    app::check_size(opts.size.0, opts.size.1)?;
    let entries = select(&opts.only)?;
    let shared = shared_assets_dir()?;
    let shared_missing = match (&shared, entries.iter().any(|e| e.origin == Origin::Shared)) {
        (None, true) => {
            let msg = "the shared assets folder was not found (set IRIS_SHARED_ASSETS; \
                       IRIS_REQUIRE_SHARED=1 makes this an error): its entries are left out"
                .to_string();
            eprintln!("iris gallery: {msg}");
            Some(msg)
        }
        _ => None,
    };
    crate::fileio::output::check_dir(&opts.out)?;
    std::fs::create_dir_all(&opts.out).map_err(|e| Error::Output {
        path: opts.out.clone(),
        reason: format!("cannot create directory: {e}"),
    })?;
    let mut rendered = Vec::new();
    let count = entries.len();
    // A signal stops the entry in flight, and the page of what is done is written.
    let _honour = crate::interrupt::Honour::begin();
    for (i, entry) in entries.into_iter().enumerate() {
        let source = match (entry.origin, &shared) {
            (Origin::Project, _) => PathBuf::from(entry.path),
            (Origin::Shared, Some(dir)) => dir.join(entry.path),
            (Origin::Shared, None) => continue,
        };
        if !opts.quiet {
            eprintln!("iris gallery [{}/{count}] {}", i + 1, source.display());
        }
        let output = opts.out.join(format!("{}.png", entry.name));
        let summary = render_entry(&source, &output, opts)?;
        rendered.push(Rendered {
            entry,
            source,
            summary,
        });
        // Ctrl-C: the interrupted image is written; stop and write the page of what is done.
        if crate::render::guard::stop_requested() {
            break;
        }
    }
    let page = opts.out.join("README.md");
    let mut text = page_text(
        opts,
        &rendered,
        shared.as_deref(),
        shared_missing.as_deref(),
    );
    // `--only` into a gallery that has a page: put the new sections into it.
    if let (false, Some(old)) = (opts.only.is_empty(), read_text(&page)) {
        let names: Vec<&str> = ENTRIES.iter().map(|e| e.name).collect();
        text = splice::splice(&old, &text, &names);
    }
    crate::output::atomic::write_file_atomic(&page, text.as_bytes())?;
    Ok(GallerySummary {
        rendered,
        shared_missing,
        page,
    })
}

/// The text of the page or manifest at `path` (a regular file within
/// [`crate::fileio::input::TEXT_BYTES`], UTF-8 with invalid bytes replaced), if there is one.
fn read_text(path: &Path) -> Option<String> {
    let bytes = crate::fileio::input::read(path, crate::fileio::Input::Text).ok()?;
    Some(String::from_utf8_lossy(&bytes).into_owned())
}

/// The licence / attribution cell of `MANIFEST.md`'s table row for `path` (relative to the
/// shared folder's parent, i.e. `assets/<path>`), if the manifest has one.
pub fn manifest_licence(manifest: &str, path: &str) -> Option<String> {
    let key = format!("| `assets/{path}`");
    let row = manifest.lines().find(|l| l.starts_with(&key))?;
    // Columns: path | size | source | licence / attribution | tris | KHR values.
    row.split('|')
        .nth(4)
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
}

/// The Markdown page.
fn page_text(
    opts: &GalleryOptions,
    rendered: &[Rendered],
    shared: Option<&Path>,
    shared_missing: Option<&str>,
) -> String {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let manifest = shared
        .and_then(|d| read_text(&d.join("MANIFEST.md")))
        .unwrap_or_default();
    let mut s = String::from("# Iris gallery\n\n");
    let _ = writeln!(
        s,
        "Produced by `{}` (Iris {}) on a machine with {cores} cores ({} {}). Each image is \
         `iris render FILE --size {}x{}{}` with every other flag at its default: {} (a file \
         without camera or light gets the drop-in preview's framing, studio and floor; the \
         PNG is denoised). The render time is the wall-clock time of the render loop \
         (loading and the acceleration build are listed apart); the line under it says \
         what ended the render.\n",
        opts.command,
        env!("CARGO_PKG_VERSION"),
        std::env::consts::OS,
        std::env::consts::ARCH,
        opts.size.0,
        opts.size.1,
        opts.time
            .map_or(String::new(), |t| format!(" --time {}", t.as_secs_f64())),
        match opts.time {
            Some(_) => "the time limit ends each render",
            None =>
                "`--method auto`, rendered until the estimated display error of the \
                     written (denoised) picture is 0.01 or for 120 s",
        }
    );
    if let Some(msg) = shared_missing {
        let _ = writeln!(s, "**Note:** {msg}.\n");
    }
    for r in rendered {
        let sum = &r.summary;
        let file = sum.output.file_name().map_or_else(
            || format!("{}.png", r.entry.name),
            |f| f.to_string_lossy().into_owned(),
        );
        let _ = writeln!(s, "## {}\n", r.entry.name);
        let before = format!("{}_before.png", r.entry.name);
        match r.entry.before {
            Some(caption) if opts.out.join(&before).is_file() => {
                let _ = writeln!(s, "| before | now |\n|---|---|");
                let _ = writeln!(
                    s,
                    "| ![{0} before]({before}) | ![{0}]({file}) |\n| {caption} | these \
                     defaults (below) |\n",
                    r.entry.name
                );
            }
            _ => {
                let _ = writeln!(s, "![{}]({file})\n", r.entry.name);
            }
        }
        let _ = writeln!(s, "{}\n", r.entry.about);
        match r.entry.origin {
            Origin::Project => {
                let _ = writeln!(
                    s,
                    "- source: `{}` (generated by Iris, CC0 1.0: `assets/LICENSE`)",
                    r.entry.path
                );
            }
            Origin::Shared => {
                let _ = writeln!(
                    s,
                    "- source: `assets/{}` in the shared third-party assets",
                    r.entry.path
                );
                let licence = manifest_licence(&manifest, r.entry.path)
                    .unwrap_or_else(|| "see the shared assets' MANIFEST.md".into());
                let _ = writeln!(s, "- licence / attribution: {licence}");
            }
        }
        let _ = writeln!(s, "- method: {}", sum.method.name());
        let _ = writeln!(
            s,
            "- render time: {:.2} s (load {:.2} s, build {:.2} s, {})",
            sum.stats.time.as_secs_f64(),
            sum.load_time.as_secs_f64(),
            sum.build_time.as_secs_f64(),
            sum.backend
        );
        let _ = writeln!(
            s,
            "- work: {} at {}x{}, {} triangles",
            sum.work_done(),
            sum.image.width,
            sum.image.height,
            sum.triangles
        );
        let _ = writeln!(s, "- {}", sum.end_text());
        let _ = writeln!(s, "\n```text\n{}```\n", sum.plan.text());
        if !sum.notes.is_empty() {
            let _ = writeln!(s, "Notes from the render:\n");
            for n in &sum.notes {
                let _ = writeln!(s, "- {}", n.replace('\n', " "));
            }
            s.push('\n');
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entry_names_are_unique_and_file_safe() {
        for (i, e) in ENTRIES.iter().enumerate() {
            assert!(e
                .name
                .bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_'));
            assert!(ENTRIES[..i].iter().all(|o| o.name != e.name), "{}", e.name);
        }
    }

    #[test]
    fn select_keeps_matches_and_rejects_unknown_patterns() {
        // Case-insensitive substring: the three diamonds, in page order.
        let got = select(&["DIAMOND".into()]).expect("matches");
        let names: Vec<&str> = got.iter().map(|e| e.name).collect();
        assert_eq!(
            names,
            [
                "round_diamond",
                "round_diamond_bare",
                "moissanite_and_diamond"
            ]
        );
        assert_eq!(select(&[]).expect("all").len(), ENTRIES.len());
        let err = select(&["prism".into(), "nothing_like_this".into()]).expect_err("unknown");
        assert!(err.to_string().contains("nothing_like_this"), "{err}");
    }

    #[test]
    fn manifest_licence_reads_the_fourth_column() {
        let m = "| Path | Size | Source | License | Tris |\n\
                 | `assets/khronos/X/X.glb` | 1 | repo | CC0-1.0 (A. Author) | 2 |\n";
        assert_eq!(
            manifest_licence(m, "khronos/X/X.glb").as_deref(),
            Some("CC0-1.0 (A. Author)")
        );
        assert_eq!(manifest_licence(m, "khronos/Y/Y.glb"), None);
    }
}
