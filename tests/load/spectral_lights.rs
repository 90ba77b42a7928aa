//! Spectral light sources from scene files (`iris_spectrum`): the RGB colour each spectrum
//! gives, loading good and bad values from glTF (light and material extras) and MTL, `iris
//! info`, and a small render whose colour ratios must be the spectrum's.

use crate::common;

use glam::Vec3;
use iris::accel::Backend;
use iris::app::{info_command, render_command, RenderOptions};
use iris::integrator::Method;
use iris::load::load_scene;
use iris::output::DisplayOptions;
use iris::scene::desc::{LightDesc, SceneDesc};
use iris::spectrum::cie::{chromaticity, cmf, xyz_to_linear_srgb};
use iris::spectrum::EmissionSpectrum;
use iris::LoadErrorKind;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// XYZ of Planck's law at `kelvin`, summed independently of `iris::spectrum` (f64, 1 nm,
/// 360–830 nm, c2 = 1.4388e-2 m·K as in CIE 15:2004), only the CMF table is shared.
fn planck_xyz(kelvin: f64) -> [f64; 3] {
    const C2: f64 = 1.4388e-2;
    let mut xyz = [0.0f64; 3];
    for nm in 360..=830 {
        let l = f64::from(nm) * 1e-9;
        // Relative spectral radiance; constant factors cancel in chromaticity.
        let b = 1.0 / (l.powi(5) * ((C2 / (l * kelvin)).exp() - 1.0));
        let c = cmf(nm as f32);
        for k in 0..3 {
            xyz[k] += b * f64::from(c[k]);
        }
    }
    xyz
}

fn xy(xyz: [f64; 3]) -> [f64; 2] {
    let s = xyz[0] + xyz[1] + xyz[2];
    [xyz[0] / s, xyz[1] / s]
}

fn close2(a: [f32; 2], b: [f64; 2], tol: f64) -> bool {
    (f64::from(a[0]) - b[0]).abs() < tol && (f64::from(a[1]) - b[1]).abs() < tol
}

fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

#[test]
fn d65_is_rgb_white() {
    let c = EmissionSpectrum::D65.linear_srgb();
    // The D65 table and the sRGB matrix (4 decimals) agree to ~2e-4 per channel.
    assert!((c - Vec3::ONE).abs().max_element() < 1e-3, "{c}");
}

#[test]
fn blackbody_colours_follow_the_planckian_locus() {
    // Published locus points (CIE 1931 2°, c2 = 1.4388e-2 m·K): 2700 K (0.4599, 0.4106),
    // 6500 K (0.3135, 0.3236). 1e-3 covers the 1 nm sum and the 4-decimal published values.
    for (kelvin, published) in [(2700.0f32, [0.4599, 0.4106]), (6500.0, [0.3135, 0.3236])] {
        let s = EmissionSpectrum::Blackbody { kelvin };
        let got = chromaticity(s.xyz());
        let independent = xy(planck_xyz(f64::from(kelvin)));
        assert!(
            close2(got, published, 1e-3),
            "{kelvin} K: {got:?} vs {published:?}"
        );
        assert!(
            close2(got, independent, 1e-4),
            "{kelvin} K: {got:?} vs {independent:?}"
        );
        // Luminance 1 (f32 rounding of the matrix product only).
        let c = s.linear_srgb();
        eprintln!("{kelvin} K: xy {got:?}, independent {independent:?}, linear sRGB {c}");
        assert!((luminance(c) - 1.0).abs() < 1e-4, "{kelvin} K: {c}");
        // The RGB colour is the independent XYZ through the sRGB matrix, scaled to Y = 1.
        let x = planck_xyz(f64::from(kelvin));
        let want = Vec3::from(xyz_to_linear_srgb(x.map(|v| (v / x[1]) as f32)));
        assert!(
            (c - want).abs().max_element() < 1e-3,
            "{kelvin} K: {c} vs {want}"
        );
    }
    let warm = EmissionSpectrum::Blackbody { kelvin: 2700.0 }.linear_srgb();
    assert!(warm.x > warm.y && warm.y > warm.z && warm.z > 0.0, "{warm}");
}

#[test]
fn sun_is_a_5772_k_blackbody_and_extremes_stay_valid() {
    let sun = EmissionSpectrum::Sun.linear_srgb();
    eprintln!(
        "sun: xy {:?}, linear sRGB {sun}; D65 {}",
        chromaticity(EmissionSpectrum::Sun.xyz()),
        EmissionSpectrum::D65.linear_srgb()
    );
    let bb = EmissionSpectrum::Blackbody { kelvin: 5772.0 }.linear_srgb();
    assert_eq!(sun, bb);
    // Slightly warmer than D65 (6504 K): red above blue.
    assert!(sun.x > sun.z, "{sun}");
    for kelvin in [1000.0, 40000.0] {
        let c = EmissionSpectrum::Blackbody { kelvin }.linear_srgb();
        assert!(c.is_finite() && c.min_element() >= 0.0, "{kelvin} K: {c}");
        assert!((luminance(c) - 1.0).abs() < 1e-4, "{kelvin} K: {c}");
    }
}

// ---------------------------------------------------------------- scene files

/// A white Lambert square (y = 0, |x|, |z| ≤ 1, facing +Y) seen from above by a camera
/// 2 m up (every pixel sees the square), lit by a point light 1 m up. `light_extras` and
/// `material_extras` go into the light's and material's `extras`.
fn plane_gltf(dir: &Path, light_extras: Value, material_extras: Value) -> PathBuf {
    let positions: [[f32; 3]; 4] = [
        [-1.0, 0.0, -1.0],
        [-1.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 0.0, -1.0],
    ];
    let indices: [u32; 6] = [0, 1, 2, 0, 2, 3];
    let mut bin = Vec::new();
    for v in positions.iter().flatten() {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    for i in indices {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    std::fs::write(dir.join("plane.bin"), &bin).expect("write bin");
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let doc = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "Key", "type": "point", "intensity": 10.0, "extras": light_extras}
        ]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "Plane", "mesh": 0},
            {"name": "Bulb", "translation": [0.0, 1.0, 0.0],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "Cam", "camera": 0, "translation": [0.0, 2.0, 0.0],
             "rotation": [-h, 0.0, 0.0, h]}
        ],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": 0.5, "aspectRatio": 1.0, "znear": 0.01}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"name": "Lamp", "extras": material_extras,
                       "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "buffers": [{"uri": "plane.bin", "byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 24}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1.0, 0.0, -1.0], "max": [1.0, 0.0, 1.0]},
            {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}
        ]
    });
    let path = dir.join("plane.gltf");
    std::fs::write(&path, serde_json::to_string_pretty(&doc).expect("json")).expect("write");
    path
}

fn light_spectrum(desc: &SceneDesc) -> Option<EmissionSpectrum> {
    match &desc.lights[0] {
        LightDesc::Point { spectrum, .. } => *spectrum,
        other => panic!("expected a point light, got {other:?}"),
    }
}

#[test]
fn gltf_good_values() {
    let dir = common::scratch_dir("spectral_gltf_good");
    let cases: [(Value, EmissionSpectrum); 5] = [
        (json!("D65"), EmissionSpectrum::D65),
        (json!("sUn"), EmissionSpectrum::Sun),
        (
            json!({"blackbody": 2700}),
            EmissionSpectrum::Blackbody { kelvin: 2700.0 },
        ),
        (
            json!({"BlackBody": 1000.0}),
            EmissionSpectrum::Blackbody { kelvin: 1000.0 },
        ),
        (
            json!("blackbody 40000"),
            EmissionSpectrum::Blackbody { kelvin: 40000.0 },
        ),
    ];
    for (value, want) in cases {
        let path = plane_gltf(
            &dir,
            json!({"iris_spectrum": value}),
            json!({"iris_spectrum": value}),
        );
        let desc = load_scene(&path).unwrap_or_else(|e| panic!("{value}: {e}"));
        assert_eq!(light_spectrum(&desc), Some(want), "{value}");
        assert_eq!(desc.materials[0].emission_spectrum, Some(want), "{value}");
    }
    // Without the key: no spectrum; other extras keys are ignored.
    let desc = load_scene(&plane_gltf(&dir, json!({"note": 1}), json!(null))).expect("loads");
    assert_eq!(light_spectrum(&desc), None);
    assert_eq!(desc.materials[0].emission_spectrum, None);
}

#[test]
fn gltf_bad_values_name_file_element_and_key() {
    let dir = common::scratch_dir("spectral_gltf_bad");
    let bad = [
        json!("tungsten"),
        json!(""),
        json!({"blackbody": 999}),
        json!({"blackbody": 40001}),
        json!({"blackbody": "hot"}),
        json!({"temperature": 3000}),
        json!({"blackbody": 3000, "extra": 1}),
        json!(6500),
        json!(["D65"]),
        json!("blackbody"),
        json!("blackbody warm"),
    ];
    for value in bad {
        for on_light in [true, false] {
            let (l, m) = if on_light {
                (json!({"iris_spectrum": value}), json!(null))
            } else {
                (json!(null), json!({"iris_spectrum": value}))
            };
            let err = load_scene(&plane_gltf(&dir, l, m)).expect_err("must fail");
            let msg = err.to_string();
            assert_eq!(err.kind, LoadErrorKind::InvalidValue, "{value}: {msg}");
            let element = if on_light {
                "light 0 \"Key\""
            } else {
                "material 0 \"Lamp\""
            };
            assert!(
                msg.contains("plane.gltf")
                    && msg.contains(element)
                    && msg.contains("extras.iris_spectrum"),
                "{value}: {msg}"
            );
        }
    }
}

fn write_obj(dir: &Path, mtl: &str) -> PathBuf {
    std::fs::write(dir.join("m.mtl"), mtl).expect("write mtl");
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 3\n";
    let path = dir.join("lamp.obj");
    std::fs::write(&path, obj).expect("write obj");
    path
}

#[test]
fn mtl_good_and_bad_values() {
    let dir = common::scratch_dir("spectral_mtl");
    for (line, want) in [
        (
            "iris_spectrum blackbody 3200",
            EmissionSpectrum::Blackbody { kelvin: 3200.0 },
        ),
        ("iris_spectrum D65", EmissionSpectrum::D65),
        ("iris_spectrum SUN", EmissionSpectrum::Sun),
    ] {
        let path = write_obj(&dir, &format!("newmtl lamp\nKe 5 5 5\n{line}\n"));
        let desc = load_scene(&path).unwrap_or_else(|e| panic!("{line}: {e}"));
        let m = desc.materials.iter().find(|m| m.name.contains("\"lamp\""));
        assert_eq!(m.and_then(|m| m.emission_spectrum), Some(want), "{line}");
    }
    for line in [
        "iris_spectrum",
        "iris_spectrum neon",
        "iris_spectrum blackbody",
        "iris_spectrum blackbody 99999",
        "iris_spectrum blackbody hot",
        "iris_spectrum blackbody 3000 K",
    ] {
        let path = write_obj(&dir, &format!("newmtl lamp\nKe 5\n\n{line}\n"));
        let err = load_scene(&path).expect_err(line);
        let msg = err.to_string();
        assert_eq!(err.kind, LoadErrorKind::InvalidValue, "{msg}");
        assert!(
            msg.contains("m.mtl") && msg.contains("\"lamp\"") && msg.contains("line 4"),
            "{line}: {msg}"
        );
    }
    // A spectrum on a material that does not emit is kept, with a warning.
    let desc = load_scene(&write_obj(&dir, "newmtl lamp\niris_spectrum d65\n")).expect("loads");
    let warnings = desc.warnings.join("\n");
    assert!(
        warnings.contains("iris_spectrum D65 has no effect"),
        "{warnings}"
    );
}

#[test]
fn info_shows_the_spectra() {
    let dir = common::scratch_dir("spectral_info");
    let path = plane_gltf(
        &dir,
        json!({"iris_spectrum": {"blackbody": 2700}}),
        json!({"iris_spectrum": "D65"}),
    );
    let info = info_command(&path).expect("info");
    assert!(
        info.contains("point \"Key\"") && info.contains("spectrum blackbody 2700 K (sRGB ["),
        "{info}"
    );
    assert!(
        info.contains("spectrum D65 (sRGB [1.000 1.000 1.000])"),
        "{info}"
    );
}

/// A white Lambert plane under a 2700 K point light, RGB transport (`--spectral off`; auto
/// would go spectral for a named spectrum): every pixel's colour ratios are the spectrum's
/// sRGB ratios, and a D65 light renders grey.
#[test]
fn render_under_a_2700_k_light_has_its_colour() {
    let dir = common::scratch_dir("spectral_render");
    let render = |extras: Value| {
        let scene = plane_gltf(&dir, json!({"iris_spectrum": extras}), json!(null));
        let opts = RenderOptions {
            scene,
            output: Some(dir.join("out.exr")),
            size: Some((16, 16)),
            spp: 1,
            method: Method::Whitted,
            max_depth: 4,
            time_limit: None,
            checkpoint: None,
            watch: false,
            photon: Default::default(),
            accel: Backend::Auto,
            seed: 1,
            sampler: Default::default(),
            threads: 1,
            camera: None,
            look_at: None,
            display: DisplayOptions::default(),
            quiet: true,
            spectral: iris::app::SpectralMode::Off, // the RGB renderer's colour
            polarization: Default::default(),
            polarizer: None,
            env: None,
            fog: None,
            measure: Default::default(),
            preview: Default::default(),
            looks: Vec::new(),
            explain: false,
            denoise: Default::default(),
            adaptive: Default::default(),
            spin: None,
            exr_copy: None,
            shard: None,
        };
        render_command(&opts).expect("render").image
    };
    let want = EmissionSpectrum::Blackbody { kelvin: 2700.0 }.linear_srgb();
    let image = render(json!({"blackbody": 2700}));
    let mut checked = 0;
    let mut worst = 0.0f32;
    for (i, p) in image.data.iter().enumerate() {
        // The plane is white, so the pixel is the light colour times a scalar (BRDF,
        // cosine, distance); only f32 rounding and the EXR's storage precision separate the
        // ratios, far below the 1 % allowed.
        assert!(p.y > 0.0, "pixel {i} is black: {p}");
        let (got_r, got_b) = (p.x / p.y, p.z / p.y);
        let (want_r, want_b) = (want.x / want.y, want.z / want.y);
        worst = worst.max(
            (got_r / want_r - 1.0)
                .abs()
                .max((got_b / want_b - 1.0).abs()),
        );
        assert!(
            (got_r / want_r - 1.0).abs() < 0.01 && (got_b / want_b - 1.0).abs() < 0.01,
            "pixel {i}: {p} vs light colour {want}"
        );
        checked += 1;
    }
    assert_eq!(checked, 256);
    eprintln!("2700 K render: worst R/G, B/G ratio error {worst:e} over {checked} pixels");
    let grey = render(json!("D65"));
    for p in &grey.data {
        // D65 is (1, 1, 1) within 1e-3 (see `d65_is_rgb_white`).
        assert!(
            (p.x / p.y - 1.0).abs() < 2e-3 && (p.z / p.y - 1.0).abs() < 2e-3,
            "{p}"
        );
    }
    // Same photometric intensity: the luminance is the same for both lights (the warm
    // light's Y = 1 as D65's), within 1 % for the sRGB luminance weights' rounding.
    let lum = |img: &iris::image::ImageRgb| -> f32 { img.data.iter().map(|p| luminance(*p)).sum() };
    let (a, b) = (lum(&image), lum(&grey));
    eprintln!("summed luminance 2700 K {a}, D65 {b}");
    assert!((a / b - 1.0).abs() < 0.01, "{a} vs {b}");
}

/// Spectral transport (`--spectral on`) under the same 2700 K light: the light reaches the
/// white plane as Planck's law itself (not its upsampled sRGB colour), so the image mean's
/// chromaticity is the Planckian locus point computed independently here (`planck_xyz`)
/// within 0.002 — the 4-wavelength estimate is noisy per pixel, 64 spp × 256 pixels on the
/// mean.
#[test]
fn spectral_render_under_a_2700_k_light_has_the_planckian_chromaticity() {
    let dir = common::scratch_dir("spectral_render_on");
    let scene = plane_gltf(
        &dir,
        json!({"iris_spectrum": {"blackbody": 2700}}),
        json!(null),
    );
    let opts = RenderOptions {
        scene,
        output: Some(dir.join("out.exr")),
        size: Some((16, 16)),
        spp: 64,
        method: Method::Path,
        max_depth: 4,
        time_limit: None,
        checkpoint: None,
        watch: false,
        photon: Default::default(),
        accel: Backend::Auto,
        seed: 1,
        sampler: Default::default(),
        threads: 2,
        camera: None,
        look_at: None,
        display: DisplayOptions::default(),
        quiet: true,
        spectral: iris::app::SpectralMode::On,
        polarization: Default::default(),
        polarizer: None,
        env: None,
        fog: None,
        measure: Default::default(),
        preview: Default::default(),
        looks: Vec::new(),
        explain: false,
        denoise: Default::default(),
        adaptive: Default::default(),
        spin: None,
        exr_copy: None,
        shard: None,
    };
    let image = render_command(&opts).expect("render").image;
    let mean = image.data.iter().fold(Vec3::ZERO, |a, p| a + *p) / image.data.len() as f32;
    let got =
        iris::spectrum::cie::chromaticity(iris::spectrum::cie::linear_srgb_to_xyz(mean.to_array()));
    let want = xy(planck_xyz(2700.0));
    eprintln!("spectral 2700 K: mean {mean}, xy {got:?} vs Planck {want:?}");
    assert!(close2(got, want, 0.002), "xy {got:?} vs {want:?}");
}

/// `--spectral auto` turns spectral transport on for a scene whose only spectral feature is
/// a named light spectrum, and leaves a plain scene on RGB.
#[test]
fn auto_mode_goes_spectral_for_a_named_light_spectrum() {
    use iris::app::SpectralMode;
    let dir = common::scratch_dir("spectral_auto");
    let named = plane_gltf(
        &dir,
        json!({"iris_spectrum": {"blackbody": 2700}}),
        json!(null),
    );
    let (scene, _) = iris::app::load(&named, Backend::Auto).unwrap();
    assert!(SpectralMode::Auto.resolve(&scene, iris::integrator::Method::Path));
    assert!(!SpectralMode::Off.resolve(&scene, iris::integrator::Method::Path));
    let dir2 = common::scratch_dir("spectral_auto_plain");
    let plain = plane_gltf(&dir2, json!(null), json!(null));
    let (scene, _) = iris::app::load(&plain, Backend::Auto).unwrap();
    assert!(!SpectralMode::Auto.resolve(&scene, iris::integrator::Method::Path));
    assert!(SpectralMode::On.resolve(&scene, iris::integrator::Method::Path));
}
