//! A GLB split into its JSON and BIN chunks, the compressed streams it holds (Draco
//! buffer views, meshopt-compressed ranges), and the four mutation kinds of the exporter
//! pass, applied to one stream (re-spliced into a valid GLB) or to the whole file.

use super::Rng;
use serde_json::Value;

/// The mutation kinds of the exporter pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// 1–4 bytes XORed with a random non-zero byte.
    Flip,
    /// The data cut short at a random length.
    Truncate,
    /// A run of 1–64 bytes repeated 1–4 more times in place.
    Duplicate,
    /// A 32-bit little-endian field set to one of [`FIELDS`].
    Overwrite,
}

impl Kind {
    pub const ALL: [Kind; 4] = [Kind::Flip, Kind::Truncate, Kind::Duplicate, Kind::Overwrite];
}

/// Where a mutation lands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// Inside one compressed stream; the GLB is rebuilt around it (lengths and offsets
    /// fixed), so the mutant reaches the decoder.
    Stream,
    /// Anywhere in the file bytes (GLB header, JSON, BIN), as a naive mutator would.
    File,
}

/// 32-bit values for [`Kind::Overwrite`]: the extremes, and small and large counts.
pub const FIELDS: [u32; 12] = [
    0,
    0xffff_ffff,
    0x7fff_ffff,
    0x8000_0000,
    1,
    2,
    3,
    16,
    255,
    1 << 16,
    1 << 20,
    1 << 28,
];

/// Where a compressed stream's offset and length are declared in the JSON.
#[derive(Clone, Debug)]
enum Declared {
    /// `bufferViews[i]` (the view a KHR_draco_mesh_compression primitive names).
    View(usize),
    /// `bufferViews[i].extensions[name]` (EXT/KHR_meshopt_compression).
    Meshopt(usize, &'static str),
}

/// One compressed stream in the BIN chunk.
#[derive(Clone, Debug)]
pub struct Stream {
    declared: Declared,
    offset: usize,
    length: usize,
}

/// A GLB as JSON and BIN.
pub struct Glb {
    json: Value,
    bin: Vec<u8>,
    /// Where the BIN chunk's data starts in the file.
    bin_start: usize,
}

/// Pads `v` with zeros to a multiple of 4 bytes (a stream appended to the BIN chunk
/// starts 4-aligned).
fn align4(v: &mut Vec<u8>) {
    while !v.len().is_multiple_of(4) {
        v.push(0);
    }
}

fn u32_at(b: &[u8], at: usize) -> Option<usize> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?) as usize)
}

impl Glb {
    /// Parses a well-formed GLB with a JSON and a BIN chunk.
    pub fn parse(bytes: &[u8]) -> Option<Glb> {
        let json_len = u32_at(bytes, 12)?;
        let json = serde_json::from_slice(bytes.get(20..20 + json_len)?).ok()?;
        let bin_len = u32_at(bytes, 20 + json_len)?;
        let bin_start = 28 + json_len;
        let bin = bytes.get(bin_start..bin_start + bin_len)?.to_vec();
        Some(Glb {
            json,
            bin,
            bin_start,
        })
    }

    /// The file: header, JSON chunk (space-padded), BIN chunk (zero-padded).
    pub fn build(&self) -> Vec<u8> {
        super::common::glb(&self.json, &self.bin)
    }

    /// The compressed streams in buffer 0 (the BIN chunk): Draco primitives' views and
    /// meshopt-compressed views.
    pub fn streams(&self) -> Vec<Stream> {
        let views = self.json["bufferViews"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        let range = |v: &Value| -> Option<(usize, usize)> {
            (v["buffer"].as_u64()? == 0).then_some(())?;
            Some((
                v["byteOffset"].as_u64().unwrap_or(0) as usize,
                v["byteLength"].as_u64()? as usize,
            ))
        };
        let mut out = Vec::new();
        let mut draco_views: Vec<usize> = self.json["meshes"]
            .as_array()
            .into_iter()
            .flatten()
            .flat_map(|m| m["primitives"].as_array().cloned().unwrap_or_default())
            .filter_map(|p| p["extensions"]["KHR_draco_mesh_compression"]["bufferView"].as_u64())
            .map(|v| v as usize)
            .collect();
        draco_views.sort_unstable();
        draco_views.dedup();
        for i in draco_views {
            if let Some((offset, length)) = views.get(i).and_then(range) {
                out.push(Stream {
                    declared: Declared::View(i),
                    offset,
                    length,
                });
            }
        }
        for (i, view) in views.iter().enumerate() {
            for name in ["EXT_meshopt_compression", "KHR_meshopt_compression"] {
                if let Some((offset, length)) = range(&view["extensions"][name]) {
                    out.push(Stream {
                        declared: Declared::Meshopt(i, name),
                        offset,
                        length,
                    });
                }
            }
        }
        out.retain(|s| s.length > 0 && s.offset + s.length <= self.bin.len());
        out
    }

    /// The JSON object declaring `stream`'s offset and length.
    fn declaration(&mut self, declared: &Declared) -> &mut Value {
        match *declared {
            Declared::View(i) => &mut self.json["bufferViews"][i],
            Declared::Meshopt(i, name) => &mut self.json["bufferViews"][i]["extensions"][name],
        }
    }

    /// The file with `stream` replaced by `bytes`: in place if they fit, else appended to
    /// the BIN chunk (4-aligned) with the offset, the length and buffer 0's byteLength
    /// updated.
    pub fn with_stream(&self, stream: &Stream, bytes: &[u8]) -> Vec<u8> {
        let mut glb = Glb {
            json: self.json.clone(),
            bin: self.bin.clone(),
            bin_start: self.bin_start,
        };
        let offset = if bytes.len() <= stream.length {
            glb.bin[stream.offset..stream.offset + bytes.len()].copy_from_slice(bytes);
            stream.offset
        } else {
            align4(&mut glb.bin);
            let at = glb.bin.len();
            glb.bin.extend_from_slice(bytes);
            align4(&mut glb.bin);
            glb.json["buffers"][0]["byteLength"] = glb.bin.len().into();
            at
        };
        let d = glb.declaration(&stream.declared);
        d["byteOffset"] = offset.into();
        d["byteLength"] = bytes.len().into();
        glb.build()
    }

    /// A mutant of `file` (this GLB's bytes): `kind` applied to a random stream, or to
    /// the whole file.
    pub fn mutant(&self, file: &[u8], rng: &mut Rng, kind: Kind, region: Region) -> Vec<u8> {
        let streams = self.streams();
        if region == Region::File || streams.is_empty() {
            return mutate_bytes(rng, file, kind);
        }
        let stream = &streams[rng.below(streams.len())];
        match kind {
            // Same length: mutate the file in place (the JSON stays byte for byte).
            Kind::Flip | Kind::Overwrite => {
                let start = self.bin_start + stream.offset;
                let mut out = file.to_vec();
                let part = mutate_bytes(rng, &file[start..start + stream.length], kind);
                out[start..start + stream.length].copy_from_slice(&part);
                out
            }
            Kind::Truncate | Kind::Duplicate => {
                let data = &self.bin[stream.offset..stream.offset + stream.length];
                self.with_stream(stream, &mutate_bytes(rng, data, kind))
            }
        }
    }
}

/// `kind` applied to `data` (not empty).
pub fn mutate_bytes(rng: &mut Rng, data: &[u8], kind: Kind) -> Vec<u8> {
    let mut d = data.to_vec();
    match kind {
        Kind::Flip => {
            for _ in 0..1 + rng.below(4) {
                let i = rng.below(d.len());
                d[i] ^= 1 + rng.below(255) as u8;
            }
        }
        Kind::Truncate => d.truncate(rng.below(d.len())),
        Kind::Duplicate => {
            let a = rng.below(d.len());
            let len = 1 + rng.below((d.len() - a).min(64));
            let run = d[a..a + len].to_vec();
            let copies = 1 + rng.below(4);
            d.splice(a..a, run.iter().copied().cycle().take(len * copies));
        }
        Kind::Overwrite => {
            let value = FIELDS[rng.below(FIELDS.len())].to_le_bytes();
            let i = rng.below(d.len());
            // A field cut by the end of the data keeps its first bytes.
            for (k, b) in value.iter().enumerate() {
                if let Some(slot) = d.get_mut(i + k) {
                    *slot = *b;
                }
            }
        }
    }
    d
}
