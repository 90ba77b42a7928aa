//! Scattering inside a material's volume, into [`VolumeScatter`] (see [`crate::volume`]):
//!
//! - `KHR_materials_volume_scatter` (draft, glTF PR #2453) and its successor draft
//!   `KHR_materials_scatter` (PR #2579): `multiscatterColor` (linear RGB multiple-scattering
//!   albedo, default [0, 0, 0]: nothing scatters) and `scatterAnisotropy` (the
//!   Henyey–Greenstein g in (−1, 1), default 0). The extinction is KHR_materials_volume's
//!   attenuation. `scatterStrengthFactor` is not read (a warning says so when it is not 1).
//! - Material `extras.iris_medium` (Iris's own, for what the drafts cannot say):
//!   `{"rayleigh": S}` is Rayleigh scattering with σ_s(550 nm) = S per scene unit, λ⁻⁴ and
//!   the Rayleigh phase function, the attenuation then being absorption on top;
//!   `"anisotropy": g` replaces the phase function by Henyey–Greenstein. The extras win
//!   over the extensions.
//!
//! Malformed values (not numbers, the wrong length, g outside (−1, 1), negative or
//! non-finite coefficients) are `InvalidValue` errors naming the material and the field;
//! ranges are checked again for every source by `scene::validate`.

use super::{Ctx, Warnings};
use crate::error::{LoadError, LoadErrorKind};
use crate::volume::{Phase, Scattering, VolumeScatter};
use glam::Vec3;
use serde_json::Value;

/// The draft extensions read, in order of precedence.
pub(super) const EXTENSIONS: [&str; 2] = ["KHR_materials_scatter", "KHR_materials_volume_scatter"];

/// The material's scattering (module docs); `None` when it says nothing about it.
pub(super) fn read_scatter(
    ctx: &Ctx<'_>,
    m: &gltf::Material<'_>,
    element: &str,
    warnings: &mut Warnings,
) -> Result<Option<VolumeScatter>, LoadError> {
    let invalid = |detail: String| ctx.error(element, LoadErrorKind::InvalidValue, detail);
    if let Some(medium) = super::extras::extras_key(ctx, m.extras(), element, "iris_medium")? {
        return iris_medium(&medium).map(Some).map_err(invalid);
    }
    for name in EXTENSIONS {
        let Some(ext) = m.extension_value(name) else {
            continue;
        };
        let ext = ext
            .as_object()
            .ok_or_else(|| invalid(format!("{name} must be a JSON object")))?;
        let field = |key: &str| format!("{name}.{key}");
        let multiscatter = match ext.get("multiscatterColor") {
            None => Vec3::ZERO,
            Some(v) => rgb(v).ok_or_else(|| {
                invalid(format!(
                    "{} must be [r, g, b] numbers, found {v}",
                    field("multiscatterColor")
                ))
            })?,
        };
        let g = match ext.get("scatterAnisotropy") {
            None => 0.0,
            Some(v) => anisotropy(v)
                .map_err(|e| invalid(format!("{}: {e}", field("scatterAnisotropy"))))?,
        };
        if ext
            .get("scatterStrengthFactor")
            .and_then(Value::as_f64)
            .is_some_and(|s| s != 1.0)
        {
            warnings.ignored_properties.push(format!(
                "{element}: {} (not read)",
                field("scatterStrengthFactor")
            ));
        }
        return Ok(Some(VolumeScatter {
            scattering: Scattering::Albedo { multiscatter },
            phase: hg(g),
        }));
    }
    Ok(None)
}

/// `extras.iris_medium`: `{"rayleigh": S, "anisotropy": g}` (module docs).
fn iris_medium(v: &Value) -> Result<VolumeScatter, String> {
    let shape = || {
        format!("extras.iris_medium must be {{\"rayleigh\": S}} (optionally \"anisotropy\": g), found {v}")
    };
    let fields = v.as_object().ok_or_else(shape)?;
    if let Some(k) = fields
        .keys()
        .find(|k| !matches!(k.as_str(), "rayleigh" | "anisotropy"))
    {
        return Err(format!(
            "extras.iris_medium: unknown key {k:?} (use rayleigh, anisotropy)"
        ));
    }
    let s = fields
        .get("rayleigh")
        .and_then(Value::as_f64)
        .map(|s| s as f32)
        .ok_or_else(shape)?;
    if !(s.is_finite() && s >= 0.0) {
        return Err(format!(
            "extras.iris_medium.rayleigh = {s} must be a finite number >= 0"
        ));
    }
    let phase = match fields.get("anisotropy") {
        None => Phase::Rayleigh,
        Some(g) => hg(anisotropy(g).map_err(|e| format!("extras.iris_medium.anisotropy: {e}"))?),
    };
    Ok(VolumeScatter {
        scattering: Scattering::Rayleigh { at_550: s },
        phase,
    })
}

/// Henyey–Greenstein with mean cosine `g`, isotropic for 0.
fn hg(g: f32) -> Phase {
    if g == 0.0 {
        Phase::Isotropic
    } else {
        Phase::HenyeyGreenstein { g }
    }
}

/// An anisotropy value: a number in (−1, 1).
fn anisotropy(v: &Value) -> Result<f32, String> {
    let g = v.as_f64().ok_or_else(|| format!("{v} is not a number"))? as f32;
    if g.is_finite() && g > -1.0 && g < 1.0 {
        Ok(g)
    } else {
        Err(format!("{g} must lie in (-1, 1)"))
    }
}

/// Three numbers.
fn rgb(v: &Value) -> Option<Vec3> {
    let a = v.as_array()?;
    if a.len() != 3 {
        return None;
    }
    let c: Option<Vec<f32>> = a.iter().map(|x| x.as_f64().map(|x| x as f32)).collect();
    c.map(|c| Vec3::new(c[0], c[1], c[2]))
}
