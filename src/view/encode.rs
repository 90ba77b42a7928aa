//! What the live view hands out: frames as PNG bytes (the render's display transform:
//! exposure, tone map, sRGB), the final render's file name, and a command line a POSIX
//! shell reads back as the same arguments.

use crate::image::ImageRgb;
use crate::output::DisplayOptions;
use std::path::{Path, PathBuf};

/// `image` tone-mapped for display and encoded as an 8-bit RGB PNG (fast compression: a
/// frame is looked at once).
pub fn png(image: &ImageRgb, display: DisplayOptions) -> Vec<u8> {
    let rgb = crate::output::tonemap::to_srgb8(image, display.exposure, display.tonemap);
    let mut out = Vec::new();
    let written = {
        let mut encoder = png::Encoder::new(&mut out, image.width, image.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        // Writing into a Vec fails only for a buffer not of the header's size.
        encoder
            .write_header()
            .and_then(|mut w| w.write_image_data(&rgb).and_then(|_| w.finish()))
            .is_ok()
    };
    if written {
        out
    } else {
        Vec::new()
    }
}

/// `DIR/<scene stem>-view-<k>.png` for the first k from 1 that names no file yet.
pub fn free_output(dir: &Path, scene: &str) -> crate::Result<PathBuf> {
    let stem = Path::new(scene)
        .file_stem()
        .map_or("render".into(), |s| s.to_string_lossy().into_owned());
    (1..100_000)
        .map(|k| dir.join(format!("{stem}-view-{k}.png")))
        .find(|p| !p.exists())
        .ok_or_else(|| crate::Error::Usage(format!("{}: no free output name left", dir.display())))
}

/// `iris render ARGS…` with each argument quoted for a POSIX shell when it needs it.
pub fn command_line(args: &[String]) -> String {
    let quoted: Vec<String> = args.iter().map(|a| quote(a)).collect();
    format!("iris render {}", quoted.join(" "))
}

fn quote(arg: &str) -> String {
    let plain = !arg.is_empty()
        && arg
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./,:=+@%".contains(c));
    if plain {
        arg.to_string()
    } else {
        format!("'{}'", arg.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoting_keeps_plain_words_and_quotes_the_rest() {
        let args = ["a b.glb", "--camera-look-at", "0,-1,2:0,0,0:35", "it's"].map(String::from);
        assert_eq!(
            command_line(&args),
            r"iris render 'a b.glb' --camera-look-at 0,-1,2:0,0,0:35 'it'\''s'"
        );
    }

    #[test]
    fn frames_are_pngs_of_the_image_size() {
        let img = ImageRgb::new(5, 3);
        let bytes = png(&img, DisplayOptions::default());
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let reader = decoder.read_info().unwrap();
        assert_eq!((reader.info().width, reader.info().height), (5, 3));
    }
}
