//! Reading Markdown for `tests/cli/docs/mod.rs`: fenced blocks and prose with their line numbers,
//! `\` continuations, inline code spans, link targets and GitHub's heading anchors.

use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};

/// A Markdown text split into fenced blocks (info string, numbered lines) and prose lines.
#[derive(Default)]
pub struct Markdown {
    pub blocks: Vec<(String, Vec<(usize, String)>)>,
    pub prose: Vec<(usize, String)>,
}

pub fn split_markdown(text: &str) -> Markdown {
    let mut md = Markdown::default();
    let mut open: Option<(String, Vec<(usize, String)>)> = None;
    for (i, line) in text.lines().enumerate() {
        let fence = line.trim_start().strip_prefix("```");
        match (fence, open.take()) {
            (Some(info), None) => open = Some((info.trim().to_string(), Vec::new())),
            (Some(_), Some(block)) => md.blocks.push(block),
            (None, Some(mut block)) => {
                block.1.push((i + 1, line.to_string()));
                open = Some(block);
            }
            (None, None) => md.prose.push((i + 1, line.to_string())),
        }
    }
    md
}

/// The command lines of a block: `\` continuations joined, a line starting with `[`
/// appended to the line before (a synopsis continued), comment-only lines dropped.
pub fn logical_lines(lines: &[(usize, String)]) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    let mut continued = false;
    for (n, raw) in lines {
        let line = raw.trim_end();
        let (body, cont) = match line.strip_suffix('\\') {
            Some(b) => (b, true),
            None => (line, false),
        };
        let body = body.trim_start();
        let comment_only = body.starts_with('#') && !continued;
        let joins = continued || body.starts_with('[');
        match out.last_mut() {
            _ if comment_only => {}
            Some(last) if joins => {
                last.1.push(' ');
                last.1.push_str(body);
            }
            _ => out.push((*n, body.strip_prefix("$ ").unwrap_or(body).to_string())),
        }
        continued = cont;
    }
    out
}

/// Inline code spans of the prose, with the line each starts on (spans may wrap lines
/// within a paragraph).
pub fn code_spans(prose: &[(usize, String)]) -> Vec<(usize, String)> {
    let mut spans = Vec::new();
    for paragraph in prose.split(|(_, l)| l.trim().is_empty()) {
        let mut text = String::new();
        let mut starts = Vec::new();
        for (n, l) in paragraph {
            starts.push((text.len(), *n));
            text.push_str(l);
            text.push('\n');
        }
        let mut at = 0;
        while let Some(open) = text[at..].find('`').map(|o| at + o) {
            let ticks = text[open..].len() - text[open..].trim_start_matches('`').len();
            let fence = "`".repeat(ticks);
            let Some(close) = text[open + ticks..].find(&fence).map(|c| open + ticks + c) else {
                break;
            };
            let line = starts
                .iter()
                .rev()
                .find(|(s, _)| *s <= open)
                .map_or(0, |s| s.1);
            let body = text[open + ticks..close].replace('\n', " ");
            spans.push((line, body.trim().to_string()));
            at = close + ticks;
        }
    }
    spans
}

/// GitHub's heading anchors: lower case, letters, digits, `-` and `_` kept, spaces to `-`,
/// everything else dropped; a repeated slug gets `-1`, `-2`, ….
pub fn heading_slugs(text: &str) -> Vec<String> {
    let mut seen: HashMap<String, usize> = HashMap::new();
    let md = split_markdown(text);
    let headings = md.prose.iter().filter_map(|(_, l)| {
        let t = l.trim_start_matches('#');
        (t.len() < l.len() && t.starts_with(' ')).then_some(t.trim())
    });
    headings
        .map(|h| {
            let slug: String = h
                .to_lowercase()
                .chars()
                .filter_map(|c| match c {
                    ' ' => Some('-'),
                    c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
                    _ => None,
                })
                .collect();
            let n = seen.entry(slug.clone()).or_insert(0);
            *n += 1;
            if *n == 1 {
                slug
            } else {
                format!("{slug}-{}", *n - 1)
            }
        })
        .collect()
}

/// `a/b/../c` → `a/c`, without touching the file system.
pub fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

pub fn link_targets(prose: &[(usize, String)]) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (n, line) in prose {
        for (at, _) in line.match_indices("](") {
            let rest = &line[at + 2..];
            let end = rest.find(')').unwrap_or(rest.len());
            out.push((
                *n,
                rest[..end]
                    .split_whitespace()
                    .next()
                    .unwrap_or_default()
                    .into(),
            ));
        }
    }
    out
}
