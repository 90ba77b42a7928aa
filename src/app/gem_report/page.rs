//! The gem report's pages: one document ([`Block`]s: headings, paragraphs, tables, rows of
//! pictures) written as Markdown (`report.md`) and as a self-contained HTML page
//! (`report.html`, pictures by relative path), so the two never disagree. Text may hold
//! `code` spans in backticks; HTML escapes everything else. Percentages have one decimal.

use super::figures::{self, Returns};
use super::figures::{FIRE_SOURCE_DEG, FLASH_LEVEL};
use super::{Figures, GemReport, GemReportOptions};
use crate::spectrum::ior::{LAMBDA_C, LAMBDA_D, LAMBDA_F};
use crate::studio::instrument::{spot_directions, OBSCURED_DEG, SPOT_ELEVATIONS, SPOT_RADIUS_DEG};
use std::fmt::Write as _;

/// A part of the page.
enum Block {
    Heading(String),
    Para(String),
    Table(Vec<&'static str>, Vec<Vec<String>>),
    /// Pictures side by side: (file, caption).
    Pictures(Vec<(String, String)>),
}

/// The sources the page cites, in citation order.
const SOURCES: [&str; 7] = [
    "[1] AGS Laboratories, ASET (Angular Spectrum Evaluation Tool): the stone seen \
     through a hemisphere coloured red for light from 45°–75° above the girdle plane, \
     green for 0°–45°, blue for 75°–90° (the observer's obscuration), black or white \
     where it leaks.",
    "[2] J. Sasian, J. Quick, J. Sheffield, J. Caudill, P. Yantzer, \"Evaluation of \
     brilliance, fire, and scintillation in round brilliant gemstones\", Optical \
     Engineering 46(9), 093604 (2007), doi:10.1117/1.2769018.",
    "[3] G. Holloway, the Ideal-Scope (after K. Okuda's FireScope, 1970s): a red \
     reflector with a black viewing lens; light return red, leakage white, the \
     observer's obscuration black.",
    "[4] T. S. Hemphill et al., \"Modeling the appearance of the round brilliant cut \
     diamond: an analysis of brilliance\", Gems & Gemology 34(3), 158–183 (1998).",
    "[5] I. M. Reinitz et al., \"Modeling the appearance of the round brilliant cut \
     diamond: an analysis of fire, and more about brilliance\", Gems & Gemology 37(3) \
     (2001).",
    "[6] T. M. Moses et al., \"A foundation for grading the overall cut quality of round \
     brilliant cut diamonds\", Gems & Gemology 40(3) (2004).",
    "[7] P. Moon, D. E. Spencer, \"Illumination from a non-uniform sky\", Illuminating \
     Engineering 37 (1942); the CIE standard overcast sky, CIE S 011/E:2003: luminance \
     (1 + 2 sin e)/3 of the zenith's at elevation e.",
];

/// A fraction as a percentage with one decimal.
fn pct(x: f64) -> String {
    format!("{:.1} %", 100.0 * x)
}

/// The returns' columns: light return, high, low, obscured, leakage, other.
fn returns_row(r: &Returns) -> Vec<String> {
    [
        r.light_return(),
        r.high,
        r.low,
        r.obscured,
        r.leakage,
        r.other,
    ]
    .iter()
    .map(|&x| pct(x))
    .collect()
}

/// The returns' column heads (after the row's own first column).
const RETURNS_HEAD: [&str; 6] = [
    "light return",
    "high (red)",
    "low (green)",
    "obscured (blue)",
    "leakage",
    "other",
];

/// The whole document.
fn document(
    opts: &GemReportOptions,
    report: &GemReport,
    f: &Figures,
    names: &[&str],
) -> Vec<Block> {
    let mut doc = vec![Block::Heading(format!(
        "Gem report: {}",
        opts.scene.display()
    ))];
    doc.push(Block::Para(about(opts, report)));
    doc.push(Block::Heading("Figures, face-up".into()));
    let r = &f.face_up;
    doc.push(Block::Table(
        vec!["figure", "value", "what it is"],
        vec![
            vec!["light return".into(), pct(r.light_return()), format!("light the viewer sees coming from 0°–{OBSCURED_DEG}° above the girdle plane (ASET red + green) [1][2]")],
            vec!["high-angle return".into(), pct(r.high), "from 45°–75° (ASET red, the brightest light)".into()],
            vec!["low-angle return".into(), pct(r.low), "from 0°–45° (ASET green)".into()],
            vec!["obscured".into(), pct(r.obscured), format!("from {OBSCURED_DEG}°–90°, where the viewer's head is (ASET blue, contrast) [1]")],
            vec!["leakage".into(), pct(r.leakage), "from below the girdle plane: light through the pavilion (Ideal-Scope white) [3]".into()],
            vec!["other".into(), pct(r.other), "absorbed, or lost at the depth limit; the five rows sum to 100 %".into()],
            vec!["brilliance".into(), pct(f.brilliance), format!("mean face luminance under the CIE overcast sky, head cone ({OBSCURED_DEG}°–90°) dark, relative to the zenith [4][7]")],
            vec!["fire".into(), pct(f.fire), format!("share of the face that shows a {FIRE_SOURCE_DEG}° light source in colour: where red ({LAMBDA_C:.0} nm) and blue ({LAMBDA_F:.0} nm) light come from directions {FIRE_SOURCE_DEG}° or more apart (linear below) [2][5]")],
            vec!["spectral spread (median)".into(), format!("{:.2}°", f.median_spread), "the median of that angle over the pixels whose light comes from above the girdle plane".into()],
            vec!["scintillation: flashes".into(), format!("{} ({} of the face lit)", f.flashes, pct(f.lit)), format!(
                    "bright flashes (at least {FLASH_LEVEL} of a spot's radiance) face-up under {} spots of {SPOT_RADIUS_DEG}° radius from {}° to {}° [2][6]",
                    spot_directions().len(),
                    SPOT_ELEVATIONS[0],
                    SPOT_ELEVATIONS[SPOT_ELEVATIONS.len() - 1]
                )],
        ],
    ));
    doc.push(Block::Heading("ASET and Ideal-Scope".into()));
    doc.push(Block::Pictures(vec![
        (
            names[0].into(),
            "ASET: red 45°–75°, green 0°–45°, blue 75°–90° (observer), black: leakage".into(),
        ),
        (
            names[1].into(),
            "Ideal-Scope: red returned, white leakage, black observer".into(),
        ),
    ]));
    doc.push(Block::Heading("By zone (face-up)".into()));
    let mut head = vec!["zone (ρ / girdle radius)"];
    head.extend(RETURNS_HEAD);
    let rows = f
        .zones
        .iter()
        .zip(figures::ZONES)
        .map(|((name, r), (_, lo, hi))| {
            let range = if hi.is_finite() {
                format!("{lo}–{hi}")
            } else {
                format!("≥ {lo}")
            };
            let mut row = vec![format!("{name} ({range})")];
            row.extend(returns_row(r));
            row
        })
        .collect();
    doc.push(Block::Table(head, rows));
    doc.push(Block::Para(
        "A too-deep pavilion darkens the centre (the \"nailhead\": the light there comes \
         back from the viewer's own direction, obscured) and leaks near the girdle; a \
         too-shallow one leaks in a ring round the table (a \"fish-eye\")."
            .into(),
    ));
    tilt_section(&mut doc, f, names);
    doc.push(Block::Heading("Face-up, fire and directions".into()));
    let n = names.len();
    doc.push(Block::Pictures(vec![
        (names[n - 3].into(), "face-up under the overcast sky (brilliance)".into()),
        (names[n - 2].into(), format!("spots ({SPOT_RADIUS_DEG}° radius) at the C, d, F lines as red, green, blue (fire)")),
        (names[n - 1].into(), "direction map: colour (d + 1)/2 of the direction d the light comes from (d line); uniform patches are virtual facets".into()),
    ]));
    doc.push(Block::Heading("Definitions and what they simplify".into()));
    for p in definitions() {
        doc.push(Block::Para(p));
    }
    doc.push(Block::Heading("Sources".into()));
    for s in SOURCES {
        doc.push(Block::Para(s.into()));
    }
    doc
}

/// The tilt series: the table and the pictures.
fn tilt_section(doc: &mut Vec<Block>, f: &Figures, names: &[&str]) {
    doc.push(Block::Heading("Tilt series".into()));
    doc.push(Block::Para(
        "The stone tipped about the image's horizontal axis (its table towards the bottom \
         of the image), viewer and lighting fixed, as in the tilt views of [2]."
            .into(),
    ));
    let mut head = vec!["tilt"];
    head.extend(RETURNS_HEAD);
    let rows = f
        .tilts
        .iter()
        .map(|(t, r)| {
            let mut row = vec![format!("{t}°")];
            row.extend(returns_row(r));
            row
        })
        .collect();
    doc.push(Block::Table(head, rows));
    for (offset, instrument) in [(0, "ASET"), (1, "Ideal-Scope")] {
        let pictures = f
            .tilts
            .iter()
            .enumerate()
            .map(|(k, (t, _))| {
                (
                    names[2 * k + offset].to_string(),
                    format!("{instrument}, tilt {t}°"),
                )
            })
            .collect();
        doc.push(Block::Pictures(pictures));
    }
}

/// What was rendered, and how.
fn about(opts: &GemReportOptions, report: &GemReport) -> String {
    let s = &report.stone;
    let table = if s.table_found {
        "the largest up-facing facet"
    } else {
        "given or +Y"
    };
    let mut text = format!(
        "Stone: {} (table direction ({:.3}, {:.3}, {:.3}), {table}; girdle radius {:.4}, \
         height {:.4}, file units). Images {}×{} px, {} samples per pixel, Whitted ray \
         tracing of every Fresnel branch in RGB with the stone's index at the d line \
         ({LAMBDA_D} nm) unless a line is named; the viewer looks straight down the table \
         (orthographic).",
        s.meshes.join(", "),
        s.table.x,
        s.table.y,
        s.table.z,
        s.girdle_radius,
        s.height,
        opts.size,
        opts.size,
        opts.spp
    );
    if s.birefringent {
        text += " The stone is birefringent: every picture is the mean of two renders, one \
                 per polarization mode, each as an isotropic stone whose index is the middle \
                 of the range that mode's index runs over (n_o itself for the ordinary mode \
                 of a uniaxial stone).";
    }
    if !opts.command.is_empty() {
        let _ = write!(text, " Command: `{}`.", opts.command);
    }
    text
}

/// The definitions paragraph by paragraph (the module docs of [`figures`] hold the same).
fn definitions() -> Vec<String> {
    vec![
        "Light return, obscuration, leakage: fractions of the light the viewer sees in the \
         face (pixels weighted by how much of them the stone covers), by where it comes \
         from: ASET's bands [1][2] for light return (0°–75°, red + green) and obscuration \
         (75°–90°), Ideal-Scope's white [3] for leakage (below the girdle plane). \
         Simplified: a viewer at infinity straight above the table; the obscured cone is \
         fixed at 15° round the axis for both instruments."
            .into(),
        "Brilliance: after GIA's weighted light return [4]: the face's mean luminance under \
         a diffuse sky with the viewer's head dark. Simplified: one viewing direction and \
         the CIE overcast sky [7] instead of GIA's weighting of the returned rays."
            .into(),
        format!(
            "Fire: after GIA's dispersed coloured light return [5] and the angular spread \
             of the spectrum [2]: per pixel the angle between the directions red \
             ({LAMBDA_C:.0} nm, C line) and blue ({LAMBDA_F:.0} nm, F line) light come \
             from (light from below the girdle plane counts 0); a light source smaller than this \
             angle shows in colour. Fire is the share of the face where the angle reaches \
             {FIRE_SOURCE_DEG}° (counted in proportion below). Simplified: two wavelengths, \
             one mean direction per pixel, no threshold of visibility."
        ),
        "Scintillation: after GIA's sparkle [6] and the virtual facets of [2]: the number \
         of bright flashes face-up under a ceiling of small spots, each a virtual facet \
         showing a spot; the more and smaller, the more the stone sparkles as it, the \
         light or the viewer moves. Simplified: one still view under one standard \
         lighting, counted at this resolution (regions below 1/20 000 of the face, or 2 \
         pixels, are not counted)."
            .into(),
    ]
}

/// The document as Markdown.
pub fn markdown(
    opts: &GemReportOptions,
    report: &GemReport,
    f: &Figures,
    names: &[&str],
) -> String {
    let mut out = String::new();
    for block in document(opts, report, f, names) {
        match block {
            Block::Heading(h) if out.is_empty() => out += &format!("# {h}\n\n"),
            Block::Heading(h) => out += &format!("## {h}\n\n"),
            Block::Para(p) => out += &format!("{p}\n\n"),
            Block::Table(head, rows) => {
                out += &format!("| {} |\n", head.join(" | "));
                out += &format!("|{}\n", "---|".repeat(head.len()));
                for row in rows {
                    out += &format!("| {} |\n", row.join(" | "));
                }
                out += "\n";
            }
            Block::Pictures(p) => {
                out += &format!(
                    "| {} |\n",
                    p.iter()
                        .map(|(_, c)| c.as_str())
                        .collect::<Vec<_>>()
                        .join(" | ")
                );
                out += &format!("|{}\n", "---|".repeat(p.len()));
                let cells: Vec<String> = p
                    .iter()
                    .map(|(file, c)| format!("![{c}]({file})"))
                    .collect();
                out += &format!("| {} |\n\n", cells.join(" | "));
            }
        }
    }
    out
}

/// HTML text: escaped, with `code` spans.
fn inline(s: &str) -> String {
    let escaped = s
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;");
    let mut out = String::new();
    for (i, part) in escaped.split('`').enumerate() {
        if i % 2 == 1 {
            let _ = write!(out, "<code>{part}</code>");
        } else {
            out += part;
        }
    }
    out
}

/// The document as a self-contained HTML page.
pub fn html(opts: &GemReportOptions, report: &GemReport, f: &Figures, names: &[&str]) -> String {
    let mut out = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Gem report</title>\n\
         <style>body{font-family:sans-serif;max-width:70em;margin:auto;padding:1em}\
         table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:0.2em 0.5em}\
         figure{display:inline-block;margin:0.5em;max-width:22em}img{max-width:100%}</style>\n\
         </head><body>\n",
    );
    let mut first = true;
    for block in document(opts, report, f, names) {
        match block {
            Block::Heading(h) => {
                let tag = if first { "h1" } else { "h2" };
                let _ = writeln!(out, "<{tag}>{}</{tag}>", inline(&h));
            }
            Block::Para(p) => {
                let _ = writeln!(out, "<p>{}</p>", inline(&p));
            }
            Block::Table(head, rows) => {
                out += "<table><tr>";
                for h in head {
                    let _ = write!(out, "<th>{}</th>", inline(h));
                }
                out += "</tr>\n";
                for row in rows {
                    out += "<tr>";
                    for c in row {
                        let _ = write!(out, "<td>{}</td>", inline(&c));
                    }
                    out += "</tr>\n";
                }
                out += "</table>\n";
            }
            Block::Pictures(p) => {
                for (file, c) in p {
                    let _ = writeln!(
                        out,
                        "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>",
                        inline(&file),
                        inline(&c),
                        inline(&c)
                    );
                }
            }
        }
        first = false;
    }
    out += "</body></html>\n";
    out
}
