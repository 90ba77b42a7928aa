//! The partial image of a shard (`iris render --shard I/N`, [`crate::app::shard`]): an
//! OpenEXR file any viewer opens, that also carries everything `iris merge` needs to add it
//! exactly to the other shards and to refuse a wrong merge.
//!
//! ## Layout (one part, ZIP-compressed, lossless)
//! - `R`, `G`, `B` (f32): the shard's own mean, linear RGB, as `iris render` writes an EXR.
//! - `iris.s{h}{c}{w}` (u32), h ∈ {0, 1} the half, c ∈ {R, G, B}, w ∈ {0, 1, 2, 3}: the
//!   half's fixed-point sum ([`crate::image::fixed`]) of channel c, an `i128` stored as
//!   its two's-complement bits in four 32-bit words, least significant first (24 channels).
//! - `iris.n0`, `iris.n1` (u32): the units (samples, or passes) in each half of the pixel.
//! - The text-vector attribute [`ATTRIBUTE`]: ordered `key=value` entries (the shard's
//!   identity, [`crate::app::shard::ShardHeader`]), the first being [`FORMAT`]. Values are
//!   printable ASCII (other characters escaped as `\u{…}`), so the bytes are the same on
//!   every machine. One attribute, in order: the `exr` crate writes several custom
//!   attributes in hash-map order, which would make equal shards differ in bytes.
//!
//! Pixels are row-major, top row first. A file without the attribute is not a partial
//! ([`read`] says so, naming it).

use super::atomic::write_file_atomic;
use super::exr_io::{encode_channels, open_checked, plane};
use crate::error::{Error, LoadError, LoadErrorKind, Result};
use crate::image::ExactImage;
use exr::prelude::*;
use std::path::Path;

/// The attribute holding the shard's header.
pub const ATTRIBUTE: &str = "irisPartial";

/// The first entry of the header: the format and its version.
pub const FORMAT: &str = "format=iris-partial-1";

/// A partial image read back: its header entries and its exact sums.
#[derive(Debug, Clone, PartialEq)]
pub struct Partial {
    /// `key=value` entries, in file order, the first being [`FORMAT`].
    pub entries: Vec<(String, String)>,
    /// The exact sums and unit counts.
    pub exact: ExactImage,
}

/// `s` with every character outside printable ASCII escaped (`\n`, `\u{e9}`, …).
pub fn ascii(s: &str) -> String {
    s.chars()
        .flat_map(|c| {
            let printable = c.is_ascii_graphic() || c == ' ';
            let esc: Vec<char> = if printable && c != '\\' {
                vec![c]
            } else {
                c.escape_default().collect()
            };
            esc
        })
        .collect()
}

/// The names of the sum channels of half `h`, channel `c` (0 = R), words 0..4.
fn sum_channel(h: usize, c: usize, w: usize) -> String {
    format!("iris.s{h}{}{w}", ["R", "G", "B"][c])
}

/// Encodes `exact` (mean in `R`, `G`, `B`) with the header `entries` (keys and values
/// ASCII; [`FORMAT`] is put first).
pub fn encode(entries: &[(String, String)], exact: &ExactImage) -> Result<Vec<u8>> {
    let (w, h) = (exact.width as usize, exact.height as usize);
    let n = w * h;
    if n == 0 || exact.sums.len() != n || exact.units.len() != n {
        return Err(Error::Usage(format!(
            "partial image of {w}×{h} pixels holds {} sums and {} counts",
            exact.sums.len(),
            exact.units.len()
        )));
    }
    let mean = exact.mean();
    let mut list = Vec::with_capacity(29);
    for (k, c) in ["R", "G", "B"].into_iter().enumerate() {
        list.push(AnyChannel::new(c, FlatSamples::F32(plane(&mean, k))));
    }
    for half in 0..2 {
        for c in 0..3 {
            for word in 0..4 {
                let plane = exact
                    .sums
                    .iter()
                    .map(|s| ((s[half].0[c] as u128) >> (32 * word)) as u32)
                    .collect();
                let name = sum_channel(half, c, word);
                list.push(AnyChannel::new(name.as_str(), FlatSamples::U32(plane)));
            }
        }
        let units = exact
            .units
            .iter()
            .map(|u| u32::try_from(u[half]).unwrap_or(u32::MAX))
            .collect();
        let name = format!("iris.n{half}");
        list.push(AnyChannel::new(name.as_str(), FlatSamples::U32(units)));
    }
    let mut text = vec![text(FORMAT)?];
    for (k, v) in entries {
        text.push(self::text(&format!("{}={}", ascii(k), ascii(v)))?);
    }
    let mut attributes = LayerAttributes::named("rgb");
    attributes
        .other
        .insert(self::text(ATTRIBUTE)?, AttributeValue::TextVector(text));
    encode_channels((w, h), attributes, list)
        .map_err(|e| Error::Usage(format!("cannot encode the partial image: {e}")))
}

/// An EXR text (ASCII by construction).
fn text(s: &str) -> Result<Text> {
    Text::new_or_none(s).ok_or_else(|| Error::Usage(format!("not ASCII: {s:?}")))
}

/// Writes the partial image to `path` atomically ([`super::atomic`]): a reader sees no
/// file, or the whole of it.
pub fn write(path: &Path, entries: &[(String, String)], exact: &ExactImage) -> Result<()> {
    let bytes = encode(entries, exact).map_err(|e| Error::Output {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })?;
    write_file_atomic(path, &bytes)
}

/// Reads a partial image; errors name the file and what is wrong (not an EXR, not a
/// partial — no [`ATTRIBUTE`] —, another format version, a missing channel).
pub fn read(path: &Path) -> std::result::Result<Partial, LoadError> {
    let file = open_checked(path, "", |i| format!("layer {i}"))?;
    let err = |element: &str, kind, detail: String| LoadError::new(path, element, kind, detail);
    let image =
        read_all_channels(file).map_err(|e| err("", LoadErrorKind::Parse, e.to_string()))?;
    let layer = image.layer_data.first().ok_or_else(|| {
        err(
            "",
            LoadErrorKind::Parse,
            "the file holds no image layer".into(),
        )
    })?;
    let Some(AttributeValue::TextVector(lines)) = layer.attributes.other.get(&text_key()) else {
        return Err(err(
            "",
            LoadErrorKind::Unsupported,
            format!(
                "not an Iris partial image (no {ATTRIBUTE} attribute; write one with iris \
                 render --shard I/N -o PART.exr)"
            ),
        ));
    };
    let mut entries = Vec::with_capacity(lines.len());
    for (i, line) in lines.iter().enumerate() {
        let line = String::from_utf8_lossy(line.as_slice()).into_owned();
        if i == 0 && line != FORMAT {
            return Err(err(
                &format!("attribute {ATTRIBUTE}"),
                LoadErrorKind::Unsupported,
                format!("format {line:?}, this Iris reads {FORMAT:?}"),
            ));
        }
        if i > 0 {
            let (k, v) = line.split_once('=').ok_or_else(|| {
                let element = format!("attribute {ATTRIBUTE} entry {i}");
                err(
                    &element,
                    LoadErrorKind::Parse,
                    format!("{line:?} is not key=value"),
                )
            })?;
            entries.push((k.to_string(), v.to_string()));
        }
    }
    let size = layer.size;
    let n = size.area();
    let channel = |name: &str| -> std::result::Result<&[u32], LoadError> {
        let ch = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == text_or_empty(name));
        match ch.map(|c| &c.sample_data) {
            Some(FlatSamples::U32(v)) if v.len() == n => Ok(v),
            Some(_) => Err(err(
                &format!("channel {name}"),
                LoadErrorKind::Parse,
                "not a u32 channel of the image's size".into(),
            )),
            None => Err(err(
                &format!("channel {name}"),
                LoadErrorKind::MissingBuffer,
                "missing".into(),
            )),
        }
    };
    let mut exact = ExactImage::new(size.width() as u32, size.height() as u32);
    for half in 0..2 {
        for c in 0..3 {
            for word in 0..4 {
                let plane = channel(&sum_channel(half, c, word))?;
                for (s, &v) in exact.sums.iter_mut().zip(plane) {
                    let bits = (s[half].0[c] as u128) | (u128::from(v) << (32 * word));
                    s[half].0[c] = bits as i128;
                }
            }
        }
        let units = channel(&format!("iris.n{half}"))?;
        for (u, &v) in exact.units.iter_mut().zip(units) {
            u[half] = u64::from(v);
        }
    }
    Ok(Partial { entries, exact })
}

/// The attribute's name as an EXR text.
fn text_key() -> Text {
    text_or_empty(ATTRIBUTE)
}

/// `s` as an EXR text (empty if it is not one: never matches a real name).
fn text_or_empty(s: &str) -> Text {
    Text::new_or_none(s).unwrap_or_default()
}

/// Every channel of every layer of the EXR `file`, at full resolution, with attributes.
fn read_all_channels(
    file: impl std::io::Read + std::io::Seek,
) -> exr::error::Result<Image<Layers<AnyChannels<FlatSamples>>>> {
    exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .non_parallel()
        .from_buffered(file)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::fixed::FixedRgb;
    use glam::DVec3;

    fn exact() -> ExactImage {
        let mut e = ExactImage::new(5, 3);
        for (i, s) in e.sums.iter_mut().enumerate() {
            let v = DVec3::new(i as f64 * 1.5, -(i as f64) * 1e-12, 3e11);
            s[0] = FixedRgb::from_dvec3(v);
            s[1] = FixedRgb::from_dvec3(-v);
            e.units[i] = [i as u64 + 2, i as u64 + 1];
        }
        e.sums[4][1].0[2] = i128::MIN + 7;
        e
    }

    #[test]
    fn round_trip_is_exact_and_bytes_are_deterministic() {
        let dir = std::env::temp_dir().join(format!("iris-partial-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("p.exr");
        let entries = vec![
            ("camera".to_string(), "Caméra \"1\"\n".to_string()),
            ("seed".to_string(), "7".to_string()),
        ];
        let e = exact();
        write(&path, &entries, &e).unwrap();
        let p = read(&path).unwrap();
        assert_eq!(p.exact, e);
        assert_eq!(p.entries[1], ("seed".into(), "7".into()));
        assert_eq!(p.entries[0].1, "Cam\\u{e9}ra \"1\"\\n");
        // The viewable channels are the mean.
        assert_eq!(super::super::exr_io::decode(&path).unwrap(), e.mean());
        assert_eq!(encode(&entries, &e).unwrap(), encode(&entries, &e).unwrap());
        // A plain EXR is refused, by name.
        let plain = dir.join("plain.exr");
        super::super::write_image(&plain, &e.mean(), &Default::default()).unwrap();
        let msg = read(&plain).unwrap_err().to_string();
        assert!(
            msg.contains("plain.exr") && msg.contains("not an Iris partial"),
            "{msg}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
