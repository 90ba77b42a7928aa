//! The file format of the albedo tables embedded in the binary ([`super::energy`]'s E_ss,
//! [`super::sheen`]'s E): `len` values in [0, 1], each a little-endian u16 of value·65535
//! (quantisation 1.5e-5), in the owning module's index order.

/// Quantises a value in [0, 1] (clamped) to the file's u16.
pub(super) fn quantise(e: f32) -> u16 {
    (e.clamp(0.0, 1.0) * 65535.0).round() as u16
}

/// Decodes an embedded table of `len` values; a file of another size (stale after a change
/// of the grid constants) is replaced by `generate()`'s bytes, so a lookup never fails.
pub(super) fn decode(file: &[u8], len: usize, generate: impl FnOnce() -> Vec<u8>) -> Vec<f32> {
    let bytes = if file.len() == 2 * len {
        file.to_vec()
    } else {
        generate()
    };
    bytes
        .chunks_exact(2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]) as f32 / 65535.0)
        .collect()
}
