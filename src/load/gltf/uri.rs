//! URIs of glTF buffers and images (glTF 2.0 §3.2 "URIs"): `data:` URIs (RFC 2397) with
//! base64 payloads (RFC 4648 §4), and relative file references, which are percent-decoded
//! (RFC 3986 §2.1) and resolved against the directory of the scene file.
//!
//! Nothing here panics on malformed input: every failure is a `String` the caller wraps
//! with the element (`buffer 0 "geo"`, `image 2`) into a `LoadError`.

use std::path::{Path, PathBuf};

/// Where the bytes of a buffer or image come from.
#[derive(Debug)]
pub(super) enum UriSource {
    /// Embedded bytes of a `data:` URI (the media type is not needed: images are
    /// recognised by their magic bytes).
    Embedded(Vec<u8>),
    /// An external file.
    File(PathBuf),
}

/// Resolves `uri` relative to `base_dir` (the directory holding the .gltf file).
pub(super) fn resolve(uri: &str, base_dir: &Path) -> Result<UriSource, String> {
    if let Some(rest) = strip_prefix_ci(uri, "data:") {
        let (header, payload) = rest
            .split_once(',')
            .ok_or_else(|| "data URI without a ',' separator".to_string())?;
        let bytes = if header.ends_with(";base64") {
            decode_base64(payload)?
        } else {
            percent_decode(payload)?
        };
        return Ok(UriSource::Embedded(bytes));
    }
    if let Some(rest) = strip_prefix_ci(uri, "file://").or_else(|| strip_prefix_ci(uri, "file:")) {
        let decoded = utf8(percent_decode(rest)?)?;
        return Ok(UriSource::File(PathBuf::from(decoded)));
    }
    if has_scheme(uri) {
        return Err(format!(
            "unsupported URI scheme in {uri:?} (only data: and relative files)"
        ));
    }
    let decoded = utf8(percent_decode(uri)?)?;
    Ok(UriSource::File(base_dir.join(decoded)))
}

/// True if `uri` starts with an RFC 3986 scheme (`ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"`).
/// A one-letter scheme is taken as a Windows drive letter, not a scheme.
fn has_scheme(uri: &str) -> bool {
    match uri.split_once(':') {
        Some((scheme, _)) => {
            scheme.len() > 1
                && scheme
                    .chars()
                    .next()
                    .is_some_and(|c| c.is_ascii_alphabetic())
                && scheme
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
        }
        None => false,
    }
}

fn strip_prefix_ci<'a>(s: &'a str, prefix: &str) -> Option<&'a str> {
    let head = s.get(..prefix.len())?;
    if head.eq_ignore_ascii_case(prefix) {
        s.get(prefix.len()..)
    } else {
        None
    }
}

fn utf8(bytes: Vec<u8>) -> Result<String, String> {
    String::from_utf8(bytes).map_err(|_| "percent-decoded URI is not valid UTF-8".to_string())
}

/// Decodes `%XX` escapes (RFC 3986 §2.1). A `%` not followed by two hex digits is an error.
pub(super) fn percent_decode(s: &str) -> Result<Vec<u8>, String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while let Some(&b) = bytes.get(i) {
        if b == b'%' {
            let hi = bytes.get(i + 1).and_then(|&c| hex_value(c));
            let lo = bytes.get(i + 2).and_then(|&c| hex_value(c));
            match (hi, lo) {
                (Some(hi), Some(lo)) => out.push(hi << 4 | lo),
                _ => return Err(format!("bad percent-escape at byte {i} of URI")),
            }
            i += 3;
        } else {
            out.push(b);
            i += 1;
        }
    }
    Ok(out)
}

fn hex_value(c: u8) -> Option<u8> {
    match c {
        b'0'..=b'9' => Some(c - b'0'),
        b'a'..=b'f' => Some(c - b'a' + 10),
        b'A'..=b'F' => Some(c - b'A' + 10),
        _ => None,
    }
}

/// Decodes base64 (RFC 4648 §4; the URL-safe alphabet of §5 is accepted too). ASCII
/// whitespace is skipped; `=` padding is optional but nothing may follow it.
pub(super) fn decode_base64(s: &str) -> Result<Vec<u8>, String> {
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    let mut acc: u32 = 0;
    let mut bits = 0u32;
    let mut padding = false;
    for (pos, c) in s.bytes().enumerate() {
        if c.is_ascii_whitespace() {
            continue;
        }
        if c == b'=' {
            padding = true;
            continue;
        }
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => {
                return Err(format!(
                    "invalid base64 character at byte {pos} of data URI"
                ))
            }
        };
        if padding {
            return Err(format!(
                "base64 data continues after '=' padding at byte {pos}"
            ));
        }
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push(((acc >> bits) & 0xff) as u8);
        }
    }
    if bits >= 6 {
        // A single leftover sextet cannot encode a whole byte (RFC 4648 §4).
        return Err("truncated base64 data".to_string());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_values() {
        assert_eq!(decode_base64("aGVsbG8=").as_deref(), Ok(&b"hello"[..]));
        assert_eq!(decode_base64("aGVsbG8").as_deref(), Ok(&b"hello"[..]));
        assert_eq!(
            decode_base64("AAEC/w==").as_deref(),
            Ok(&[0u8, 1, 2, 255][..])
        );
        assert!(decode_base64("a").is_err());
        assert!(decode_base64("ab=c").is_err());
        assert!(decode_base64("a*b").is_err());
    }

    #[test]
    fn percent_and_schemes() {
        assert_eq!(percent_decode("a%20b").as_deref(), Ok(&b"a b"[..]));
        assert!(percent_decode("a%2").is_err());
        assert!(percent_decode("%zz").is_err());
        let base = Path::new("/scenes");
        match resolve("my%20mesh.bin", base) {
            Ok(UriSource::File(p)) => assert_eq!(p, Path::new("/scenes/my mesh.bin")),
            other => panic!("unexpected {other:?}"),
        }
        match resolve("data:application/octet-stream;base64,AAE=", base) {
            Ok(UriSource::Embedded(bytes)) => assert_eq!(bytes, vec![0, 1]),
            other => panic!("unexpected {other:?}"),
        }
        assert!(resolve("https://example.com/a.bin", base).is_err());
        assert!(resolve("%FF.bin", base).is_err());
    }
}
