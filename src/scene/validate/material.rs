//! Material and image checks (part of [`validate`](super::validate)).
//!
//! Rules: texture references must name an existing image (`IndexOutOfRange`); an image
//! holds exactly `width·height·4` bytes (`MissingBuffer`). Every scalar must be finite
//! (`InvalidValue` naming the field; `attenuation_distance` may be +∞). The IOR may not be
//! NaN, infinite or negative (`InvalidIor`); 0 is KHR_materials_ior's special mode; values
//! in (0, 1) model a bubble (e.g. air in water) and only warn. A Cauchy model needs finite
//! `b > 0`, `c ≥ 0`, a Sellmeier model finite `b_i, c_i ≥ 0`, and a glass name must be one
//! of `spectrum::ior::KNOWN_NAMES` (`InvalidIor`); a model with a resonance (pole) inside
//! the sampled range `LAMBDA_MIN`–`LAMBDA_MAX` (360–830 nm) is `InvalidIor` too; every material then resolves to exactly one `spectrum::IorModel`
//! ([`MaterialDesc::spectral_ior`]: `ior` 0 > explicit model > KHR dispersion > constant).
//! `ior` 0 with an explicit model or `dispersion > 0` warns that dispersion is off. Unit-interval factors (base colour, metallic,
//! roughness, transmission, specular, attenuation colour, alpha cutoff) outside [0, 1] are
//! clamped with one warning per material; a negative specular colour is clamped to 0.
//! `attenuation_distance > 0`, `thickness ≥ 0`, `dispersion ≥ 0` and `emissive ≥ 0` are
//! errors when violated (`InvalidValue`), as is an `emission_spectrum` blackbody outside
//! [`BLACKBODY_KELVIN`](crate::spectrum::BLACKBODY_KELVIN).

use super::{element, fail};
use crate::error::{LoadError, LoadErrorKind};
use crate::material::{AlphaMode, ExplicitIor, ImageDesc, MaterialDesc};
use crate::scene::desc::SceneDesc;
use crate::spectrum::{LAMBDA_MAX, LAMBDA_MIN};
use glam::Vec3;
use std::path::Path;

pub(super) fn check_images(src: &Path, images: &[ImageDesc]) -> Result<(), LoadError> {
    for (i, image) in images.iter().enumerate() {
        let expected = u64::from(image.width) * u64::from(image.height) * 4;
        let actual = image.rgba8.len() as u64;
        if actual != expected {
            return Err(fail(
                src,
                &element(&image.name, "image", i),
                LoadErrorKind::MissingBuffer,
                format!(
                    "{actual} bytes of pixel data, expected {}×{}×4 = {expected}",
                    image.width, image.height
                ),
            ));
        }
    }
    Ok(())
}

pub(super) fn check_material(
    src: &Path,
    index: usize,
    m: &mut MaterialDesc,
    image_count: usize,
    warnings: &mut Vec<String>,
) -> Result<(), LoadError> {
    let name = element(&m.name, "material", index);
    let invalid = |kind, detail: String| fail(src, &name, kind, detail);
    for (field, texture) in m.textures() {
        if let Some(t) = texture.filter(|t| t.image >= image_count) {
            return Err(invalid(
                LoadErrorKind::IndexOutOfRange,
                format!("{field} refers to image {} ({image_count} images)", t.image),
            ));
        }
    }
    let extension_rules = [
        m.iridescence.map(|i| i.check()),
        m.anisotropy.map(|a| a.check()),
        m.crystal.map(|_| crystal_rule(m)),
    ];
    for rule in extension_rules.into_iter().flatten() {
        rule.map_err(|detail| invalid(LoadErrorKind::InvalidValue, detail))?;
    }
    if let Some(axis) = m.polarizer {
        m.polarizer = Some(
            polarizer_rule(m, axis)
                .map_err(|detail| invalid(LoadErrorKind::InvalidValue, detail))?,
        );
    }

    let cutoff = match m.alpha_mode {
        AlphaMode::Mask(c) => c,
        _ => 0.5,
    };
    let scalars: [(&str, &[f32]); 11] = [
        ("baseColor", &m.base_color.to_array()),
        ("metallic", &[m.metallic]),
        ("roughness", &[m.roughness]),
        ("emissive", &m.emissive.to_array()),
        ("transmission", &[m.transmission]),
        ("thickness", &[m.thickness]),
        ("attenuationColor", &m.attenuation_color.to_array()),
        ("specular", &[m.specular]),
        ("specularColor", &m.specular_color.to_array()),
        ("dispersion", &[m.dispersion]),
        ("alphaCutoff", &[cutoff]),
    ];
    for (field, values) in scalars {
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(invalid(
                LoadErrorKind::InvalidValue,
                format!("{field} is {v} (must be finite)"),
            ));
        }
    }
    if m.attenuation_distance.is_nan() || m.attenuation_distance <= 0.0 {
        return Err(invalid(
            LoadErrorKind::InvalidValue,
            format!(
                "attenuationDistance is {} (must be > 0)",
                m.attenuation_distance
            ),
        ));
    }
    for (field, value) in [
        ("thickness", m.thickness),
        ("dispersion", m.dispersion),
        ("emissive", m.emissive.min_element()),
    ] {
        if value < 0.0 {
            return Err(invalid(
                LoadErrorKind::InvalidValue,
                format!("{field} is negative ({value})"),
            ));
        }
    }
    if let Some(Err(e)) = m.emission_spectrum.map(|s| s.check()) {
        return Err(invalid(
            LoadErrorKind::InvalidValue,
            format!("iris_spectrum: {e}"),
        ));
    }
    if let Some(spectrum) = m.emission_spectrum.filter(|_| m.emissive == Vec3::ZERO) {
        warnings.push(format!(
            "{name}: iris_spectrum {spectrum} has no effect without an emissive colour"
        ));
    }
    check_ior(m, &name, warnings).map_err(|d| invalid(LoadErrorKind::InvalidIor, d))?;
    clamp_factors(m, &name, warnings);
    Ok(())
}

/// IOR and IOR-model rules; `Err` carries the detail of an `InvalidIor` error.
fn check_ior(m: &MaterialDesc, name: &str, warnings: &mut Vec<String>) -> Result<(), String> {
    let ior = m.ior;
    if !ior.is_finite() || ior < 0.0 {
        return Err(format!("ior is {ior} (must be finite and ≥ 0)"));
    }
    if ior > 0.0 && ior < 1.0 {
        warnings.push(format!(
            "{name}: ior {ior} < 1 is outside KHR_materials_ior's range; kept (a bubble, e.g. air in water)"
        ));
    }
    if let Some(ExplicitIor::Cauchy { b, c }) = m.ior_model {
        if !(b.is_finite() && c.is_finite() && b > 0.0 && c >= 0.0) {
            return Err(format!(
                "Cauchy model b = {b}, c = {c} (needs finite b > 0 and c ≥ 0)"
            ));
        }
    }
    if let Some(ExplicitIor::Sellmeier { b, c }) = m.ior_model {
        let bad = |v: &f32| !v.is_finite() || *v < 0.0;
        if b.iter().chain(&c).any(bad) {
            return Err(format!(
                "Sellmeier model b = {b:?}, c = {c:?} (needs finite b ≥ 0 and c ≥ 0 µm²)"
            ));
        }
    }
    // An unknown name fails even under ior 0, so a typo never goes unnoticed.
    if let Some(ExplicitIor::Glass(glass)) = &m.ior_model {
        crate::spectrum::IorModel::named(glass).map_err(|e| e.to_string())?;
    }
    if ior == 0.0 {
        let ignored = match (&m.ior_model, m.dispersion > 0.0) {
            (Some(ExplicitIor::Glass(glass)), _) => Some(format!("iris_glass \"{glass}\"")),
            (Some(ExplicitIor::Cauchy { .. }), _) => Some("the Cauchy model".to_string()),
            (Some(ExplicitIor::Sellmeier { .. }), _) => Some("the Sellmeier model".to_string()),
            (None, true) => Some(format!("dispersion {}", m.dispersion)),
            (None, false) => None,
        };
        if let Some(ignored) = ignored {
            warnings.push(format!(
                "{name}: ior 0 (KHR_materials_ior infinite-IOR mode) has no dispersion; {ignored} ignored"
            ));
        }
    }
    let model = m.spectral_ior().map_err(|e| e.to_string())?;
    if let Some(pole) = model.pole_in(LAMBDA_MIN, LAMBDA_MAX) {
        return Err(format!(
            "Sellmeier resonance at {pole:.1} nm lies inside the sampled range \
             {LAMBDA_MIN}–{LAMBDA_MAX} nm, where n(λ) diverges; move the pole (√C_i, µm) \
             outside it"
        ));
    }
    Ok(())
}

/// Clamps unit-interval factors (and negative specular colour), noting each change.
fn clamp_factors(m: &mut MaterialDesc, name: &str, warnings: &mut Vec<String>) {
    let mut notes = Vec::new();
    let mut unit = |field: &str, v: &mut f32| {
        let c = v.clamp(0.0, 1.0);
        if c != *v {
            notes.push(format!("{field} {v} → {c}"));
            *v = c;
        }
    };
    for (k, ch) in ["r", "g", "b", "a"].iter().enumerate() {
        unit(&format!("baseColor.{ch}"), &mut m.base_color[k]);
    }
    unit("metallic", &mut m.metallic);
    unit("roughness", &mut m.roughness);
    unit("transmission", &mut m.transmission);
    unit("specular", &mut m.specular);
    for (k, ch) in ["r", "g", "b"].iter().enumerate() {
        unit(
            &format!("attenuationColor.{ch}"),
            &mut m.attenuation_color[k],
        );
    }
    if let AlphaMode::Mask(c) = &mut m.alpha_mode {
        unit("alphaCutoff", c);
    }
    for (k, ch) in ["r", "g", "b"].iter().enumerate() {
        let v = &mut m.specular_color[k];
        if *v < 0.0 {
            notes.push(format!("specularColor.{ch} {v} → 0"));
            *v = 0.0;
        }
    }
    if !notes.is_empty() {
        warnings.push(format!("{name}: clamped: {}", notes.join(", ")));
    }
}

/// What the material extensions cannot do in this scene, one warning per kind: meshes whose
/// anisotropic material has neither TANGENT nor TEXCOORD_0 (the brushing direction falls
/// back to an arbitrary, deterministic frame), and iridescent materials that transmit (the
/// film is applied to the opaque lobes' reflection only; the transmissive lobe keeps the
/// plain dielectric Fresnel).
pub(super) fn extension_warnings(desc: &SceneDesc) -> Vec<String> {
    let mut out = Vec::new();
    let tangentless: Vec<&str> = desc
        .meshes
        .iter()
        .filter(|m| {
            m.material
                .and_then(|i| desc.materials.get(i))
                .is_some_and(MaterialDesc::is_anisotropic)
                && m.tangents.is_empty()
                && m.uvs.is_empty()
        })
        .map(|m| m.name.as_str())
        .collect();
    if !tangentless.is_empty() {
        out.push(format!(
            "KHR_materials_anisotropy without TANGENT or TEXCOORD_0: the brushing direction is arbitrary on {}",
            short(&tangentless)
        ));
    }
    let transmissive: Vec<&str> = desc
        .materials
        .iter()
        .filter(|m| m.transmission > 0.0 && m.iridescence.is_some_and(|i| i.factor > 0.0))
        .map(|m| m.name.as_str())
        .collect();
    if !transmissive.is_empty() {
        out.push(format!(
            "KHR_materials_iridescence on transmissive materials is applied to their opaque reflection only (the transmission lobe keeps the plain Fresnel): {}",
            short(&transmissive)
        ));
    }
    out
}

/// The first six names, then how many more.
fn short(names: &[&str]) -> String {
    let shown = names.iter().take(6).copied().collect::<Vec<_>>().join(", ");
    match names.len().saturating_sub(6) {
        0 => shown,
        more => format!("{shown} and {more} more"),
    }
}

/// A crystal (`extras.iris_crystal`) is a volume: transmissive with a thickness.
fn crystal_rule(m: &MaterialDesc) -> Result<(), String> {
    if m.transmission > 0.0 && m.thickness > 0.0 && m.metallic < 1.0 {
        Ok(())
    } else {
        Err("extras.iris_crystal needs a transmissive volume (KHR_materials_transmission > 0 and KHR_materials_volume thicknessFactor > 0, not metallic)".into())
    }
}

/// A polarizer sheet (`extras.iris_polarizer`) is thin-walled and transmissive, with a
/// direction: its axis `axis` as a unit vector.
fn polarizer_rule(m: &MaterialDesc, axis: Vec3) -> Result<Vec3, String> {
    let axis = crate::math::unit_direction(axis.as_dvec3())
        .map_err(|why| format!("extras.iris_polarizer.axis {why}: {axis}"))?;
    if m.transmission > 0.0 && m.thickness == 0.0 && m.metallic < 1.0 {
        Ok(axis)
    } else {
        Err("extras.iris_polarizer needs a thin-walled transmissive surface (KHR_materials_transmission > 0, no KHR_materials_volume thickness, not metallic)".into())
    }
}
