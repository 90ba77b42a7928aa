//! `report.json`: the gem report's numbers for programs. Fractions are percentages (0 to
//! 100, rounded to 0.001), the median spread in degrees (0.0001), lengths in the file's units; no
//! times, so the same file and flags give the same bytes. Keys:
//! `file`, `stone` {`meshes`, `table`, `table_found`, `girdle_radius`, `height`,
//! `birefringent`},
//! `settings` {`size`, `spp`, `seed`, `tilts`}, `face_up` and each `zones[]` / `tilts[]`
//! entry {`light_return`, `high`, `low`, `obscured`, `leakage`, `other`} (zones add `zone`,
//! `from`, `to` as fractions of the girdle radius, `to` null when unbounded; tilts add
//! `tilt` in degrees), `brilliance`, `fire`, `median_spread_degrees`, `flashes` (a
//! count), `lit`, and `definitions` (one sentence each, with the sources' numbers of
//! `report.md`).

use super::figures::Returns;
use super::{Figures, GemReport, GemReportOptions};
use crate::error::{Error, Result};
use serde_json::{json, Value};

/// A fraction as a percentage rounded to 0.001.
fn pct(x: f64) -> f64 {
    (100_000.0 * x).round() / 1000.0
}

/// The returns' fields.
fn returns(r: &Returns) -> serde_json::Map<String, Value> {
    let mut m = serde_json::Map::new();
    for (k, v) in [
        ("light_return", r.light_return()),
        ("high", r.high),
        ("low", r.low),
        ("obscured", r.obscured),
        ("leakage", r.leakage),
        ("other", r.other),
    ] {
        m.insert(k.into(), json!(pct(v)));
    }
    m
}

/// The report as pretty-printed JSON (see the module docs).
pub fn json(opts: &GemReportOptions, report: &GemReport, f: &Figures) -> Result<String> {
    let s = &report.stone;
    let zones: Vec<Value> = f
        .zones
        .iter()
        .zip(super::figures::ZONES)
        .map(|((name, r), (_, lo, hi))| {
            let mut m = returns(r);
            m.insert("zone".into(), json!(name));
            m.insert("from".into(), json!(lo));
            m.insert(
                "to".into(),
                if hi.is_finite() {
                    json!(hi)
                } else {
                    Value::Null
                },
            );
            Value::Object(m)
        })
        .collect();
    let tilts: Vec<Value> = f
        .tilts
        .iter()
        .map(|(t, r)| {
            let mut m = returns(r);
            m.insert("tilt".into(), json!(t));
            Value::Object(m)
        })
        .collect();
    let doc = json!({
        "file": opts.scene.display().to_string(),
        "stone": {
            "meshes": s.meshes,
            "table": [s.table.x, s.table.y, s.table.z],
            "table_found": s.table_found,
            "girdle_radius": s.girdle_radius,
            "height": s.height,
            "birefringent": s.birefringent,
        },
        "settings": {
            "size": opts.size,
            "spp": opts.spp,
            "seed": opts.seed,
            "tilts": opts.tilts,
        },
        "face_up": Value::Object(returns(&f.face_up)),
        "zones": zones,
        "tilts": tilts,
        "brilliance": pct(f.brilliance),
        "fire": pct(f.fire),
        "median_spread_degrees": (f.median_spread * 10_000.0).round() / 10_000.0,
        "flashes": f.flashes,
        "lit": pct(f.lit),
        "definitions": {
            "light_return": "percent of the face's light from 0-75 degrees above the girdle plane (ASET red + green) [1][2]",
            "obscured": "percent from 75-90 degrees, the viewer's head (ASET blue) [1]",
            "leakage": "percent from below the girdle plane (Ideal-Scope white) [3]",
            "other": "percent absorbed or lost at the depth limit; the five sum to 100",
            "brilliance": "mean face luminance under the CIE overcast sky with the head cone dark, percent of the zenith's [4][7]",
            "fire": "percent of the face where C-line (656 nm) and F-line (486 nm) light come from directions at least 1 degree apart, in proportion below [2][5]",
            "median_spread_degrees": "median angle between those directions over the pixels whose light comes from above the girdle plane",
            "flashes": "bright flashes (at least 0.25 of a spot's radiance) face-up under the spot dome [2][6]",
            "lit": "percent of the face lit at least 0.25 of a spot's radiance under the spot dome",
        },
    });
    serde_json::to_string_pretty(&doc)
        .map(|t| t + "\n")
        .map_err(|e| Error::Output {
            path: opts.out_dir.join("report.json"),
            reason: e.to_string(),
        })
}
