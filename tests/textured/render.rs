#![allow(dead_code)]
//! Renders through the `iris` binary into an OpenEXR file (linear radiance, no denoising,
//! no tone mapping) and reads it back with the `exr` crate.

use std::path::Path;

/// A linear RGB image, row-major from the top-left.
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub px: Vec<[f32; 3]>,
}

/// Renders `scene` to `<dir>/<out>.exr` with `--denoise off`, `--quiet` and `args` (size,
/// method, seed, sample counts), and reads the result. Panics with iris's stderr on failure.
pub fn render(scene: &Path, out: &str, args: &[&str]) -> Image {
    let dir = scene.parent().expect("scene dir");
    let exr = dir.join(format!("{out}.exr"));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_iris"))
        .arg("render")
        .arg(scene)
        .arg("-o")
        .arg(&exr)
        .args(["--denoise", "off", "--quiet"])
        .args(args)
        .output()
        .expect("run iris");
    assert!(
        o.status.success(),
        "iris render {} {args:?} failed: {}",
        scene.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    read(&exr)
}

/// Reads the RGB channels of an EXR file.
pub fn read(path: &Path) -> Image {
    let img = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |res, _| Image {
            width: res.width(),
            height: res.height(),
            px: vec![[0.0; 3]; res.area()],
        },
        |img: &mut Image, pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            let w = img.width;
            img.px[pos.y() * w + pos.x()] = [r, g, b];
        },
    )
    .unwrap_or_else(|e| panic!("read {}: {e}", path.display()));
    img.layer_data.channel_data.pixels
}

impl Image {
    /// The mean of `(r + g + b) / 3` over the pixels whose centres (x + ½, y + ½), divided
    /// by the image size (so in [0, 1]²), satisfy `keep`; panics when no pixel is kept.
    pub fn mean_where(&self, keep: impl Fn(f64, f64) -> bool) -> f64 {
        let (mut sum, mut n) = (0.0, 0usize);
        for y in 0..self.height {
            for x in 0..self.width {
                let (u, v) = (
                    (x as f64 + 0.5) / self.width as f64,
                    (y as f64 + 0.5) / self.height as f64,
                );
                if keep(u, v) {
                    let p = self.px[y * self.width + x].map(f64::from);
                    sum += (p[0] + p[1] + p[2]) / 3.0;
                    n += 1;
                }
            }
        }
        assert!(n > 0, "empty region");
        sum / n as f64
    }

    /// Means of `k × k` pixel blocks, per channel, row-major (width and height multiples of
    /// `k`): the unit the transform tests compare.
    pub fn blocks(&self, k: usize) -> Vec<[f64; 3]> {
        assert!(self.width.is_multiple_of(k) && self.height.is_multiple_of(k));
        let mut out = Vec::new();
        for by in 0..self.height / k {
            for bx in 0..self.width / k {
                let mut s = [0.0; 3];
                for y in by * k..(by + 1) * k {
                    for x in bx * k..(bx + 1) * k {
                        let p = self.px[y * self.width + x];
                        for c in 0..3 {
                            s[c] += f64::from(p[c]);
                        }
                    }
                }
                out.push(s.map(|v| v / (k * k) as f64));
            }
        }
        out
    }

    /// Whether every pixel is finite.
    pub fn finite(&self) -> bool {
        self.px.iter().flatten().all(|v| v.is_finite())
    }
}

/// Largest |a − b| over blocks and channels.
pub fn max_diff(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs()))
        .fold(0.0, f64::max)
}

/// The largest spread of one channel's block means.
pub fn contrast(a: &[[f64; 3]]) -> f64 {
    (0..3)
        .map(|c| {
            let v = a.iter().map(|p| p[c]);
            v.clone().fold(f64::MIN, f64::max) - v.fold(f64::MAX, f64::min)
        })
        .fold(0.0, f64::max)
}
