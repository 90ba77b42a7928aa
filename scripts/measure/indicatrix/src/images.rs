//! Linear images (EXR), the one display transform both renders go through, the label
//! strips and the side-by-side composition, and the numbers compared.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use glam::Vec3;
use image::{Rgb, Rgb32FImage, RgbImage};
use indicatrix::optics::raytracer::xyz_to_srgb_gamma;

/// Linear sRGB (D65) -> CIE XYZ, the inverse of indicatrix's `ColorSpace::Srgb` matrix
/// (IEC 61966-2-1 primaries, as tabulated by Lindbloom).
pub fn rgb_to_xyz(c: Vec3) -> Vec3 {
    Vec3::new(
        0.412_456_4 * c.x + 0.357_576_1 * c.y + 0.180_437_5 * c.z,
        0.212_672_9 * c.x + 0.715_152_2 * c.y + 0.072_175_0 * c.z,
        0.019_333_9 * c.x + 0.119_192_0 * c.y + 0.950_304_1 * c.z,
    )
}

/// CIE XYZ -> linear sRGB (D65), indicatrix's own `ColorSpace::Srgb` matrix.
pub fn xyz_to_rgb(x: Vec3) -> Vec3 {
    Vec3::new(
        3.240_454_2 * x.x - 1.537_138_5 * x.y - 0.498_531_4 * x.z,
        -0.969_266 * x.x + 1.876_010_8 * x.y + 0.041_556 * x.z,
        0.055_643_4 * x.x - 0.204_025_9 * x.y + 1.057_225_2 * x.z,
    )
}

/// Writes mean XYZ as a linear-sRGB float EXR (negative, out-of-gamut values kept).
pub fn write_exr_from_xyz(path: &str, size: u32, xyz: &[Vec3]) {
    let img = Rgb32FImage::from_fn(size, size, |x, y| {
        let c = xyz_to_rgb(xyz[(y * size + x) as usize]);
        Rgb([c.x, c.y, c.z])
    });
    image::DynamicImage::ImageRgb32F(img)
        .save(path)
        .unwrap_or_else(|e| panic!("writing {path}: {e}"));
}

/// Reads a linear-sRGB EXR as XYZ, row-major.
pub fn read_exr_xyz(path: &str) -> (u32, u32, Vec<Vec3>) {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("reading {path}: {e}"))
        .into_rgb32f();
    let (w, h) = img.dimensions();
    let xyz = img
        .pixels()
        .map(|p| rgb_to_xyz(Vec3::new(p[0], p[1], p[2])))
        .collect();
    (w, h, xyz)
}

/// indicatrix's display transform, for both renders: exposure 1, ACES filmic on the
/// luminance only, chromaticity-preserving gamut mapping, the sRGB transfer curve
/// (`xyz_to_srgb_gamma`, what its viewer and exports show).
pub fn display(w: u32, h: u32, xyz: &[Vec3]) -> RgbImage {
    RgbImage::from_fn(w, h, |x, y| {
        let c = xyz_to_srgb_gamma(xyz[(y * w + x) as usize]);
        Rgb([c[0], c[1], c[2]])
    })
}

/// Numbers over the stone's pixels (`mask`).
#[derive(Default, Debug)]
pub struct Stats {
    pub mean_y: f64,
    /// Chromaticity of the summed XYZ over the stone.
    pub mean_xy: (f64, f64),
    pub mean_display_luma: f64,
    /// Fraction of stone pixels that are coloured and not dark: HSV saturation >= 0.5 and
    /// value >= 0.3 (display values).
    pub fire_fraction: f64,
    /// Mean HSV saturation of stone pixels with value >= 0.3.
    pub mean_saturation: f64,
    /// Fraction of stone pixels with display luma >= 0.9 (near-white highlights).
    pub bright_fraction: f64,
}

fn hsv_sv(p: &Rgb<u8>) -> (f64, f64) {
    let [r, g, b] = p.0.map(|c| f64::from(c) / 255.0);
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let s = if max > 0.0 { (max - min) / max } else { 0.0 };
    (s, max)
}

fn luma(p: &Rgb<u8>) -> f64 {
    let [r, g, b] = p.0.map(|c| f64::from(c) / 255.0);
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

pub fn stats(xyz: &[Vec3], disp: &RgbImage, mask: &[bool]) -> Stats {
    let mut s = Stats::default();
    let mut n = 0.0f64;
    let mut n_lit = 0.0f64;
    let mut sum = glam::DVec3::ZERO;
    for (i, p) in disp.pixels().enumerate() {
        if !mask[i] {
            continue;
        }
        n += 1.0;
        s.mean_y += f64::from(xyz[i].y);
        sum += xyz[i].as_dvec3();
        let l = luma(p);
        s.mean_display_luma += l;
        if l >= 0.9 {
            s.bright_fraction += 1.0;
        }
        let (sat, val) = hsv_sv(p);
        if val >= 0.3 {
            n_lit += 1.0;
            s.mean_saturation += sat;
            if sat >= 0.5 {
                s.fire_fraction += 1.0;
            }
        }
    }
    s.mean_y /= n;
    let t = sum.x + sum.y + sum.z;
    s.mean_xy = (sum.x / t, sum.y / t);
    s.mean_display_luma /= n;
    s.bright_fraction /= n;
    s.fire_fraction /= n;
    s.mean_saturation /= n_lit.max(1.0);
    s
}

/// Noise of one image from two independent renders of it (different seeds, same budget):
/// RMS of their difference / √2 over the stone, in display 8-bit levels (mean over the
/// channels) and relative to the mean luminance (linear Y).
pub fn noise(
    xyz_a: &[Vec3],
    disp_a: &RgbImage,
    xyz_b: &[Vec3],
    disp_b: &RgbImage,
    mask: &[bool],
) -> (f64, f64) {
    let (mut d2, mut y2, mut ysum, mut n) = (0.0, 0.0, 0.0, 0.0);
    for (i, (pa, pb)) in disp_a.pixels().zip(disp_b.pixels()).enumerate() {
        if !mask[i] {
            continue;
        }
        n += 1.0;
        for c in 0..3 {
            let d = f64::from(pa[c]) - f64::from(pb[c]);
            d2 += d * d / 3.0;
        }
        let dy = f64::from(xyz_a[i].y - xyz_b[i].y);
        y2 += dy * dy;
        ysum += 0.5 * f64::from(xyz_a[i].y + xyz_b[i].y);
    }
    let display = (d2 / n).sqrt() / std::f64::consts::SQRT_2;
    let relative = (y2 / n).sqrt() / std::f64::consts::SQRT_2 / (ysum / n);
    (display, relative)
}

const FONT_PATHS: [&str; 2] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
];

/// Draws `text` in white with its top-left at (x, y); silently nothing without a font.
pub fn draw_text(img: &mut RgbImage, x: i32, y: i32, px: f32, text: &str) {
    let Some(bytes) = FONT_PATHS.iter().find_map(|p| std::fs::read(p).ok()) else {
        return;
    };
    let font = FontRef::try_from_slice(&bytes).expect("a TrueType font");
    let scaled = font.as_scaled(PxScale::from(px));
    let mut caret = x as f32;
    let baseline = y as f32 + scaled.ascent();
    let mut last = None;
    for ch in text.chars() {
        let id = font.glyph_id(ch);
        if let Some(prev) = last {
            caret += scaled.kern(prev, id);
        }
        let glyph = id.with_scale_and_position(PxScale::from(px), ab_glyph::point(caret, baseline));
        caret += scaled.h_advance(id);
        last = Some(id);
        if let Some(outline) = font.outline_glyph(glyph) {
            let bounds = outline.px_bounds();
            outline.draw(|gx, gy, cov| {
                let px_x = bounds.min.x as i32 + gx as i32;
                let px_y = bounds.min.y as i32 + gy as i32;
                if px_x >= 0 && px_y >= 0 && (px_x as u32) < img.width() && (px_y as u32) < img.height()
                {
                    let p = img.get_pixel_mut(px_x as u32, px_y as u32);
                    for c in 0..3 {
                        p[c] = (f32::from(p[c]) * (1.0 - cov) + 255.0 * cov) as u8;
                    }
                }
            });
        }
    }
}

/// Panels side by side, each with a label strip (one or two lines) above it.
pub fn compose(panels: &[(&RgbImage, &str, &str)], footer: &str) -> RgbImage {
    let gap = 6;
    let strip = 44;
    let foot = if footer.is_empty() { 0 } else { 24 };
    let w = panels.iter().map(|(p, ..)| p.width()).sum::<u32>() + gap * (panels.len() as u32 - 1);
    let h = panels.iter().map(|(p, ..)| p.height()).max().unwrap() + strip + foot;
    let mut out = RgbImage::from_pixel(w, h, Rgb([24, 24, 28]));
    let mut x0 = 0;
    for (p, l1, l2) in panels {
        image::imageops::replace(&mut out, *p, i64::from(x0), i64::from(strip));
        draw_text(&mut out, x0 as i32 + 6, 3, 17.0, l1);
        draw_text(&mut out, x0 as i32 + 6, 24, 13.0, l2);
        x0 += p.width() + gap;
    }
    if !footer.is_empty() {
        draw_text(&mut out, 8, (h - foot + 4) as i32, 13.0, footer);
    }
    out
}
