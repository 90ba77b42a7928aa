//! The counts a Draco mesh stream declares before its connectivity (faces, vertices),
//! read without decoding so that the loader can bound them by the glTF accessors first.
//!
//! Layout (Draco bitstream specification 2.2, sections "Header", "Metadata",
//! "Sequential connectivity", "EdgeBreaker connectivity"): `"DRACO"`, major, minor,
//! geometry type (1 = triangular mesh), encoder method (0 sequential, 1 Edgebreaker),
//! u16 flags (bit 15: a metadata section follows); the metadata section (a LEB128 count of
//! attribute blocks, each a LEB128 attribute id and a metadata block, then the geometry's
//! metadata block; a block is a LEB128 entry count, entries of a u8-length name and a
//! LEB128-length value, then a LEB128 count of u8-length-named sub-blocks); then the
//! connectivity header: sequential `num_faces, num_points`, Edgebreaker traversal type
//! (u8), `num_encoded_vertices, num_faces` (all LEB128).
//!
//! The fields are read as the vendored decoder reads them (`header.rs`, `metadata.rs`,
//! the sequential and Edgebreaker connectivity headers: same order, LEB128 values, u8
//! name lengths, nesting cap); where the decoder is looser (LEB128 values longer than
//! ten bytes) this reader refuses, so counts read here are the counts the decoder uses.
//! The decoder's parsers are private to it, and calling them would mean a sixth patch.
//!
//! Invariant: every stream the decoder would accept (bar over-long LEB128 values, which no
//! encoder writes) has readable counts here. A stream whose counts cannot be read is
//! refused with the reason, never handed to the decoder unbounded (fuzzing found a
//! metadata-flagged stream whose unchecked face count made the decoder ask for 7.5 EB
//! and abort: fuzz/regressions/gltf/draco_metadata_faces.glb).

/// Face and vertex counts from a Draco 2.2 mesh stream's connectivity header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct HeaderCounts {
    /// Triangles.
    pub faces: usize,
    /// Points (sequential) or encoded vertices (Edgebreaker).
    pub vertices: usize,
}

/// Deepest sub-metadata nesting read (the reference decoder's cap).
const MAX_METADATA_DEPTH: usize = 1000;

/// Reads the [`HeaderCounts`] of `bytes`, or says why the stream is not a Draco 2.2
/// triangular mesh whose counts can be read.
pub(super) fn header_counts(bytes: &[u8]) -> Result<HeaderCounts, String> {
    let truncated = || "the stream ends inside its header".to_string();
    if bytes.get(..5).ok_or_else(truncated)? != b"DRACO" {
        return Err("the stream does not start with the DRACO magic".into());
    }
    let (major, minor, geometry) = match bytes.get(5..8) {
        Some(&[a, b, c]) => (a, b, c),
        _ => return Err(truncated()),
    };
    if geometry == 0 {
        return Err("the stream is a point cloud, not a triangle mesh".into());
    }
    if (major, minor) != (2, 2) {
        return Err(format!(
            "Draco bitstream {major}.{minor} is not supported (only 2.2, which every current encoder writes)"
        ));
    }
    if geometry != 1 {
        return Err(format!("unknown Draco geometry type {geometry}"));
    }
    let method = *bytes.get(8).ok_or_else(truncated)?;
    let flags = u16::from_le_bytes([
        *bytes.get(9).ok_or_else(truncated)?,
        *bytes.get(10).ok_or_else(truncated)?,
    ]);
    let mut at = 11;
    if flags & 0x8000 != 0 {
        skip_metadata_section(bytes, &mut at)
            .ok_or("the metadata section is truncated or malformed")?;
    }
    let counts = || "the connectivity header is truncated or its counts overflow".to_string();
    match method {
        0 => {
            let faces = varint(bytes, &mut at).ok_or_else(counts)?;
            let vertices = varint(bytes, &mut at).ok_or_else(counts)?;
            Ok(HeaderCounts { faces, vertices })
        }
        1 => {
            at += 1; // traversal type
            let vertices = varint(bytes, &mut at).ok_or_else(counts)?;
            let faces = varint(bytes, &mut at).ok_or_else(counts)?;
            Ok(HeaderCounts { faces, vertices })
        }
        m => Err(format!("unknown Draco encoder method {m}")),
    }
}

/// Skips the metadata section at `*at`; `None` when it is truncated or nests too deep.
/// Every loop iteration consumes at least one byte, so the work is bounded by the stream.
fn skip_metadata_section(bytes: &[u8], at: &mut usize) -> Option<()> {
    let blocks = varint(bytes, at)?;
    for _ in 0..blocks {
        varint(bytes, at)?; // attribute unique id
        skip_block(bytes, at, 0)?;
    }
    skip_block(bytes, at, 0)
}

/// Skips one metadata block (entries, then named sub-blocks, depth first).
fn skip_block(bytes: &[u8], at: &mut usize, depth: usize) -> Option<()> {
    if depth > MAX_METADATA_DEPTH {
        return None;
    }
    let entries = varint(bytes, at)?;
    for _ in 0..entries {
        skip_name(bytes, at)?;
        let len = varint(bytes, at)?;
        skip(bytes, at, len)?;
    }
    let subs = varint(bytes, at)?;
    for _ in 0..subs {
        skip_name(bytes, at)?;
        skip_block(bytes, at, depth + 1)?;
    }
    Some(())
}

/// Skips a u8-length-prefixed name.
fn skip_name(bytes: &[u8], at: &mut usize) -> Option<()> {
    let len = usize::from(*bytes.get(*at)?);
    *at += 1;
    skip(bytes, at, len)
}

/// Advances `*at` by `len` bytes if the stream holds them.
fn skip(bytes: &[u8], at: &mut usize, len: usize) -> Option<()> {
    let end = at.checked_add(len)?;
    (end <= bytes.len()).then(|| *at = end)
}

/// An unsigned LEB128 varint at `*at` (at most 64 bits).
fn varint(bytes: &[u8], at: &mut usize) -> Option<usize> {
    let mut value: u64 = 0;
    for shift in (0..64).step_by(7) {
        let b = *bytes.get(*at)?;
        *at += 1;
        value |= u64::from(b & 0x7f).checked_shl(shift)?;
        if b & 0x80 == 0 {
            return usize::try_from(value).ok();
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_read_from_both_connectivity_methods() {
        let mut seq = b"DRACO\x02\x02\x01\x00\x00\x00".to_vec();
        seq.extend([0x96, 0x01, 5]); // 150 faces, 5 points
        let c = header_counts(&seq).expect("sequential");
        assert_eq!((c.faces, c.vertices), (150, 5));
        let mut eb = b"DRACO\x02\x02\x01\x01\x00\x00".to_vec();
        eb.extend([0, 8, 12]); // traversal 0, 8 vertices, 12 faces
        let c = header_counts(&eb).expect("edgebreaker");
        assert_eq!((c.faces, c.vertices), (12, 8));
    }

    #[test]
    fn counts_are_read_past_a_metadata_section() {
        let mut eb = b"DRACO\x02\x02\x01\x01\x00\x80".to_vec();
        // One attribute block (id 3): one entry "n" = "ab", no sub-blocks.
        eb.extend([1, 3, 1, 1, b'n', 2, b'a', b'b', 0]);
        // Geometry block: no entries, one sub-block "s" with one entry "k" = "v".
        eb.extend([0, 1, 1, b's', 1, 1, b'k', 1, b'v', 0]);
        eb.extend([0, 8, 12]);
        assert_eq!(
            header_counts(&eb),
            Ok(HeaderCounts {
                faces: 12,
                vertices: 8
            })
        );
        // Cut anywhere inside the metadata: refused, not guessed.
        for cut in 12..eb.len() - 3 {
            assert!(header_counts(&eb[..cut]).is_err(), "cut at {cut}");
        }
    }

    #[test]
    fn streams_without_readable_counts_are_refused_with_the_reason() {
        let cases: [(&[u8], &str); 6] = [
            (b"DRECO\x02\x02\x01\x00\x00\x00\x01\x01", "magic"),
            (b"DRACO\x02\x02", "ends inside"),
            (b"DRACO\x02\x03\x00\x00\x00\x00", "point cloud"),
            (
                b"DRACO\x02\x01\x01\x00\x00\x00\x01\x01",
                "2.1 is not supported",
            ),
            (b"DRACO\x02\x02\x01\x07\x00\x00\x01\x01", "encoder method 7"),
            (b"DRACO\x02\x02\x01\x00\x00\x80\xff\xff", "metadata"),
        ];
        for (bytes, reason) in cases {
            let err = header_counts(bytes).expect_err(reason);
            assert!(err.contains(reason), "{err}");
        }
        // Nesting deeper than the cap ends (no stack overflow, no hang).
        let mut deep = b"DRACO\x02\x02\x01\x00\x00\x80\x00".to_vec();
        for _ in 0..2000 {
            deep.extend([0, 1, 0]); // no entries, one unnamed sub-block
        }
        assert!(header_counts(&deep).is_err());
    }

    #[test]
    fn varints_stop_at_overflow_and_truncation() {
        let mut at = 0;
        assert_eq!(varint(&[0xe5, 0x8e, 0x26], &mut at), Some(624_485));
        assert_eq!(at, 3);
        assert_eq!(varint(&[0x80, 0x80], &mut 0), None);
        assert_eq!(varint(&[0xff; 11], &mut 0), None);
    }
}
