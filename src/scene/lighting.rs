//! Whether a description brings light of its own, the one place where a description with
//! none gets the default key and fill lights ([`light_if_unlit`]), and the render lights a
//! description asks for ([`render_lights`]).
//!
//! "Light of its own" is a punctual light or an emitting triangle, by the test
//! [`AreaLights::build`] applies (luminance × area × π > 0 and finite), so the description
//! and the built scene always agree on it. Units: candela, lux and nits as in
//! [`crate::light`]; frames: world space.

use super::desc::{AddedLights, LightDesc, SceneDesc, SpotKey};
use crate::light::area::AreaLights;
use crate::light::{self, Light, PunctualLight};
use crate::material::Material;
use glam::Vec3;

/// Whether the file's description has a punctual light or an emitting triangle.
pub fn has_own_light(desc: &SceneDesc) -> bool {
    !desc.lights.is_empty() || has_emitter(desc)
}

/// Whether the file's description has an emitting triangle (an emissive material on a
/// mesh, by [`AreaLights::build`]'s test).
pub fn has_emitter(desc: &SceneDesc) -> bool {
    desc.meshes.iter().any(|m| mesh_emits(desc, m))
}

/// Whether `mesh` has a triangle that [`AreaLights::build`] would keep as an emitter.
pub fn mesh_emits(desc: &SceneDesc, mesh: &super::desc::MeshDesc) -> bool {
    // A mesh without a material uses the default one, which does not emit.
    let Some(mat) = mesh.material.and_then(|i| desc.materials.get(i)) else {
        return false;
    };
    // Zero emissive times any tint is zero (or NaN): never an emitter.
    if mat.emissive == Vec3::ZERO || mesh.indices.is_empty() {
        return false;
    }
    let m = Material::new(mat.clone());
    let (le, two_sided) = (m.emission(), m.desc.double_sided);
    let tris = mesh.indices.iter().enumerate().filter_map(|(k, t)| {
        let p = t.map(|i| mesh.positions.get(i as usize).copied());
        Some((k as u32, [p[0]?, p[1]?, p[2]?], 0))
    });
    !AreaLights::build(tris, |_| (le, two_sided)).is_empty()
}

/// Whether anything lights the description: its own lights or emitters, an environment
/// light, or lights Iris added.
pub fn is_lit(desc: &SceneDesc) -> bool {
    desc.environment_light.is_some()
        || desc.added_lights != AddedLights::None
        || has_own_light(desc)
}

/// Gives a description that nothing lights the default key and fill lights
/// ([`AddedLights::KeyFill`]); returns whether it did. The one place this decision is
/// taken: [`crate::prepare`] calls it after the studio's turn, and [`super::Scene::build`]
/// for every other caller.
pub fn light_if_unlit(desc: &mut SceneDesc) -> bool {
    let unlit = !is_lit(desc);
    if unlit {
        desc.added_lights = AddedLights::KeyFill;
    }
    unlit
}

/// The render light of a studio key.
pub fn spot(k: &SpotKey) -> Light {
    Light::Spot {
        position: k.position,
        direction: k.direction,
        intensity: Vec3::splat(k.intensity),
        cos_inner: k.cos_inner,
        cos_outer: k.cos_outer,
        range: None,
    }
}

/// The lights to render `desc` with: its own punctual lights, each with the exact spectral
/// shape of a light that names one, then the added ones.
pub fn render_lights(desc: &SceneDesc) -> Vec<PunctualLight> {
    let own = desc.lights.iter().map(|l| PunctualLight {
        light: render_light(l),
        shape: l
            .spectrum()
            .map(|s| s.emitter_shape(l.color() * l.intensity())),
    });
    let added = match &desc.added_lights {
        AddedLights::None => Vec::new(),
        AddedLights::KeyFill => light::default_lights(),
        AddedLights::Studio(keys) => keys.iter().map(spot).collect(),
    };
    own.chain(
        added
            .into_iter()
            .map(|light| PunctualLight { light, shape: None }),
    )
    .collect()
}

/// The render light of a validated description: colour × intensity (the colour including
/// the spectrum's sRGB colour, [`LightDesc::effective_color`]), unit directions, cosines
/// of the cone angles.
fn render_light(d: &LightDesc) -> Light {
    let color = d.effective_color();
    match d {
        LightDesc::Point {
            position,
            intensity,
            range,
            ..
        } => Light::Point {
            position: *position,
            intensity: color * *intensity,
            range: *range,
        },
        LightDesc::Spot {
            position,
            direction,
            intensity,
            range,
            inner_cone,
            outer_cone,
            ..
        } => Light::Spot {
            position: *position,
            direction: direction.normalize_or(Vec3::NEG_Z),
            intensity: color * *intensity,
            cos_inner: inner_cone.cos(),
            cos_outer: outer_cone.cos(),
            range: *range,
        },
        LightDesc::Directional {
            direction,
            intensity,
            ..
        } => Light::Directional {
            direction: direction.normalize_or(Vec3::NEG_Y),
            illuminance: color * *intensity,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::env::Environment;
    use crate::material::MaterialDesc;
    use crate::scene::desc::MeshDesc;

    fn quad(material: Option<usize>, h: f32) -> MeshDesc {
        MeshDesc {
            name: "quad".into(),
            positions: vec![
                Vec3::new(-h, 0.0, -h),
                Vec3::new(-h, 0.0, h),
                Vec3::new(h, 0.0, h),
                Vec3::new(h, 0.0, -h),
            ],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            material,
            ..MeshDesc::default()
        }
    }

    #[test]
    fn only_an_unlit_description_gets_the_key_and_fill() {
        let emitter = MaterialDesc {
            emissive: Vec3::ONE,
            ..MaterialDesc::default()
        };
        let mut d = SceneDesc {
            meshes: vec![quad(None, 1.0)],
            materials: vec![emitter],
            ..SceneDesc::default()
        };
        assert!(!has_own_light(&d));
        let mut lit = d.clone();
        lit.environment_light = Some(Environment::Uniform {
            radiance: Vec3::ONE,
        });
        assert!(!light_if_unlit(&mut lit));
        assert_eq!(lit.added_lights, AddedLights::None);
        // An emitting quad is light of its own; a zero-area one is not (as for AreaLights).
        d.meshes.push(quad(Some(0), 0.0));
        assert!(!has_own_light(&d));
        d.meshes.push(quad(Some(0), 1.0));
        assert!(has_own_light(&d));
        d.meshes.pop();
        assert!(light_if_unlit(&mut d));
        assert_eq!(d.added_lights, AddedLights::KeyFill);
        // Once lit, it stays as it is.
        assert!(!light_if_unlit(&mut d));
        let lights = render_lights(&d);
        assert_eq!(lights.len(), light::default_lights().len());
        assert!(lights.iter().all(|l| l.shape.is_none()));
    }
}
