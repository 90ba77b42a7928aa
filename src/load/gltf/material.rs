//! Materials (glTF 2.0 §3.9 metallic-roughness) plus the KHR extensions Iris reads, into
//! [`MaterialDesc`]. Absent properties take the spec defaults (see `MaterialDesc::default`).
//!
//! - Colours are linear (factors are stored linear by the spec); textures are referenced,
//!   not decoded here, except that their images are decoded once by `source::ImageCache`.
//! - `KHR_materials_ior.ior` is copied as written, including the special value 0
//!   (infinite IOR) and values in (0,1) such as 0.8 for a bubble in water; `scene::validate`
//!   judges them.
//! - `KHR_materials_emissive_strength` multiplies `emissiveFactor`.
//! - `KHR_materials_volume.attenuationDistance` defaults to +∞ (never 0).
//! - `KHR_materials_dispersion.dispersion` (= 20/V_d) is read from the raw extension JSON,
//!   which the `gltf` crate does not type.
//! - KHR_materials_iridescence and KHR_materials_anisotropy: `super::iridescence_anisotropy`.
//! - KHR_materials_volume_scatter / KHR_materials_scatter and `extras.iris_medium`:
//!   `super::scatter`.
//! - Material `extras` (`docs/spectral.md`, "IOR models"): `{"iris_glass": "N-BK7"}` names a
//!   built-in Sellmeier glass (`spectrum::ior::KNOWN_NAMES`, case-insensitive) and gives
//!   `ExplicitIor::Glass`; `{"cauchy": {"b": B, "c": C}}` gives `ExplicitIor::Cauchy`
//!   (n(λ) = B + C/λ², λ in µm, C in µm²; finite B ≥ 1 and C ≥ 0). Both on one material,
//!   a non-string name or an unknown name are `InvalidValue` errors naming the material.
//!   `{"sellmeier": {"b": [B1, …], "c": [C1, …]}}` (1–4 terms, C in µm²) gives
//!   `ExplicitIor::Sellmeier`; validation rejects a resonance √C inside 360–830 nm.
//!   Either overrides KHR_materials_dispersion (the KHR values stay the fallback other
//!   viewers use); `ior: 0` overrides both (see `MaterialDesc::spectral_ior`).
//! - `extras.iris_spectrum` (material or KHR_lights_punctual light, [`iris_spectrum`]):
//!   `"D65"`, `"sun"`, `{"blackbody": K}` or `"blackbody K"` (case-insensitive, K in
//!   1000–40000) gives [`EmissionSpectrum`], the emission's spectral shape (Y = 1); the
//!   colour / `emissiveFactor` then acts as a filter. Anything else is `InvalidValue`
//!   naming the element and `extras.iris_spectrum`.

use super::extras::extras_key;
use super::material_layers;
use super::source::ImageCache;
use super::{label, spec_gloss, texture_source, texture_transform, unlit, Ctx, Warnings};
use crate::error::{LoadError, LoadErrorKind};
use crate::material::texture::TEXCOORD_SETS;
use crate::material::{AlphaMode, ExplicitIor, ImageDesc, MaterialDesc, TextureRef};
use crate::spectrum::EmissionSpectrum;
use glam::{Vec3, Vec4};
use serde_json::Value;

/// Reads every material of the document (index = glTF material index) and decodes the
/// images their base colour, metallic-roughness, emissive and transmission textures use.
pub(super) fn read_materials(
    ctx: &Ctx<'_>,
    used: &std::collections::BTreeSet<usize>,
    warnings: &mut Warnings,
) -> Result<(Vec<MaterialDesc>, Vec<ImageDesc>, usize), LoadError> {
    let mut images = ImageCache::default();
    let mut materials = Vec::new();
    let mut skipped = 0;
    for (index, material) in ctx.doc.materials().enumerate() {
        let textures = if used.contains(&index) {
            Some(&mut images)
        } else {
            None
        };
        let (m, s) = read_material(ctx, index, &material, textures, warnings)?;
        materials.push(m);
        skipped += s;
    }
    Ok((materials, images.into_images(), skipped))
}

/// Resolves a material's texture references to decoded images (through the document's
/// one [`ImageCache`]), counting the slots of an unused material it leaves undecoded and
/// noting what the loader warns about (texCoord sets, undecodable sources).
struct TextureResolver<'a> {
    /// `None` when no mesh uses the material: textures are counted, not decoded.
    images: Option<&'a mut ImageCache>,
    element: &'a str,
    skipped: usize,
    texcoord_sets: Vec<String>,
    undecodable: Vec<String>,
}

impl TextureResolver<'_> {
    /// (slot, glTF texture, texCoord, KHR_texture_transform) → the decoded image's reference.
    fn resolve(
        &mut self,
        ctx: &Ctx<'_>,
        slot: &str,
        tex: &gltf::Texture<'_>,
        texcoord: u32,
        transform: glam::Affine2,
    ) -> Result<Option<TextureRef>, LoadError> {
        let Some(images) = self.images.as_deref_mut() else {
            self.skipped += 1;
            return Ok(None);
        };
        let Some(source) = texture_source::image_of(ctx.doc, tex) else {
            self.undecodable.push(format!("{} {slot}", self.element));
            return Ok(None);
        };
        let image = images.get(ctx, source)?;
        if texcoord >= TEXCOORD_SETS as u32 {
            self.texcoord_sets
                .push(format!("{} {slot} (texCoord {texcoord})", self.element));
        }
        Ok(Some(TextureRef {
            image,
            texcoord,
            transform,
        }))
    }

    /// A core `textureInfo` typed by the `gltf` crate, with its KHR_texture_transform (whose
    /// `texCoord` overrides the info's).
    fn info(
        &mut self,
        ctx: &Ctx<'_>,
        slot: &str,
        info: Option<gltf::texture::Info<'_>>,
    ) -> Result<Option<TextureRef>, LoadError> {
        let Some(info) = info else { return Ok(None) };
        let (transform, texcoord_override) = texture_transform::of_info(&info).map_err(|e| {
            ctx.error(
                self.element,
                LoadErrorKind::InvalidValue,
                format!("{slot}: {e}"),
            )
        })?;
        let texcoord = texcoord_override.unwrap_or(info.tex_coord());
        self.resolve(ctx, slot, &info.texture(), texcoord, transform)
    }
}

/// The texture slots of the core material and of the extensions the `gltf` crate types.
struct CoreTextures {
    base_color: Option<TextureRef>,
    metallic_roughness: Option<TextureRef>,
    emissive: Option<TextureRef>,
    diffuse: Option<TextureRef>,
    specular: Option<TextureRef>,
    specular_color: Option<TextureRef>,
    transmission: Option<TextureRef>,
}

impl CoreTextures {
    fn read(
        ctx: &Ctx<'_>,
        m: &gltf::Material<'_>,
        r: &mut TextureResolver<'_>,
    ) -> Result<CoreTextures, LoadError> {
        let pbr = m.pbr_metallic_roughness();
        let spec_gloss = m.pbr_specular_glossiness();
        let specular = m.specular();
        let transmission = m.transmission();
        Ok(CoreTextures {
            base_color: r.info(ctx, "baseColorTexture", pbr.base_color_texture())?,
            metallic_roughness: r.info(
                ctx,
                "metallicRoughnessTexture",
                pbr.metallic_roughness_texture(),
            )?,
            emissive: r.info(ctx, "emissiveTexture", m.emissive_texture())?,
            diffuse: r.info(
                ctx,
                "diffuseTexture",
                spec_gloss.as_ref().and_then(|s| s.diffuse_texture()),
            )?,
            specular: r.info(
                ctx,
                "specularTexture",
                specular.as_ref().and_then(|s| s.specular_texture()),
            )?,
            specular_color: r.info(
                ctx,
                "specularColorTexture",
                specular.as_ref().and_then(|s| s.specular_color_texture()),
            )?,
            transmission: r.info(
                ctx,
                "transmissionTexture",
                transmission.as_ref().and_then(|t| t.transmission_texture()),
            )?,
        })
    }
}

/// Reads material `index`; with `images` `None` (no mesh uses the material) its textures
/// are not decoded, and their count is returned beside the material.
fn read_material(
    ctx: &Ctx<'_>,
    index: usize,
    m: &gltf::Material<'_>,
    images: Option<&mut ImageCache>,
    warnings: &mut Warnings,
) -> Result<(MaterialDesc, usize), LoadError> {
    let element = label("material", index, m.name());
    let mut r = TextureResolver {
        images,
        element: &element,
        skipped: 0,
        texcoord_sets: Vec::new(),
        undecodable: Vec::new(),
    };
    let tex = CoreTextures::read(ctx, m, &mut r)?;
    let mut by_texture = |slot: &str, t: &gltf::Texture<'_>, set: u32, transform| {
        r.resolve(ctx, slot, t, set, transform)
    };
    let layers = material_layers::read_layers(ctx, m, &element, &mut by_texture, warnings)?;
    let (iridescence, anisotropy) = super::iridescence_anisotropy::read_iridescence_anisotropy(
        ctx,
        m,
        &element,
        &mut by_texture,
        warnings,
    )?;
    warnings.texcoord_sets.append(&mut r.texcoord_sets);
    warnings.undecodable_textures.append(&mut r.undecodable);
    let skipped = r.skipped;
    let material = MaterialDesc {
        layers,
        iridescence,
        anisotropy,
        scatter: super::scatter::read_scatter(ctx, m, &element, warnings)?,
        ..factors(ctx, m, &element, &tex)?
    };
    let (material, dropped) =
        spec_gloss::apply(m.pbr_specular_glossiness().as_ref(), tex.diffuse, material);
    if dropped {
        warnings.spec_gloss_textures.push(material.name.clone());
    }
    Ok((unlit::apply(m, material), skipped))
}

/// The material's factors and the Iris extras, with the core texture slots `tex`; the layer
/// and thin-film extensions at their defaults.
fn factors(
    ctx: &Ctx<'_>,
    m: &gltf::Material<'_>,
    element: &str,
    tex: &CoreTextures,
) -> Result<MaterialDesc, LoadError> {
    let defaults = MaterialDesc::default();
    let pbr = m.pbr_metallic_roughness();
    let transmission = m.transmission();
    let volume = m.volume();
    let specular = m.specular();
    let alpha_mode = match m.alpha_mode() {
        gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
        // alphaCutoff defaults to 0.5 (§3.9.4).
        gltf::material::AlphaMode::Mask => AlphaMode::Mask(m.alpha_cutoff().unwrap_or(0.5)),
        gltf::material::AlphaMode::Blend => AlphaMode::Blend,
    };
    Ok(MaterialDesc {
        base_color: Vec4::from(pbr.base_color_factor()),
        base_color_texture: tex.base_color,
        metallic: pbr.metallic_factor(),
        roughness: pbr.roughness_factor(),
        metallic_roughness_texture: tex.metallic_roughness,
        emissive: Vec3::from(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0),
        emissive_texture: tex.emissive,
        emission_spectrum: iris_spectrum(ctx, m.extras(), element)?,
        ior: m.ior().unwrap_or(defaults.ior),
        transmission: transmission
            .as_ref()
            .map_or(defaults.transmission, |t| t.transmission_factor()),
        transmission_texture: tex.transmission,
        thickness: volume
            .as_ref()
            .map_or(defaults.thickness, |v| v.thickness_factor()),
        attenuation_color: volume.as_ref().map_or(defaults.attenuation_color, |v| {
            Vec3::from(v.attenuation_color())
        }),
        attenuation_distance: volume
            .as_ref()
            .map_or(defaults.attenuation_distance, |v| v.attenuation_distance()),
        specular: specular
            .as_ref()
            .map_or(defaults.specular, |s| s.specular_factor()),
        specular_color: specular.as_ref().map_or(defaults.specular_color, |s| {
            Vec3::from(s.specular_color_factor())
        }),
        specular_texture: tex.specular,
        specular_color_texture: tex.specular_color,
        dispersion: dispersion(ctx, m, element)?,
        ior_model: explicit_ior(ctx, m, element)?,
        priority: priority(ctx, m, element)?,
        crystal: super::crystal::read_crystal(ctx, m, element)?,
        polarizer: super::crystal::read_polarizer(ctx, m, element)?,
        double_sided: m.double_sided(),
        alpha_mode,
        name: element.to_string(),
        stated: stated(m),
        extras: m
            .extras()
            .as_ref()
            .and_then(|x| serde_json::from_str(x.get()).ok()),
        ..defaults
    })
}

/// The names of the extensions on `m` ([`MaterialDesc::stated`]): those the `gltf` crate
/// types, then the rest as the file names them.
fn stated(m: &gltf::Material<'_>) -> std::collections::BTreeSet<String> {
    let typed = [
        ("KHR_materials_ior", m.ior().is_some()),
        ("KHR_materials_transmission", m.transmission().is_some()),
        ("KHR_materials_volume", m.volume().is_some()),
        ("KHR_materials_specular", m.specular().is_some()),
        (
            "KHR_materials_emissive_strength",
            m.emissive_strength().is_some(),
        ),
    ];
    let typed = typed.into_iter().filter(|(_, present)| *present);
    let others = m.extensions().into_iter().flat_map(|x| x.keys());
    typed
        .map(|(name, _)| name.to_string())
        .chain(others.cloned())
        .collect()
}

/// `KHR_materials_dispersion.dispersion` (default 0).
fn dispersion(ctx: &Ctx<'_>, m: &gltf::Material<'_>, element: &str) -> Result<f32, LoadError> {
    let Some(ext) = m.extension_value("KHR_materials_dispersion") else {
        return Ok(0.0);
    };
    let invalid = |detail: &str| ctx.error(element, LoadErrorKind::InvalidValue, detail);
    let ext = ext
        .as_object()
        .ok_or_else(|| invalid("KHR_materials_dispersion must be a JSON object"))?;
    match ext.get("dispersion") {
        None => Ok(0.0),
        Some(v) => v
            .as_f64()
            .map(|d| d as f32)
            .ok_or_else(|| invalid("KHR_materials_dispersion.dispersion is not a number")),
    }
}

/// The Iris extras keys `iris_glass`, `cauchy` and `sellmeier` (at most one); other extras keys and
/// non-object extras are ignored.
fn explicit_ior(
    ctx: &Ctx<'_>,
    m: &gltf::Material<'_>,
    element: &str,
) -> Result<Option<ExplicitIor>, LoadError> {
    let invalid = |detail: String| ctx.error(element, LoadErrorKind::InvalidValue, detail);
    let mut given: Vec<(&str, Value)> = Vec::new();
    for key in ["iris_glass", "cauchy", "sellmeier"] {
        if let Some(v) = extras_key(ctx, m.extras(), element, key)? {
            given.push((key, v));
        }
    }
    if given.len() > 1 {
        let keys: Vec<&str> = given.iter().map(|(k, _)| *k).collect();
        return Err(invalid(format!(
            "extras give both {}; keep one IOR model",
            keys.join(" and ")
        )));
    }
    match given.first() {
        Some(("iris_glass", v)) => glass_name(v).map(Some).map_err(invalid),
        Some(("cauchy", v)) => cauchy_model(v).map(Some).map_err(invalid),
        Some((_, v)) => sellmeier_model(v).map(Some).map_err(invalid),
        None => Ok(None),
    }
}

/// `extras.sellmeier`: `{"b": [B1, …], "c": [C1, …]}`, 1 to 4 terms of each (same count),
/// C in µm². Range checks (finite, ≥ 0, no resonance in the sampled range) are
/// `scene::validate`'s.
fn sellmeier_model(sellmeier: &Value) -> Result<ExplicitIor, String> {
    let shape = || {
        format!("extras.sellmeier must be {{\"b\": [B1, …], \"c\": [C1, …]}} with 1 to 4 numbers each, found {sellmeier}")
    };
    let terms = |key: &str| -> Result<Vec<f32>, String> {
        let list = sellmeier
            .get(key)
            .and_then(Value::as_array)
            .ok_or_else(shape)?;
        if list.is_empty() || list.len() > 4 {
            return Err(shape());
        }
        list.iter()
            .map(|v| v.as_f64().map(|x| x as f32).ok_or_else(shape))
            .collect()
    };
    let (b_list, c_list) = (terms("b")?, terms("c")?);
    if b_list.len() != c_list.len() {
        return Err(shape());
    }
    let (mut b, mut c) = ([0.0f32; 4], [0.0f32; 4]);
    b[..b_list.len()].copy_from_slice(&b_list);
    c[..c_list.len()].copy_from_slice(&c_list);
    Ok(ExplicitIor::Sellmeier { b, c })
}

/// `extras.iris_priority`: the nested-media priority, an integer in ±1,000,000 (default 0).
fn priority(ctx: &Ctx<'_>, m: &gltf::Material<'_>, element: &str) -> Result<i32, LoadError> {
    let Some(p) = extras_key(ctx, m.extras(), element, "iris_priority")? else {
        return Ok(0);
    };
    p.as_i64()
        .filter(|v| v.abs() <= 1_000_000)
        .map(|v| v as i32)
        .ok_or_else(|| {
            ctx.error(
                element,
                LoadErrorKind::InvalidValue,
                format!("extras.iris_priority must be an integer in ±1000000, found {p}"),
            )
        })
}

/// `extras.iris_glass`: a string naming a known glass.
fn glass_name(glass: &Value) -> Result<ExplicitIor, String> {
    let name = glass.as_str().ok_or_else(|| {
        format!("extras.iris_glass must be a string naming a glass, found {glass}")
    })?;
    match crate::spectrum::IorModel::named(name) {
        Ok(_) => Ok(ExplicitIor::Glass(name.to_string())),
        Err(e) => Err(format!("extras.iris_glass: {e}")),
    }
}

/// `extras.cauchy`: `{"b": B, "c": C}` with finite B ≥ 1, C ≥ 0.
fn cauchy_model(cauchy: &Value) -> Result<ExplicitIor, String> {
    let fields = cauchy.as_object().ok_or_else(|| {
        format!("extras.cauchy must be an object {{\"b\": …, \"c\": …}}, found {cauchy}")
    })?;
    let number = |key: &str| -> Result<f32, String> {
        fields
            .get(key)
            .and_then(Value::as_f64)
            .map(|v| v as f32)
            .ok_or_else(|| format!("extras.cauchy.{key} is missing or not a number"))
    };
    let (b, c) = (number("b")?, number("c")?);
    if !(b.is_finite() && b >= 1.0) {
        return Err(format!(
            "extras.cauchy.b = {b} must be a finite number >= 1"
        ));
    }
    if !(c.is_finite() && c >= 0.0) {
        return Err(format!(
            "extras.cauchy.c = {c} (µm²) must be a finite number >= 0"
        ));
    }
    Ok(ExplicitIor::Cauchy { b, c })
}

/// `extras.iris_spectrum` of a material or light (`element` names it for errors); `None`
/// when absent or when the extras are not a JSON object.
pub(super) fn iris_spectrum(
    ctx: &Ctx<'_>,
    extras: &gltf::json::Extras,
    element: &str,
) -> Result<Option<EmissionSpectrum>, LoadError> {
    let Some(value) = extras_key(ctx, extras, element, "iris_spectrum")? else {
        return Ok(None);
    };
    spectrum_value(&value).map(Some).map_err(|detail| {
        ctx.error(
            format!("{element} extras.iris_spectrum"),
            LoadErrorKind::InvalidValue,
            detail,
        )
    })
}

/// `"D65"`, `"sun"`, `"blackbody K"` or `{"blackbody": K}` (keys and names
/// case-insensitive).
fn spectrum_value(value: &Value) -> Result<EmissionSpectrum, String> {
    match value {
        Value::String(s) => {
            EmissionSpectrum::parse_words(&s.split_whitespace().collect::<Vec<_>>())
        }
        Value::Object(map) if map.len() == 1 => {
            let Some((key, k)) = map.iter().next() else {
                return Err("empty spectrum object".into());
            };
            if !key.eq_ignore_ascii_case("blackbody") {
                return Err(format!(
                    "unknown spectrum object key `{key}`; expected {{\"blackbody\": K}}"
                ));
            }
            let kelvin = k.as_f64().ok_or_else(|| {
                format!("blackbody temperature must be a number in kelvin, found {k}")
            })?;
            EmissionSpectrum::blackbody(kelvin)
        }
        other => Err(format!(
            "expected \"D65\", \"sun\" or {{\"blackbody\": K}}, found {other}"
        )),
    }
}
