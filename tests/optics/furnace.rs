//! White furnace: inside a uniform white environment (radiance 1), a non-absorbing object
//! must vanish — every pixel renders 1. Mostly the path tracer; on rough glass also SPPM and
//! bidirectional path tracing, whose photons and light subpaths see the BSDF's adjoint.
//! - A smooth glass sphere (IOR 1.5): every path is a chain of delta bounces weighted
//!   exactly (Fresnel choice, 1/η² in and η² out), so each pixel is 1 up to rounding;
//!   tolerance 1 % per pixel and on the mean. One exception, measured: a ray entering the
//!   faceted icosphere at grazing incidence (88.6°) refracts to the critical angle (41.8°);
//!   inside, the facets' normals scatter its incidence around the critical angle, so it is
//!   totally reflected (or reflected with R ≈ 0.99) at every bounce and still inside at the
//!   path tracer's cap of 1024 delta bounces, where it counts 0 (found with the Sobol'
//!   sampler: seed 11, pixel (0, 14), sample 12; 1 sample in 110 000). So rim pixels, whose
//!   centre ray meets the sphere beyond 0.9 of its radius, may lose one sample: 1/spp.
//! - A white Lambertian sphere (albedo 1, no specular layer): the estimate is noisy but
//!   unbiased; with 64 spp at 24×24 the image mean is within 1 % (σ of the mean ≈ 0.2 %).
//! - A rough glass sphere (IOR 1.5, roughness 0.3 and 0.7, α = roughness²): the GGX
//!   dielectric with multiple-scattering compensation (`bsdf::energy`) keeps every vertex's
//!   expected throughput at 1. Noisy (per-sample σ ≈ 0.6 and 0.8: the compensation's weights
//!   exceed 1 and compound along internal reflections), so 16 renders of a 6×6 image give
//!   65 536 / 131 072 spp per pixel and a per-pixel standard error ≈ 0.21 % (RMS; ≈ 0.1 %
//!   inside the silhouette, up to 0.39 % on it), making 1 % a ≥ 4σ bound except at the
//!   rim. Measured (2026-12-01): r 0.3 mean 1.0001, max |pixel − 1| 0.45 %; r 0.7 mean
//!   0.9992, max 0.56 %. Without the compensation (factor forced to 1; 8×8 image) the same
//!   test fails: r 0.3 mean 0.956 (worst pixel −9.6 %), r 0.7 mean 0.651 (worst −51 %).

use crate::common;

use glam::Vec3;
use iris::camera::Camera;
use iris::integrator::{Integrator, Method, PhotonSettings};
use iris::material::MaterialDesc;
use iris::render::RenderSettings;
use iris::scene::desc::CameraDesc;

/// The camera 4 m from the unit sphere at the origin.
fn furnace_camera() -> CameraDesc {
    common::camera_facing_origin(0.5)
}

fn furnace(material: MaterialDesc, spp: u32) -> Vec<Vec3> {
    furnace_image(material, 24, spp, 11)
}

/// A `size`×`size` path-traced image of the sphere in the white furnace (RGB transport).
fn furnace_image(material: MaterialDesc, size: u32, spp: u32, seed: u64) -> Vec<Vec3> {
    furnace_render(material, size, spp, seed, false)
}

/// As [`furnace_image`], choosing RGB or spectral transport.
fn furnace_render(
    material: MaterialDesc,
    size: u32,
    spp: u32,
    seed: u64,
    spectral: bool,
) -> Vec<Vec3> {
    let scene = common::sphere_in_white_environment(material);
    let cam = furnace_camera();
    let settings = RenderSettings {
        width: size,
        height: size,
        spp,
        seed,
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
        Integrator::new(Method::Path, 64, &PhotonSettings::default()).expect("a resolved method");
    integrator
        .render(&scene, &Camera::new(&cam, size, size), &settings)
        .unwrap()
        .0
        .data
}

#[test]
fn smooth_glass_sphere_vanishes_in_a_white_furnace() {
    let glass = common::clear_glass("glass", 1.5);
    let spp = 16;
    let px = furnace(glass, spp);
    let mean = px.iter().map(|p| p.x as f64).sum::<f64>() / px.len() as f64;
    assert!((mean - 1.0).abs() < 0.01, "mean {mean}");
    let camera = Camera::new(&furnace_camera(), 24, 24);
    for (i, p) in px.iter().enumerate() {
        // Impact parameter of the pixel's centre ray: distance of the sphere's centre
        // (the origin) from the ray's line.
        let ray = camera.generate_ray(glam::Vec2::new((i % 24) as f32, (i / 24) as f32) + 0.5);
        let d = ray.dir.normalize();
        let b = (ray.origin - d * ray.origin.dot(d)).length();
        let tol = if (0.9..1.1).contains(&b) {
            0.01 + 1.0 / spp as f32
        } else {
            0.01
        };
        assert!(
            (p.max_element() - 1.0).abs() < tol && (p.min_element() - 1.0).abs() < tol,
            "pixel {i} (impact parameter {b}): {p}"
        );
    }
}

#[test]
fn white_lambertian_sphere_vanishes_in_a_white_furnace() {
    let white = common::white_lambert();
    let px = furnace(white, 64);
    let mean = px.iter().map(|p| p.x as f64).sum::<f64>() / px.len() as f64;
    assert!((mean - 1.0).abs() < 0.01, "mean {mean}");
    assert!(px.iter().all(|p| p.is_finite()));
}

/// Image size of the rough-glass furnace (the sphere covers all but the corner pixels; 6×6
/// keeps each test under ~12 s with Embree, ~25 s with the BVH, on 2 shared cores).
const SIZE: u32 = 6;

/// Rough glass (IOR 1.5, perceptual roughness `roughness`, α = roughness²) in the furnace:
/// `K` independent renders (seeds 100..100+K) of `spp` samples each; returns per pixel the
/// mean over the K renders and the standard error of that mean (sample s.d. / √K).
fn rough_glass_furnace(roughness: f32, spp: u32) -> (Vec<f64>, Vec<f64>) {
    const K: usize = 16;
    let glass = MaterialDesc {
        roughness,
        ..common::clear_glass("rough glass", 1.5)
    };
    let images: Vec<Vec<Vec3>> = (0..K as u64)
        .map(|k| furnace_image(glass.clone(), SIZE, spp, 100 + k))
        .collect();
    let n = images[0].len();
    let mut mean = vec![0.0; n];
    let mut se = vec![0.0; n];
    for i in 0..n {
        // Luminance-free check: the furnace is white, so every channel must be 1; use the
        // channel mean per render and check channels separately below.
        let v: Vec<f64> = images.iter().map(|im| im[i].x as f64).collect();
        let m = v.iter().sum::<f64>() / K as f64;
        let var = v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (K - 1) as f64;
        mean[i] = m;
        se[i] = (var / K as f64).sqrt();
        for im in &images {
            let p = im[i];
            assert!(
                (p.x - p.y).abs() < 1e-4 && (p.x - p.z).abs() < 1e-4,
                "pixel {i} not grey: {p}"
            );
        }
    }
    (mean, se)
}

fn check_rough_glass(roughness: f32, spp: u32) {
    let (mean, se) = rough_glass_furnace(roughness, spp);
    let n = mean.len() as f64;
    let img_mean = mean.iter().sum::<f64>() / n;
    let rms_se = (se.iter().map(|s| s * s).sum::<f64>() / n).sqrt();
    let max_se = se.iter().cloned().fold(0.0, f64::max);
    let max_err = mean.iter().map(|m| (m - 1.0).abs()).fold(0.0, f64::max);
    eprintln!(
        "rough glass r {roughness}: mean {img_mean:.5}, max |pixel − 1| {max_err:.5}, \
         per-pixel s.e. rms {rms_se:.5} max {max_se:.5}"
    );
    for row in 0..SIZE as usize {
        let r = row * SIZE as usize..(row + 1) * SIZE as usize;
        let fmt = |v: &[f64]| v.iter().map(|x| format!("{x:7.4}")).collect::<String>();
        eprintln!("  mean {}   s.e. {}", fmt(&mean[r.clone()]), fmt(&se[r]));
    }
    // Noise budget: the per-pixel standard error must be ≤ 0.25 % (RMS over pixels) so a
    // 1 % deviation is ≥ 4σ. Measured: ≈ 0.1 % at the centre, 0.2–0.4 % on the silhouette
    // (grazing entry, long chains of internal reflections; the corner pixels see only the
    // environment and have 0). The rim pixels are capped at 0.5 % (1 % ≥ 2σ there); each
    // s.e. estimate has 15 degrees of freedom (±18 %).
    assert!(
        rms_se <= 0.0025,
        "too noisy to judge 1 %: rms s.e. {rms_se}"
    );
    assert!(max_se <= 0.005, "too noisy to judge 1 %: max s.e. {max_se}");
    assert!((img_mean - 1.0).abs() < 0.01, "mean {img_mean}");
    for (i, m) in mean.iter().enumerate() {
        assert!((m - 1.0).abs() < 0.01, "pixel {i}: {m} ± {}", se[i]);
    }
}

#[test]
fn rough_glass_sphere_vanishes_in_a_white_furnace_r03() {
    check_rough_glass(0.3, 4096);
}

#[test]
fn rough_glass_sphere_vanishes_in_a_white_furnace_r07() {
    check_rough_glass(0.7, 8192);
}

/// Spectral transport keeps white white and conserves energy: in the white furnace (the
/// environment's RGB (1,1,1) becomes the D65 illuminant, the film converts through CIE XYZ)
/// a smooth glass sphere (IOR 1.5, non-dispersive) and a white Lambertian sphere render with
/// mean 1 within 1 % per channel and the chromaticity of D65 within 0.002 (x, y), as in RGB.
/// Per pixel: the glass within 1 % too (the hero wavelengths are stratified over a pixel's
/// samples; measured worst 0.35 % at 256 spp, 7.6 % without stratification); the Lambert
/// sphere's pixels carry Monte Carlo noise (worst 5.6 % measured), held to 20 %.
#[test]
fn spectral_transport_keeps_white_white_and_energy() {
    use iris::spectrum::cie::{chromaticity, linear_srgb_to_xyz};
    // CIE 15:2004, D65 white point (2° observer).
    const D65_XY: [f32; 2] = [0.3127, 0.3290];
    let glass = common::clear_glass("glass", 1.5);
    let white = common::white_lambert();
    for (name, m, spp, px_tol) in [("glass", glass, 256, 0.01f32), ("white", white, 256, 0.2)] {
        let px = furnace_render(m, 24, spp, 7, true);
        let mean = px.iter().fold(glam::DVec3::ZERO, |a, p| a + p.as_dvec3()) / px.len() as f64;
        for c in mean.to_array() {
            assert!((c - 1.0).abs() < 0.01, "{name}: mean {mean}");
        }
        let xy = chromaticity(linear_srgb_to_xyz(mean.as_vec3().to_array()));
        assert!(
            (xy[0] - D65_XY[0]).abs() < 0.002 && (xy[1] - D65_XY[1]).abs() < 0.002,
            "{name}: chromaticity {xy:?} vs D65 {D65_XY:?}"
        );
        let worst = px
            .iter()
            .map(|p| {
                (p.max_element() - 1.0)
                    .abs()
                    .max((p.min_element() - 1.0).abs())
            })
            .fold(0f32, f32::max);
        eprintln!("{name}: mean {mean}, chromaticity {xy:?}, worst pixel error {worst}");
        assert!(worst < px_tol, "{name}: worst pixel error {worst}");
    }
}

/// The image mean of `K` renders of `size`² of the rough glass sphere (IOR 1.5, perceptual
/// roughness `roughness`) in the furnace by `method` (`spp` samples or SPPM passes,
/// `photons` per pass), with its standard error from the spread of all K·size² pixel
/// values (each an independent estimate of 1).
fn rough_glass_mean(
    roughness: f32,
    method: Method,
    (size, spp, photons): (u32, u32, u64),
) -> (f64, f64) {
    const K: u64 = 4;
    let glass = MaterialDesc {
        roughness,
        ..common::clear_glass("rough glass", 1.5)
    };
    let scene = common::sphere_in_white_environment(glass);
    let photon = PhotonSettings {
        photons,
        passes: spp,
        ..PhotonSettings::default()
    };
    let integrator = Integrator::new(method, 64, &photon).expect("a resolved method");
    let camera = Camera::new(&furnace_camera(), size, size);
    let values: Vec<f64> = (0..K)
        .flat_map(|k| {
            let settings = common::render_settings((size, size), spp, 300 + k, 2);
            let img = integrator.render(&scene, &camera, &settings).unwrap().0;
            img.data.iter().map(|p| f64::from(p.x)).collect::<Vec<_>>()
        })
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Photon methods gather on rough glass as the path tracer sees it: SPPM's visible points
/// lie on the rough glass sphere (roughness 0.6, α 0.36 ≥ the 0.25 from which a glossy lobe
/// is gathered on), where it gathers the photons that crossed the sphere; bidirectional
/// path tracing connects light subpaths through it. The rough dielectric's energy
/// compensation is not reciprocal, so photons must see its exact adjoint (Importance mode
/// divides by E_ss(wi), `iris::bsdf`'s energy module): with the camera's own compensation
/// (1/E_ss at the photon's incoming direction) SPPM read 0.876 and BPT 0.977 here. In the
/// furnace every method must read 1: the path tracer and BPT within 2 % (4 × 8×8 × 256
/// samples, standard error asserted ≤ 0.5 %: ≥ 4σ); SPPM (64 passes of 4 096 photons, 4
/// seeds; s.e. asserted ≤ 0.75 %) within 4 % of 1 and of the path tracer, the bound holding
/// its progressive radius's bias after 64 passes (about 1–2 %, shrinking with the passes).
#[test]
fn photon_methods_on_rough_glass_agree_with_the_path_tracer_in_a_white_furnace() {
    let (path, path_se) = rough_glass_mean(0.6, Method::Path, (8, 256, 0));
    let (bpt, bpt_se) = rough_glass_mean(0.6, Method::Bpt, (8, 256, 0));
    let (sppm, sppm_se) = rough_glass_mean(0.6, Method::Sppm, (8, 64, 4096));
    eprintln!(
        "rough glass r 0.6: path {path:.4} ± {path_se:.4}, bpt {bpt:.4} ± {bpt_se:.4}, \
         sppm {sppm:.4} ± {sppm_se:.4}"
    );
    assert!((path - 1.0).abs() < 0.02, "path {path}");
    assert!((bpt - 1.0).abs() < 0.02, "bpt {bpt}");
    assert!((sppm - 1.0).abs() < 0.04, "sppm {sppm}");
    assert!((sppm - path).abs() < 0.04, "sppm {sppm} vs path {path}");
    assert!(path_se <= 0.005 && bpt_se <= 0.005 && sppm_se <= 0.0075);
}
