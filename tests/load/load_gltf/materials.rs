//! Materials (Cauchy extras, IOR pass-through, textures), lights and cameras.

use super::fixtures::*;
use super::{common, load, material};
use glam::{Mat4, Vec3};
use iris::material::ExplicitIor;
use iris::scene::desc::{LightDesc, Projection};
use serde_json::json;

#[test]
fn cauchy_ior_and_texture_values_pass_through() {
    let dir = common::scratch_dir("gltf_materials");
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!([
        "KHR_materials_ior",
        "KHR_materials_dispersion",
        "KHR_materials_volume"
    ]);
    doc["images"] = json!([{"name": "checker", "uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0}]);
    doc["materials"] = json!([
        {"name": "Glass", "extras": {"cauchy": {"b": 1.5, "c": 0.0042}, "other": 1},
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}},
         "extensions": {"KHR_materials_dispersion": {"dispersion": 0.36}}},
        {"name": "Bubble", "extensions": {"KHR_materials_ior": {"ior": 0.8},
         "KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationColor": [0.5, 0.6, 0.7]}}},
        {"name": "Infinite", "extensions": {"KHR_materials_ior": {"ior": 0.0}},
         "emissiveFactor": [1.0, 0.5, 0.25], "alphaMode": "MASK", "doubleSided": true,
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}
    ]);
    // Glass and Infinite on the cube (textures are decoded only for materials in use).
    let mut second = doc["meshes"][0]["primitives"][0].clone();
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    second["material"] = json!(2);
    doc["meshes"][0]["primitives"]
        .as_array_mut()
        .unwrap()
        .push(second);
    let desc = load(&write_json(&dir, "materials.gltf", &doc));
    let glass = material(&desc, "Glass");
    assert_eq!(
        glass.ior_model,
        Some(ExplicitIor::Cauchy { b: 1.5, c: 0.0042 })
    );
    assert_eq!(glass.dispersion, 0.36);
    assert_eq!(glass.ior, 1.5);
    let bubble = material(&desc, "Bubble");
    assert_eq!((bubble.ior, bubble.thickness), (0.8, 1.0));
    assert_eq!(bubble.attenuation_distance, f32::INFINITY);
    assert_eq!(bubble.attenuation_color, Vec3::new(0.5, 0.6, 0.7));
    let infinite = material(&desc, "Infinite");
    assert_eq!(infinite.ior, 0.0);
    assert_eq!(infinite.emissive, Vec3::new(1.0, 0.5, 0.25));
    assert!(infinite.double_sided);
    assert_eq!(infinite.alpha_mode, iris::material::AlphaMode::Mask(0.5));
    // One decoded image shared by both slots.
    assert_eq!(desc.images.len(), 1);
    assert_eq!((desc.images[0].width, desc.images[0].height), (2, 2));
    assert_eq!(desc.images[0].rgba8[12..16], [9, 9, 9, 128]);
    assert_eq!(
        glass.base_color_texture.map(|t| (t.image, t.texcoord)),
        Some((0, 1))
    );
    assert_eq!(infinite.base_color_texture.map(|t| t.image), Some(0));
    let texcoord: Vec<_> = desc
        .warnings
        .iter()
        .filter(|w| w.contains("texCoord"))
        .collect();
    assert_eq!(texcoord.len(), 1, "{:?}", desc.warnings);
    assert!(texcoord[0].contains("material 0 \"Glass\""));
}

#[test]
fn lights_and_cameras_in_world_space() {
    let dir = common::scratch_dir("gltf_lights");
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"name": "Bulb", "type": "point", "intensity": 100.0, "color": [1.0, 0.9, 0.8], "range": 10.0},
        {"type": "spot", "intensity": 5.0, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.4}},
        {"name": "Sun", "type": "directional", "intensity": 3.0}
    ]}});
    doc["cameras"] = json!([
        {"name": "Main", "type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.01}},
        {"type": "orthographic", "orthographic": {"xmag": 2.0, "ymag": 1.0, "znear": 0.0, "zfar": 10.0}}
    ]);
    // Rotation of +90° about X maps local −Z to world +Y; scales must not change intensity.
    let half = std::f32::consts::FRAC_1_SQRT_2;
    doc["nodes"] = json!([
        {"name": "Cube", "mesh": 0},
        {"name": "Lamp", "translation": [1.0, 2.0, 3.0], "scale": [4.0, 4.0, 4.0],
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "Spot", "rotation": [half, 0.0, 0.0, half], "scale": [2.0, 3.0, 0.5],
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"name": "SunNode", "extensions": {"KHR_lights_punctual": {"light": 2}}},
        {"name": "CamNode", "camera": 0, "translation": [0.0, 0.0, 5.0], "scale": [2.0, 2.0, 2.0]},
        {"camera": 1}
    ]);
    doc["scenes"][0]["nodes"] = json!([0, 1, 2, 3, 4, 5]);
    let desc = load(&write_json(&dir, "lights.gltf", &doc));
    assert_eq!(desc.lights.len(), 3);
    match &desc.lights[0] {
        LightDesc::Point {
            name,
            position,
            color,
            intensity,
            range,
            ..
        } => {
            assert_eq!(
                (name.as_str(), *intensity, *range),
                ("Bulb", 100.0, Some(10.0))
            );
            assert_eq!(*position, Vec3::new(1.0, 2.0, 3.0));
            assert_eq!(*color, Vec3::new(1.0, 0.9, 0.8));
        }
        other => panic!("expected a point light, got {other:?}"),
    }
    match &desc.lights[1] {
        LightDesc::Spot {
            direction,
            intensity,
            inner_cone,
            outer_cone,
            ..
        } => {
            assert!((*direction - Vec3::Y).length() < 1e-5, "{direction}");
            assert_eq!((*intensity, *inner_cone, *outer_cone), (5.0, 0.1, 0.4));
        }
        other => panic!("expected a spot light, got {other:?}"),
    }
    match &desc.lights[2] {
        LightDesc::Directional {
            direction,
            intensity,
            ..
        } => {
            assert_eq!((*direction, *intensity), (Vec3::NEG_Z, 3.0));
        }
        other => panic!("expected a directional light, got {other:?}"),
    }
    assert_eq!(desc.cameras.len(), 2);
    let main = &desc.cameras[0];
    assert_eq!(main.name, "Main");
    assert_eq!(
        main.projection,
        Projection::Perspective {
            yfov: 0.6,
            aspect: Some(1.5)
        }
    );
    assert!(main
        .world_from_camera
        .abs_diff_eq(Mat4::from_translation(Vec3::new(0.0, 0.0, 5.0)), 1e-6));
    assert_eq!(
        desc.cameras[1].projection,
        Projection::Orthographic {
            xmag: 2.0,
            ymag: 1.0
        }
    );
    assert_eq!(desc.cameras[1].name, "camera 1");
}

/// KHR_texture_transform: the transform and its texCoord override reach the material, the
/// shaded colour follows the transformed coordinate, and a bad value names the material.
#[test]
fn texture_transform_moves_the_lookup() {
    let dir = common::scratch_dir("gltf_texture_transform");
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(["KHR_texture_transform"]);
    doc["images"] = json!([{"uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0}]);
    // Texel centres: red (0.25, 0.25), green (0.75, 0.25), blue (0.25, 0.75).
    // offset (0.5, 0) moves a lookup at the red texel's centre onto the green one.
    doc["materials"] = json!([
        {"name": "Shifted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
         "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.0], "texCoord": 0}}}}}
    ]);
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    let desc = load(&write_json(&dir, "shifted.gltf", &doc));
    let m = material(&desc, "Shifted");
    let t = m.base_color_texture.expect("texture");
    let moved = t.transform.transform_point2(glam::Vec2::new(0.25, 0.25));
    assert!(
        (moved - glam::Vec2::new(0.75, 0.25)).length() < 1e-6,
        "{moved}"
    );
    let mat = iris::material::Material::new(m.clone());
    let c = mat
        .shade(&iris::material::TextureContext::new(
            &desc.images,
            iris::material::TexCoords::single(glam::Vec2::new(0.25, 0.25)),
        ))
        .base_color;
    assert!(
        c.y > 0.99 && c.x < 0.01 && c.z < 0.01,
        "expected green, got {c}"
    );
    assert!(
        !desc
            .warnings
            .iter()
            .any(|w| w.contains("KHR_texture_transform")),
        "{:?}",
        desc.warnings
    );

    // A texCoord override of 1 is reported like a texture info's own texCoord 1.
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]
        ["KHR_texture_transform"]["texCoord"] = json!(1);
    let desc = load(&write_json(&dir, "texcoord1.gltf", &doc));
    assert_eq!(
        material(&desc, "Shifted")
            .base_color_texture
            .unwrap()
            .texcoord,
        1
    );
}

/// KHR_materials_unlit: the base colour (factor and texture) becomes the emission and the
/// surface reflects nothing; other materials are untouched.
#[test]
fn unlit_emits_its_base_colour() {
    let dir = common::scratch_dir("gltf_unlit");
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(["KHR_materials_unlit"]);
    doc["images"] = json!([{"uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0}]);
    doc["materials"] = json!([
        {"name": "Flat", "extensions": {"KHR_materials_unlit": {}},
         "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1.0, 0.75],
            "baseColorTexture": {"index": 0}, "metallicFactor": 1.0}},
        {"name": "Lit", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1.0, 1.0]}}
    ]);
    let mut second = doc["meshes"][0]["primitives"][0].clone();
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    second["material"] = json!(1);
    doc["meshes"][0]["primitives"]
        .as_array_mut()
        .unwrap()
        .push(second);
    let desc = load(&write_json(&dir, "unlit.gltf", &doc));
    assert!(desc.warnings.is_empty(), "{:?}", desc.warnings);
    let flat = material(&desc, "Flat");
    assert_eq!(flat.emissive, Vec3::new(0.5, 0.25, 1.0));
    assert_eq!(flat.emissive_texture.map(|t| t.image), Some(0));
    assert_eq!(flat.base_color, glam::Vec4::new(0.0, 0.0, 0.0, 0.75));
    assert_eq!(
        (flat.metallic, flat.specular, flat.transmission),
        (0.0, 0.0, 0.0)
    );
    // The shaded emission at the red texel is the factor times red.
    let sp =
        iris::material::Material::new(flat.clone()).shade(&iris::material::TextureContext::new(
            &desc.images,
            iris::material::TexCoords::single(glam::Vec2::new(0.25, 0.25)),
        ));
    assert!(
        (sp.emissive - Vec3::new(0.5, 0.0, 0.0)).length() < 1e-3,
        "{}",
        sp.emissive
    );
    assert_eq!(sp.base_color, Vec3::ZERO);
    let lit = material(&desc, "Lit");
    assert_eq!(lit.emissive, Vec3::ZERO);
    assert_eq!(lit.base_color, glam::Vec4::new(0.5, 0.25, 1.0, 1.0));
}

/// EXT_texture_webp (a glTF-Transform file whose texture has only a WebP source) decodes to
/// the same texels as the PNG it was made from; a texture with only a KTX2 image
/// (KHR_texture_basisu, not decoded) is left out with one warning naming the material.
#[test]
fn webp_textures_decode_and_ktx2_only_textures_are_left_out() {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/textures");
    let png = load(&data.join("checker_png.glb"));
    let webp = load(&data.join("checker_webp.glb"));
    assert!(webp.warnings.is_empty(), "{:?}", webp.warnings);
    assert_eq!(png.images.len(), 1);
    assert_eq!(webp.images.len(), 1);
    let (a, b) = (&png.images[0], &webp.images[0]);
    assert_eq!((a.width, a.height), (b.width, b.height));
    // Lossless WebP: the very same texels.
    assert_eq!(a.rgba8, b.rgba8);
    assert!(webp.materials[0].base_color_texture.is_some());

    // The same document with the texture turned into a KTX2-only one.
    let dir = common::scratch_dir("gltf_ktx2");
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(["KHR_texture_basisu"]);
    doc["extensionsRequired"] = json!(["KHR_texture_basisu"]);
    doc["images"] = json!([{"uri": "never_read.ktx2", "mimeType": "image/ktx2"}]);
    doc["textures"] = json!([{"extensions": {"KHR_texture_basisu": {"source": 0}}}]);
    doc["materials"] =
        json!([{"name": "Basis", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]);
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    let desc = load(&write_json(&dir, "ktx2.gltf", &doc));
    assert!(material(&desc, "Basis").base_color_texture.is_none());
    let ktx: Vec<_> = desc
        .warnings
        .iter()
        .filter(|w| w.contains("KTX2"))
        .collect();
    assert_eq!(ktx.len(), 1, "{:?}", desc.warnings);
    assert!(
        ktx[0].contains("material 0 \"Basis\" baseColorTexture"),
        "{}",
        ktx[0]
    );
    // A texture with neither a source nor a format extension is still invalid.
    doc["textures"] = json!([{}]);
    let err = iris::load::load_scene(&write_json(&dir, "nosource.gltf", &doc)).unwrap_err();
    assert!(err.to_string().contains("textures[0].source"), "{err}");
}

/// KHR_materials_pbrSpecularGlossiness is approximated: diffuse → base colour (factor and
/// texture), 1 − glossiness → roughness, specularFactor → the glTF-PBR f0 through
/// KHR_materials_specular's colour; a specularGlossinessTexture is named in one warning.
#[test]
fn specular_glossiness_maps_to_metallic_roughness() {
    let dir = common::scratch_dir("gltf_spec_gloss");
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(["KHR_materials_pbrSpecularGlossiness"]);
    doc["images"] = json!([{"uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0}]);
    doc["materials"] = json!([
        {"name": "Old", "extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "diffuseFactor": [0.5, 0.4, 0.3, 1.0], "diffuseTexture": {"index": 0},
            "specularFactor": [0.02, 0.04, 0.08], "glossinessFactor": 0.75,
            "specularGlossinessTexture": {"index": 0}}}}
    ]);
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    let desc = load(&write_json(&dir, "specgloss.gltf", &doc));
    let m = material(&desc, "Old");
    assert_eq!(m.base_color, glam::Vec4::new(0.5, 0.4, 0.3, 1.0));
    assert_eq!(m.base_color_texture.map(|t| t.image), Some(0));
    assert_eq!(
        (m.metallic, m.roughness, m.ior, m.specular),
        (0.0, 0.25, 1.5, 1.0)
    );
    // f0 = ((1.5 − 1)/(1.5 + 1))² · colour = 0.04 · colour = specularFactor.
    let f0 = m.specular_color * 0.04;
    assert!((f0 - Vec3::new(0.02, 0.04, 0.08)).length() < 1e-6, "{f0}");
    let w: Vec<_> = desc
        .warnings
        .iter()
        .filter(|w| w.contains("specularGlossinessTexture"))
        .collect();
    assert_eq!(w.len(), 1, "{:?}", desc.warnings);
    assert!(w[0].contains("material 0 \"Old\""), "{}", w[0]);
}

/// KHR_materials_specular textures: specularTexture's alpha scales the factor and
/// specularColorTexture's (sRGB) colour scales the colour at the shading point.
#[test]
fn specular_textures_scale_the_factors() {
    let dir = common::scratch_dir("gltf_specular_textures");
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(["KHR_materials_specular"]);
    doc["images"] = json!([{"uri": data_uri("image/png", &png_2x2())}]);
    doc["textures"] = json!([{"source": 0}]);
    doc["materials"] = json!([{"name": "Spec", "extensions": {"KHR_materials_specular": {
        "specularFactor": 0.5, "specularTexture": {"index": 0},
        "specularColorFactor": [1.0, 0.5, 1.0], "specularColorTexture": {"index": 0}}}}]);
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    let desc = load(&write_json(&dir, "spec.gltf", &doc));
    let m = material(&desc, "Spec");
    assert!(m.specular_texture.is_some() && m.specular_color_texture.is_some());
    let mat = iris::material::Material::new(m.clone());
    // Texel (1, 1) is (9, 9, 9, 128): alpha 128/255, colour sRGB 9 ≈ 0.00273 linear.
    let sp = mat.shade(&iris::material::TextureContext::new(
        &desc.images,
        iris::material::TexCoords::single(glam::Vec2::new(0.75, 0.75)),
    ));
    assert!(
        (sp.specular - 0.5 * 128.0 / 255.0).abs() < 1e-3,
        "{}",
        sp.specular
    );
    let c9 = 9.0f32 / 255.0 / 12.92;
    assert!(
        (sp.specular_color - Vec3::new(c9, 0.5 * c9, c9)).length() < 1e-4,
        "{}",
        sp.specular_color
    );
    // The red texel keeps the full factor and the colour's red channel.
    let sp = mat.shade(&iris::material::TextureContext::new(
        &desc.images,
        iris::material::TexCoords::single(glam::Vec2::new(0.25, 0.25)),
    ));
    assert!((sp.specular - 0.5).abs() < 1e-6);
    assert!(
        (sp.specular_color - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-5,
        "{}",
        sp.specular_color
    );
}
