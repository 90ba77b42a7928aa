//! KHR_texture_transform: an affine map applied to a texture reference's coordinates
//! before the lookup (KHR_texture_transform README, "glTF Schema Updates"):
//!
//! uv' = T · R · S · uv, with T = translate(offset), S = scale(scale) and
//! R = [[cos r, sin r], [−sin r, cos r]] for `rotation` r in radians.
//!
//! Texture coordinates are glTF's: (0,0) at the image's top-left, v down; the map is
//! applied in that space, so a rotation is counter-clockwise as seen in the image. A
//! `texCoord` inside the extension overrides the texture info's own. Values are only
//! checked to be finite (JSON numbers always are; the check guards the raw-JSON path).
//! KHR_mesh_quantization exporters (gltfpack) rely on this extension to dequantize
//! integer texture coordinates, so it is read wherever a texture is.

use glam::{Affine2, Vec2};
use serde_json::Value;

/// The KHR_texture_transform matrix T · R · S.
pub(crate) fn matrix(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> Affine2 {
    let (s, c) = rotation.sin_cos();
    Affine2::from_cols(
        Vec2::new(c * scale[0], -s * scale[0]),
        Vec2::new(s * scale[1], c * scale[1]),
        Vec2::from(offset),
    )
}

/// The transform of a texture info read by the `gltf` crate, and its `texCoord` override.
pub(super) fn of_info(info: &gltf::texture::Info<'_>) -> Result<(Affine2, Option<u32>), String> {
    match info.texture_transform() {
        None => Ok((Affine2::IDENTITY, None)),
        Some(t) => checked(t.offset(), t.rotation(), t.scale(), t.tex_coord()),
    }
}

/// The transform in a texture info given as raw JSON (`{"index": …, "extensions":
/// {"KHR_texture_transform": {…}}}`), for the material extensions the `gltf` crate does not
/// model; identity without the extension.
pub(crate) fn of_json(info: &Value) -> Result<(Affine2, Option<u32>), String> {
    let Some(t) = info
        .get("extensions")
        .and_then(|e| e.get("KHR_texture_transform"))
    else {
        return Ok((Affine2::IDENTITY, None));
    };
    let pair = |key: &str, default: [f32; 2]| -> Result<[f32; 2], String> {
        match t.get(key) {
            None => Ok(default),
            Some(Value::Array(a)) if a.len() == 2 => {
                let x = a[0].as_f64().ok_or(format!("{key}[0] is not a number"))?;
                let y = a[1].as_f64().ok_or(format!("{key}[1] is not a number"))?;
                Ok([x as f32, y as f32])
            }
            Some(_) => Err(format!("{key} must be an array of two numbers")),
        }
    };
    let rotation = match t.get("rotation") {
        None => 0.0,
        Some(v) => v.as_f64().ok_or("rotation is not a number")? as f32,
    };
    let tex_coord = match t.get("texCoord") {
        None => None,
        Some(v) => Some(
            v.as_u64()
                .and_then(|n| u32::try_from(n).ok())
                .ok_or("texCoord is not a non-negative integer")?,
        ),
    };
    checked(
        pair("offset", [0.0, 0.0])?,
        rotation,
        pair("scale", [1.0, 1.0])?,
        tex_coord,
    )
}

fn checked(
    offset: [f32; 2],
    rotation: f32,
    scale: [f32; 2],
    tex_coord: Option<u32>,
) -> Result<(Affine2, Option<u32>), String> {
    let all = [offset[0], offset[1], rotation, scale[0], scale[1]];
    if all.iter().any(|v| !v.is_finite()) {
        return Err(format!(
            "KHR_texture_transform has a non-finite value (offset {offset:?}, rotation {rotation}, scale {scale:?})"
        ));
    }
    Ok((matrix(offset, rotation, scale), tex_coord))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn order_is_scale_then_rotate_then_offset() {
        // The README's example: offset [0, 1], rotation π/2, scale [0.5, 0.5] maps the
        // unit square's corner (1, 0) to T·R·(0.5, 0) = (0, 1) + (0, −0.5).
        let m = matrix([0.0, 1.0], std::f32::consts::FRAC_PI_2, [0.5, 0.5]);
        let p = m.transform_point2(Vec2::new(1.0, 0.0));
        assert!((p - Vec2::new(0.0, 0.5)).length() < 1e-6, "{p}");
        let q = m.transform_point2(Vec2::new(0.0, 1.0));
        assert!((q - Vec2::new(0.5, 1.0)).length() < 1e-6, "{q}");
        // Identity parameters give the identity.
        assert_eq!(matrix([0.0, 0.0], 0.0, [1.0, 1.0]), Affine2::IDENTITY);
    }

    #[test]
    fn raw_json_reads_every_field_and_rejects_bad_ones() {
        let (m, tc) = of_json(&json!({"index": 0, "extensions": {"KHR_texture_transform":
            {"offset": [0.25, 0.5], "scale": [2.0, 4.0], "texCoord": 1}}}))
        .unwrap();
        assert_eq!(tc, Some(1));
        assert_eq!(
            m.transform_point2(Vec2::new(1.0, 1.0)),
            Vec2::new(2.25, 4.5)
        );
        assert_eq!(
            of_json(&json!({"index": 0})).unwrap(),
            (Affine2::IDENTITY, None)
        );
        for bad in [
            json!({"offset": [1.0]}),
            json!({"offset": "x"}),
            json!({"scale": [1.0, "y"]}),
            json!({"rotation": "r"}),
            json!({"texCoord": -1}),
        ] {
            let info = json!({"index": 0, "extensions": {"KHR_texture_transform": bad}});
            assert!(of_json(&info).is_err(), "{info}");
        }
    }
}
