//! Material `extras.iris_crystal` (Iris's own; docs/gem-optics.md): a birefringent crystal,
//! into [`CrystalDesc`].
//!
//! `{"stone": NAME}` takes the crystal table's entry ([`crate::spectrum::crystals`]);
//! `{"n": [n_o, n_e]}` (uniaxial) or `{"n": [n_α, n_β, n_γ]}` (biaxial) gives constant
//! principal indices instead (each from 1 to 4). `"optic_axis": [x, y, z]` is the principal
//! z axis (uniaxial: the optic axis c) in the mesh's frame, default +Y (the glTF up, the
//! table normal of Iris's gems); `"x_axis"` the principal x axis (made ⊥ the optic axis),
//! needed only to orient a biaxial crystal's other axes. Axes are directions of any length,
//! normalised safely ([`unit_direction`]: `[3e38, 3e38, 0]` is the diagonal). Malformed
//! values (unknown keys or stones, a zero or non-finite axis, indices out of range) are
//! `InvalidValue` errors naming the material and the field.

use super::extras::extras_key;
use super::Ctx;
use crate::error::{LoadError, LoadErrorKind};
use crate::material::crystal::check_indices;
use crate::material::{CrystalDesc, CrystalOptics};
use crate::math::unit_direction;
use glam::{DVec3, Vec3};
use serde_json::Value;

/// The material's crystal (module docs); `None` without `extras.iris_crystal`.
pub(super) fn read_crystal(
    ctx: &Ctx<'_>,
    m: &gltf::Material<'_>,
    element: &str,
) -> Result<Option<CrystalDesc>, LoadError> {
    let Some(v) = extras_key(ctx, m.extras(), element, "iris_crystal")? else {
        return Ok(None);
    };
    crystal(&v).map(Some).map_err(|d| {
        ctx.error(
            element,
            LoadErrorKind::InvalidValue,
            format!("extras.iris_crystal: {d}"),
        )
    })
}

/// The material's polarizer sheet, `extras.iris_polarizer = {"axis": [x, y, z]}` (the
/// transmission axis in the mesh's frame); `None` without it.
pub(super) fn read_polarizer(
    ctx: &Ctx<'_>,
    m: &gltf::Material<'_>,
    element: &str,
) -> Result<Option<Vec3>, LoadError> {
    let Some(v) = extras_key(ctx, m.extras(), element, "iris_polarizer")? else {
        return Ok(None);
    };
    let invalid = |d: String| ctx.error(element, LoadErrorKind::InvalidValue, d);
    let axis = v
        .as_object()
        .filter(|o| o.len() == 1)
        .and_then(|o| o.get("axis"))
        .ok_or_else(|| {
            invalid(format!(
                "extras.iris_polarizer must be {{\"axis\": [x, y, z]}}, found {v}"
            ))
        })?;
    direction(axis, "extras.iris_polarizer.axis")
        .map(Some)
        .map_err(invalid)
}

/// Parses the `iris_crystal` object.
pub fn crystal(v: &Value) -> Result<CrystalDesc, String> {
    let obj = v.as_object().ok_or_else(|| {
        format!("must be an object such as {{\"stone\": \"calcite\"}}, found {v}")
    })?;
    for k in obj.keys() {
        if !["stone", "n", "optic_axis", "x_axis"].contains(&k.as_str()) {
            return Err(format!(
                "unknown key {k:?} (use stone, n, optic_axis, x_axis)"
            ));
        }
    }
    let optics = match (obj.get("stone"), obj.get("n")) {
        (Some(_), Some(_)) => return Err("give either stone or n, not both".into()),
        (None, None) => return Err("needs stone (a crystal's name) or n (its indices)".into()),
        (Some(s), None) => {
            let name = s
                .as_str()
                .ok_or_else(|| format!("stone must be a string, found {s}"))?;
            let c = crate::spectrum::crystals::named(name).ok_or_else(|| {
                let names: Vec<&str> = crate::spectrum::crystals::CRYSTALS
                    .iter()
                    .map(|c| c.name)
                    .collect();
                format!("unknown stone {name:?} (known: {})", names.join(", "))
            })?;
            CrystalOptics::Table(c)
        }
        (None, Some(n)) => CrystalOptics::Indices(indices(n)?),
    };
    let c = match obj.get("optic_axis") {
        Some(a) => direction(a, "optic_axis")?,
        None => Vec3::Y,
    };
    let x = obj
        .get("x_axis")
        .map(|a| direction(a, "x_axis"))
        .transpose()?;
    CrystalDesc::oriented(optics, c, x)
}

/// `n`: two (uniaxial n_o, n_e) or three (n_α, n_β, n_γ) numbers, as principal x, y, z.
fn indices(n: &Value) -> Result<[f32; 3], String> {
    let list: Vec<f32> = n
        .as_array()
        .and_then(|a| a.iter().map(|x| x.as_f64().map(|v| v as f32)).collect())
        .ok_or_else(|| format!("n must be [n_o, n_e] or [n_alpha, n_beta, n_gamma], found {n}"))?;
    check_indices(&list).map_err(|e| format!("n: {e}"))?;
    match list[..] {
        [o, e] => Ok([o, o, e]),
        [a, b, g] if a <= b && b <= g => Ok([a, b, g]),
        [_, _, _] => Err(format!("n = {list:?}: give n_alpha <= n_beta <= n_gamma")),
        _ => Err(format!("n has {} numbers; give 2 or 3", list.len())),
    }
}

/// A direction `[x, y, z]` as a unit vector, normalised in f64 before any rounding to f32
/// ([`unit_direction`]: any finite non-zero numbers, however large or small); the error
/// names `what` and the value as written.
fn direction(a: &Value, what: &str) -> Result<Vec3, String> {
    let v: Option<Vec<f64>> = a
        .as_array()
        .and_then(|a| a.iter().map(Value::as_f64).collect());
    match v.as_deref() {
        Some(&[x, y, z]) => {
            unit_direction(DVec3::new(x, y, z)).map_err(|why| format!("{what} {why}: {a}"))
        }
        _ => Err(format!("{what} must be [x, y, z], found {a}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn stones_and_indices_parse_and_bad_values_are_named() {
        let c = crystal(&json!({"stone": "calcite", "optic_axis": [0, 0, 3]})).unwrap();
        assert!((c.axes.z_axis - Vec3::Z).length() < 1e-6);
        let c = crystal(&json!({"n": [1.658, 1.486]})).unwrap();
        assert_eq!(c.indices(500.0), [1.658, 1.658, 1.486]);
        assert!((c.axes.z_axis - Vec3::Y).length() < 1e-6);
        for (bad, says) in [
            (json!({"stone": "calcite", "optic_axis": [0, 0, 0]}), "zero"),
            (json!({"n": [1.6, 0.9]}), "index 2"),
            (json!({"n": [1.6, 1.5, 1.7]}), "n_alpha <= n_beta"),
            (json!({"n": [1.6]}), "give 2 or 3"),
            (json!({"stone": "unobtainium"}), "unknown stone"),
            (
                json!({"stone": "calcite", "axis": [0, 1, 0]}),
                "unknown key",
            ),
            (json!({"optic_axis": [0, 1, 0]}), "needs stone"),
            (
                json!({"n": [1.6, 1.5], "optic_axis": [0, "a", 0]}),
                "optic_axis must be",
            ),
            (json!("calcite"), "must be an object"),
        ] {
            let e = crystal(&bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }
}
