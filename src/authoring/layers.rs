//! The KHR material layer extensions of a written material ([`LayerDesc`], the description's
//! own type): KHR_materials_clearcoat, KHR_materials_sheen and
//! KHR_materials_diffuse_transmission, their checks and their glTF JSON, with the property
//! names exactly as the Khronos specifications spell them (the names Iris's loader,
//! `load::gltf::material_layers`, reads).
//!
//! Units: factors and roughnesses are unitless in [0, 1]; colours are linear RGB in [0, 1].
//! Only factors are written (no textures). A layer is written when the material states its
//! extension ([`crate::material::MaterialDesc::stated`]) or when its values differ from the
//! spec defaults; a stated layer is written even when its factor is 0 (the clearcoat test
//! scene shows that a coat of factor 0 renders like no coat).

use super::json_number::{num, vec3};
use crate::material::LayerDesc;
use glam::Vec3;
use serde_json::{json, Map, Value};
use std::collections::BTreeSet;

fn unit(x: f32) -> bool {
    (0.0..=1.0).contains(&x)
}

fn unit_rgb(c: Vec3) -> bool {
    c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0
}

/// `Err(property)` naming the first value outside its range (`extension.property`).
pub fn check(l: &LayerDesc) -> Result<(), &'static str> {
    let checks = [
        (unit(l.clearcoat), "KHR_materials_clearcoat.clearcoatFactor"),
        (
            unit(l.clearcoat_roughness),
            "KHR_materials_clearcoat.clearcoatRoughnessFactor",
        ),
        (
            unit_rgb(l.sheen_color),
            "KHR_materials_sheen.sheenColorFactor",
        ),
        (
            unit(l.sheen_roughness),
            "KHR_materials_sheen.sheenRoughnessFactor",
        ),
        (
            unit(l.diffuse_transmission),
            "KHR_materials_diffuse_transmission.diffuseTransmissionFactor",
        ),
        (
            unit_rgb(l.diffuse_transmission_color),
            "KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor",
        ),
    ];
    match checks.iter().find(|(ok, _)| !ok) {
        Some((_, property)) => Err(property),
        None => Ok(()),
    }
}

/// Inserts the layers to write (module docs) into a material's `extensions` object.
pub(super) fn write(l: &LayerDesc, stated: &BTreeSet<String>, ext: &mut Map<String, Value>) {
    let mut put = |name: &'static str, differs: bool, value: Value| {
        if differs || stated.contains(name) {
            ext.insert(name.into(), value);
        }
    };
    put(
        "KHR_materials_clearcoat",
        l.clearcoat != 0.0 || l.clearcoat_roughness != 0.0,
        json!({"clearcoatFactor": num(l.clearcoat), "clearcoatRoughnessFactor": num(l.clearcoat_roughness)}),
    );
    put(
        "KHR_materials_sheen",
        l.sheen_color != Vec3::ZERO || l.sheen_roughness != 0.0,
        json!({"sheenColorFactor": vec3(l.sheen_color), "sheenRoughnessFactor": num(l.sheen_roughness)}),
    );
    put(
        "KHR_materials_diffuse_transmission",
        l.diffuse_transmission != 0.0 || l.diffuse_transmission_color != Vec3::ONE,
        json!({"diffuseTransmissionFactor": num(l.diffuse_transmission),
               "diffuseTransmissionColorFactor": vec3(l.diffuse_transmission_color)}),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_spec_property_names_and_rejects_out_of_range() {
        let layers = LayerDesc {
            clearcoat: 0.0,
            clearcoat_roughness: 0.5,
            sheen_color: Vec3::new(1.0, 0.5, 0.25),
            sheen_roughness: 0.3,
            diffuse_transmission: 0.5,
            diffuse_transmission_color: Vec3::new(1.0, 0.4, 0.1),
            ..LayerDesc::default()
        };
        assert_eq!(check(&layers), Ok(()));
        let mut ext = Map::new();
        write(&layers, &BTreeSet::new(), &mut ext);
        assert_eq!(ext.len(), 3);
        let v = Value::Object(ext);
        assert_eq!(v["KHR_materials_clearcoat"]["clearcoatFactor"], 0.0);
        assert_eq!(
            v["KHR_materials_clearcoat"]["clearcoatRoughnessFactor"],
            0.5
        );
        assert_eq!(v["KHR_materials_sheen"]["sheenColorFactor"][1], 0.5);
        assert_eq!(v["KHR_materials_sheen"]["sheenRoughnessFactor"], 0.3);
        let dt = &v["KHR_materials_diffuse_transmission"];
        assert_eq!(dt["diffuseTransmissionFactor"], 0.5);
        assert_eq!(dt["diffuseTransmissionColorFactor"][2], 0.1);

        // Defaults are written only when stated.
        let mut ext = Map::new();
        write(&LayerDesc::default(), &BTreeSet::new(), &mut ext);
        assert!(ext.is_empty());
        write(
            &LayerDesc::default(),
            &BTreeSet::from(["KHR_materials_clearcoat".to_string()]),
            &mut ext,
        );
        assert_eq!(ext["KHR_materials_clearcoat"]["clearcoatFactor"], 0.0);

        let bad = LayerDesc {
            sheen_color: Vec3::new(1.5, 0.0, 0.0),
            ..layers
        };
        assert_eq!(check(&bad), Err("KHR_materials_sheen.sheenColorFactor"));
        let bad = LayerDesc {
            clearcoat: f32::NAN,
            ..layers
        };
        assert_eq!(check(&bad), Err("KHR_materials_clearcoat.clearcoatFactor"));
        assert_eq!(check(&LayerDesc::default()), Ok(()));
    }
}
