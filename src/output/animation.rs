//! Animated previews of a frame sequence (`iris turntable`): APNG, and GIF on request.
//!
//! - **APNG** (the default; the `png` crate's encoder): lossless, 8-bit sRGB RGB or RGBA
//!   exactly as the frame PNGs hold them, so a gem's fire keeps every colour. Written with
//!   the `.png` extension, as the APNG specification recommends: a viewer without APNG
//!   support shows the first frame. Every frame is a full frame (`fcTL` dispose none, blend
//!   source); the first image is frame 0 of the animation.
//! - **GIF** (`gif` crate): for chat and mail, where APNG is not always animated. Lossy:
//!   each frame gets its own 256-colour palette by NeuQuant (Dekker 1994; speed 10, the
//!   crate's quality/speed compromise), which bands smooth gradients and thins out a
//!   stone's spectral colours; alpha becomes 1-bit (any alpha > 0 opaque). Its delays are
//!   whole centiseconds: 1/fps is rounded (12 fps plays at 12.5).
//!
//! Both loop forever. The frame time is 1/fps s (APNG stores the fraction 1/fps exactly).
//! Frames arrive one at a time ([`AnimationEncoder::push`]), so memory holds the encoded
//! files, not every decoded frame; the caller writes the bytes atomically
//! ([`super::atomic`]), so a failure leaves no partial animation.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Largest `--fps`: browsers slow GIF delays under 2 cs down to 10 cs.
pub const MAX_FPS: u32 = 50;

/// NeuQuant sampling factor for GIF palettes (1 best … 30 fastest; 10 is the gif crate's
/// suggested compromise).
const GIF_QUANT_SPEED: i32 = 10;

/// One frame: 8-bit sRGB pixels, row-major, top row first, RGB or RGBA (straight alpha).
#[derive(Debug, Clone, PartialEq)]
pub struct Frame8 {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Whether `data` is RGBA (else RGB).
    pub alpha: bool,
    /// `width × height × (3 or 4)` bytes.
    pub data: Vec<u8>,
}

impl Frame8 {
    /// Reads a PNG frame (8-bit RGB or RGBA, as `iris render` writes them; other layouts
    /// are converted). Errors name the file.
    pub fn read_png(path: &Path) -> Result<Frame8> {
        let file = crate::fileio::input::open(path, crate::fileio::Input::Image)
            .map_err(|e| bad(path, e.to_string()))?;
        let img = image::ImageReader::new(std::io::BufReader::new(file))
            .with_guessed_format()
            .map_err(|e| bad(path, e.to_string()))?
            .decode()
            .map_err(|e| bad(path, e.to_string()))?;
        let (width, height) = (img.width(), img.height());
        let (alpha, data) = if img.color().has_alpha() {
            (true, img.into_rgba8().into_raw())
        } else {
            (false, img.into_rgb8().into_raw())
        };
        Ok(Frame8 {
            width,
            height,
            alpha,
            data,
        })
    }

    /// The pixels as RGBA.
    fn rgba(&self) -> Vec<u8> {
        if self.alpha {
            return self.data.clone();
        }
        self.data
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect()
    }

    fn describe(&self) -> String {
        format!(
            "{}x{} {}",
            self.width,
            self.height,
            if self.alpha { "RGBA" } else { "RGB" }
        )
    }
}

fn bad(path: &Path, reason: String) -> Error {
    Error::Usage(format!(
        "{}: not a readable frame: {reason}",
        path.display()
    ))
}

/// Encodes frames pushed one at a time into an APNG (and a GIF), into byte buffers the
/// caller owns.
pub struct AnimationEncoder<'a> {
    apng: png::Writer<&'a mut Vec<u8>>,
    gif: Option<gif::Encoder<&'a mut Vec<u8>>>,
    first: Frame8,
    first_name: PathBuf,
    gif_delay: u16,
}

fn encode_err(what: &str, e: impl std::fmt::Display) -> Error {
    Error::Usage(format!("{what} encoder: {e}"))
}

impl<'a> AnimationEncoder<'a> {
    /// An encoder for `frames` frames shaped like `first` (read from `first_name`, which
    /// errors about later frames name), shown at `fps` (1 to [`MAX_FPS`]), writing the APNG
    /// into `apng` and, when given, a GIF into `gif`.
    pub fn new(
        first: &Frame8,
        first_name: &Path,
        frames: u32,
        fps: u32,
        apng: &'a mut Vec<u8>,
        gif: Option<&'a mut Vec<u8>>,
    ) -> Result<Self> {
        if !(1..=MAX_FPS).contains(&fps) {
            return Err(Error::Usage(format!(
                "--fps {fps}: frames per second must be 1 to {MAX_FPS}"
            )));
        }
        let fps16 = u16::try_from(fps).map_err(|e| encode_err("APNG", e))?;
        let mut enc = png::Encoder::new(apng, first.width, first.height);
        enc.set_color(if first.alpha {
            png::ColorType::Rgba
        } else {
            png::ColorType::Rgb
        });
        enc.set_depth(png::BitDepth::Eight);
        enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        enc.set_animated(frames, 0)
            .map_err(|e| encode_err("APNG", e))?;
        enc.set_frame_delay(1, fps16)
            .map_err(|e| encode_err("APNG", e))?;
        let apng = enc.write_header().map_err(|e| encode_err("APNG", e))?;
        let gif = gif
            .map(|out| -> Result<_> {
                let size = |v: u32| {
                    u16::try_from(v).map_err(|_| {
                        Error::Usage(format!(
                            "--gif: {}x{} frames are larger than GIF's 65535 pixels a side",
                            first.width, first.height
                        ))
                    })
                };
                let mut g = gif::Encoder::new(out, size(first.width)?, size(first.height)?, &[])
                    .map_err(|e| encode_err("GIF", e))?;
                g.set_repeat(gif::Repeat::Infinite)
                    .map_err(|e| encode_err("GIF", e))?;
                Ok(g)
            })
            .transpose()?;
        Ok(AnimationEncoder {
            apng,
            gif,
            first: Frame8 {
                data: Vec::new(),
                ..first.clone()
            },
            first_name: first_name.to_path_buf(),
            gif_delay: ((100.0 / f64::from(fps)).round() as u16).max(2),
        })
    }

    /// Appends `frame` (read from `name`): it must have the first frame's size and layout.
    pub fn push(&mut self, frame: &Frame8, name: &Path) -> Result<()> {
        let f = &self.first;
        let channels = if frame.alpha { 4 } else { 3 };
        if (frame.width, frame.height, frame.alpha) != (f.width, f.height, f.alpha)
            || frame.data.len() as u64
                != u64::from(frame.width) * u64::from(frame.height) * channels
        {
            return Err(Error::Usage(format!(
                "{} is {} but {} is {}: the frames come from different renders (same --size \
                 and --background for every frame)",
                name.display(),
                frame.describe(),
                self.first_name.display(),
                f.describe()
            )));
        }
        self.apng
            .write_image_data(&frame.data)
            .map_err(|e| encode_err("APNG", e))?;
        if let Some(g) = &mut self.gif {
            // Sizes were checked to fit u16 when the encoder was made.
            let mut rgba = frame.rgba();
            let mut gf = gif::Frame::from_rgba_speed(
                frame.width as u16,
                frame.height as u16,
                &mut rgba,
                GIF_QUANT_SPEED,
            );
            gf.delay = self.gif_delay;
            g.write_frame(&gf).map_err(|e| encode_err("GIF", e))?;
        }
        Ok(())
    }

    /// Finishes both files (every frame announced to [`AnimationEncoder::new`] pushed, else
    /// an error).
    pub fn finish(self) -> Result<()> {
        self.apng.finish().map_err(|e| encode_err("APNG", e))?;
        if let Some(g) = self.gif {
            g.into_inner().map_err(|e| encode_err("GIF", e))?;
        }
        Ok(())
    }
}
