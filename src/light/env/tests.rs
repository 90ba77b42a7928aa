//! Tests of the environment light: mapping round trip, pdf normalisation, sampling
//! distribution (chi-square), irradiance furnace checks, sun share and loading.

use super::*;
use crate::math::Rng;
use crate::output::{write_image, DisplayOptions};
use std::path::PathBuf;

const W: u32 = 64;
const H: u32 = 32;
/// The sun block: columns SUN_X..SUN_X+2, rows SUN_Y..SUN_Y+2.
const SUN_X: u32 = 40;
const SUN_Y: u32 = 8;
const SUN: Vec3 = Vec3::new(120.0, 100.0, 80.0);

/// A dim sky brightening towards the zenith, a black bottom row (zero-probability region)
/// and one bright 2×2 "sun" block.
fn synthetic_image() -> ImageRgb {
    let mut img = ImageRgb::new(W, H);
    for y in 0..H {
        for x in 0..W {
            let t = 1.0 - y as f32 / H as f32;
            let mut c = Vec3::new(0.2, 0.3, 0.5) * (0.2 + t) + Vec3::splat(0.01 * (x % 7) as f32);
            if y == H - 1 {
                c = Vec3::ZERO;
            }
            if (SUN_X..SUN_X + 2).contains(&x) && (SUN_Y..SUN_Y + 2).contains(&y) {
                c = SUN;
            }
            img.data[(y * W + x) as usize] = c;
        }
    }
    img
}

fn synthetic() -> Environment {
    Environment::Map(EnvMap::from_image(synthetic_image(), Path::new("synthetic")).unwrap())
}

fn uniform() -> Environment {
    Environment::Uniform {
        radiance: Vec3::new(0.5, 1.0, 2.0),
    }
}

/// Midpoint quadrature of f(dir)·dω over a (θ, φ) grid aligned with the texel grid
/// (`sub` cells per texel in each direction).
fn quadrature(sub: u32, f: impl Fn(Vec3) -> f64) -> f64 {
    let (nu, nv) = (W * sub, H * sub);
    let mut sum = 0.0;
    for j in 0..nv {
        let v = (j as f32 + 0.5) / nv as f32;
        // Exact solid angle of the cell: (2π/nu)(cos θ0 − cos θ1).
        let t0 = std::f64::consts::PI * j as f64 / nv as f64;
        let t1 = std::f64::consts::PI * (j + 1) as f64 / nv as f64;
        let d_omega = 2.0 * std::f64::consts::PI / nu as f64 * (t0.cos() - t1.cos());
        for i in 0..nu {
            let u = (i as f32 + 0.5) / nu as f32;
            sum += f(uv_to_dir(Vec2::new(u, v))) * d_omega;
        }
    }
    sum
}

fn rng_u(rng: &mut Rng) -> Vec2 {
    Vec2::new(rng.next_f32(), rng.next_f32())
}

fn random_dir(rng: &mut Rng) -> Vec3 {
    uniform_sphere(rng_u(rng))
}

#[test]
fn mapping_round_trip() {
    let mut rng = Rng::new(&[1]);
    for _ in 0..100_000 {
        let d = random_dir(&mut rng).normalize();
        let back = uv_to_dir(dir_to_uv(d));
        assert!((back - d).length() < 1e-5, "{d} → {back}");
        let uv = Vec2::new(rng.next_f32() * 0.98 + 0.01, rng.next_f32() * 0.98 + 0.01);
        let uv2 = dir_to_uv(uv_to_dir(uv));
        assert!((uv2 - uv).length() < 1e-5, "{uv} → {uv2}");
    }
    for d in [Vec3::Y, -Vec3::Y, Vec3::X, -Vec3::X, Vec3::Z, -Vec3::Z] {
        let back = uv_to_dir(dir_to_uv(d));
        assert!((back - d).length() < 1e-5, "{d} → {back}");
    }
    // The stated convention: centre = −Z, u = 0.75 = +X, top = +Y, bottom = −Y.
    assert!((dir_to_uv(-Vec3::Z) - Vec2::new(0.5, 0.5)).length() < 1e-6);
    assert!((dir_to_uv(Vec3::X) - Vec2::new(0.75, 0.5)).length() < 1e-6);
    assert!(dir_to_uv(Vec3::Y).y.abs() < 1e-6);
    assert!((dir_to_uv(-Vec3::Y).y - 1.0).abs() < 1e-6);
}

#[test]
fn poles_give_zero_pdf_not_nan() {
    let env = synthetic();
    for d in [Vec3::Y, -Vec3::Y] {
        let p = env.pdf(d);
        assert!(p.is_finite() && p >= 0.0, "pdf {p} at {d}");
    }
    assert_eq!(env.pdf(Vec3::Y), 0.0);
    for u in [Vec2::ZERO, Vec2::new(0.3, 0.0), Vec2::new(0.999, 0.9999)] {
        if let Some(s) = env.sample(u) {
            assert!(s.pdf.is_finite() && s.pdf > 0.0 && s.wi.is_finite());
        }
    }
    assert_eq!(env.pdf(Vec3::NAN), 0.0);
    assert_eq!(env.eval(Vec3::NAN), Vec3::ZERO);
}

#[test]
fn pdf_integrates_to_one() {
    for env in [synthetic(), uniform()] {
        let total = quadrature(4, |d| env.pdf(d) as f64);
        assert!((total - 1.0).abs() < 0.01, "∫pdf dω = {total}");
    }
}

#[test]
fn pdf_zero_only_where_radiance_zero() {
    let env = synthetic();
    let mut rng = Rng::new(&[2]);
    let mut zero_seen = 0;
    for _ in 0..100_000 {
        let d = random_dir(&mut rng);
        if env.pdf(d) == 0.0 {
            zero_seen += 1;
            assert_eq!(env.eval(d), Vec3::ZERO, "pdf 0 but radiance at {d}");
        }
    }
    assert!(zero_seen > 0, "the black bottom row should have pdf 0");
}

/// Chi-square test of sample() against pdf() on an `nu` × `nv` (φ, θ) grid of equal-angle
/// bins (aligned with the texels; finer than them when `nu > W`, which checks the placement
/// of samples inside a texel), plus the per-sample consistency of the pdf and radiance
/// fields.
fn chi_square(env: &Environment, seed: u64, nu: u32, nv: u32) {
    const N: usize = 400_000;
    // Expected probability per bin from pdf() by quadrature (bins align with texels).
    let mut expected = vec![0.0f64; (nu * nv) as usize];
    let sub = 8;
    let (qu, qv) = (W * sub, H * sub);
    for j in 0..qv {
        let t0 = std::f64::consts::PI * j as f64 / qv as f64;
        let t1 = std::f64::consts::PI * (j + 1) as f64 / qv as f64;
        let d_omega = 2.0 * std::f64::consts::PI / qu as f64 * (t0.cos() - t1.cos());
        for i in 0..qu {
            let uv = Vec2::new((i as f32 + 0.5) / qu as f32, (j as f32 + 0.5) / qv as f32);
            let bin = (j * nv / qv) * nu + i * nu / qu;
            expected[bin as usize] += env.pdf(uv_to_dir(uv)) as f64 * d_omega;
        }
    }
    let mut observed = vec![0u64; expected.len()];
    let mut rng = Rng::new(&[seed]);
    let mut none = 0usize;
    for _ in 0..N {
        let Some(s) = env.sample(rng_u(&mut rng)) else {
            none += 1;
            continue;
        };
        let p = env.pdf(s.wi);
        assert!(
            s.pdf > 0.0 && ((s.pdf - p) / p).abs() < 1e-4,
            "{} vs {p}",
            s.pdf
        );
        assert_eq!(s.radiance, env.eval(s.wi));
        assert!((s.wi.length() - 1.0).abs() < 1e-5);
        let uv = dir_to_uv(s.wi);
        let (x, y) = mapping::uv_to_pixel(uv, nu, nv);
        observed[(y * nu + x) as usize] += 1;
    }
    assert!(none < N / 1000, "{none} samples failed");
    // Pool bins with expected count < 5 into one.
    let n = (N - none) as f64;
    let (mut chi2, mut dof) = (0.0, 0usize);
    let (mut pool_e, mut pool_o) = (0.0, 0.0);
    for (e, &o) in expected.iter().zip(&observed) {
        let e = e * n;
        if e < 5.0 {
            pool_e += e;
            pool_o += o as f64;
            assert!(e > 0.0 || o == 0, "samples in a zero-probability bin");
        } else {
            chi2 += (o as f64 - e).powi(2) / e;
            dof += 1;
        }
    }
    if pool_e >= 5.0 {
        chi2 += (pool_o - pool_e).powi(2) / pool_e;
        dof += 1;
    }
    let dof = dof.saturating_sub(1).max(1) as f64;
    // Wilson–Hilferty: the 1 − 1e-6 quantile is ≈ dof + 4.75·sqrt(2·dof) for these dofs;
    // use a generous dof + 6·sqrt(2·dof) so a correct sampler never fails.
    let limit = dof + 6.0 * (2.0 * dof).sqrt();
    assert!(
        chi2 < limit,
        "chi² = {chi2:.1} with {dof} dof (limit {limit:.1})"
    );
}

#[test]
fn sampling_matches_pdf_chi_square() {
    chi_square(&synthetic(), 3, 16, 8);
    chi_square(&uniform(), 4, 16, 8);
}

#[test]
fn sampling_matches_pdf_within_texels() {
    // 2 × 2 bins per texel: a sampler that picks the right texel but places the sample
    // wrongly inside it fails here.
    chi_square(&synthetic(), 8, 2 * W, 2 * H);
}

/// ∫ L(ω)·max(ω.y, 0) dω, the irradiance on an upward-facing plane.
fn irradiance_mc(env: &Environment, n: usize, seed: u64) -> Vec3 {
    let mut rng = Rng::new(&[seed]);
    let mut sum = glam::DVec3::ZERO;
    for _ in 0..n {
        if let Some(s) = env.sample(rng_u(&mut rng)) {
            sum += (s.radiance * s.wi.y.max(0.0) / s.pdf).as_dvec3();
        }
    }
    (sum / n as f64).as_vec3()
}

#[test]
fn irradiance_matches_quadrature() {
    let env = synthetic();
    let q = Vec3::new(
        quadrature(8, |d| (env.eval(d).x * d.y.max(0.0)) as f64) as f32,
        quadrature(8, |d| (env.eval(d).y * d.y.max(0.0)) as f64) as f32,
        quadrature(8, |d| (env.eval(d).z * d.y.max(0.0)) as f64) as f32,
    );
    let mc = irradiance_mc(&env, 400_000, 5);
    let rel = ((mc - q) / q).abs();
    assert!(rel.max_element() < 0.01, "MC {mc} vs quadrature {q}");
}

#[test]
fn uniform_furnace() {
    let env = uniform();
    let l = Vec3::new(0.5, 1.0, 2.0);
    let mc = irradiance_mc(&env, 400_000, 6);
    let expect = l * PI;
    let rel = ((mc - expect) / expect).abs();
    assert!(rel.max_element() < 0.01, "MC {mc} vs π·L {expect}");
    assert!((env.power_proxy() - luminance(l) * 4.0 * PI).abs() < 1e-4);
}

#[test]
fn sun_gets_its_share() {
    let env = synthetic();
    let img = synthetic_image();
    // Share = Σ_sun Y·ΔΩ / Σ_all Y·ΔΩ with exact texel solid angles.
    let d_omega = |y: u32| {
        let t0 = PI as f64 * y as f64 / H as f64;
        let t1 = PI as f64 * (y + 1) as f64 / H as f64;
        2.0 * std::f64::consts::PI / W as f64 * (t0.cos() - t1.cos())
    };
    let (mut sun, mut all) = (0.0, 0.0);
    for y in 0..H {
        for x in 0..W {
            let w = luminance(img.get(x, y).unwrap()) as f64 * d_omega(y);
            all += w;
            if (SUN_X..SUN_X + 2).contains(&x) && (SUN_Y..SUN_Y + 2).contains(&y) {
                sun += w;
            }
        }
    }
    let share = sun / all;
    assert!(share > 0.2 && share < 0.8, "test map: sun share {share}");
    assert!((env.power_proxy() as f64 - all).abs() < 1e-3 * all);
    let n = 200_000;
    let mut rng = Rng::new(&[7]);
    let mut hits = 0;
    for _ in 0..n {
        if let Some(s) = env.sample(rng_u(&mut rng)) {
            let (x, y) = mapping::uv_to_pixel(dir_to_uv(s.wi), W, H);
            if (SUN_X..SUN_X + 2).contains(&x) && (SUN_Y..SUN_Y + 2).contains(&y) {
                hits += 1;
            }
        }
    }
    let got = hits as f64 / n as f64;
    assert!(
        ((got - share) / share).abs() < 0.05,
        "sun share {got} vs {share}"
    );
}

/// A unique scratch directory under the system temp dir.
fn scratch(name: &str) -> PathBuf {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    let dir =
        std::env::temp_dir().join(format!("iris-envmap-{name}-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Loads the environment file at `path` through `--env`'s parser; it must be a W×H map.
fn load_map(path: &Path) -> Environment {
    let env = Environment::parse_arg(path.to_str().unwrap())
        .unwrap()
        .unwrap();
    assert_eq!((map_of(&env).width(), map_of(&env).height()), (W, H));
    env
}

fn map_of(env: &Environment) -> &EnvMap {
    let Environment::Map(m) = env else {
        panic!("expected a map");
    };
    m
}

#[test]
fn load_exr_round_trip_and_clamp() {
    let dir = scratch("exr");
    let path = dir.join("sky.exr");
    let mut img = synthetic_image();
    img.data[3] = Vec3::new(f32::NAN, 1.0, 1.0);
    img.data[5] = Vec3::new(-1.0, 1.0, 1.0);
    img.data[7] = Vec3::new(f32::INFINITY, 0.0, 0.0);
    write_image(&path, &img, &DisplayOptions::default()).unwrap();
    let env = load_map(&path);
    let m = map_of(&env);
    assert_eq!(m.texel(SUN_X, SUN_Y), SUN);
    assert_eq!(m.texel(3, 0), Vec3::new(0.0, 1.0, 1.0));
    assert_eq!(m.texel(5, 0), Vec3::new(0.0, 1.0, 1.0));
    assert_eq!(m.texel(7, 0), Vec3::ZERO);
    assert_eq!(env.warnings().len(), 1);
    assert!(
        env.warnings()[0].contains("3 environment texel"),
        "{:?}",
        env.warnings()
    );
    assert!(env.warnings()[0].contains("sky.exr"));
    // eval at a texel centre returns the stored texel.
    let d = uv_to_dir(Vec2::new(
        (SUN_X as f32 + 0.5) / W as f32,
        (SUN_Y as f32 + 0.5) / H as f32,
    ));
    assert_eq!(env.eval(d), SUN);
    let total = quadrature(2, |d| env.pdf(d) as f64);
    assert!((total - 1.0).abs() < 0.01);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn load_hdr() {
    use image::codecs::hdr::HdrEncoder;
    let dir = scratch("hdr");
    let path = dir.join("sky.HDR");
    let img = synthetic_image();
    let px: Vec<image::Rgb<f32>> = img
        .data
        .iter()
        .map(|c| image::Rgb([c.x, c.y, c.z]))
        .collect();
    let file = std::fs::File::create(&path).unwrap();
    HdrEncoder::new(std::io::BufWriter::new(file))
        .encode(&px, W as usize, H as usize)
        .unwrap();
    let env = load_map(&path);
    let m = map_of(&env);
    // RGBE keeps ~1 % precision.
    let got = m.texel(SUN_X, SUN_Y);
    assert!(((got - SUN) / SUN).abs().max_element() < 0.01, "{got}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn errors_name_the_file_or_flag() {
    let dir = scratch("err");
    let missing = dir.join("missing-sky.exr");
    let e = Environment::parse_arg(missing.to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("missing-sky.exr"), "{e}");
    let e = Environment::parse_arg(dir.join("missing.hdr").to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("missing.hdr"), "{e}");
    let png = dir.join("sky.png");
    write_image(&png, &synthetic_image(), &DisplayOptions::default()).unwrap();
    let e = Environment::parse_arg(png.to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("sky.png"), "{e}");
    // A corrupt .exr names the file too.
    let bad = dir.join("bad.exr");
    std::fs::write(&bad, b"not an exr").unwrap();
    let e = Environment::parse_arg(bad.to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("bad.exr"), "{e}");
    for s in ["-1,0,0", "nan", "inf", "1,2", "0,0,-0.5"] {
        let e = Environment::parse_arg(s).unwrap_err();
        assert!(
            matches!(e, Error::Usage(_)) && e.to_string().contains("--env"),
            "{s}: {e}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn parse_colours_and_none() {
    assert!(Environment::parse_arg("none").unwrap().is_none());
    let Some(Environment::Uniform { radiance }) = Environment::parse_arg("1, 0.5,0").unwrap()
    else {
        panic!("expected uniform");
    };
    assert_eq!(radiance, Vec3::new(1.0, 0.5, 0.0));
    let Some(Environment::Uniform { radiance }) = Environment::parse_arg("0.5").unwrap() else {
        panic!("expected uniform");
    };
    assert_eq!(radiance, Vec3::splat(0.5));
}

#[test]
fn size_limits() {
    let e = EnvMap::from_image(ImageRgb::new(0, 0), Path::new("empty.exr")).unwrap_err();
    assert!(e.to_string().contains("empty.exr"), "{e}");
    // Checked before the (absent) data is touched.
    let huge = ImageRgb {
        width: 1 << 14,
        height: (1 << 12) + 1,
        data: Vec::new(),
    };
    let e = EnvMap::from_image(huge, Path::new("huge.exr")).unwrap_err();
    assert!(
        matches!(&e, Error::Load(l) if l.kind == LoadErrorKind::TooLarge),
        "{e}"
    );
    let short = ImageRgb {
        width: 4,
        height: 2,
        data: vec![Vec3::ONE; 3],
    };
    assert!(EnvMap::from_image(short, Path::new("short.exr")).is_err());
}

#[test]
fn black_map_samples_nothing() {
    let env =
        Environment::Map(EnvMap::from_image(ImageRgb::new(8, 4), Path::new("black")).unwrap());
    assert!(env.sample(Vec2::new(0.3, 0.7)).is_none());
    assert_eq!(env.pdf(Vec3::X), 0.0);
    assert_eq!(env.power_proxy(), 0.0);
}
