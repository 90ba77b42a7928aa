//! Line scanner for OBJ text, run before tobj.
//!
//! tobj reports errors without line numbers, accepts `nan`/`inf` coordinates, resolves
//! relative indices with unchecked integer casts and treats `l` polylines as polygons.
//! This scanner reads the file once, line by line (1-based, `\n` or `\r\n` endings, the
//! same numbering as tobj's `BufRead::lines`), and either reports the **first** offending
//! line or produces a *canonical* copy of the text that tobj cannot misread:
//!
//! - every line keeps its position (dropped statements become empty lines), so tobj's
//!   vertex counts and our line numbers agree;
//! - `v x y z [w]` is kept (vertex colours `v x y z r g b` are dropped: Iris ignores them
//!   and tobj fails when only some vertices have them); `vt u [v [w]]` becomes `vt u v`;
//! - face corners are rewritten as absolute, 1-based, range-checked `v/vt/vn` indices;
//! - faces with fewer than 3 corners, `l` polylines and free-form statements are dropped
//!   (listed in one warning); `#` starts a comment anywhere on a line.
//!
//! Errors: unparsable numbers → `Parse`, non-finite positions → `NonFinite`, indices out of
//! range (0, past the vertices defined so far, or relative indices before the first
//! vertex) → `IndexOutOfRange`, more than [`MAX_ELEMENTS`] vertices or triangles →
//! `TooLarge`. Each names `line N`. Forward references to vertices defined later in the
//! file are rejected: every exporter writes vertices before the faces that use them.

use crate::error::{LoadError, LoadErrorKind};
use crate::scene::validate::MAX_ELEMENTS;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt::Write as _;
use std::path::Path;

/// What a model name was declared with (`o` or `g`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum NameKind {
    /// `o name`
    Object,
    /// `g name`
    Group,
}

impl NameKind {
    /// The word used in element names (`object "x"`, `group "x"`).
    pub(super) fn word(self) -> &'static str {
        match self {
            NameKind::Object => "object",
            NameKind::Group => "group",
        }
    }
}

/// The scanner's result: text tobj can parse safely, plus what the scanner learnt.
#[derive(Debug, Default)]
pub(super) struct Scan {
    /// Canonical OBJ text, same line count as the input.
    pub text: String,
    /// Model name → how it was last declared.
    pub names: HashMap<String, NameKind>,
    /// Every material name used by `usemtl`.
    pub used_materials: HashSet<String>,
    /// Triangles after fan triangulation.
    pub triangles: usize,
    /// Statements dropped: keyword → (count, first line).
    pub ignored: BTreeMap<String, (usize, usize)>,
}

/// Running element counts while scanning.
#[derive(Default)]
struct Counts {
    v: usize,
    vt: usize,
    vn: usize,
}

/// Scans `src` (the OBJ at `path`); see the module docs.
pub(super) fn scan(path: &Path, src: &str) -> Result<Scan, LoadError> {
    let mut out = Scan {
        text: String::with_capacity(src.len()),
        ..Scan::default()
    };
    let mut counts = Counts::default();
    for (i, raw) in src.lines().enumerate() {
        let line_no = i + 1;
        let content = raw.split('#').next().unwrap_or("");
        scan_line(path, line_no, content, &mut counts, &mut out)?;
        out.text.push('\n');
    }
    Ok(out)
}

fn err(path: &Path, line: usize, kind: LoadErrorKind, detail: String) -> LoadError {
    LoadError::new(path, format!("line {line}"), kind, detail)
}

/// Scans one line (comment already removed) and appends its canonical form (no newline).
fn scan_line(
    path: &Path,
    line: usize,
    content: &str,
    counts: &mut Counts,
    out: &mut Scan,
) -> Result<(), LoadError> {
    let mut words = content.split_whitespace();
    let Some(keyword) = words.next() else {
        return Ok(());
    };
    let rest: Vec<&str> = words.collect();
    match keyword {
        "v" => {
            vertex(path, line, &rest, &mut out.text)?;
            counts.v += 1;
            if counts.v > MAX_ELEMENTS {
                return Err(too_large(path, line, "vertices"));
            }
        }
        "vt" => {
            texcoord(path, line, &rest, &mut out.text)?;
            counts.vt += 1;
        }
        "vn" => {
            let [x, y, z] = numbers::<3>(path, line, "vn", &rest, "x y z")?;
            let _ = write!(out.text, "vn {x} {y} {z}");
            counts.vn += 1;
        }
        "f" if rest.len() >= 3 => {
            face(path, line, &rest, counts, &mut out.text)?;
            out.triangles += rest.len() - 2;
            if out.triangles > MAX_ELEMENTS {
                return Err(too_large(path, line, "triangles"));
            }
        }
        "f" if rest.is_empty() => {
            return Err(err(
                path,
                line,
                LoadErrorKind::Parse,
                "face without vertices".into(),
            ));
        }
        "o" | "g" => {
            let name = content.trim_start().get(1..).unwrap_or("").trim();
            let name = if name.is_empty() {
                "unnamed_object"
            } else {
                name
            };
            let kind = if keyword == "o" {
                NameKind::Object
            } else {
                NameKind::Group
            };
            out.names.insert(name.to_string(), kind);
            let _ = write!(out.text, "{keyword} {name}");
        }
        "usemtl" | "mtllib" => {
            let arg = content
                .trim_start()
                .strip_prefix(keyword)
                .unwrap_or("")
                .trim();
            if arg.is_empty() {
                return Err(err(
                    path,
                    line,
                    LoadErrorKind::Parse,
                    format!("`{keyword}` without a name"),
                ));
            }
            if keyword == "usemtl" {
                out.used_materials.insert(arg.to_string());
            }
            let _ = write!(out.text, "{keyword} {arg}");
        }
        // Smoothing groups: Iris uses the file's normals (or geometric ones) as given.
        "s" => {}
        other => {
            // `f` with 1–2 corners, `l`, `p`, free-form geometry, unknown statements.
            let key = if other == "f" {
                "f (fewer than 3 vertices)"
            } else {
                other
            };
            let mut key = truncate(key);
            if out.ignored.len() >= 16 && !out.ignored.contains_key(&key) {
                key = "(other statements)".into();
            }
            let entry = out.ignored.entry(key).or_insert((0, line));
            entry.0 += 1;
        }
    }
    Ok(())
}

/// Keeps warning keys short even for binary junk.
fn truncate(s: &str) -> String {
    s.chars().take(24).collect()
}

fn too_large(path: &Path, line: usize, what: &str) -> LoadError {
    err(
        path,
        line,
        LoadErrorKind::TooLarge,
        format!("more than {MAX_ELEMENTS} {what}"),
    )
}

fn parse_f32(path: &Path, line: usize, keyword: &str, word: &str) -> Result<f32, LoadError> {
    word.parse::<f32>().map_err(|_| {
        err(
            path,
            line,
            LoadErrorKind::Parse,
            format!("`{keyword}`: `{word}` is not a number"),
        )
    })
}

/// Parses exactly `N` numbers.
fn numbers<const N: usize>(
    path: &Path,
    line: usize,
    keyword: &str,
    words: &[&str],
    expected: &str,
) -> Result<[f32; N], LoadError> {
    if words.len() != N {
        return Err(err(
            path,
            line,
            LoadErrorKind::Parse,
            format!(
                "`{keyword}` expects {expected}, found {} values",
                words.len()
            ),
        ));
    }
    let mut values = [0.0; N];
    for (value, word) in values.iter_mut().zip(words) {
        *value = parse_f32(path, line, keyword, word)?;
    }
    Ok(values)
}

/// `v x y z`, `v x y z w` or `v x y z r g b`.
fn vertex(path: &Path, line: usize, words: &[&str], text: &mut String) -> Result<(), LoadError> {
    let (xyz, tail) = match words.len() {
        3 | 4 | 6 => words.split_at(3),
        n => {
            return Err(err(
                path,
                line,
                LoadErrorKind::Parse,
                format!("`v` expects x y z [w] or x y z r g b, found {n} values"),
            ))
        }
    };
    let [x, y, z] = numbers::<3>(path, line, "v", xyz, "x y z")?;
    let mut w = 1.0;
    match tail {
        [w_word] => {
            w = parse_f32(path, line, "v", w_word)?;
            if w == 0.0 {
                return Err(err(
                    path,
                    line,
                    LoadErrorKind::Parse,
                    "`v`: weight w is 0".into(),
                ));
            }
        }
        [_, _, _] => {
            numbers::<3>(path, line, "v", tail, "r g b")?;
        }
        _ => {}
    }
    let p = [x / w, y / w, z / w];
    if p.iter().any(|c| !c.is_finite()) {
        return Err(err(
            path,
            line,
            LoadErrorKind::NonFinite,
            format!("vertex position ({x}, {y}, {z}) / w={w} is not finite"),
        ));
    }
    let _ = write!(text, "v {} {} {}", p[0], p[1], p[2]);
    Ok(())
}

/// `vt u [v [w]]` → `vt u v` (v defaults to 0, w is ignored).
fn texcoord(path: &Path, line: usize, words: &[&str], text: &mut String) -> Result<(), LoadError> {
    if words.is_empty() || words.len() > 3 {
        return Err(err(
            path,
            line,
            LoadErrorKind::Parse,
            format!("`vt` expects u [v [w]], found {} values", words.len()),
        ));
    }
    let mut uv = [0.0f32; 2];
    for (k, word) in words.iter().enumerate() {
        let value = parse_f32(path, line, "vt", word)?;
        if let Some(slot) = uv.get_mut(k) {
            *slot = value;
        }
    }
    let _ = write!(text, "vt {} {}", uv[0], uv[1]);
    Ok(())
}

/// Rewrites `f a/b/c ...` with absolute 1-based indices, checking every one.
fn face(
    path: &Path,
    line: usize,
    corners: &[&str],
    counts: &Counts,
    text: &mut String,
) -> Result<(), LoadError> {
    text.push('f');
    for corner in corners {
        let parts: Vec<&str> = corner.split('/').collect();
        if parts.len() > 3 || parts.first().is_none_or(|p| p.is_empty()) {
            return Err(err(
                path,
                line,
                LoadErrorKind::Parse,
                format!("face corner `{corner}` is not v, v/vt, v//vn or v/vt/vn"),
            ));
        }
        text.push(' ');
        let limits = [
            (counts.v, "vertex"),
            (counts.vt, "texture coordinate"),
            (counts.vn, "normal"),
        ];
        for (k, (part, (count, what))) in parts.iter().zip(limits).enumerate() {
            if k > 0 {
                text.push('/');
            }
            if part.is_empty() {
                continue;
            }
            let index = resolve(path, line, part, count, what)?;
            let _ = write!(text, "{}", index + 1);
        }
    }
    Ok(())
}

/// Resolves one OBJ index (1-based, or negative = relative) to a 0-based index `< count`.
fn resolve(
    path: &Path,
    line: usize,
    word: &str,
    count: usize,
    what: &str,
) -> Result<usize, LoadError> {
    let value: i64 = word.parse().map_err(|_| {
        err(
            path,
            line,
            LoadErrorKind::Parse,
            format!("face {what} index `{word}` is not an integer"),
        )
    })?;
    let resolved = if value > 0 {
        usize::try_from(value - 1).ok()
    } else if value < 0 {
        usize::try_from(value.unsigned_abs())
            .ok()
            .and_then(|back| count.checked_sub(back))
    } else {
        None
    };
    match resolved {
        Some(index) if index < count => Ok(index),
        _ => {
            Err(err(
                path,
                line,
                LoadErrorKind::IndexOutOfRange,
                if value == 0 {
                    format!("face {what} index 0 is invalid (OBJ indices start at 1)")
                } else {
                    format!("face {what} index {value} is out of range: {count} defined before this line")
                },
            ))
        }
    }
}

#[cfg(test)]
mod tests;
