//! A scene description's material ([`MaterialDesc`], what the glTF loader fills) as the
//! generator writes it: the constructors the shipped scenes start from, the checks the
//! writer relies on, and its glTF JSON (the inverse of `load::gltf::material` for factor
//! materials).
//!
//! What is written:
//! - the `pbrMetallicRoughness` factors;
//! - `emissive` (linear radiance, may exceed one) as `emissiveFactor`, the colour over its
//!   largest component, with that component as `KHR_materials_emissive_strength`;
//! - each KHR extension the material states ([`MaterialDesc::stated`]) or whose values
//!   differ from the spec defaults (ior 1.5, transmission 0, volume thickness 0 with white
//!   attenuation at +∞, dispersion 0, specular 1 and white, the layers' defaults);
//!   KHR_materials_volume_scatter for albedo scattering (Rayleigh scattering is Iris's
//!   `extras.iris_medium`);
//! - `alphaMode` and `doubleSided` when not the defaults, and the `extras` unchanged, which
//!   carry Iris's own keys.
//!
//! Textures and a measured metal (`conductor`, a render override) have no file form here
//! and are refused.
//!
//! Units: colours linear RGB; lengths metres; the volume's thickness is the typical
//! thickness rasterisers read.

use super::invalid::bad;
use super::json_number::{num, vec3};
use crate::error::Result;
use crate::material::{AlphaMode, ExplicitIor, MaterialDesc};
use crate::volume::{Phase, Scattering};
use glam::{Vec3, Vec4};
use serde_json::{json, Map, Value};
use std::collections::BTreeSet;

impl MaterialDesc {
    /// An opaque dielectric diffuse-looking material (metallic 0, roughness 1).
    pub fn diffuse(name: &str, color: Vec3) -> Self {
        MaterialDesc {
            name: name.into(),
            base_color: color.extend(1.0),
            metallic: 0.0,
            roughness: 1.0,
            ..MaterialDesc::default()
        }
    }

    /// A black diffuse surface emitting `radiance` (linear RGB) from its front face: an
    /// area light.
    pub fn emitter(name: &str, radiance: Vec3) -> Self {
        MaterialDesc {
            emissive: radiance,
            ..MaterialDesc::diffuse(name, Vec3::ZERO)
        }
    }

    /// Clear, smooth, fully transmissive glass bounding a solid volume of typical
    /// `thickness` (metres), with index of refraction `ior` and no absorption; its IOR,
    /// transmission and volume extensions are stated (written even at default values).
    pub fn clear_glass(name: &str, ior: f32, thickness: f32) -> Self {
        MaterialDesc {
            name: name.into(),
            base_color: Vec4::ONE,
            metallic: 0.0,
            roughness: 0.0,
            ior,
            transmission: 1.0,
            thickness,
            stated: glass_extensions(),
            ..MaterialDesc::default()
        }
    }
}

impl MaterialDesc {
    /// [`MaterialDesc::clear_glass`] of the named Sellmeier glass `glass` (Iris's
    /// `extras.iris_glass`, read as [`ExplicitIor::Glass`]), with `n_d` as the
    /// KHR_materials_ior other viewers use.
    pub fn named_glass(name: &str, glass: &str, n_d: f32, thickness: f32) -> Self {
        MaterialDesc {
            ior_model: Some(ExplicitIor::Glass(glass.into())),
            extras: Some(json!({ "iris_glass": glass })),
            ..MaterialDesc::clear_glass(name, n_d, thickness)
        }
    }
}

/// The extensions a written glass states: IOR, transmission and volume (written even at
/// their default values, so that other viewers see a solid refracting volume).
pub fn glass_extensions() -> BTreeSet<String> {
    ["ior", "transmission", "volume"]
        .map(|x| format!("KHR_materials_{x}"))
        .into()
}

fn in_unit(x: f32) -> bool {
    (0.0..=1.0).contains(&x)
}

fn unit_rgb(c: Vec3) -> bool {
    c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0
}

/// Material `i`: factors in their glTF ranges, finite non-negative ior, dispersion and
/// emission, valid volume and layer parameters, no textures and no measured metal.
pub(super) fn check_material(i: usize, m: &MaterialDesc) -> Result<()> {
    let el = format!("material {i} \"{}\"", m.name);
    let c = m.base_color;
    if !(c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0) {
        return Err(bad(&el, "base colour outside [0, 1]"));
    }
    if !in_unit(m.metallic) || !in_unit(m.roughness) || !in_unit(m.transmission) {
        return Err(bad(
            &el,
            "metallic, roughness or transmission outside [0, 1]",
        ));
    }
    if !(m.ior.is_finite() && m.ior >= 0.0) {
        return Err(bad(&el, "ior must be finite and ≥ 0"));
    }
    if !(m.dispersion.is_finite() && m.dispersion >= 0.0) {
        return Err(bad(&el, "dispersion must be finite and ≥ 0"));
    }
    if let Some(i) = &m.iridescence {
        i.check().map_err(|e| bad(&el, e))?;
    }
    if let Some(a) = &m.anisotropy {
        a.check().map_err(|e| bad(&el, e))?;
    }
    if m.textures().iter().any(|(_, t)| t.is_some()) {
        return Err(bad(&el, "the writer writes no textures"));
    }
    if m.conductor.is_some() {
        return Err(bad(
            &el,
            "a measured metal is a render override, not a file value",
        ));
    }
    if !(m.emissive.is_finite() && m.emissive.min_element() >= 0.0) {
        return Err(bad(&el, "emissive radiance must be finite and ≥ 0"));
    }
    let volume_ok = m.thickness.is_finite()
        && m.thickness >= 0.0
        && unit_rgb(m.attenuation_color)
        && m.attenuation_distance > 0.0;
    if !volume_ok {
        return Err(bad(&el, "invalid volume parameters"));
    }
    if let Err(property) = super::layers::check(&m.layers) {
        return Err(bad(&el, format!("{property} outside [0, 1]")));
    }
    Ok(())
}

/// Whether extension `name` is written: stated, or `differs` from its defaults.
fn written(m: &MaterialDesc, name: &str, differs: bool) -> bool {
    differs || m.stated.contains(name)
}

/// The material's glTF JSON (module docs); the extensions written are added to `used`.
pub(super) fn material(m: &MaterialDesc, used: &mut BTreeSet<String>) -> Value {
    let mut out = Map::new();
    out.insert("name".into(), json!(m.name));
    out.insert(
        "pbrMetallicRoughness".into(),
        json!({
            "baseColorFactor": m.base_color.to_array().map(num),
            "metallicFactor": num(m.metallic),
            "roughnessFactor": num(m.roughness),
        }),
    );
    let mut ext = Map::new();
    if m.emissive.max_element() > 0.0 {
        // emissiveFactor is limited to [0, 1]; the strength carries the magnitude.
        let strength = m.emissive.max_element();
        out.insert("emissiveFactor".into(), vec3(m.emissive / strength));
        if strength != 1.0 {
            ext.insert(
                "KHR_materials_emissive_strength".into(),
                json!({"emissiveStrength": num(strength)}),
            );
        }
    }
    if written(m, "KHR_materials_ior", m.ior != 1.5) {
        ext.insert("KHR_materials_ior".into(), json!({"ior": num(m.ior)}));
    }
    if written(m, "KHR_materials_transmission", m.transmission != 0.0) {
        ext.insert(
            "KHR_materials_transmission".into(),
            json!({"transmissionFactor": num(m.transmission)}),
        );
    }
    volume(m, &mut ext);
    if written(m, "KHR_materials_dispersion", m.dispersion != 0.0) {
        ext.insert(
            "KHR_materials_dispersion".into(),
            json!({"dispersion": num(m.dispersion)}),
        );
    }
    let specular_differs = m.specular != 1.0 || m.specular_color != Vec3::ONE;
    if written(m, "KHR_materials_specular", specular_differs) {
        ext.insert(
            "KHR_materials_specular".into(),
            json!({"specularFactor": num(m.specular), "specularColorFactor": vec3(m.specular_color)}),
        );
    }
    thin_film_and_anisotropy(m, &mut ext);
    super::layers::write(&m.layers, &m.stated, &mut ext);
    used.extend(ext.keys().cloned());
    if !ext.is_empty() {
        out.insert("extensions".into(), Value::Object(ext));
    }
    match m.alpha_mode {
        AlphaMode::Opaque => {}
        AlphaMode::Mask(cutoff) => {
            out.insert("alphaMode".into(), json!("MASK"));
            out.insert("alphaCutoff".into(), num(cutoff));
        }
        AlphaMode::Blend => {
            out.insert("alphaMode".into(), json!("BLEND"));
        }
    }
    if m.double_sided {
        out.insert("doubleSided".into(), json!(true));
    }
    if let Some(x) = &m.extras {
        out.insert("extras".into(), x.clone());
    }
    Value::Object(out)
}

/// KHR_materials_volume and, for albedo scattering, KHR_materials_volume_scatter.
fn volume(m: &MaterialDesc, ext: &mut Map<String, Value>) {
    let albedo = match m.scatter {
        Some(s) => match s.scattering {
            Scattering::Albedo { multiscatter } => Some((multiscatter, s.phase)),
            Scattering::Rayleigh { .. } => None,
        },
        None => None,
    };
    let differs = m.thickness != 0.0
        || m.attenuation_color != Vec3::ONE
        || m.attenuation_distance.is_finite()
        || albedo.is_some();
    if !written(m, "KHR_materials_volume", differs) {
        return;
    }
    let mut vol = Map::new();
    vol.insert("thicknessFactor".into(), num(m.thickness));
    vol.insert("attenuationColor".into(), vec3(m.attenuation_color));
    if m.attenuation_distance.is_finite() {
        vol.insert("attenuationDistance".into(), num(m.attenuation_distance));
    }
    ext.insert("KHR_materials_volume".into(), Value::Object(vol));
    if let Some((multiscatter, phase)) = albedo {
        let g = match phase {
            Phase::HenyeyGreenstein { g } => g,
            Phase::Isotropic | Phase::Rayleigh => 0.0,
        };
        ext.insert(
            "KHR_materials_volume_scatter".into(),
            json!({"multiscatterColor": vec3(multiscatter), "scatterAnisotropy": num(g)}),
        );
    }
}

/// KHR_materials_iridescence and KHR_materials_anisotropy (factors only).
fn thin_film_and_anisotropy(m: &MaterialDesc, ext: &mut Map<String, Value>) {
    if let Some(i) = &m.iridescence {
        ext.insert(
            "KHR_materials_iridescence".into(),
            json!({
                "iridescenceFactor": num(i.factor),
                "iridescenceIor": num(i.ior),
                "iridescenceThicknessMinimum": num(i.thickness_min),
                "iridescenceThicknessMaximum": num(i.thickness_max),
            }),
        );
    }
    if let Some(a) = &m.anisotropy {
        ext.insert(
            "KHR_materials_anisotropy".into(),
            json!({
                "anisotropyStrength": num(a.strength),
                "anisotropyRotation": num(a.rotation),
            }),
        );
    }
}
