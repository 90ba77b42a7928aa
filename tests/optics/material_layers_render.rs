//! Render tests for the KHR material layers on the generated test scenes of
//! `assets/materials/` (`iris::assets::material_layers`) and on a real clearcoat file (the shared
//! Sketchfab DiamondLowPoly): each renders finite and not black, and shows the property its
//! extension must show, measured on pixel regions located by projecting the scenes' known
//! geometry (sphere centres, highlight points, sheet centres) through the file's camera.
//!
//! Renders are the path tracer at a fixed size, seed and sample count (RGB, and spectral for
//! the generated scenes), so every number below is a deterministic function of the code.
//! Thresholds (measured values in the test docs) leave a factor ≥ 1.5 of margin to what a
//! missing or wrong layer would give; "within noise" tolerances are several times the
//! measured sample noise of the region mean at these counts.

use crate::common;

use glam::{Vec2, Vec3};
use iris::accel::Backend;
use iris::assets::material_layers::{
    row, CLEARCOATS, CLEARCOAT_LIGHT, DIFFUSE_TRANSMISSION, SHEENS, SHEET_CENTRES, SPHERE_RADIUS,
    TRANSMISSION_COLOR,
};
use iris::camera::Camera;
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::render::RenderSettings;
use iris::scene::desc::{CameraDesc, SceneDesc};
use iris::scene::Scene;
use serde_json::Value;
use std::path::{Path, PathBuf};

const W: u32 = 160;
const H: u32 = 120;

fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/materials")
        .join(name)
}

/// A rendered image with the camera that made it.
struct Shot {
    px: Vec<Vec3>,
    camera: Camera,
    desc: CameraDesc,
}

impl Shot {
    fn at(&self, x: u32, y: u32) -> Vec3 {
        self.px[(y * W + x) as usize]
    }

    fn raster(&self, p: Vec3) -> Vec2 {
        self.camera
            .project(p)
            .unwrap_or_else(|| panic!("{p} is not in view"))
            .raster
    }

    /// Projected centre and radius (pixels) of the sphere at `c`.
    fn disk(&self, c: Vec3) -> (Vec2, f32) {
        let right = self
            .desc
            .world_from_camera
            .transform_vector3(Vec3::X)
            .normalize();
        let centre = self.raster(c);
        (
            centre,
            self.raster(c + SPHERE_RADIUS * right).distance(centre),
        )
    }

    /// Pixels whose centres lie in the ring `lo·r ≤ d < hi·r` of the disk (`upper`: only
    /// those above the centre).
    fn ring(&self, c: Vec3, lo: f32, hi: f32, upper: bool) -> Vec<Vec3> {
        let (centre, r) = self.disk(c);
        let mut out = Vec::new();
        for y in 0..H {
            for x in 0..W {
                let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                let d = p.distance(centre);
                if d >= lo * r && d < hi * r && (!upper || p.y < centre.y) {
                    out.push(self.at(x, y));
                }
            }
        }
        assert!(
            out.len() >= 8,
            "region of {c} has only {} pixels",
            out.len()
        );
        out
    }

    /// The pixels of the square of half side `half` pixels around `p`'s projection.
    fn window(&self, p: Vec3, half: i32) -> Vec<Vec3> {
        let c = self.raster(p);
        let (cx, cy) = (c.x.floor() as i32, c.y.floor() as i32);
        let mut out = Vec::new();
        for y in cy - half..=cy + half {
            for x in cx - half..=cx + half {
                if (0..W as i32).contains(&x) && (0..H as i32).contains(&y) {
                    out.push(self.at(x as u32, y as u32));
                }
            }
        }
        out
    }
}

fn lum(p: Vec3) -> f32 {
    p.element_sum() / 3.0
}

fn mean(px: &[Vec3]) -> Vec3 {
    px.iter().copied().sum::<Vec3>() / px.len() as f32
}

fn peak(px: &[Vec3]) -> f32 {
    px.iter().map(|&p| lum(p)).fold(0.0, f32::max)
}

fn build(desc: SceneDesc) -> Scene {
    Scene::build(desc, Backend::Auto).expect("build")
}

/// Renders `desc` through `camera` with the path tracer (32 spp, seed 3).
fn render(desc: SceneDesc, camera: CameraDesc, spectral: bool) -> Shot {
    let scene = build(desc);
    let settings = RenderSettings {
        width: W,
        height: H,
        spp: 32,
        seed: 3,
        threads: 2,
        quiet: true,
        spectral,
        time_limit: None,
        sampler: Default::default(),
        adaptive: None,
        cancel: Default::default(),
        kernel: Default::default(),
    };
    let integrator =
        Integrator::new(Method::Path, 32, &PhotonSettings::default()).expect("path tracer");
    let cam = Camera::new(&camera, W, H);
    let (img, stats) = integrator.render(&scene, &cam, &settings).expect("render");
    assert_eq!(stats.bad_samples, 0, "NaN/inf samples");
    assert!(img.data.iter().all(|p| p.is_finite()), "non-finite pixels");
    assert!(
        img.data.iter().any(|p| p.max_element() > 0.0),
        "black image"
    );
    Shot {
        px: img.data,
        camera: cam,
        desc: camera,
    }
}

/// Loads a file and renders it through its own camera.
fn render_file(path: &Path, spectral: bool) -> Shot {
    let desc = iris::load::load_scene(path).unwrap_or_else(|e| panic!("{e}"));
    let camera = desc.cameras.first().expect("the file has a camera").clone();
    render(desc, camera, spectral)
}

/// The GLB `bytes` with extension `ext` removed from the materials `which` selects (by
/// index; all if `None`), and from `extensionsUsed` when no material uses it any more.
fn strip_extension(bytes: &[u8], ext: &str, which: Option<usize>) -> Vec<u8> {
    let word = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().expect("4 bytes"));
    assert_eq!(&bytes[..4], b"glTF");
    let json_len = word(12) as usize;
    assert_eq!(&bytes[16..20], b"JSON");
    let mut root: Value = serde_json::from_slice(&bytes[20..20 + json_len]).expect("JSON");
    let mut removed = 0;
    let mut still_used = false;
    for (i, m) in root["materials"]
        .as_array_mut()
        .expect("materials")
        .iter_mut()
        .enumerate()
    {
        let Some(exts) = m.get_mut("extensions").and_then(Value::as_object_mut) else {
            continue;
        };
        if which.is_none_or(|k| k == i) {
            removed += usize::from(exts.remove(ext).is_some());
        } else {
            still_used |= exts.contains_key(ext);
        }
    }
    assert!(removed > 0, "no material had {ext}");
    if !still_used {
        if let Some(used) = root.get_mut("extensionsUsed").and_then(Value::as_array_mut) {
            used.retain(|e| e != ext);
        }
    }
    let mut json = serde_json::to_vec(&root).expect("encode");
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let rest = &bytes[20 + json_len..];
    let mut out = Vec::with_capacity(20 + json.len() + rest.len());
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&((20 + json.len() + rest.len()) as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(rest);
    out
}

/// Writes `bytes` as `name` in a scratch directory and loads it.
fn load_bytes(scratch: &str, name: &str, bytes: &[u8]) -> SceneDesc {
    let path = common::scratch_dir(scratch).join(name);
    std::fs::write(&path, bytes).expect("write");
    iris::load::load_scene(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The point of the sphere at `c` where the light at `light` mirrors into the eye.
fn highlight_point(c: Vec3, eye: Vec3, light: Vec3) -> Vec3 {
    let h = ((eye - c).normalize() + (light - c).normalize()).normalize();
    c + SPHERE_RADIUS * h
}

/// Clearcoat: the coat adds a sharp highlight over the rough base. Per sphere, the ratio
/// of the brightest pixel in a 5 × 5 window around the mirror point of the panel light to
/// the mean of the sphere's disk (0.9 r) must grow with the coat. Measured (RGB; spectral
/// within 5 %): coat 0: 1.65 (the base's own roughness-0.6 lobe), coat 0.5: 14.1, coat 1:
/// 18.1, coat 1 of roughness 0.5: 2.26. Asserted: coat 1 ≥ 5 × coat 0, coat 0.5 ≥ 4 ×
/// coat 0 and below coat 1, the rough coat below half the smooth one (it spreads the
/// highlight). The coat-0 sphere equals the same sphere with the extension stripped from
/// its material: disk means within 1 % (measured: identical, both render the base BSDF).
#[test]
fn clearcoat_adds_a_sharp_highlight() {
    let path = asset("clearcoat.glb");
    let centres = row(CLEARCOATS.len());
    for spectral in [false, true] {
        let shot = render_file(&path, spectral);
        let eye = shot.desc.world_from_camera.transform_point3(Vec3::ZERO);
        let ratios: Vec<f32> = centres
            .iter()
            .map(|&c| {
                let hl = shot.window(highlight_point(c, eye, CLEARCOAT_LIGHT), 2);
                peak(&hl) / lum(mean(&shot.ring(c, 0.0, 0.9, false)))
            })
            .collect();
        eprintln!(
            "clearcoat spectral={spectral}: peak/mean per sphere {ratios:?} ({CLEARCOATS:?})"
        );
        let [c0, c05, c1, rough] = ratios[..] else {
            unreachable!()
        };
        assert!(c1 >= 5.0 * c0, "coat 1 {c1} vs coat 0 {c0}");
        assert!(
            c05 >= 4.0 * c0 && c05 < c1,
            "coat 0.5 {c05} not between {c0} and {c1}"
        );
        assert!(rough < 0.5 * c1, "rough coat {rough} vs smooth {c1}");
    }

    // Coat 0 (material 1, after the floor) renders like no coat at all.
    let bytes = std::fs::read(&path).expect("read");
    let stripped = load_bytes(
        "clearcoat_stripped",
        "clearcoat.glb",
        &strip_extension(&bytes, "KHR_materials_clearcoat", Some(1)),
    );
    assert_eq!(stripped.materials[1].layers, Default::default());
    let camera = stripped.cameras[0].clone();
    let plain = render(stripped, camera, false);
    let coated = render_file(&path, false);
    let (a, b) = (
        lum(mean(&coated.ring(centres[0], 0.0, 0.9, false))),
        lum(mean(&plain.ring(centres[0], 0.0, 0.9, false))),
    );
    eprintln!("coat 0 disk mean {a}, no extension {b}");
    assert!((a - b).abs() <= 0.01 * b, "coat 0 {a} vs no coat {b}");
}

/// Sheen: on the back-lit dark spheres the sheen brightens the grazing rim (ring 0.75–0.97 r,
/// upper half, towards the back light) relative to the no-sheen sphere, more than the
/// centre (disk 0.4 r, lit by the front fill). Gains are region means over the no-sheen
/// sphere's. Measured (RGB; spectral within 1 %), rim / centre gain: white 0.3: 5.8 / 1.7,
/// white 0.8: 8.2 / 4.1, blue 0.3: 3.8 / 1.5, blue 0.8: 4.6 / 2.4. Asserted: rim gain ≥ 1.5
/// and ≥ 1.5 × the centre gain (lowest measured 1.93 ×); the blue sheen's rim blue/red ≥
/// 1.5 × the white one's (measured 3.2 vs 1.0).
#[test]
fn sheen_brightens_the_grazing_rim() {
    let centres = row(SHEENS.len());
    for spectral in [false, true] {
        let shot = render_file(&asset("sheen.glb"), spectral);
        let rim = |c| lum(mean(&shot.ring(c, 0.75, 0.97, true)));
        let middle = |c| lum(mean(&shot.ring(c, 0.0, 0.4, false)));
        let (rim0, mid0) = (rim(centres[0]), middle(centres[0]));
        for (i, sheen) in SHEENS.iter().enumerate().skip(1) {
            let (rg, mg) = (rim(centres[i]) / rim0, middle(centres[i]) / mid0);
            eprintln!("sheen {sheen:?} spectral={spectral}: rim gain {rg}, centre gain {mg}");
            assert!(rg >= 1.5, "{sheen:?}: rim gain {rg}");
            assert!(
                rg >= 1.5 * mg,
                "{sheen:?}: rim gain {rg} vs centre gain {mg}"
            );
        }
        // The blue sheen tints the rim blue; the white one does not.
        let tint = |i: usize| {
            let m = mean(&shot.ring(centres[i], 0.75, 0.97, true));
            m.z / m.x
        };
        eprintln!("rim blue/red: white {} blue {}", tint(1), tint(3));
        assert!(tint(3) >= 1.5 * tint(1), "blue sheen rim not blue");
    }
}

/// Diffuse transmission: each sheet is lit from behind by its own spot (same geometry for
/// the three), so its camera side (a window of ± 0.15 m around its centre) is bright in
/// proportion to the factor and tinted by the orange diffuseTransmissionColor. Measured
/// (RGB; spectral within 1 %) mean luminance 0.031 / 0.209 / 0.380 for factor 0 / 0.5 / 1
/// (factor 0 shows only the faint front fill), so factor 0.5 carries 0.51 of factor 1's
/// transmitted light; colour (0.74, 0.33, 0.07) at factor 1. Asserted: factor 0 < 0.1 ×
/// factor 1, factor 0.5 > 2 × factor 0 and < factor 1, its share in [0.35, 0.65], and
/// red > green > blue with blue/red < 3 × the colour's 0.1.
#[test]
fn diffuse_transmission_lets_the_back_light_through() {
    for spectral in [false, true] {
        let shot = render_file(&asset("diffuse_transmission.glb"), spectral);
        let half = {
            let c = shot.raster(SHEET_CENTRES[1]);
            (shot.raster(SHEET_CENTRES[1] + Vec3::new(0.15, 0.0, 0.0)).x - c.x).floor() as i32
        };
        let m: Vec<Vec3> = SHEET_CENTRES
            .iter()
            .map(|&c| mean(&shot.window(c, half)))
            .collect();
        eprintln!("sheets {DIFFUSE_TRANSMISSION:?} spectral={spectral}: {m:?} (half {half} px)");
        let l: Vec<f32> = m.iter().map(|&p| lum(p)).collect();
        assert!(l[0] < 0.1 * l[2], "factor 0 {} not dark vs {}", l[0], l[2]);
        assert!(
            l[1] > 2.0 * l[0] && l[1] < l[2],
            "factor 0.5 {} not between",
            l[1]
        );
        let half_share = (l[1] - l[0]) / (l[2] - l[0]);
        assert!(
            (0.35..=0.65).contains(&half_share),
            "factor 0.5 gives {half_share} of factor 1's transmitted light"
        );
        let want = TRANSMISSION_COLOR.z / TRANSMISSION_COLOR.x;
        for (i, p) in m.iter().enumerate().skip(1) {
            assert!(p.z / p.x < 3.0 * want, "sheet {i} {p} not tinted orange");
            assert!(p.x > p.y && p.y > p.z, "sheet {i} {p} not orange");
        }
    }
}

/// The diamond lit by one white panel (half side 0.5 × the camera distance, above the
/// camera, facing the stone; radiance 5), seen by the automatic three-quarter camera.
fn lit_diamond(mut desc: SceneDesc) -> (SceneDesc, CameraDesc) {
    let pts: Vec<Vec3> = desc
        .meshes
        .iter()
        .flat_map(|m| m.positions.iter().copied())
        .collect();
    let camera =
        iris::framing::frame_points(&pts, iris::framing::View::ThreeQuarter, W as f32 / H as f32);
    let (lo, hi) = pts
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), &p| {
            (a.min(p), b.max(p))
        });
    let centre = 0.5 * (lo + hi);
    let eye = camera.world_from_camera.transform_point3(Vec3::ZERO);
    let up = camera
        .world_from_camera
        .transform_vector3(Vec3::Y)
        .normalize();
    let dist = eye.distance(centre);
    let at = eye + 0.5 * dist * up;
    let turn = glam::Mat3::from_quat(glam::Quat::from_rotation_arc(
        Vec3::Y,
        (centre - at).normalize(),
    ));
    let panel = iris::authoring::shapes::ground_plane(0.5 * dist, 0.5 * dist).transformed(turn, at);
    desc.materials.push(iris::material::MaterialDesc {
        name: "panel".into(),
        base_color: glam::Vec4::new(0.0, 0.0, 0.0, 1.0),
        emissive: Vec3::splat(5.0),
        ..Default::default()
    });
    desc.meshes.push(iris::scene::desc::MeshDesc {
        name: "panel".into(),
        positions: panel.positions,
        normals: panel.normals,
        indices: panel.indices,
        material: Some(desc.materials.len() - 1),
        ..Default::default()
    });
    let desc = iris::scene::validate::validate(desc).expect("valid lit diamond");
    (desc, camera)
}

/// Mean red of the brightest 1 % of pixels by red. The base is cyan (red 0), so red is the
/// white panel's specular reflection alone: the sharp highlight.
fn highlight_red(shot: &Shot) -> f32 {
    let mut red: Vec<f32> = shot.px.iter().map(|p| p.x).collect();
    red.sort_by(|a, b| b.total_cmp(a));
    let top = &red[..red.len() / 100];
    top.iter().sum::<f32>() / top.len() as f32
}

/// The shared Sketchfab "Diamond [Low-Poly]" (CC-BY-4.0): KHR_materials_clearcoat factor 1
/// (roughness 0.04) over an opaque cyan base (roughness 0). Under one white panel it renders
/// finite and not black, and its sharp highlight (the red channel, see [`highlight_red`]) is
/// brighter with the coat than with the extension stripped from the GLB's JSON: a smooth
/// coat over a smooth base reflects about 0.04 + 0.96² · 0.04 ≈ 0.077 at normal incidence
/// against 0.04, so ≈ 1.9 ×; asserted ≥ 1.4 ×.
#[test]
fn real_clearcoat_diamond_has_a_brighter_highlight_than_without_coat() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let path = shared.join("gems/DiamondLowPoly/diamond.glb");
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let coated = load_bytes("diamond_coated", "diamond.glb", &bytes);
    assert_eq!(coated.materials[0].layers.clearcoat, 1.0);
    let stripped = load_bytes(
        "diamond_stripped",
        "diamond.glb",
        &strip_extension(&bytes, "KHR_materials_clearcoat", None),
    );
    assert_eq!(stripped.materials[0].layers, Default::default());
    let (desc, camera) = lit_diamond(coated);
    let with = highlight_red(&render(desc, camera, false));
    let (desc, camera) = lit_diamond(stripped);
    let without = highlight_red(&render(desc, camera, false));
    eprintln!("diamond highlight red: with coat {with}, without {without}");
    assert!(without > 0.0, "the panel must mirror in the facets");
    assert!(with >= 1.4 * without, "coat {with} vs none {without}");
}
