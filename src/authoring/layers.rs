//! The KHR material layer extensions a generated material may carry
//! (KHR_materials_clearcoat, KHR_materials_sheen, KHR_materials_diffuse_transmission): their
//! parameters ([`GenLayers`]), their validation and their glTF JSON, with the property names
//! exactly as the Khronos specifications spell them (the names Iris's loader,
//! `load::gltf::material_layers`, reads).
//!
//! Units: factors and roughnesses are unitless in [0, 1]; colours are linear RGB in [0, 1].
//! Only factors are written (no textures). A layer that is `None` is not written at all; a
//! layer that is `Some` is written even when its factor is 0 (the clearcoat test scene
//! shows that a coat of factor 0 renders like no coat).

use super::gltf_json::{num, vec3};
use glam::Vec3;
use serde_json::{json, Map, Value};
use std::collections::BTreeSet;

/// KHR_materials_clearcoat: a smooth or rough dielectric coat (F0 0.04) over the material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenClearcoat {
    /// `clearcoatFactor` in [0, 1].
    pub factor: f32,
    /// `clearcoatRoughnessFactor` in [0, 1].
    pub roughness: f32,
}

/// KHR_materials_sheen: a microfibre (Charlie) lobe over the base, strongest at grazing angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenSheen {
    /// `sheenColorFactor`, linear RGB in [0, 1].
    pub color: Vec3,
    /// `sheenRoughnessFactor` in [0, 1].
    pub roughness: f32,
}

/// KHR_materials_diffuse_transmission: part of the diffuse lobe goes through a thin wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenDiffuseTransmission {
    /// `diffuseTransmissionFactor` in [0, 1].
    pub factor: f32,
    /// `diffuseTransmissionColorFactor`, linear RGB in [0, 1].
    pub color: Vec3,
}

/// The layer extensions of one material; all `None` (the default) writes none of them.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GenLayers {
    /// KHR_materials_clearcoat.
    pub clearcoat: Option<GenClearcoat>,
    /// KHR_materials_sheen.
    pub sheen: Option<GenSheen>,
    /// KHR_materials_diffuse_transmission.
    pub diffuse_transmission: Option<GenDiffuseTransmission>,
}

fn unit(x: f32) -> bool {
    (0.0..=1.0).contains(&x)
}

fn unit_rgb(c: Vec3) -> bool {
    c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0
}

impl GenLayers {
    /// `Err(property)` naming the first value outside its range (`extension.property`).
    pub fn check(&self) -> Result<(), &'static str> {
        if let Some(c) = self.clearcoat {
            if !unit(c.factor) {
                return Err("KHR_materials_clearcoat.clearcoatFactor");
            }
            if !unit(c.roughness) {
                return Err("KHR_materials_clearcoat.clearcoatRoughnessFactor");
            }
        }
        if let Some(s) = self.sheen {
            if !unit_rgb(s.color) {
                return Err("KHR_materials_sheen.sheenColorFactor");
            }
            if !unit(s.roughness) {
                return Err("KHR_materials_sheen.sheenRoughnessFactor");
            }
        }
        if let Some(d) = self.diffuse_transmission {
            if !unit(d.factor) {
                return Err("KHR_materials_diffuse_transmission.diffuseTransmissionFactor");
            }
            if !unit_rgb(d.color) {
                return Err("KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor");
            }
        }
        Ok(())
    }

    /// Inserts the present layers into a material's `extensions` object and records their
    /// names in `used` (for `extensionsUsed`).
    pub(super) fn write(&self, ext: &mut Map<String, Value>, used: &mut BTreeSet<&'static str>) {
        let mut put = |name: &'static str, value: Value| {
            ext.insert(name.into(), value);
            used.insert(name);
        };
        if let Some(c) = self.clearcoat {
            put(
                "KHR_materials_clearcoat",
                json!({"clearcoatFactor": num(c.factor), "clearcoatRoughnessFactor": num(c.roughness)}),
            );
        }
        if let Some(s) = self.sheen {
            put(
                "KHR_materials_sheen",
                json!({"sheenColorFactor": vec3(s.color), "sheenRoughnessFactor": num(s.roughness)}),
            );
        }
        if let Some(d) = self.diffuse_transmission {
            put(
                "KHR_materials_diffuse_transmission",
                json!({"diffuseTransmissionFactor": num(d.factor),
                       "diffuseTransmissionColorFactor": vec3(d.color)}),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_spec_property_names_and_rejects_out_of_range() {
        let layers = GenLayers {
            clearcoat: Some(GenClearcoat {
                factor: 0.0,
                roughness: 0.5,
            }),
            sheen: Some(GenSheen {
                color: Vec3::new(1.0, 0.5, 0.25),
                roughness: 0.3,
            }),
            diffuse_transmission: Some(GenDiffuseTransmission {
                factor: 0.5,
                color: Vec3::new(1.0, 0.4, 0.1),
            }),
        };
        assert_eq!(layers.check(), Ok(()));
        let (mut ext, mut used) = (Map::new(), BTreeSet::new());
        layers.write(&mut ext, &mut used);
        assert_eq!(used.len(), 3);
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

        let mut bad = layers;
        bad.sheen = Some(GenSheen {
            color: Vec3::new(1.5, 0.0, 0.0),
            roughness: 0.3,
        });
        assert_eq!(bad.check(), Err("KHR_materials_sheen.sheenColorFactor"));
        let mut bad = layers;
        bad.clearcoat = Some(GenClearcoat {
            factor: f32::NAN,
            roughness: 0.0,
        });
        assert_eq!(bad.check(), Err("KHR_materials_clearcoat.clearcoatFactor"));
        assert_eq!(GenLayers::default().check(), Ok(()));
    }
}
