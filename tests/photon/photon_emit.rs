//! Photon emission (`iris::photon::emit`): for every light type, the mean photon power equals
//! the analytic flux written out independently here, the photons start where they should and
//! travel where they should, and mixed scenes choose lights in proportion to luminance.
//!
//! Statistical tolerances: means are compared within 5 standard errors (estimated from the
//! samples themselves; a false failure has probability < 1e-6 per check) plus 1e-4 relative
//! for f32 rounding (photons whose power is constant have zero sample variance).

use glam::{Vec2, Vec3};
use iris::light::env::{luminance, EnvMap, Environment};
use iris::light::Light;
use iris::material::{ImageDesc, MaterialDesc, TextureRef};
use iris::math::Rng;
use iris::photon::emit::{EmittedPhoton, PhotonEmitter, DISC_MARGIN};
use iris::scene::desc::{MeshDesc, SceneDesc};
use iris::scene::Scene;
use std::f32::consts::PI;

/// A square of half-size `half` at height `y`, facing −Y (`down`) or +Y.
fn quad(y: f32, half: f32, down: bool, material: usize) -> MeshDesc {
    let mut indices = vec![[0, 1, 2], [0, 2, 3]];
    if !down {
        indices = vec![[0, 2, 1], [0, 3, 2]];
    }
    MeshDesc {
        name: format!("quad{y}"),
        positions: vec![
            Vec3::new(-half, y, -half),
            Vec3::new(half, y, -half),
            Vec3::new(half, y, half),
            Vec3::new(-half, y, half),
        ],
        indices,
        material: Some(material),
        ..Default::default()
    }
}

/// A floor (2 × 2 at y = 0) plus `extra` meshes; materials 0 = grey, then `materials`.
fn scene(extra: Vec<MeshDesc>, materials: Vec<MaterialDesc>) -> Scene {
    scene_with_images(extra, materials, vec![])
}

/// [`scene`]'s validated description, to build with exact lights ([`with_lights`]).
fn scene_desc(extra: Vec<MeshDesc>, materials: Vec<MaterialDesc>) -> SceneDesc {
    desc_under(extra, materials, vec![], None)
}

fn scene_with_images(
    extra: Vec<MeshDesc>,
    materials: Vec<MaterialDesc>,
    images: Vec<ImageDesc>,
) -> Scene {
    scene_under(extra, materials, images, None)
}

/// The disc scene with `extra` meshes, lit only by its emitters and the environment `env`.
fn scene_under(
    extra: Vec<MeshDesc>,
    materials: Vec<MaterialDesc>,
    images: Vec<ImageDesc>,
    env: Option<Environment>,
) -> Scene {
    with_lights(desc_under(extra, materials, images, env), vec![])
}

/// [`scene_under`]'s validated description.
fn desc_under(
    extra: Vec<MeshDesc>,
    mut materials: Vec<MaterialDesc>,
    images: Vec<ImageDesc>,
    env: Option<Environment>,
) -> SceneDesc {
    materials.insert(0, MaterialDesc::default());
    let mut meshes = vec![quad(0.0, 1.0, false, 0)];
    meshes.extend(extra);
    let desc = SceneDesc {
        source: "photon_emit".into(),
        meshes,
        materials,
        images,
        environment_light: env,
        ..Default::default()
    };
    iris::scene::validate::validate(desc).expect("valid scene")
}

/// The scene of `desc` with exactly the punctual `lights` (no default lights), built once.
fn with_lights(desc: SceneDesc, lights: Vec<Light>) -> Scene {
    Scene::build_with_lights(desc, iris::accel::Backend::Bvh, lights).expect("build")
}

fn emitter(le: Vec3, double_sided: bool) -> MaterialDesc {
    MaterialDesc {
        name: "lamp".into(),
        emissive: le,
        double_sided,
        ..Default::default()
    }
}

/// `n` photons from independent uniform numbers (degenerate samples skipped).
fn photons<'a>(e: &PhotonEmitter, s: &'a Scene, n: usize, seed: u64) -> Vec<EmittedPhoton<'a>> {
    let mut rng = Rng::new(&[seed]);
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        let ul = rng.next_f32();
        let up = Vec2::new(rng.next_f32(), rng.next_f32());
        let ud = Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(p) = e.emit(s, ul, up, ud) {
            out.push(p);
        }
    }
    out
}

/// Mean photon power (over `n` attempts, counting degenerate ones as 0) ≈ `expected`.
fn assert_mean(ph: &[EmittedPhoton], n: usize, expected: Vec3) {
    for c in 0..3 {
        let (mut s1, mut s2) = (0.0f64, 0.0f64);
        for p in ph {
            let x = p.power[c] as f64;
            s1 += x;
            s2 += x * x;
        }
        let mean = s1 / n as f64;
        let var = (s2 / n as f64 - mean * mean).max(0.0);
        let se = (var / n as f64).sqrt();
        let e = expected[c] as f64;
        assert!(
            (mean - e).abs() <= 5.0 * se + 1e-4 * e.abs(),
            "channel {c}: mean power {mean} vs flux {e} (se {se})"
        );
    }
}

fn close(a: Vec3, b: Vec3, rel: f32) -> bool {
    (a - b).abs().max_element() <= rel * b.abs().max_element()
}

/// Bounding-sphere centre and disc radius, recomputed from the scene's bounds.
fn disc(s: &Scene) -> (Vec3, f32, f32) {
    let (lo, hi) = s.bounds();
    let big_r = 0.5 * (hi - lo).length();
    (0.5 * (lo + hi), DISC_MARGIN * big_r, big_r)
}

/// Origins lie on the disc of radius r ⟂ `dir`, r upstream of the centre, outside the
/// bounding sphere; returns the mean squared distance to the axis.
fn check_disc(p: &EmittedPhoton, dir: Vec3, s: &Scene) -> f32 {
    let (c, r, big_r) = disc(s);
    let v = p.ray.origin - c;
    let along = v.dot(dir);
    // f32 positions of magnitude ~2: 1e-5 absolute is ~40 ulps.
    assert!(
        (along + r).abs() < 1e-5 * r,
        "disc plane: {along} vs {}",
        -r
    );
    let rho2 = (v - dir * along).length_squared();
    assert!(rho2 <= r * r * (1.0 + 1e-5), "outside the disc: {rho2}");
    assert!(v.length() > big_r, "origin inside the bounding sphere");
    assert!((p.ray.dir - dir).length() < 1e-5, "direction {}", p.ray.dir);
    rho2
}

#[test]
fn point_light_flux_is_4_pi_i() {
    let i = Vec3::new(10.0, 20.0, 5.0);
    let pos = Vec3::new(0.2, 1.5, -0.3);
    let s = with_lights(
        scene_desc(vec![], vec![]),
        vec![Light::Point {
            position: pos,
            intensity: i,
            range: Some(4.0),
        }],
    );
    let e = PhotonEmitter::new(&s);
    assert!(close(e.total_power(), 4.0 * PI * i, 1e-6));
    let n = 20_000;
    let ph = photons(&e, &s, n, 1);
    assert_eq!(ph.len(), n);
    let mut mean_dir = Vec3::ZERO;
    for p in &ph {
        assert_eq!(p.ray.origin, pos);
        assert_eq!(p.range, Some(4.0));
        assert!((p.ray.dir.length() - 1.0).abs() < 1e-5);
        mean_dir += p.ray.dir;
    }
    // Uniform sphere: each component of the mean direction has σ = 1/√(3n) ≈ 0.004.
    assert!((mean_dir / n as f32).length() < 0.03);
    assert_mean(&ph, n, 4.0 * PI * i);
}

#[test]
fn spot_light_stays_in_its_cone_with_t_squared_falloff() {
    let i = Vec3::new(50.0, 40.0, 30.0);
    let (inner, outer) = (0.3f32, 0.6f32);
    let (ci, co) = (inner.cos(), outer.cos());
    let axis = Vec3::new(0.3, -1.0, 0.2).normalize();
    let s = with_lights(
        scene_desc(vec![], vec![]),
        vec![Light::Spot {
            position: Vec3::new(0.0, 2.0, 0.0),
            direction: axis,
            intensity: i,
            cos_inner: ci,
            cos_outer: co,
            range: None,
        }],
    );
    let t2 = |c: f64| {
        let t = ((c - co as f64) / (ci as f64 - co as f64)).clamp(0.0, 1.0);
        t * t
    };
    // Φ = 2π I ∫_{cos_o}^1 t(c)² dc, midpoint rule with 200k steps (error ~1e-10).
    let steps = 200_000;
    let h = (1.0 - co as f64) / steps as f64;
    let k: f64 = (0..steps)
        .map(|j| t2(co as f64 + (j as f64 + 0.5) * h) * h)
        .sum();
    let flux = i * (2.0 * PI * k as f32);
    let e = PhotonEmitter::new(&s);
    assert!(close(e.total_power(), flux, 1e-5), "{}", e.total_power());
    let n = 100_000;
    let ph = photons(&e, &s, n, 2);
    assert_eq!(ph.len(), n);
    assert_mean(&ph, n, flux);
    // Power-weighted histogram of cos θ over [cos_o, 1] follows t²: 8 bins.
    let bins = 8;
    let width = (1.0 - co as f64) / bins as f64;
    let mut hist = vec![0.0f64; bins];
    let total: f64 = ph.iter().map(|p| p.power.x as f64).sum();
    for p in &ph {
        let c = p.ray.dir.dot(axis);
        assert!(
            c >= co - 1e-5,
            "photon outside the outer cone: cos {c} < {co}"
        );
        let b = (((c - co) as f64 / width) as usize).min(bins - 1);
        hist[b] += p.power.x as f64 / total;
    }
    for (b, got) in hist.iter().enumerate() {
        let m = 1000;
        let hb = width / m as f64;
        let lo = co as f64 + b as f64 * width;
        let want: f64 = (0..m)
            .map(|j| t2(lo + (j as f64 + 0.5) * hb) * hb)
            .sum::<f64>()
            / k;
        // Equal weights: a bin fraction is binomial, σ = √(p(1−p)/n) ≤ 0.0016; 5σ + rounding.
        let sigma = (want * (1.0 - want) / n as f64).sqrt();
        assert!(
            (got - want).abs() <= 5.0 * sigma + 1e-4,
            "bin {b}: {got} vs {want}"
        );
    }
}

#[test]
fn directional_light_starts_on_a_disc_upstream() {
    let ill = Vec3::new(3.0, 2.0, 1.0);
    let dir = Vec3::new(1.0, -2.0, 0.5).normalize();
    let s = with_lights(
        scene_desc(vec![quad(1.0, 0.3, true, 0)], vec![]),
        vec![Light::Directional {
            direction: dir,
            illuminance: ill,
        }],
    );
    let (_, r, _) = disc(&s);
    let e = PhotonEmitter::new(&s);
    assert!(close(e.total_power(), ill * PI * r * r, 1e-5));
    let n = 40_000;
    let ph = photons(&e, &s, n, 3);
    assert_eq!(ph.len(), n);
    let rho2: Vec<f64> = ph.iter().map(|p| check_disc(p, dir, &s) as f64).collect();
    // Uniform on the disc: ρ²/r² is uniform on [0, 1], mean ½, σ = 1/√12.
    let m = rho2.iter().sum::<f64>() / n as f64 / (r * r) as f64;
    let se = (1.0 / 12.0 / n as f64).sqrt();
    assert!((m - 0.5).abs() < 5.0 * se, "mean ρ²/r² = {m}");
    assert_mean(&ph, n, ill * PI * r * r);
}

#[test]
fn area_light_single_sided_emits_down_only() {
    let le = Vec3::new(2.0, 3.0, 4.0);
    let (height, half) = (1.5f32, 0.25f32);
    let s = scene(vec![quad(height, half, true, 1)], vec![emitter(le, false)]);
    let e = PhotonEmitter::new(&s);
    let area = 4.0 * half * half;
    let flux = le * PI * area;
    assert!(close(e.total_power(), flux, 1e-5));
    let n = 40_000;
    let ph = photons(&e, &s, n, 4);
    assert_eq!(ph.len(), n);
    let mut mean_cos = 0.0f64;
    for p in &ph {
        let o = p.ray.origin;
        // On the quad, offset along the normal by ~1e-5 at most.
        assert!(
            (o.y - height).abs() < 1e-4 && o.x.abs() <= half + 1e-6 && o.z.abs() <= half + 1e-6
        );
        assert!(o.y < height, "origin on the emitting side");
        assert!(p.ray.dir.y < 0.0, "single-sided emitter shone backwards");
        mean_cos += -p.ray.dir.y as f64;
    }
    // Cosine-weighted: E[cos θ] = 2/3, σ(cos θ) = √(1/2 − 4/9) ≈ 0.236.
    let se = 0.236 / (n as f64).sqrt();
    assert!((mean_cos / n as f64 - 2.0 / 3.0).abs() < 5.0 * se);
    assert_mean(&ph, n, flux);
}

#[test]
fn area_light_applies_the_emissive_texture_at_the_sampled_uv() {
    // A 2 × 1 texture, black then white, on a quad with u = (x + h)/2h. Bilinear, repeat
    // wrap (texture::sample): f(u) = 0.5 − 2u below u = ¼, then 1 − |2u − 1.5|; mean ½.
    let f = |u: f32| {
        if u < 0.25 {
            0.5 - 2.0 * u
        } else {
            1.0 - (2.0 * u - 1.5).abs()
        }
    };
    let (le, half, height) = (Vec3::new(2.0, 1.0, 0.5), 0.5f32, 1.2f32);
    let mut lamp = quad(height, half, true, 1);
    lamp.uvs = lamp
        .positions
        .iter()
        .map(|p| Vec2::new((p.x + half) / (2.0 * half), (p.z + half) / (2.0 * half)))
        .collect();
    let mut mat = emitter(le, false);
    mat.emissive_texture = Some(TextureRef::new(0, 0));
    let img = ImageDesc {
        name: "bw".into(),
        width: 2,
        height: 1,
        rgba8: std::sync::Arc::new(vec![0, 0, 0, 255, 255, 255, 255, 255]),
    };
    let s = scene_with_images(vec![lamp], vec![mat], vec![img]);
    let e = PhotonEmitter::new(&s);
    let flux = le * PI * 4.0 * half * half;
    // total_power uses the emissive factor (documented upper bound for textured emitters).
    assert!(close(e.total_power(), flux, 1e-5));
    let n = 40_000;
    let ph = photons(&e, &s, n, 9);
    for p in &ph {
        let u = (p.ray.origin.x + half) / (2.0 * half);
        // Every photon carries factor flux × f(u); f32 interpolation of uv and the
        // bilinear weights err by ~1e-6, so 1e-4 of the largest flux is ample.
        let want = flux * f(u);
        assert!(
            (p.power - want).abs().max_element() < 1e-4 * flux.max_element(),
            "u {u}: {} vs {want}",
            p.power
        );
    }
    assert_mean(&ph, n, 0.5 * flux);
}

#[test]
fn area_light_double_sided_emits_both_ways() {
    let le = Vec3::new(1.0, 0.5, 0.25);
    let half = 0.4f32;
    let s = scene(vec![quad(1.0, half, true, 1)], vec![emitter(le, true)]);
    let e = PhotonEmitter::new(&s);
    let flux = le * PI * 4.0 * half * half * 2.0;
    assert!(close(e.total_power(), flux, 1e-5));
    let n = 40_000;
    let ph = photons(&e, &s, n, 5);
    let up = ph.iter().filter(|p| p.ray.dir.y > 0.0).count();
    for p in &ph {
        // The origin is offset to the side the photon leaves by.
        assert_eq!(p.ray.origin.y > 1.0, p.ray.dir.y > 0.0);
    }
    // Binomial(n, ½): σ = √n/2 = 100.
    assert!(
        (up as f64 - n as f64 / 2.0).abs() < 500.0,
        "{up} of {n} upward"
    );
    assert_mean(&ph, n, flux);
}

#[test]
fn uniform_environment_flux_is_l_4pi_pi_r2() {
    let l = Vec3::new(0.5, 1.0, 2.0);
    let s = scene_under(
        vec![],
        vec![],
        vec![],
        Some(Environment::Uniform { radiance: l }),
    );
    let (_, r, _) = disc(&s);
    let flux = l * 4.0 * PI * PI * r * r;
    let e = PhotonEmitter::new(&s);
    assert!(close(e.total_power(), flux, 1e-5));
    let n = 20_000;
    let ph = photons(&e, &s, n, 6);
    assert_eq!(ph.len(), n);
    for p in &ph {
        check_disc(p, p.ray.dir, &s);
        assert!(p.shape.is_none() && p.range.is_none());
    }
    assert_mean(&ph, n, flux);
}

/// An 8 × 4 map with one bright coloured texel and varied others.
fn small_map() -> Environment {
    let data = (0..32)
        .map(|i| {
            let f = i as f32;
            if i == 13 {
                Vec3::new(40.0, 10.0, 2.0)
            } else {
                Vec3::new(0.1 + 0.05 * f, 0.3, 0.02 * (31.0 - f))
            }
        })
        .collect();
    let img = iris::image::ImageRgb {
        width: 8,
        height: 4,
        data,
    };
    Environment::Map(EnvMap::from_image(img, std::path::Path::new("test.exr")).unwrap())
}

#[test]
fn environment_map_flux_matches_quadrature() {
    let env = small_map();
    // ∫ L dω by the midpoint rule on a 1600 × 800 (θ, φ) grid aligned with the texels, so
    // only the sin θ quadrature errs (relative O(1/800²)).
    let (nu, nv) = (1600, 800);
    let mut integral = [0.0f64; 3];
    for j in 0..nv {
        let theta = (j as f64 + 0.5) / nv as f64 * std::f64::consts::PI;
        for k in 0..nu {
            let u = (k as f32 + 0.5) / nu as f32;
            let v = (j as f32 + 0.5) / nv as f32;
            let l = env.eval(iris::light::env::uv_to_dir(Vec2::new(u, v)));
            let w = theta.sin()
                * (std::f64::consts::PI / nv as f64)
                * (2.0 * std::f64::consts::PI / nu as f64);
            for c in 0..3 {
                integral[c] += l[c] as f64 * w;
            }
        }
    }
    let integral = Vec3::new(integral[0] as f32, integral[1] as f32, integral[2] as f32);
    let s = scene_under(vec![], vec![], vec![], Some(env));
    let (_, r, _) = disc(&s);
    let flux = integral * PI * r * r;
    let e = PhotonEmitter::new(&s);
    assert!(
        close(e.total_power(), flux, 1e-4),
        "{} vs {flux}",
        e.total_power()
    );
    let n = 100_000;
    let ph = photons(&e, &s, n, 7);
    for p in &ph {
        check_disc(p, p.ray.dir, &s);
    }
    assert_mean(&ph, n, flux);
}

#[test]
fn mixed_lights_are_chosen_by_luminance() {
    let le = Vec3::new(1.0, 1.0, 1.0);
    let base = desc_under(
        vec![quad(1.8, 0.2, true, 1)],
        vec![emitter(le, false)],
        vec![],
        Some(Environment::Uniform {
            radiance: Vec3::splat(0.05),
        }),
    );
    let sun = Vec3::new(-0.3, -1.0, 0.1).normalize();
    let p_pos = Vec3::new(0.5, 1.0, 0.5);
    let s_pos = Vec3::new(-0.5, 1.0, -0.5);
    let lights = vec![
        Light::Point {
            position: p_pos,
            intensity: Vec3::new(1.0, 0.2, 0.2),
            range: None,
        },
        Light::Spot {
            position: s_pos,
            direction: -Vec3::Y,
            intensity: Vec3::new(5.0, 5.0, 8.0),
            cos_inner: 0.9,
            cos_outer: 0.7,
            range: None,
        },
        Light::Directional {
            direction: sun,
            illuminance: Vec3::splat(0.4),
        },
        // Zero power: never chosen.
        Light::Point {
            position: Vec3::ZERO,
            intensity: Vec3::ZERO,
            range: None,
        },
    ];
    let s = with_lights(base, lights);
    let (_, r, _) = disc(&s);
    let fluxes = [
        4.0 * PI * Vec3::new(1.0, 0.2, 0.2),
        2.0 * PI * (0.1 + 0.2 / 3.0) * Vec3::new(5.0, 5.0, 8.0),
        PI * r * r * Vec3::splat(0.4),
        PI * 0.16 * le,
        4.0 * PI * PI * r * r * Vec3::splat(0.05),
    ];
    let total: Vec3 = fluxes.iter().sum();
    let e = PhotonEmitter::new(&s);
    assert!(close(e.total_power(), total, 1e-5));
    let n = 100_000;
    let ph = photons(&e, &s, n, 8);
    let mut counts = [0usize; 5];
    for p in &ph {
        let k = if p.ray.origin == p_pos {
            0
        } else if p.ray.origin == s_pos {
            1
        } else if (p.ray.dir - sun).length() < 1e-6 {
            2
        } else if (p.ray.origin.y - 1.8).abs() < 1e-4 && p.ray.origin.x.abs() <= 0.2 + 1e-6 {
            3
        } else {
            4
        };
        assert_ne!(p.ray.origin, Vec3::ZERO, "the dark light was chosen");
        counts[k] += 1;
    }
    let lum_total: f32 = fluxes.iter().map(|f| luminance(*f)).sum();
    for (k, f) in fluxes.iter().enumerate() {
        let want = (luminance(*f) / lum_total) as f64;
        let got = counts[k] as f64 / n as f64;
        let sigma = (want * (1.0 - want) / n as f64).sqrt();
        assert!(
            (got - want).abs() < 5.0 * sigma,
            "light {k}: {got} vs {want}"
        );
    }
    assert_mean(&ph, n, total);
}

#[test]
fn no_light_means_empty() {
    let s = with_lights(
        scene_desc(vec![], vec![]),
        vec![Light::Point {
            position: Vec3::ONE,
            intensity: Vec3::ZERO,
            range: None,
        }],
    );
    let e = PhotonEmitter::new(&s);
    assert!(e.is_empty());
    assert_eq!(e.total_power(), Vec3::ZERO);
    assert!(e
        .emit(&s, 0.5, Vec2::splat(0.5), Vec2::splat(0.5))
        .is_none());
}
