#![allow(dead_code)]
//! The scenes of the texture tests and the material properties they texture. Each
//! [`Feature`] is one textured property on a material chosen so that the property alone
//! decides what the camera sees, on a [`Stage`]:
//!
//! - [`flat`]: a 2 m × 2 m quad in the z = 0 plane facing +Z, u along +x, v along −y
//!   (TEXCOORD_0; TEXCOORD_1 when given), seen by an orthographic camera at z = 2 whose
//!   square image the quad fills (pixel column ↔ u, row ↔ v), lit by one directional light
//!   of illuminance π ([`Light`]). Lit by a delta light through next-event estimation only
//!   (nothing else in the scene reflects), its renders vary with the seed only through
//!   the pixel-filter positions (and the wavelengths, in spectral transport).
//! - [`reflector`]: the textured quad reflects a spot light onto a ceiling the camera
//!   sees; only photons carry that light.

use super::gltf::{orthographic, quad, Doc};
use image::RgbaImage;
use serde_json::{json, Value};

/// How the flat quad is lit.
#[derive(Clone, Copy)]
pub enum Light {
    /// Directional, along −Z (normal incidence).
    Normal,
    /// Directional, 40° from the normal, travelling towards −x.
    Oblique,
    /// Directional, along +Z: from behind the quad.
    Behind,
}

/// TEXCOORD_0 at the quad's corners (counter-clockwise from the bottom-left).
pub const UV0: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];

/// TEXCOORD_0 mirrored in u.
pub const UV0_MIRRORED: [[f32; 2]; 4] = [[1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0]];

/// The flat-quad scene with `material`, `image` as texture 0, TEXCOORD_0 `uv0` and, when
/// given, TEXCOORD_1 `uv1` at the corners.
pub fn flat(
    material: Value,
    image: RgbaImage,
    light: Light,
    uv0: [[f32; 2]; 4],
    uv1: Option<[[f32; 2]; 4]>,
) -> Doc {
    let rotation = match light {
        Light::Normal => [0.0, 0.0, 0.0, 1.0],
        Light::Oblique => {
            let (s, c) = (40f32.to_radians() / 2.0).sin_cos();
            [0.0, s, 0.0, c]
        }
        Light::Behind => [0.0, 1.0, 0.0, 0.0],
    };
    let mut mesh = quad(
        [
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        uv0,
        0,
    );
    mesh.uv1 = uv1.map(|u| u.to_vec());
    Doc {
        meshes: vec![mesh],
        materials: vec![material],
        images: vec![image],
        camera: orthographic(1.0),
        camera_at: ([0.0, 0.0, 2.0], [0.0, 0.0, 0.0, 1.0]),
        lights: vec![(
            json!({"type": "directional", "intensity": std::f32::consts::PI}),
            [0.0, 0.0, 2.0],
            rotation,
        )],
    }
}

/// Where a feature is shown.
#[derive(Clone, Copy)]
pub enum Stage {
    Flat(Light),
    Reflector,
}

impl Stage {
    /// The scene with `material` and `image` as texture 0.
    pub fn doc(self, material: Value, image: RgbaImage) -> Doc {
        match self {
            Stage::Flat(light) => flat(material, image, light, UV0, None),
            Stage::Reflector => reflector(material, image),
        }
    }
}

/// A textured property: its material (given the textureInfo in its slot), its texels
/// where the mask is on and off, and the stage that shows it.
pub struct Feature {
    pub name: &'static str,
    pub material: fn(Value) -> Value,
    pub on: [u8; 4],
    pub off: [u8; 4],
    pub stage: Stage,
}

/// A black, non-specular surface (base colour 0, KHR_materials_specular factor 0) with
/// the extension objects `ext` added.
pub fn black(ext: Value) -> Value {
    let mut e = json!({"KHR_materials_specular": {"specularFactor": 0.0}});
    for (k, v) in ext.as_object().unwrap() {
        e[k] = v.clone();
    }
    json!({"pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0},
           "extensions": e})
}

pub const WHITE: [u8; 4] = [255, 255, 255, 255];
pub const BLACK: [u8; 4] = [0, 0, 0, 255];

/// Base colour (Lambertian, no specular layer): works today, the control.
pub const BASE_COLOUR: Feature = Feature {
    name: "base_colour",
    material: |tex| {
        json!({"pbrMetallicRoughness": {"baseColorTexture": tex, "metallicFactor": 0.0},
               "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}})
    },
    on: [230, 230, 230, 255],
    off: [40, 40, 40, 255],
    stage: Stage::Flat(Light::Normal),
};

/// Clearcoat factor (R) on a black base: the coat's GGX highlight (coat roughness 0.3)
/// under the normal light shows only where the factor is 1.
pub const CLEARCOAT: Feature = Feature {
    name: "clearcoat",
    material: |tex| {
        black(json!({"KHR_materials_clearcoat": {"clearcoatFactor": 1.0,
            "clearcoatTexture": tex, "clearcoatRoughnessFactor": 0.3}}))
    },
    on: WHITE,
    off: BLACK,
    stage: Stage::Flat(Light::Normal),
};

/// Sheen colour (RGB) on a black base, roughness 0.5, under the oblique light.
pub const SHEEN: Feature = Feature {
    name: "sheen",
    material: |tex| {
        black(
            json!({"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0],
            "sheenColorTexture": tex, "sheenRoughnessFactor": 0.5}}),
        )
    },
    on: WHITE,
    off: BLACK,
    stage: Stage::Flat(Light::Oblique),
};

/// Diffuse transmission strength (A) on a black base, lit from behind.
pub const DIFFUSE_TRANSMISSION: Feature = Feature {
    name: "diffuse_transmission",
    material: |tex| {
        black(
            json!({"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 1.0,
            "diffuseTransmissionTexture": tex}}),
        )
    },
    on: WHITE,
    off: [255, 255, 255, 0],
    stage: Stage::Flat(Light::Behind),
};

/// Iridescence thickness (G: 200 nm off, 600 nm on; film IOR 1.8) on a black dielectric of
/// roughness 0.3: the highlight's colour follows the thickness.
pub const IRIDESCENCE: Feature = Feature {
    name: "iridescence_thickness",
    material: |tex| {
        json!({"pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0],
                "metallicFactor": 0.0, "roughnessFactor": 0.3},
               "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1.0,
                "iridescenceIor": 1.8, "iridescenceThicknessMinimum": 200.0,
                "iridescenceThicknessMaximum": 600.0, "iridescenceThicknessTexture": tex}}})
    },
    on: [0, 255, 0, 255],
    off: [0, 0, 0, 255],
    stage: Stage::Flat(Light::Normal),
};

/// Anisotropy (RG direction, B strength) on a white metal of roughness 0.4 under the
/// oblique light: stretched along the tangent (on) the highlight reaches the camera,
/// stretched along the bitangent (off) it does not. A texture transform moves which texel
/// is read, not the direction the texel holds (KHR_texture_transform maps texture
/// coordinates only), so a baked image holds the same directions.
pub const ANISOTROPY: Feature = Feature {
    name: "anisotropy",
    material: |tex| {
        json!({"pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0],
                "metallicFactor": 1.0, "roughnessFactor": 0.4},
               "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1.0,
                "anisotropyTexture": tex}}})
    },
    on: [255, 128, 255, 255],
    off: [128, 255, 255, 255],
    stage: Stage::Flat(Light::Oblique),
};

/// Anisotropy strength (B) on a white metal of roughness 0.05 on the [`reflector`]: where
/// the strength is 0 the quad mirrors the spot light onto the ceiling as a sharp patch,
/// where it is 1 (along the tangent, α_t = 1) it smears that light across the ceiling.
pub const ANISOTROPY_REFLECTOR: Feature = Feature {
    name: "anisotropy_reflector",
    material: |tex| {
        json!({"pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0],
                "metallicFactor": 1.0, "roughnessFactor": 0.05},
               "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1.0,
                "anisotropyTexture": tex}}})
    },
    on: [255, 128, 0, 255],
    off: [255, 128, 255, 255],
    stage: Stage::Reflector,
};

/// The reflector scene: the textured quad (the material `material` with `image`) lies in
/// y = 0 (x, z in [−1, 1], facing up, u along +x, v along +z) under a spot light at
/// (0, 3, 3) aimed at its centre (45° incidence, cone ½ rad, 200 cd); what it reflects
/// forms its image on a white Lambertian ceiling (albedo 0.8, y = 1.5, x in [−2.2, 2.2],
/// z in [−3.7, 0.3], seen from below by an orthographic camera at (0, 0.7, −1.5) spanning
/// x in [−2, 2], z in [−3.5, 0.5], image up = +z). The light is above the ceiling's plane,
/// so the ceiling's underside receives only light the quad reflects: light → glossy
/// reflection → diffuse, which a path tracer cannot find (a point light, a near-specular
/// bounce) and photons carry.
pub fn reflector(material: Value, image: RgbaImage) -> Doc {
    let ceiling = json!({"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0],
        "metallicFactor": 0.0}, "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}});
    let (s, c) = (-std::f32::consts::FRAC_PI_8).sin_cos();
    let h = std::f32::consts::FRAC_1_SQRT_2;
    Doc {
        meshes: vec![
            quad(
                [
                    [-1.0, 0.0, -1.0],
                    [-1.0, 0.0, 1.0],
                    [1.0, 0.0, 1.0],
                    [1.0, 0.0, -1.0],
                ],
                [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]],
                0,
            ),
            quad(
                [
                    [-2.2, 1.5, -3.7],
                    [2.2, 1.5, -3.7],
                    [2.2, 1.5, 0.3],
                    [-2.2, 1.5, 0.3],
                ],
                [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                1,
            ),
        ],
        materials: vec![material, ceiling],
        images: vec![image],
        camera: orthographic(2.0),
        camera_at: ([0.0, 0.7, -1.5], [h, 0.0, 0.0, h]),
        lights: vec![(
            json!({"type": "spot", "intensity": 200.0,
                   "spot": {"innerConeAngle": 0.45, "outerConeAngle": 0.5}}),
            [0.0, 3.0, 3.0],
            [s, 0.0, 0.0, c],
        )],
    }
}
