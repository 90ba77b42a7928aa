//! Light tracing per pixel (issue 31): a caustic seen directly, splatted by
//! [`Splatter::connect`], equals in every pixel the box-filtered radiance the camera's
//! pixels integrate ([`Camera::generate_ray`] over the pixel's square), including the
//! pixels a sharp caustic edge crosses. A splat that lands in a neighbouring pixel, a
//! wider reconstruction kernel or a wrong W_e would move those pixels by tens of percent
//! while leaving the image mean alone (the peak error of a blurred caustic).
//!
//! Scene (world space, metres; the light in candela): a point light of intensity I = 1 under
//! a square perfect mirror (a closed slab of infinite index, KHR_materials_ior 0: Fresnel
//! 1, reflectance 1, a delta BSDF) above a white Lambertian floor (albedo 1) at y = 0, seen
//! from below the mirror. The mirrored light reaches the floor from the light's image
//! L' = (x, 2 y_m − y, z) in the mirror plane y = y_m, through the mirror's square only:
//! a lit square with sharp edges. The floor's radiance there is L = I cos θ / r² / π
//! (the cos θ / r² law from L', Lambert's ρ/π); pixel j's value is its mean over the
//! pixel's square of raster positions, integrated by stratified quadrature (64² points a
//! pixel, 512² within one pixel of an edge, where the lit fraction is only resolved to
//! ~2/512 of the pixel).

use crate::common;

use glam::{Vec2, Vec3};
use iris::camera::{look_at, Camera};
use iris::integrator::light_trace::Splatter;
use iris::material::MaterialDesc;
use iris::photon::emit::{Aim, PhotonEmitter, PhotonNumbers};
use iris::photon::trace::{self, Roulette, TraceSettings};
use iris::scene::desc::{CameraDesc, MeshDesc, Projection, SceneDesc};
use iris::scene::Scene;

const W: u32 = 48;
const H: u32 = 36;
/// The mirror's lower face (y) and half side.
const MIRROR_Y: f32 = 0.999;
const MIRROR_HALF: f32 = 0.2;
const FLOOR_HALF: f32 = 1.2;
const LIGHT: Vec3 = Vec3::new(0.05, 0.55, -0.03);

fn scene() -> Scene {
    let floor = common::mesh(
        "floor",
        iris::authoring::shapes::ground_plane(FLOOR_HALF, FLOOR_HALF),
        0,
    );
    let s = 2.0 * MIRROR_HALF;
    let (p, t) = common::cuboid([s, 0.002, s], [0.0, MIRROR_Y + 0.001, 0.0]);
    let mirror = MeshDesc {
        name: "mirror".into(),
        positions: p.into_iter().map(Vec3::from).collect(),
        indices: t,
        material: Some(1),
        ..Default::default()
    };
    let mirror_material = MaterialDesc {
        base_color: glam::Vec4::ONE,
        ..common::clear_glass("mirror", 0.0)
    };
    let desc = SceneDesc {
        source: "mirrored point light".into(),
        meshes: vec![floor, mirror],
        materials: vec![common::white_lambert(), mirror_material],
        lights: vec![common::white_point_light(LIGHT)],
        ..Default::default()
    };
    common::build_scene(desc)
}

fn camera() -> CameraDesc {
    CameraDesc {
        name: "cam".into(),
        projection: Projection::Perspective {
            yfov: 0.9,
            aspect: None,
        },
        world_from_camera: look_at(Vec3::new(0.0, 0.7, 1.9), Vec3::new(0.0, 0.0, -0.1), Vec3::Y),
    }
}

/// The mirrored light's radiance at the floor point seen at raster position `px` (0 off
/// the floor or outside the mirror's square as seen from L').
fn radiance_at(camera: &Camera, px: Vec2) -> f64 {
    let ray = camera.generate_ray(px);
    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    if d.y >= 0.0 {
        return 0.0;
    }
    let p = o - d * (o.y / d.y);
    let half = f64::from(FLOOR_HALF);
    if p.x.abs() > half || p.z.abs() > half {
        return 0.0;
    }
    let image = glam::DVec3::new(
        f64::from(LIGHT.x),
        2.0 * f64::from(MIRROR_Y) - f64::from(LIGHT.y),
        f64::from(LIGHT.z),
    );
    let q = image - p;
    let c = p + q * (f64::from(MIRROR_Y) / image.y);
    if c.x.abs() > f64::from(MIRROR_HALF) || c.z.abs() > f64::from(MIRROR_HALF) {
        return 0.0;
    }
    let r2 = q.length_squared();
    (q.y / r2.sqrt()) / r2 / std::f64::consts::PI
}

/// Pixel (x, y)'s mean radiance over `k`² stratified raster positions, and whether the
/// caustic's edge crosses it (some positions lit, some not).
fn pixel_quadrature(camera: &Camera, x: u32, y: u32, k: u32) -> (f64, bool) {
    let (mut sum, mut lit) = (0.0, 0u32);
    for j in 0..k {
        for i in 0..k {
            let off = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
            let v = radiance_at(camera, Vec2::new(x as f32, y as f32) + off);
            sum += v;
            lit += u32::from(v > 0.0);
        }
    }
    (sum / f64::from(k * k), lit > 0 && lit < k * k)
}

/// The analytic image: 64² points a pixel, 512² within one pixel of an edge.
fn analytic(camera: &Camera) -> Vec<f64> {
    let coarse: Vec<(f64, bool)> = (0..H)
        .flat_map(|y| (0..W).map(move |x| (x, y)))
        .map(|(x, y)| pixel_quadrature(camera, x, y, 64))
        .collect();
    let near_edge = |x: i64, y: i64| {
        (-1..=1).any(|dy| {
            (-1..=1).any(|dx| {
                let (u, v) = (x + dx, y + dy);
                u >= 0 && v >= 0 && u < i64::from(W) && v < i64::from(H) && {
                    coarse[(v * i64::from(W) + u) as usize].1
                }
            })
        })
    };
    (0..H)
        .flat_map(|y| (0..W).map(move |x| (x, y)))
        .map(|(x, y)| {
            if near_edge(i64::from(x), i64::from(y)) {
                pixel_quadrature(camera, x, y, 512).0
            } else {
                coarse[(y * W + x) as usize].0
            }
        })
        .collect()
}

/// The light-traced image of `n` photons aimed at the mirror (first floor vertices after
/// the mirror, the caustic-origin vertices the hybrid splats) and per pixel the sum of its
/// squared splats: Var(Σᵢ Xᵢ) = n Var(X) ≤ Σᵢ Xᵢ² for n photons' i.i.d. splats Xᵢ, an
/// upper bound on the image's variance (the Halton photons only lower it).
fn light_traced(scene: &Scene, camera: &Camera, n: u64) -> (Vec<f64>, Vec<f64>) {
    let splatter = Splatter::new(scene, camera, (W, H), 2, true).expect("a perspective camera");
    let emitter = PhotonEmitter::new(scene);
    let numbers = PhotonNumbers::new(31);
    let ts = TraceSettings {
        max_depth: 1,
        roulette: Roulette::Throughput,
    };
    let (mut img, mut sq) = (vec![0.0; (W * H) as usize], vec![0.0; (W * H) as usize]);
    let mut rays = 0;
    for i in 0..n {
        let Some(ph) = emitter.emit_index(scene, &numbers, i, Aim::Only) else {
            continue;
        };
        let mut rng = iris::math::Rng::new(&[31, i]);
        trace::trace::<Vec3>(scene, &ph, (), &ts, &mut rng, |v, l| {
            if v.bounces == 0 {
                return;
            }
            if let Some((p, rgb)) = splatter.connect(v, v.power / n as f32, l, &mut rays) {
                let s = f64::from(rgb.x + rgb.y + rgb.z) / 3.0;
                img[p as usize] += s;
                sq[p as usize] += s * s;
            }
        });
    }
    (img, sq)
}

/// Every pixel of the light-traced mirrored caustic within 4 σ (its own splats' bound)
/// plus 0.5 % of the brightest pixel (the edge quadrature: ≤ ~2/512 of a pixel's lit
/// fraction) of the analytic value; their z-scores' RMS at most 1 (≈ 1 for independent
/// photons, less for Halton ones). 2²¹ photons, all aimed at the mirror: ~3 000 per lit
/// pixel, σ ≈ 2 % of a lit pixel. A splat one pixel off, or spread over 2 × 2 pixels,
/// moves the edge pixels by ≥ 25 % of the lit value. Measured (2026-12-05): z RMS 0.17,
/// worst |z| 0.75; with the splat's x moved by half a pixel an edge pixel fails, with its
/// value scaled by 1.03 the z RMS is 1.6.
#[test]
fn light_traced_caustic_matches_the_analytic_pixels() {
    let scene = scene();
    let cam = Camera::new(&camera(), W, H);
    let want = analytic(&cam);
    let (got, sq) = light_traced(&scene, &cam, 1 << 21);
    let max = want.iter().copied().fold(0.0, f64::max);
    let lit = want.iter().filter(|&&v| v > 0.0).count();
    let edges = want.iter().filter(|&&v| v > 0.0 && v < 0.9 * max).count();
    assert!(
        max > 0.01 && lit > 200,
        "the caustic is in view: {lit} px, max {max}"
    );
    let (mut z2, mut worst) = (0.0, (0.0, 0usize));
    for (j, (&g, &a)) in got.iter().zip(&want).enumerate() {
        let sigma = sq[j].sqrt();
        let tol = 4.0 * sigma + 0.005 * max;
        let (x, y) = (j as u32 % W, j as u32 / W);
        assert!(
            (g - a).abs() <= tol,
            "pixel ({x}, {y}): light traced {g:.5}, analytic {a:.5}, tolerance {tol:.5}"
        );
        if a > 0.0 {
            let z = (g - a) / sigma.max(1e-12);
            z2 += z * z;
            if z.abs() > worst.0 {
                worst = (z.abs(), j);
            }
        }
    }
    let z_rms = (z2 / lit as f64).sqrt();
    eprintln!(
        "{lit} lit px ({edges} below 90 % of the max {max:.4}); z RMS {z_rms:.3}, worst |z| {:.2} at pixel {}",
        worst.0, worst.1
    );
    assert!(z_rms <= 1.0, "z-score RMS {z_rms}");
}
