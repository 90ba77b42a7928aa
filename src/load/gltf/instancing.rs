//! EXT_mesh_gpu_instancing: a node's mesh drawn once per instance (EXT_mesh_gpu_instancing
//! README). The node's `extensions.EXT_mesh_gpu_instancing.attributes` name accessors
//! `TRANSLATION` (VEC3 float), `ROTATION` (VEC4 unit quaternion x, y, z, w: float or
//! normalized byte/short) and `SCALE` (VEC3 float), one element per instance; a missing
//! attribute is the identity. Instance i is placed at `node_world · T_i · R_i · S_i`; the
//! node's children are not instanced (the spec's rule). Other attributes (custom `_ID`
//! ones) are ignored.
//!
//! Every attribute must have the same count ≥ 1; accessors are read through the loader's
//! bounds-checked reads, so a hostile count is limited by the buffer's bytes, and the
//! scene's triangle bound applies to the expanded instances.

use super::accessor::read_floats;
use super::Ctx;
use crate::error::{LoadError, LoadErrorKind};
use glam::{Mat4, Quat, Vec3};
use serde_json::Value;

/// The world matrices of `node`'s mesh instances under `world`: `[world]` without the
/// extension, one per instance with it. `element` names the node for errors.
pub(super) fn instance_transforms(
    ctx: &Ctx<'_>,
    node: &gltf::Node<'_>,
    world: Mat4,
    element: &str,
) -> Result<Vec<Mat4>, LoadError> {
    let Some(ext) = node.extension_value("EXT_mesh_gpu_instancing") else {
        return Ok(vec![world]);
    };
    let invalid = |detail: String| {
        ctx.error(
            element,
            LoadErrorKind::InvalidValue,
            format!("EXT_mesh_gpu_instancing: {detail}"),
        )
    };
    let Some(attributes) = ext.get("attributes").and_then(Value::as_object) else {
        return Err(invalid("`attributes` must be an object".into()));
    };
    let accessor = |name: &str| -> Result<Option<gltf::Accessor<'_>>, LoadError> {
        let Some(v) = attributes.get(name) else {
            return Ok(None);
        };
        let index = v
            .as_u64()
            .and_then(|i| usize::try_from(i).ok())
            .ok_or_else(|| invalid(format!("{name} is not an accessor index")))?;
        ctx.doc.accessors().nth(index).map(Some).ok_or_else(|| {
            invalid(format!(
                "{name} refers to accessor {index}, which does not exist"
            ))
        })
    };
    let read3 = |name: &str| -> Result<Option<Vec<Vec3>>, LoadError> {
        match accessor(name)? {
            None => Ok(None),
            Some(acc) => read_floats::<3>(ctx, &acc)
                .map(|v| Some(v.into_iter().map(Vec3::from).collect()))
                .map_err(|e| {
                    ctx.error(
                        element,
                        e.kind,
                        format!("EXT_mesh_gpu_instancing {name}: {}", e.detail),
                    )
                }),
        }
    };
    let translation = read3("TRANSLATION")?;
    let scale = read3("SCALE")?;
    let rotation = match accessor("ROTATION")? {
        None => None,
        Some(acc) => Some(read_floats::<4>(ctx, &acc).map_err(|e| {
            ctx.error(
                element,
                e.kind,
                format!("EXT_mesh_gpu_instancing ROTATION: {}", e.detail),
            )
        })?),
    };
    let counts: Vec<(&str, usize)> = [
        ("TRANSLATION", translation.as_ref().map(Vec::len)),
        ("ROTATION", rotation.as_ref().map(Vec::len)),
        ("SCALE", scale.as_ref().map(Vec::len)),
    ]
    .into_iter()
    .filter_map(|(n, c)| c.map(|c| (n, c)))
    .collect();
    let Some(&(_, count)) = counts.first() else {
        return Err(invalid(
            "no TRANSLATION, ROTATION or SCALE attribute".into(),
        ));
    };
    if count == 0 || counts.iter().any(|&(_, c)| c != count) {
        return Err(invalid(format!(
            "attribute counts must be equal and at least 1, got {counts:?}"
        )));
    }
    (0..count)
        .map(|i| {
            let t = translation.as_ref().map_or(Vec3::ZERO, |v| v[i]);
            let s = scale.as_ref().map_or(Vec3::ONE, |v| v[i]);
            let r = match &rotation {
                None => Quat::IDENTITY,
                Some(v) => {
                    let q = Quat::from_array(v[i]);
                    let len = q.length();
                    // Quantized quaternions are only approximately unit length.
                    if !(len > 0.5 && len < 1.5 && q.is_finite()) {
                        return Err(invalid(format!(
                            "ROTATION of instance {i} is not a unit quaternion ({:?})",
                            v[i]
                        )));
                    }
                    q / len
                }
            };
            if !(t.is_finite() && s.is_finite()) {
                return Err(invalid(format!("instance {i} has a non-finite transform")));
            }
            Ok(world * Mat4::from_scale_rotation_translation(s, r, t))
        })
        .collect()
}
