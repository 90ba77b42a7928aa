//! Which scenes the SoA kernel renders ([`qualify`]), and what it reads of them: a table of
//! the materials on triangles ([`Shade`]), their emission and absorption, the punctual
//! lights ([`Punctual`]) and the lights next-event estimation chooses among.
//!
//! The kernel's scene class: RGB or spectral transport, a perspective camera, lights of any kind the
//! scalar path tracer samples (punctual lights, emissive triangles, an environment: uniform,
//! a map or a sky) chosen uniformly, no medium or fog, alpha mask or touching faces, and no
//! glass volume that may lie inside another. Anything else is refused with the reason (one
//! line), and the scalar path tracer renders the scene instead.
//!
//! In such a scene the kernel shades four lobes across the lanes:
//! - a **pure Lambert lobe**: opaque, untextured, metallic 0, `specular` 0
//!   (`make_variant.py --spec0`; the glTF BRDF with F0 = F90 = 0 is albedo/π, sampled by
//!   cosine alone, [`crate::bsdf::gltf_brdf`]), no layers, film, anisotropy or metal; it
//!   may emit (a black one, as the usual area light, scatters nothing);
//! - the **glTF BRDF with its specular or metal part** (Lambert + GGX, KHR_materials_specular,
//!   metallic): opaque, untextured, isotropic, no layer or film, emitting or not
//!   ([`super::glossy`]: the scalar BSDF's own eval, pdf and sample, per lane);
//! - a **rough dielectric volume** (not dispersive): the scalar BSDF per lane, as the glossy
//!   lobe ([`super::glossy`]), entering and leaving the volume as the smooth one does;
//! - a **smooth dielectric volume**: transmission 1, roughness 0, thickness > 0, a finite
//!   index, untextured, absorbing or not (Beer–Lambert, [`Material::absorbs`]), dispersive
//!   or not (in spectral transport a path splits into its wavelengths at the first
//!   dispersive one, [`super::branches`]).
//!
//! Rough glass whose mesh's box overlaps another glass mesh's goes to the scalar vertex
//! (which tracks nested volumes).
//! Several dielectric materials are taken when no glass volume can lie inside another: the
//! bounding boxes of the meshes carrying a kernel dielectric are pairwise disjoint (a
//! closed volume lies inside its mesh's box, so a volume inside another would put one box
//! inside the other) and no faces touch ([`Scene::touching_triangles`]); the η at a hit is
//! then the material's index against air.
//!
//! Every other material ([`Shade::Scalar`]: textured, layered, filmed, anisotropic,
//! measured metals, rough dispersive or thin glass, crystals, polarizers, alpha blending;
//! emitting or not) is the scalar path vertex's: a lane meeting it hands its path over
//! ([`super::handoff`]), and the plan names each such material with the reason.

use crate::light::sampler::Rule;
use crate::light::Light;
use crate::light::LightId;
use crate::material::{AlphaMode, Material};
use crate::scene::Scene;
use crate::spectrum::EmitterShape;

/// How the kernel shades a material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shade {
    /// On no triangle (never met).
    Unused,
    /// f = albedo/π, cosine-sampled.
    Lambert([f32; 3]),
    /// The glTF BRDF with a specular or metal part (untextured, isotropic, no layer or
    /// film): the scalar BSDF's own eval, pdf and sample per lane ([`super::glossy`]).
    Glossy,
    /// A rough dielectric volume of index ratio `eta` (inside over outside; not dispersive,
    /// GGX α = roughness² above the smooth limit): shaded per lane as [`Shade::Glossy`].
    RoughGlass {
        /// n_inside / n_outside.
        eta: f32,
    },
    /// A smooth dielectric of index ratio `eta` (inside over outside), transmission tinted
    /// by `tint`.
    Glass {
        /// n_inside / n_outside (at the d line for a dispersive glass).
        eta: f32,
        /// The base colour, which multiplies transmission.
        tint: [f32; 3],
        /// Its index depends on the wavelength ([`Material::is_dispersive`]): in spectral
        /// transport a path keeps only its hero wavelength there, or splits.
        dispersive: bool,
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
    /// The punctual lights, in the scene's order.
    pub lights: Vec<Punctual>,
    /// The materials on triangles the kernel leaves to the scalar vertex, each named with
    /// the reason (for the plan).
    pub scalar: Vec<String>,
    /// The lights next-event estimation chooses among, each with probability 1/n, in the
    /// order of the scene's light sampler ([`crate::light::sampler::Rule::Uniform`]).
    pub sampled: Vec<LightId>,
    /// Per material index: the emitted radiance (linear RGB; zero for none) and whether it
    /// leaves both sides.
    pub emission: Vec<([f32; 3], bool)>,
    /// Per material index: the Beer–Lambert absorption coefficient σ per channel (per unit
    /// length, `transmittance_at(x)` = e^(−σx) = c^(x/d)); zero where nothing absorbs.
    pub absorption: Vec<[f32; 3]>,
    /// Per material index: the exact spectral shape its emission names, if any.
    pub emitter_shapes: Vec<Option<EmitterShape>>,
    /// Per punctual light: the exact spectral shape it names, if any.
    pub light_shapes: Vec<Option<EmitterShape>>,
    /// Spectral transport (4 wavelengths a lane) rather than RGB.
    pub spectral: bool,
}

/// The tables of `scene` seen through a perspective camera (`perspective`) in spectral
/// transport or RGB (`spectral`), or why the kernel does not render it.
pub fn qualify(scene: &Scene, perspective: bool, spectral: bool) -> Result<Tables, String> {
    if !perspective {
        return Err("an orthographic camera".into());
    }
    if scene.has_media() {
        return Err("a scattering medium or fog".into());
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
        } else {
            shades.push(shade(m).unwrap_or_else(|why| {
                scalar.push(why);
                Shade::Scalar
            }));
        }
    }
    let rough = |s: &Shade| matches!(s, Shade::RoughGlass { .. });
    if shades.iter().any(rough) && overlapping_glass(scene, &shades).is_some() {
        for (s, m) in shades.iter_mut().zip(scene.materials()) {
            if rough(s) {
                *s = Shade::Scalar;
                let why = "is rough glass whose volume may lie inside another's";
                scalar.push(format!("{} {why}", element(m)));
            }
        }
    }
    if let Some((a, b)) = overlapping_glass(scene, &shades) {
        return Err(format!(
            "the glass meshes {a} and {b} have overlapping bounding boxes (one volume might \
             lie inside the other)"
        ));
    }
    let lights = scene.lights().iter().map(|l| punctual(&l.light)).collect();
    let emission = scene
        .materials()
        .iter()
        .map(|m| (m.emission().to_array(), m.desc.double_sided))
        .collect();
    let absorption = scene.materials().iter().map(absorption).collect();
    let emitter_shapes = scene
        .materials()
        .iter()
        .map(|m| m.emitter_shape().copied())
        .collect();
    let light_shapes = scene.lights().iter().map(|l| l.shape).collect();
    Ok(Tables {
        shades,
        lights,
        scalar,
        sampled: scene.light_sampler().lights().to_vec(),
        emission,
        absorption,
        emitter_shapes,
        light_shapes,
        spectral,
    })
}

/// σ = −ln(c)/d per channel of `m`'s attenuation colour c and distance d where it bounds a
/// volume that absorbs ([`Material::is_volume`], [`Material::absorbs`]), else zero.
fn absorption(m: &Material) -> [f32; 3] {
    if !(m.is_volume() && m.absorbs()) {
        return [0.0; 3];
    }
    let d = m.desc.attenuation_distance;
    m.desc.attenuation_color.to_array().map(|c| -c.ln() / d)
}

/// Two meshes carrying a dielectric whose bounding boxes overlap, by name; `None` when the
/// boxes are pairwise disjoint (so no glass volume lies inside another).
fn overlapping_glass(scene: &Scene, shades: &[Shade]) -> Option<(String, String)> {
    let empty = (glam::Vec3::INFINITY, glam::Vec3::NEG_INFINITY);
    let mut boxes = vec![None::<(glam::Vec3, glam::Vec3)>; scene.meshes().len()];
    for t in scene.triangles() {
        if matches!(
            shades[t.material() as usize],
            Shade::Glass { .. } | Shade::RoughGlass { .. }
        ) {
            let b = &mut boxes[t.mesh as usize];
            let (lo, hi) = b.unwrap_or(empty);
            *b = Some(
                t.p.iter()
                    .fold((lo, hi), |(l, h), q| (l.min(*q), h.max(*q))),
            );
        }
    }
    let glass: Vec<(usize, glam::Vec3, glam::Vec3)> = boxes
        .iter()
        .enumerate()
        .filter_map(|(k, b)| b.map(|(lo, hi)| (k, lo, hi)))
        .collect();
    let name = |k: usize| scene.meshes()[k].name.clone();
    for (i, &(a, alo, ahi)) in glass.iter().enumerate() {
        for &(b, blo, bhi) in &glass[i + 1..] {
            if alo.cmple(bhi).all() && blo.cmple(ahi).all() {
                return Some((name(a), name(b)));
            }
        }
    }
    None
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
            return Ok(Shade::Glossy);
        }
        return Ok(Shade::Lambert(base.to_array()));
    }
    let eta = m.ior();
    let why = if transmission < 1.0 {
        Some("mixes transmission with reflection")
    } else if !m.is_volume() {
        Some("is a thin sheet")
    } else if !(eta.is_finite() && eta > 0.0) {
        Some("has an infinite index (ior 0)")
    } else {
        None
    };
    if let Some(why) = why {
        return Err(format!("{name} {why}"));
    }
    if rough(m, eta) {
        if m.is_dispersive() {
            return Err(format!(
                "{name} is rough dispersive glass (spectral MIS over its wavelengths)"
            ));
        }
        return Ok(Shade::RoughGlass { eta });
    }
    Ok(Shade::Glass {
        eta,
        tint: base.to_array(),
        dispersive: m.is_dispersive(),
    })
}

/// Whether the volume boundary of `m` (index ratio `eta` against air) is a rough
/// dielectric: its BSDF is not a delta (GGX α = roughness² at or above the smooth limit,
/// [`crate::bsdf::Bsdf::is_delta`]); below that limit the scalar path shades it as
/// smooth glass, and so does the kernel.
fn rough(m: &Material, eta: f32) -> bool {
    m.untextured().is_some_and(|sp| {
        !m.transmission_bsdf::<glam::Vec3>(sp, Some(eta), &())
            .is_delta()
    })
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
