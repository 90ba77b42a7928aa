#![allow(dead_code)]
//! The textured-emitter scenes: a 1 m × 1 m emitting panel over a Lambertian floor, seen
//! by a camera straight above, and the exact floor radiance of the direct one.
//!
//! Frame: metres, +Y up. Floor: y = 0, x and z in [−2, 2], facing up, Lambertian albedo
//! [`FLOOR_ALBEDO`] (KHR_materials_specular factor 0: no specular layer). Panel: x and z in
//! [−0.5, 0.5], single-sided, black (base colour 0, specular 0: it absorbs everything),
//! emission 1 (linear, times the texture), texture coordinates u = x + 0.5, v = z + 0.5.
//! Camera: perspective, at (0, 4, 0) looking down −Y with image up = −Z, yfov = 2·atan ½,
//! so a square image spans the floor x, z ∈ [−2, 2]: image column ↔ x, row ↔ z.
//!
//! - [`Layout::Direct`]: the panel at y = 0.5 faces down; the floor sees it directly and
//!   nothing else (the panel is black, the floor is a plane), so the floor radiance is
//!   exactly ρ/π · E, E the irradiance from the panel's emitting part ([`floor_radiance`]).
//! - [`Layout::Glass`]: the same panel with a clear thin-walled glass sheet (KHR
//!   transmission 1, no volume: a delta transmission) at y = 0.45 under it, x and z in
//!   [−0.75, 0.75], wide enough that every ray from the panel to the floor crosses it (at
//!   |x|, |z| ≤ 0.65). All
//!   floor light is then light → specular → diffuse, a caustic: what the hybrid's caustic
//!   map and light tracing carry, and what next-event estimation cannot reach (shadow rays
//!   do not pass glass). The sheet's image ends at |x|, |z| = 0.85.
//!
//! The emitting part is either a texture on the whole panel or, for the reference, the
//! same part cut out as its own untextured emitting quad with the rest of the panel kept as
//! a black, non-emitting quad (same geometry, same occlusion).

use super::gltf::{perspective, quad, Doc, Mesh, LOOK_DOWN};
use image::RgbaImage;
use serde_json::{json, Value};

/// Floor albedo ρ.
pub const FLOOR_ALBEDO: f64 = 0.8;
/// Camera height (m) and half the floor width the image spans at y = 0.
pub const CAMERA_HEIGHT: f64 = 4.0;
pub const VIEW_HALF: f64 = 2.0;

#[derive(Clone, Copy, PartialEq, Debug)]
pub enum Layout {
    Direct,
    Glass,
}

/// The panel's height (m), both layouts.
pub const PANEL_Y: f32 = 0.5;

/// The panel's texture coordinate sets.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum Sets {
    /// TEXCOORD_0 only: u = x + 0.5, v = z + 0.5.
    One,
    /// TEXCOORD_0 only, mirrored: u = 0.5 − x.
    Mirrored,
    /// TEXCOORD_0 as [`Sets::One`] and TEXCOORD_1 as [`Sets::Mirrored`].
    Both,
}

/// How the panel emits.
pub enum Emission {
    /// Emission 1 times `image`, referenced by the textureInfo `info` (`{"index": 0, …}`),
    /// on the panel with texture coordinate sets `sets`.
    Texture(RgbaImage, Value, Sets),
    /// Emission 1 on the panel rectangle u ∈ [u0, u1], v ∈ [v0, v1] (texture space of the
    /// panel), cut out as its own quad; the rest of the panel black.
    Cut { u: [f32; 2], v: [f32; 2] },
}

/// The scene of `layout` with the panel emitting as `emission`.
pub fn scene(layout: Layout, emission: Emission) -> Doc {
    let floor = json!({"name": "floor",
        "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0},
        "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}});
    let black = json!({"pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0],
        "metallicFactor": 0.0}, "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}});
    let mut emitter = black.clone();
    emitter["name"] = json!("panel");
    emitter["emissiveFactor"] = json!([1.0, 1.0, 1.0]);
    let mut doc = Doc {
        meshes: vec![floor_quad()],
        materials: vec![floor, emitter, black],
        images: Vec::new(),
        camera: perspective(2.0 * 0.5f32.atan()),
        camera_at: ([0.0, CAMERA_HEIGHT as f32, 0.0], LOOK_DOWN),
        lights: Vec::new(),
    };
    match emission {
        Emission::Texture(img, info, sets) => {
            doc.materials[1]["emissiveTexture"] = info;
            doc.images.push(img);
            let mut p = panel([0.0, 1.0], [0.0, 1.0], 1);
            let mirrored: Vec<[f32; 2]> = p.uv0.iter().map(|t| [1.0 - t[0], t[1]]).collect();
            match sets {
                Sets::One => {}
                Sets::Mirrored => p.uv0 = mirrored,
                Sets::Both => p.uv1 = Some(mirrored),
            }
            doc.meshes.push(p);
        }
        Emission::Cut { u, v } => {
            doc.meshes.push(panel(u, v, 1));
            // The rest of the panel: up to four black quads around the cut rectangle.
            for (ur, vr) in [
                ([0.0, u[0]], [0.0, 1.0]),
                ([u[1], 1.0], [0.0, 1.0]),
                ([u[0], u[1]], [0.0, v[0]]),
                ([u[0], u[1]], [v[1], 1.0]),
            ] {
                if ur[1] > ur[0] && vr[1] > vr[0] {
                    doc.meshes.push(panel(ur, vr, 2));
                }
            }
        }
    }
    if layout == Layout::Glass {
        doc.materials
            .push(json!({"name": "glass", "doubleSided": true,
            "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0],
                "metallicFactor": 0.0, "roughnessFactor": 0.0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}}}));
        let (m, y) = (0.75, 0.45);
        doc.meshes.push(quad(
            [[-m, y, -m], [-m, y, m], [m, y, m], [m, y, -m]],
            [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]],
            3,
        ));
    }
    doc
}

fn floor_quad() -> Mesh {
    let h = 2.0;
    quad(
        [[-h, 0.0, -h], [-h, 0.0, h], [h, 0.0, h], [h, 0.0, -h]],
        [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]],
        0,
    )
}

/// The part u ∈ `u`, v ∈ `v` of the panel (texture coordinates of the whole panel kept).
fn panel(u: [f32; 2], v: [f32; 2], material: usize) -> Mesh {
    let y = PANEL_Y;
    let (x0, x1, z0, z1) = (u[0] - 0.5, u[1] - 0.5, v[0] - 0.5, v[1] - 0.5);
    let uv = [[u[0], v[0]], [u[1], v[0]], [u[1], v[1]], [u[0], v[1]]];
    // Counter-clockwise seen from below: faces down.
    quad(
        [[x0, y, z0], [x1, y, z0], [x1, y, z1], [x0, y, z1]],
        uv,
        material,
    )
}

/// The floor point (x, z) at image position (s, t) ∈ [0, 1]² (left to right, top to
/// bottom).
pub fn floor_at(s: f64, t: f64) -> (f64, f64) {
    ((2.0 * s - 1.0) * VIEW_HALF, (2.0 * t - 1.0) * VIEW_HALF)
}

/// The floor strips each side of the panel (or the glass sheet) that the camera sees:
/// x ≤ −d (left), x ≥ d (right), z ≤ −d (top of the image), z ≥ d (bottom), out to
/// |x|, |z| ≤ 1.9, with d = 0.75 for [`Layout::Direct`] and 0.9 for [`Layout::Glass`]
/// (clear of the panel's or the sheet's image by a pixel or more).
pub fn strip(layout: Layout, side: Side) -> impl Fn(f64, f64) -> bool {
    let d = match layout {
        Layout::Direct => 0.75,
        Layout::Glass => 0.9,
    };
    move |s, t| {
        let (x, z) = floor_at(s, t);
        let inside = x.abs() <= 1.9 && z.abs() <= 1.9;
        inside
            && match side {
                Side::Left => x <= -d,
                Side::Right => x >= d,
                Side::Top => z <= -d,
                Side::Bottom => z >= d,
            }
    }
}

/// A floor strip ([`strip`]).
#[derive(Clone, Copy, Debug)]
pub enum Side {
    Left,
    Right,
    Top,
    Bottom,
}

/// The mean radiance of the four strips, in [`Side`] order.
pub fn strip_means(img: &super::render::Image, layout: Layout) -> [f64; 4] {
    [Side::Left, Side::Right, Side::Top, Side::Bottom].map(|s| img.mean_where(strip(layout, s)))
}

/// Irradiance at floor point `p` (normal +Y) from a Lambertian polygon of unit radiance
/// whose vertices `poly` all lie above the floor: E = ½ |Σᵢ γᵢ · n·(rᵢ × rᵢ₊₁)/|rᵢ × rᵢ₊₁||,
/// rᵢ the directions to the vertices and γᵢ the angle between rᵢ and rᵢ₊₁: Lambert's
/// formula for the irradiance from a uniform polygon (J. Arvo, "Applications of Irradiance
/// Tensors to the Simulation of Non-Lambertian Phenomena", SIGGRAPH 1995).
pub fn polygon_irradiance(p: [f64; 3], poly: &[[f64; 3]]) -> f64 {
    let dir = |q: [f64; 3]| {
        let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        d.map(|x| x / l)
    };
    let mut sum = 0.0;
    for i in 0..poly.len() {
        let (a, b) = (dir(poly[i]), dir(poly[(i + 1) % poly.len()]));
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        let gamma = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
            .clamp(-1.0, 1.0)
            .acos();
        if len > 0.0 {
            sum += gamma * c[1] / len;
        }
    }
    0.5 * sum.abs()
}

/// The exact floor radiance of [`Layout::Direct`] at floor point (x, z) when the panel
/// part u ∈ `u`, v ∈ `v` emits radiance 1: ρ/π · E.
pub fn floor_radiance(x: f64, z: f64, u: [f64; 2], v: [f64; 2]) -> f64 {
    let y = f64::from(PANEL_Y);
    let (x0, x1, z0, z1) = (u[0] - 0.5, u[1] - 0.5, v[0] - 0.5, v[1] - 0.5);
    let poly = [[x0, y, z0], [x1, y, z0], [x1, y, z1], [x0, y, z1]];
    FLOOR_ALBEDO / std::f64::consts::PI * polygon_irradiance([x, 0.0, z], &poly)
}
