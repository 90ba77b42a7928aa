#![allow(dead_code)]
//! Block textures and KHR_texture_transform baked into pixels.
//!
//! The transform is the extension's own definition (KHR_texture_transform README, "glTF
//! Schema Updates"): uv' = T · R · S · uv with R = [[cos r, sin r], [−sin r, cos r]], in
//! glTF texture space ((0, 0) top-left, v down). [`bake`] writes the image B whose lookup
//! at uv equals the lookup of A at uv′: it requires every texel centre of B to map onto a
//! texel centre of A, so the map between the two texel lattices is a lattice isometry
//! (offsets a multiple of A's texel, rotation a multiple of 90°, B's texel the image of
//! A's under the scale) and bilinear filtering with repeat wrapping gives the same function
//! of uv from both, up to float rounding: the only difference a correct renderer may show
//! between the two files is sample noise.

use image::{Rgba, RgbaImage};

/// The parameters of a KHR_texture_transform.
#[derive(Clone, Copy, Debug)]
pub struct Transform {
    pub offset: [f32; 2],
    /// Radians, counter-clockwise in the image.
    pub rotation: f32,
    pub scale: [f32; 2],
}

impl Transform {
    /// The extension object (`texCoord` added when given).
    pub fn json(&self, tex_coord: Option<u32>) -> serde_json::Value {
        let mut v = serde_json::json!({"offset": self.offset, "rotation": self.rotation,
                                       "scale": self.scale});
        if let Some(t) = tex_coord {
            v["texCoord"] = t.into();
        }
        v
    }

    /// uv′ = T · R · S · uv (in f64, so the bake is exact).
    pub fn apply(&self, uv: [f64; 2]) -> [f64; 2] {
        let (s, c) = f64::from(self.rotation).sin_cos();
        let (x, y) = (
            uv[0] * f64::from(self.scale[0]),
            uv[1] * f64::from(self.scale[1]),
        );
        [
            c * x + s * y + f64::from(self.offset[0]),
            -s * x + c * y + f64::from(self.offset[1]),
        ]
    }
}

/// The offset, rotation and scale together: offset by (2, 1) texels of an 8-texel image,
/// a quarter turn, scale 2. Each part changes a half/half mask's image.
pub const COMBINED: Transform = Transform {
    offset: [0.25, 0.125],
    rotation: std::f32::consts::FRAC_PI_2,
    scale: [2.0, 2.0],
};

/// An offset of a quarter of the image along u and a quarter turn, no scale: moves a
/// quadrant to another place at its own size (features a blurring renderer still
/// resolves).
pub const QUARTER_SHIFT: Transform = Transform {
    offset: [0.25, 0.0],
    rotation: std::f32::consts::FRAC_PI_2,
    scale: [1.0, 1.0],
};

/// An `n × n` image with `on` where `mask(x, y)` (texel indices) and `off` elsewhere.
pub fn blocks(n: u32, mask: impl Fn(u32, u32) -> bool, on: [u8; 4], off: [u8; 4]) -> RgbaImage {
    RgbaImage::from_fn(n, n, |x, y| Rgba(if mask(x, y) { on } else { off }))
}

/// The left half of an `n`-texel image: the mask every feature test starts from.
pub fn left_half(n: u32) -> impl Fn(u32, u32) -> bool {
    move |x, _| x < n / 2
}

/// The image B (`size × size`) with lookup(B, uv) = lookup(A, t(uv)) (see the module doc);
/// panics when a texel centre of B does not land on a texel centre of A.
pub fn bake(a: &RgbaImage, t: &Transform, size: u32) -> RgbaImage {
    let (aw, ah) = (i64::from(a.width()), i64::from(a.height()));
    RgbaImage::from_fn(size, size, |x, y| {
        let uv = [
            (f64::from(x) + 0.5) / f64::from(size),
            (f64::from(y) + 0.5) / f64::from(size),
        ];
        let p = t.apply(uv);
        let (fx, fy) = (p[0] * aw as f64 - 0.5, p[1] * ah as f64 - 0.5);
        let (ix, iy) = (fx.round(), fy.round());
        assert!(
            (fx - ix).abs() < 1e-6 && (fy - iy).abs() < 1e-6,
            "texel ({x}, {y}) of the baked image maps to ({fx}, {fy}) of the source, not a texel centre: {t:?}"
        );
        *a.get_pixel(
            (ix as i64).rem_euclid(aw) as u32,
            (iy as i64).rem_euclid(ah) as u32,
        )
    })
}
