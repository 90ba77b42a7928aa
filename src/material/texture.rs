//! Textures: the images a scene carries ([`ImageDesc`]), a material's reference to one
//! ([`TextureRef`]: image, texture-coordinate set, KHR_texture_transform) and the **one**
//! lookup every texture read in the renderer goes through ([`TextureContext::lookup`]).
//!
//! Texture coordinates follow glTF: (0,0) is the top-left of the image, u to the right, v
//! down. A lookup picks the reference's coordinate set (TEXCOORD_0 or TEXCOORD_1, set 0 when
//! the mesh lacks the one asked for), applies its KHR_texture_transform (uv' = T·uv, the
//! extension's offset·rotation·scale matrix), then filters bilinearly with repeat wrapping
//! on the 8-bit RGBA texels. Colour textures are sRGB-encoded and decoded here (IEC
//! 61966-2-1); data textures (metallic-roughness, transmission, layer factors) are linear.

use glam::{Affine2, Vec2, Vec4};
use std::sync::{Arc, OnceLock};

/// A decoded image, 8 bits per channel RGBA, **as stored in the file** (colour textures are
/// sRGB-encoded; the material decides how to decode each channel).
#[derive(Debug, Clone)]
pub struct ImageDesc {
    /// Name for messages (`image 2 "checker.png"`).
    pub name: String,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major RGBA8 texels, top row first, `width*height*4` bytes.
    pub rgba8: Arc<Vec<u8>>,
}

/// How many texture-coordinate sets Iris reads (glTF TEXCOORD_0 and TEXCOORD_1).
pub const TEXCOORD_SETS: usize = 2;

/// A reference from a material to a texture image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextureRef {
    /// Index into the scene's images.
    pub image: usize,
    /// Which texture-coordinate set: 0 or 1 are read (TEXCOORD_0, TEXCOORD_1); a higher set
    /// reads set 0 (the loader warns).
    pub texcoord: u32,
    /// KHR_texture_transform of this reference, applied to the texture coordinate before
    /// the lookup (identity without the extension).
    pub transform: Affine2,
}

impl TextureRef {
    /// A reference to `image` through texture-coordinate set `texcoord`, untransformed.
    pub fn new(image: usize, texcoord: u32) -> Self {
        TextureRef {
            image,
            texcoord,
            transform: Affine2::IDENTITY,
        }
    }
}

/// The texture coordinates of one surface point: TEXCOORD_0 and TEXCOORD_1 (zero where the
/// mesh has none; set 1 equals set 0 on meshes without TEXCOORD_1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TexCoords(pub [Vec2; TEXCOORD_SETS]);

impl TexCoords {
    /// One set used for both (a mesh with TEXCOORD_0 only, or a test point).
    pub fn single(uv: Vec2) -> Self {
        TexCoords([uv; TEXCOORD_SETS])
    }

    /// The coordinates of set `set` (set 0 for sets Iris does not read).
    pub fn set(&self, set: u32) -> Vec2 {
        self.0.get(set as usize).copied().unwrap_or(self.0[0])
    }
}

/// How the texel bytes are decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// RGB are sRGB-encoded, alpha is linear.
    Srgb,
    /// All channels are linear.
    Linear,
}

/// Where textures are evaluated: the scene's images and one point's texture coordinates
/// (pbrt-v4's `TextureEvalContext`). Every texture read goes through [`Self::get`] or
/// [`Self::lookup`].
#[derive(Debug, Clone, Copy)]
pub struct TextureContext<'a> {
    /// The scene's images, indexed by [`TextureRef::image`].
    pub images: &'a [ImageDesc],
    /// The point's texture coordinates.
    pub uv: TexCoords,
}

impl<'a> TextureContext<'a> {
    /// A context for `images` at `uv`.
    pub fn new(images: &'a [ImageDesc], uv: TexCoords) -> Self {
        TextureContext { images, uv }
    }

    /// The texel value of `tex` here, decoded as `enc`; `None` without a texture (or with a
    /// reference to an image the scene lacks, which validation rejects).
    pub fn get(&self, tex: Option<TextureRef>, enc: Encoding) -> Option<Vec4> {
        let t = tex?;
        let img = self.images.get(t.image)?;
        let uv = t.transform.transform_point2(self.uv.set(t.texcoord));
        Some(sample(img, uv, enc))
    }

    /// [`Self::get`], white (1, 1, 1, 1) without a texture: the factor it multiplies is
    /// then used unchanged.
    pub fn lookup(&self, tex: Option<TextureRef>, enc: Encoding) -> Vec4 {
        self.get(tex, enc).unwrap_or(Vec4::ONE)
    }
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

/// Bilinearly filtered, repeat-wrapped lookup of one image at `uv` (already the set and the
/// transform a [`TextureRef`] asks for). Validation guarantees the image holds
/// `width*height*4` bytes; an empty image returns white.
fn sample(img: &ImageDesc, uv: Vec2, enc: Encoding) -> Vec4 {
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

    fn two_texels() -> ImageDesc {
        ImageDesc {
            name: "t".into(),
            width: 2,
            height: 1,
            rgba8: Arc::new(vec![255, 255, 255, 255, 188, 188, 188, 255]),
        }
    }

    #[test]
    fn srgb_decode_and_wrap() {
        let img = two_texels();
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

    #[test]
    fn lookup_applies_the_set_and_the_transform() {
        let images = [two_texels()];
        let (white, grey) = (Vec2::new(0.25, 0.5), Vec2::new(0.75, 0.5));
        let ctx = TextureContext::new(&images, TexCoords([white, grey]));
        let linear = |tex| ctx.lookup(Some(tex), Encoding::Linear).x;
        assert_eq!(linear(TextureRef::new(0, 0)), 1.0);
        assert_eq!(linear(TextureRef::new(0, 1)), 188.0 / 255.0);
        // Sets Iris does not read fall back to set 0.
        assert_eq!(linear(TextureRef::new(0, 5)), 1.0);
        // An offset of half the image moves set 0's white texel onto the grey one.
        let shifted = TextureRef {
            transform: Affine2::from_translation(Vec2::new(0.5, 0.0)),
            ..TextureRef::new(0, 0)
        };
        assert_eq!(linear(shifted), 188.0 / 255.0);
        // No texture: white, and `get` says there is none.
        assert_eq!(ctx.lookup(None, Encoding::Srgb), Vec4::ONE);
        assert_eq!(ctx.get(None, Encoding::Srgb), None);
        // A reference to a missing image reads as no texture.
        assert_eq!(ctx.get(Some(TextureRef::new(3, 0)), Encoding::Srgb), None);
    }
}
