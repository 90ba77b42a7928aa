//! Which scenes the SoA kernel renders ([`qualify`]), and what it reads of them: a table of
//! the materials on triangles ([`Shade`]) and of the punctual lights ([`Punctual`]).
//!
//! The kernel's scene class: RGB transport, a perspective camera, punctual lights only
//! (point, spot, directional), no emissive surface, environment, medium or fog, alpha
//! mask or touching faces. Anything else is refused with the reason (one line), and the
//! scalar path tracer renders the scene instead.
//!
//! In such a scene the kernel shades two lobes across the lanes:
//! - a **pure Lambert lobe**: opaque, untextured, metallic 0, `specular` 0
//!   (`make_variant.py --spec0`; the glTF BRDF with F0 = F90 = 0 is albedo/π, sampled by
//!   cosine alone, [`crate::bsdf::gltf_brdf`]), no layers, film, anisotropy or metal;
//! - a **smooth clear dielectric volume**: transmission 1, roughness 0, thickness > 0, a
//!   finite index, no absorption (infinite attenuation distance), untextured, at most one
//!   such material (so volumes never nest and η is the material's index against air).
//!
//! Every other material ([`Shade::Scalar`]: textured, layered, specular or metal, rough,
//! thin or absorbing glass, crystals, polarizers, alpha blending) is the scalar path
//! vertex's: a lane meeting it hands its path over ([`super::handoff`]), and the plan
//! names each such material with the reason.

use crate::light::sampler::Rule;
use crate::light::Light;
use crate::material::{AlphaMode, Material};
use crate::scene::Scene;

/// How the kernel shades a material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shade {
    /// On no triangle (never met).
    Unused,
    /// f = albedo/π, cosine-sampled.
    Lambert([f32; 3]),
    /// A smooth dielectric of index ratio `eta` (inside over outside), transmission tinted
    /// by `tint`.
    Glass {
        /// n_inside / n_outside.
        eta: f32,
        /// The base colour, which multiplies transmission.
        tint: [f32; 3],
    },
    /// Shaded by the scalar path vertex: a lane meeting it hands its path over
    /// ([`super::handoff`]).
    Scalar,
}

/// A punctual light in the form the kernel evaluates without branches: a directional light
/// has `directional` set and `at` its direction toward the light; a point light is a spot
/// whose cone never cuts (cosines below −1); no range is an infinite one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Punctual {
    /// Position, or the unit direction toward a directional light.
    pub at: [f32; 3],
    /// Intensity × colour (candela), or illuminance (lux) for a directional light.
    pub intensity: [f32; 3],
    /// Whether the light is at infinity.
    pub directional: bool,
    /// The unit direction a spot points to.
    pub axis: [f32; 3],
    /// cos of the inner and outer cone angles (as the light gives them; a point light
    /// holds −2 and −3, so its falloff is 1).
    pub cos_inner: f32,
    /// As `cos_inner`.
    pub cos_outer: f32,
    /// KHR range (`f32::INFINITY` for none: its window is then 1).
    pub range: f32,
}

/// What the kernel reads of a qualifying scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Tables {
    /// Per material index (as [`crate::scene::Triangle::material`]).
    pub shades: Vec<Shade>,
    /// The punctual lights, chosen uniformly for next-event estimation as the scene's
    /// light sampler chooses them ([`crate::light::sampler::Rule::Uniform`]).
    pub lights: Vec<Punctual>,
    /// The materials on triangles the kernel leaves to the scalar vertex, each named with
    /// the reason (for the plan).
    pub scalar: Vec<String>,
}

/// The tables of `scene` seen through a perspective camera (`perspective`) in RGB
/// (`spectral` false), or why the kernel does not render it.
pub fn qualify(scene: &Scene, perspective: bool, spectral: bool) -> Result<Tables, String> {
    if spectral {
        return Err("spectral transport (the kernel carries RGB: --spectral off)".into());
    }
    if !perspective {
        return Err("an orthographic camera".into());
    }
    if scene.has_media() {
        return Err("a scattering medium or fog".into());
    }
    if scene.environment().is_some() {
        return Err("an environment light".into());
    }
    if scene.has_cutouts() {
        return Err("alpha-masked materials".into());
    }
    if scene.touching_triangles() > 0 {
        return Err("touching (coincident) faces".into());
    }
    if scene.light_sampler().rule() != Rule::Uniform {
        return Err("lights chosen by power for next-event estimation".into());
    }
    let mut used = vec![false; scene.materials().len()];
    for t in scene.triangles() {
        used[t.material() as usize] = true;
    }
    let (mut shades, mut scalar) = (Vec::with_capacity(used.len()), Vec::new());
    for (m, used) in scene.materials().iter().zip(used) {
        if !used {
            shades.push(Shade::Unused);
        } else if m.emission() != glam::Vec3::ZERO {
            return Err(format!("{} emits light", element(m)));
        } else {
            shades.push(shade(m).unwrap_or_else(|why| {
                scalar.push(why);
                Shade::Scalar
            }));
        }
    }
    let glasses = shades
        .iter()
        .filter(|s| matches!(s, Shade::Glass { .. }))
        .count();
    if glasses > 1 {
        return Err(format!(
            "{glasses} dielectric materials (the kernel takes one, so volumes never nest)"
        ));
    }
    let lights = scene.lights().iter().map(|l| punctual(&l.light)).collect();
    Ok(Tables {
        shades,
        lights,
        scalar,
    })
}

/// `m` named as an element of its file (loaded materials are named so already:
/// `material 0 "Floor"`).
fn element(m: &Material) -> String {
    if m.desc.name.starts_with("material ") {
        m.desc.name.clone()
    } else {
        format!("material \"{}\"", m.desc.name)
    }
}

/// How the kernel shades `m`, or why its lanes go to the scalar vertex.
fn shade(m: &Material) -> Result<Shade, String> {
    let d = &m.desc;
    let name = element(m);
    let l = &d.layers;
    let why = if d.textures().iter().any(|(_, t)| t.is_some()) {
        Some("is textured")
    } else if !matches!(d.alpha_mode, AlphaMode::Opaque) {
        Some("is alpha-blended")
    } else if l.clearcoat != 0.0 || l.sheen_color != glam::Vec3::ZERO {
        Some("has a clearcoat or sheen layer")
    } else if l.diffuse_transmission != 0.0 {
        Some("has diffuse transmission")
    } else if d.iridescence.is_some() || d.anisotropy.is_some() {
        Some("has a thin film or anisotropy")
    } else if d.conductor.is_some() || d.crystal.is_some() || d.polarizer.is_some() {
        Some("is a measured metal, crystal or polarizer")
    } else {
        None
    };
    if let Some(why) = why {
        return Err(format!("{name} {why}"));
    }
    let base = d
        .base_color
        .truncate()
        .clamp(glam::Vec3::ZERO, glam::Vec3::ONE);
    let transmission = d.transmission.clamp(0.0, 1.0) * (1.0 - d.metallic.clamp(0.0, 1.0));
    if transmission == 0.0 {
        if d.metallic != 0.0 || d.specular != 0.0 {
            return Err(format!(
                "{name} has a specular or metal lobe (the kernel shades a pure \
                 Lambert lobe: metallic 0, specular 0)"
            ));
        }
        return Ok(Shade::Lambert(base.to_array()));
    }
    let eta = m.ior();
    let why = if transmission < 1.0 {
        Some("mixes transmission with reflection")
    } else if !m.is_volume() {
        Some("is a thin sheet")
    } else if d.roughness != 0.0 {
        Some("is rough glass")
    } else if d.attenuation_distance.is_finite() {
        Some("absorbs (finite attenuation distance)")
    } else if !(eta.is_finite() && eta > 0.0) {
        Some("has an infinite index (ior 0)")
    } else {
        None
    };
    match why {
        Some(why) => Err(format!("{name} {why}")),
        None => Ok(Shade::Glass {
            eta,
            tint: base.to_array(),
        }),
    }
}

/// `light` in the kernel's form ([`Punctual`]).
fn punctual(light: &Light) -> Punctual {
    let point = |at: glam::Vec3, intensity: glam::Vec3, range: Option<f32>| Punctual {
        at: at.to_array(),
        intensity: intensity.to_array(),
        directional: false,
        axis: [0.0, 0.0, 1.0],
        cos_inner: -2.0,
        cos_outer: -3.0,
        range: range.filter(|r| *r > 0.0).unwrap_or(f32::INFINITY),
    };
    match *light {
        Light::Point {
            position,
            intensity,
            range,
        } => point(position, intensity, range),
        Light::Spot {
            position,
            direction,
            intensity,
            cos_inner,
            cos_outer,
            range,
        } => Punctual {
            axis: direction.to_array(),
            cos_inner,
            cos_outer,
            ..point(position, intensity, range)
        },
        Light::Directional {
            direction,
            illuminance,
        } => Punctual {
            directional: true,
            ..point(-direction, illuminance, None)
        },
    }
}
