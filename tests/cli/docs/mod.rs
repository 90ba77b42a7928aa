//! The documentation stays true to the program: `README.md` and every `docs/**/*.md`.
//!
//! **Commands.** Every `iris` command shown in a fenced code block is parsed with the
//! binary's own clap definition ([`iris::cli::Cli`], the parser `src/main.rs` runs), so a
//! renamed or removed flag, a value out of its bounds or a missing argument fails here,
//! naming the file, the line and the command. The rule:
//!
//! - A command is a fenced-block line (blocks marked `json` are data and skipped) whose
//!   simple command starts with `iris`, a path ending in `/iris`, `scripts/run render` (=
//!   `iris render`) or `scripts/run iris`. Lines are read as a shell reads them: `\` joins
//!   the next line, `# …` is a comment, `;`, `&&`, `||`, `|` separate commands, leading
//!   `VAR=value` assignments and `do`/`then`/`else` are skipped, quotes group words, and a
//!   quoted word that is itself an `iris …` command (`sbatch --wrap '…'`) is checked too. A
//!   shell variable (`$i`, `${N}`) stands for `1`; a leading `$ ` prompt is dropped.
//! - A **usage synopsis** is a command line holding `[`, `...`, `…` or an `a|b`
//!   alternative (a line starting with `[` continues the synopsis above it). Its
//!   placeholders are not values, so it is checked per flag: the subcommand must exist and
//!   every `--long` and `-s` flag it names must be one of that subcommand's arguments.
//! - Every other command is parsed whole with `Cli::try_parse_from`: placeholders such as
//!   `SCENE` or `FILE.glb` parse as the paths they stand for; `--help` counts as parsed.
//! - Inline code in prose that starts with `iris ` (or `scripts/run render`, `scripts/run
//!   iris`, `…/iris `) is usually a fragment, so it is checked per flag, like a synopsis.
//!   A command word that is a placeholder (`iris COMMAND`, `scripts/run iris ARGS`, no
//!   lower-case letter) is not checked.
//!
//! **Documented.** Every visible flag of every command appears in `docs/command-line.md`
//! (its `--long` form, or its `-s` short form).
//!
//! **Links and paths.** Every relative link (`[text](path#anchor)`, images too) points at an
//! existing file, and an anchor into a Markdown file at one of its headings (GitHub's
//! slugs); inline code naming a repository path (`src/…`, `tests/…`, `scripts/…`, …,
//! globs and placeholders aside, and not on the generated `docs/gallery/` page, whose
//! sources may be shared assets) names one that exists, and so does every module in the
//! module map of `docs/architecture.md` (under `src/`), and every top-level module is in it.
//!
//! **Test binaries.** Every `--test NAME` (in those files and `FUZZING.md`) names a test
//! binary, `tests/NAME/main.rs`.

mod markdown;
mod shell;

use clap::{CommandFactory, Parser};
use iris::cli::Cli;
use markdown::{code_spans, heading_slugs, link_targets, logical_lines, normalise, split_markdown};
use shell::{iris_args, is_synopsis, shell_commands, strip_comment};
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `README.md` and `docs/**/*.md`, as paths relative to the repository.
fn documents() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .expect("docs/ readable")
            .map(|e| e.expect("entry").path())
            .collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "md") {
                out.push(p);
            }
        }
    }
    let mut files = vec![repo().join("README.md")];
    walk(&repo().join("docs"), &mut files);
    files
        .into_iter()
        .map(|p| {
            p.strip_prefix(repo())
                .expect("inside the repo")
                .to_path_buf()
        })
        .collect()
}

/// Per-flag check of a synopsis or fragment: the subcommand exists and has every flag named.
fn check_flags(args: &[String]) -> Result<(), String> {
    let top = Cli::command();
    let (cmd, rest) = match args.split_first() {
        Some((sub, _)) if !sub.contains(|c: char| c.is_lowercase() || c == '-') => return Ok(()),
        Some((sub, rest)) if !sub.starts_with('-') => (
            top.find_subcommand(sub)
                .ok_or_else(|| format!("`iris {sub}`: no such command"))?
                .clone(),
            rest,
        ),
        _ => (top, args),
    };
    let joined = rest.join(" ");
    for token in joined.split(|c: char| c.is_whitespace() || "[]|".contains(c)) {
        let token = token.trim_end_matches(['.', '…', ',', ')']);
        let known = if let Some(long) = token.strip_prefix("--") {
            let long = long.split('=').next().unwrap_or_default();
            if !long.starts_with(|c: char| c.is_ascii_alphabetic()) {
                continue;
            }
            long == "help" || cmd.get_arguments().any(|a| a.get_long() == Some(long))
        } else if let Some(short) = token.strip_prefix('-') {
            let mut s = short.chars();
            match (s.next(), s.next()) {
                (Some(c), None) if c.is_ascii_alphabetic() => {
                    c == 'h' || cmd.get_arguments().any(|a| a.get_short() == Some(c))
                }
                _ => continue,
            }
        } else {
            continue;
        };
        if !known {
            return Err(format!("`iris {}` has no flag {token}", cmd.get_name()));
        }
    }
    Ok(())
}

/// A whole command parsed by the binary's parser.
fn check_parse(args: &[String]) -> Result<(), String> {
    use clap::error::ErrorKind::*;
    let argv = std::iter::once("iris".to_string()).chain(args.iter().cloned());
    match Cli::try_parse_from(argv) {
        Ok(_) => Ok(()),
        Err(e) if matches!(e.kind(), DisplayHelp | DisplayVersion) => Ok(()),
        Err(e) => Err(e
            .render()
            .to_string()
            .lines()
            .take_while(|l| !l.starts_with("Usage:"))
            .filter(|l| !l.trim().is_empty())
            .collect::<Vec<_>>()
            .join(" / ")),
    }
}

/// Every check of one command line of a fenced block, recursing into quoted commands.
fn check_line(line: &str, checked: &mut usize) -> Vec<String> {
    let line = strip_comment(line);
    let words = |s: &str| s.split_whitespace().map(String::from).collect::<Vec<_>>();
    if is_synopsis(line) {
        let Some(args) = iris_args(&words(line)) else {
            return Vec::new();
        };
        *checked += 1;
        return check_flags(&args).err().into_iter().collect();
    }
    let mut errors = Vec::new();
    for command in shell_commands(line) {
        for inner in command.iter().filter_map(|w| w.quoted.as_deref()) {
            if iris_args(&words(inner)).is_some() {
                errors.extend(check_line(inner, checked));
            }
        }
        let words: Vec<String> = command.into_iter().map(|w| w.text).collect();
        if let Some(args) = iris_args(&words) {
            *checked += 1;
            errors.extend(check_parse(&args).err());
        }
    }
    errors
}

/// The checks of one document's commands; returns how many commands were checked.
fn command_errors(file: &str, text: &str, errors: &mut Vec<String>) -> usize {
    let md = split_markdown(text);
    let mut checked = 0;
    for (_, lines) in md.blocks.iter().filter(|(info, _)| info != "json") {
        for (n, line) in logical_lines(lines) {
            for e in check_line(&line, &mut checked) {
                errors.push(format!("{file}:{n}: {line}\n    {e}"));
            }
        }
    }
    for (n, span) in code_spans(&md.prose) {
        let words: Vec<String> = span.split_whitespace().map(String::from).collect();
        if let Some(args) = iris_args(&words).filter(|_| words.len() > 1) {
            checked += 1;
            if let Err(e) = check_flags(&args) {
                errors.push(format!("{file}:{n}: `{span}`\n    {e}"));
            }
        }
    }
    checked
}

#[test]
fn every_command_in_the_docs_parses() {
    let mut errors = Vec::new();
    let mut checked = 0;
    for doc in documents() {
        let text = std::fs::read_to_string(repo().join(&doc)).expect("readable");
        checked += command_errors(&doc.display().to_string(), &text, &mut errors);
    }
    assert!(
        checked > 100,
        "only {checked} commands found: is the extraction broken?"
    );
    assert!(
        errors.is_empty(),
        "{} of {checked} documented commands do not parse:\n{}",
        errors.len(),
        errors.join("\n")
    );
}

#[test]
fn every_flag_is_in_the_command_line_chapter() {
    let chapter = std::fs::read_to_string(repo().join("docs/command-line.md")).expect("chapter");
    let mut missing = Vec::new();
    for sub in Cli::command().get_subcommands() {
        for arg in sub.get_arguments().filter(|a| !a.is_hide_set()) {
            let long = arg.get_long().map(|l| format!("--{l}"));
            let short = arg.get_short().map(|s| format!("-{s} "));
            let shown = |f: &Option<String>| f.as_ref().is_some_and(|f| chapter.contains(f));
            if long.is_some() && !shown(&long) && !shown(&short) {
                missing.push(format!(
                    "iris {} {}",
                    sub.get_name(),
                    long.unwrap_or_default()
                ));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "flags not in docs/command-line.md: {}",
        missing.join(", ")
    );
}

#[test]
fn links_and_paths_in_the_docs_exist() {
    const ROOTS: [&str; 9] = [
        "src/", "tests/", "scripts/", "benches/", "assets/", "fuzz/", "docs/", "vendor/", ".ci/",
    ];
    let mut errors = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(repo().join(&doc)).expect("readable");
        let md = split_markdown(&text);
        let dir = doc.parent().unwrap_or(Path::new(""));
        let generated = doc.starts_with("docs/gallery");
        for (n, target) in link_targets(&md.prose) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let (path, anchor) = target.split_once('#').unwrap_or((&target, ""));
            let file = if path.is_empty() {
                doc.clone()
            } else {
                normalise(&dir.join(path))
            };
            let full = repo().join(&file);
            if !full.exists() {
                errors.push(format!(
                    "{}:{n}: link to {target}: {} does not exist",
                    doc.display(),
                    file.display()
                ));
            } else if !anchor.is_empty() && file.extension().is_some_and(|e| e == "md") {
                let slugs = heading_slugs(&std::fs::read_to_string(&full).expect("readable"));
                if !slugs.iter().any(|s| s == anchor) {
                    errors.push(format!(
                        "{}:{n}: link to {target}: no heading #{anchor} in {}",
                        doc.display(),
                        file.display()
                    ));
                }
            }
        }
        for (n, span) in code_spans(&md.prose) {
            let placeholder = span.contains(|c: char| c.is_whitespace() || "*<>…${}".contains(c))
                || span.contains("::");
            let path = ROOTS.iter().any(|r| span.starts_with(r)) && !placeholder;
            if path && !generated && !repo().join(&span).exists() {
                errors.push(format!("{}:{n}: `{span}` does not exist", doc.display()));
            }
        }
    }
    let architecture =
        std::fs::read_to_string(repo().join("docs/architecture.md")).expect("chapter");
    let map = architecture
        .split("## Module map")
        .nth(1)
        .expect("a Module map section");
    let map = map.split("\n## ").next().unwrap_or_default();
    let modules: Vec<&str> = map
        .lines()
        .filter(|l| l.starts_with('|'))
        .skip_while(|l| !l.starts_with("|---"))
        .skip(1)
        .filter_map(|l| l.split('`').nth(1))
        .collect();
    assert!(
        modules.len() > 20,
        "the module map lists {} modules",
        modules.len()
    );
    for m in &modules {
        if !repo().join("src").join(m).exists() {
            errors.push(format!(
                "docs/architecture.md module map: src/{m} does not exist"
            ));
        }
    }
    // And the other way: every top-level module of src/ has its line in the map.
    for entry in std::fs::read_dir(repo().join("src")).expect("src/") {
        let path = entry.expect("src entry").path();
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let listed = if path.is_dir() {
            format!("{name}/")
        } else if name.ends_with(".rs") && name != "lib.rs" {
            name.to_string()
        } else {
            continue;
        };
        if !modules.contains(&listed.as_str()) {
            errors.push(format!(
                "docs/architecture.md module map: src/{listed} is not listed"
            ));
        }
    }
    assert!(
        errors.is_empty(),
        "broken links or paths:\n{}",
        errors.join("\n")
    );
}

/// Every `cargo … --test NAME` in the docs (and FUZZING.md) names a test binary that exists:
/// `tests/NAME/main.rs`.
#[test]
fn every_test_binary_named_exists() {
    let mut docs = documents();
    docs.push(PathBuf::from("FUZZING.md"));
    let mut named = 0;
    let mut errors = Vec::new();
    for doc in docs {
        let text = std::fs::read_to_string(repo().join(&doc)).expect("readable");
        for (n, line) in text.lines().enumerate() {
            let words: Vec<&str> = line.split_whitespace().collect();
            for pair in words.windows(2).filter(|w| w[0] == "--test") {
                let name = pair[1].trim_end_matches(['`', ',', '.', ')']);
                named += 1;
                if !repo().join("tests").join(name).join("main.rs").is_file() {
                    errors.push(format!("{}:{}: --test {name}", doc.display(), n + 1));
                }
            }
        }
    }
    assert!(
        named >= 3,
        "only {named} `--test NAME` found: is the scan broken?"
    );
    assert!(
        errors.is_empty(),
        "no such test binary (tests/NAME/main.rs):\n{}",
        errors.join("\n")
    );
}

/// The checker itself: it finds what it must, and reports a misspelled flag.
#[test]
fn the_checker_finds_commands_and_reports_bad_flags() {
    let doc = "Text `iris render --sppp 4` and `iris info X`.\n\n```sh\n\
        for i in 1 2; do iris render s.glb --spp 8 --shard $i/2 -o p$i.exr; done  # shards\n\
        iris render s.glb \\\n    --size 64x48   # a comment\n\
        sbatch --wrap 'iris turntable g.glb --frames 4 -o out --frame $T'\n\
        iris render SCENE [--spp N] [--method auto|path]\n                  [--no-such-flag]\n\
        scripts/run render s.glb --methd path\n\
        CPUS=8 scripts/slurm/submit.sh render s.glb out 4   # not iris\n```\n\
        ```json\n{\"iris render\": 1}\n```\n";
    let mut errors = Vec::new();
    let checked = command_errors("doc.md", doc, &mut errors);
    assert_eq!(checked, 7, "{errors:?}");
    assert_eq!(errors.len(), 3, "{errors:#?}");
    assert!(
        errors[0].starts_with("doc.md:8: iris render SCENE")
            && errors[0].contains("--no-such-flag"),
        "{}",
        errors[0]
    );
    assert!(
        errors[1].starts_with("doc.md:10: scripts/run render") && errors[1].contains("--methd"),
        "{}",
        errors[1]
    );
    assert!(
        errors[2].starts_with("doc.md:1: `iris render --sppp 4`") && errors[2].contains("--sppp"),
        "{}",
        errors[2]
    );
    assert_eq!(
        heading_slugs("# A: `b` (c)\n## A: b (c)\n"),
        ["a-b-c", "a-b-c-1"]
    );
}
