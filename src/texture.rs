//! Texture lookup: bilinear filtering with repeat wrapping on 8-bit RGBA images. Texture
//! coordinates follow glTF: (0,0) is the top-left of the image, u to the right, v down.
//! Colour textures are sRGB-encoded and decoded here (IEC 61966-2-1); data textures
//! (metallic-roughness, transmission) are linear.

use crate::scene::desc::ImageDesc;
use glam::{Vec2, Vec4};
use std::sync::OnceLock;

/// How the texel bytes are decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// RGB are sRGB-encoded, alpha is linear.
    Srgb,
    /// All channels are linear.
    Linear,
}

/// sRGB EOTF for each 8-bit code (IEC 61966-2-1).
fn srgb_lut() -> &'static [f32; 256] {
    static LUT: OnceLock<[f32; 256]> = OnceLock::new();
    LUT.get_or_init(|| {
        let mut t = [0f32; 256];
        for (i, v) in t.iter_mut().enumerate() {
            *v = crate::image::srgb::srgb_eotf(i as f32 / 255.0);
        }
        t
    })
}

fn texel(img: &ImageDesc, x: i64, y: i64, enc: Encoding) -> Vec4 {
    let w = img.width as i64;
    let h = img.height as i64;
    let xi = x.rem_euclid(w) as usize;
    let yi = y.rem_euclid(h) as usize;
    let i = (yi * img.width as usize + xi) * 4;
    let px = &img.rgba8[i..i + 4];
    let lin = |b: u8| b as f32 / 255.0;
    match enc {
        Encoding::Linear => Vec4::new(lin(px[0]), lin(px[1]), lin(px[2]), lin(px[3])),
        Encoding::Srgb => {
            let lut = srgb_lut();
            Vec4::new(
                lut[px[0] as usize],
                lut[px[1] as usize],
                lut[px[2] as usize],
                lin(px[3]),
            )
        }
    }
}

/// Bilinearly filtered, repeat-wrapped lookup. Validation guarantees the image holds
/// `width*height*4` bytes; an empty image returns white.
pub fn sample(img: &ImageDesc, uv: Vec2, enc: Encoding) -> Vec4 {
    if img.width == 0 || img.height == 0 || img.rgba8.len() < (img.width * img.height * 4) as usize
    {
        return Vec4::ONE;
    }
    let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
    let x = uv.x * img.width as f32 - 0.5;
    let y = uv.y * img.height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let a = texel(img, x0, y0, enc);
    let b = texel(img, x0 + 1, y0, enc);
    let c = texel(img, x0, y0 + 1, enc);
    let d = texel(img, x0 + 1, y0 + 1, enc);
    a.lerp(b, fx).lerp(c.lerp(d, fx), fy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn srgb_decode_and_wrap() {
        let img = ImageDesc {
            name: "t".into(),
            width: 2,
            height: 1,
            rgba8: Arc::new(vec![255, 255, 255, 255, 188, 188, 188, 255]),
        };
        // Texel centres.
        let a = sample(&img, Vec2::new(0.25, 0.5), Encoding::Srgb);
        let b = sample(&img, Vec2::new(0.75, 0.5), Encoding::Srgb);
        assert!((a.x - 1.0).abs() < 1e-6);
        assert!((b.x - 0.5029).abs() < 1e-3, "{}", b.x);
        // Repeat wrapping: u + 1 is the same.
        assert_eq!(b, sample(&img, Vec2::new(1.75, 0.5), Encoding::Srgb));
        assert!(
            (sample(&img, Vec2::new(0.75, 0.5), Encoding::Linear).x - 188.0 / 255.0).abs() < 1e-6
        );
    }
}
