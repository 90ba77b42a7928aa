//! A ball-lens focus bench: a test scene (not an asset) for the photon mapper's caustics.
//!
//! [`focus_bench`] builds, in metres with the light travelling along −Z: a glass sphere
//! centred at the origin, a black plate with a round hole at z = +2R shading everything
//! but an axial pencil of light, and a white screen at z = −d facing +Z. Varying d and
//! measuring the spot size on the screen finds the focus; the paraxial focus of a ball
//! lens is f = nR/(2(n − 1)) from its centre (Hecht, "Optics", 5th ed., §6.2: a thick lens
//! whose principal planes both pass through the centre). Rays farther from the axis focus
//! nearer (spherical aberration), so keep `aperture` small (≲ 0.2R) to measure f.
//!
//! Geometry is computed in `f64` and rounded to `f32` once; all meshes face +Z (the plate
//! and screen) or outwards (the sphere).

use super::parts::{add_mesh, camera};
use crate::authoring::lathe::sin_cos;
use crate::authoring::shapes::{ground_plane, icosphere, quarter_turn_x, TriMesh};
use crate::material::MaterialDesc;
use crate::scene::desc::LightDesc;
use crate::scene::desc::{CameraDesc, SceneDesc};
use glam::{DVec3, Vec3};

/// Smallest number of segments of [`focus_bench`]'s aperture plate.
pub const APERTURE_SEGMENTS: u32 = 256;

/// The square plate `[−half, half]²` in the plane z = 0, facing +Z, with a round hole of
/// radius `hole` (< `half`) at the origin, sampled at the angles 2πk/segments (`segments`
/// rounded up to a multiple of 8, so the square's corners are vertices): concentric rings
/// of quads whose radii grow geometrically by 1 + 2π/segments (so every quad is about as
/// long as it is wide) up to half/1.05, then one ring out to the square. Compact triangles
/// keep every BVH efficient (one ring of slivers from the hole to the square made each ray
/// test hundreds of overlapping triangles in obvhs).
pub fn aperture_plate(hole: f64, half: f64, segments: u32) -> TriMesh {
    let n = segments.max(8).div_ceil(8) * 8;
    let q = 1.0 + 2.0 * std::f64::consts::PI / f64::from(n);
    let mut radii = vec![hole];
    while radii.len() < 4096 && radii[radii.len() - 1] * q < half / 1.05 {
        let next = radii[radii.len() - 1] * q;
        radii.push(next);
    }
    let mut mesh = TriMesh::default();
    let rings = radii.len() as u32 + 1;
    for k in 0..n {
        let (s, c) = sin_cos(2.0 * std::f64::consts::PI * f64::from(k) / f64::from(n));
        for &r in &radii {
            mesh.positions.push(DVec3::new(r * c, r * s, 0.0).as_vec3());
        }
        let outer = if (8 * k) % n == 0 && (8 * k / n) % 2 == 1 {
            // A corner: exactly (±half, ±half).
            half * DVec3::new(c.signum(), s.signum(), 0.0)
        } else if c.abs() >= s.abs() {
            DVec3::new(half * c.signum(), half * s / c.abs(), 0.0)
        } else {
            DVec3::new(half * c / s.abs(), half * s.signum(), 0.0)
        };
        mesh.positions.push(outer.as_vec3());
        mesh.normals
            .extend(std::iter::repeat_n(Vec3::Z, rings as usize));
    }
    for k in 0..n {
        let (a, b) = (k * rings, ((k + 1) % n) * rings);
        for j in 0..rings - 1 {
            let (i0, o0, i1, o1) = (a + j, a + j + 1, b + j, b + j + 1);
            // Radial × tangential (counter-clockwise) = +Z.
            mesh.indices.push([i0, o0, o1]);
            mesh.indices.push([i0, o1, i1]);
        }
    }
    mesh
}

/// A ball-lens focus bench: a glass sphere of index `n` and radius `radius` centred at the
/// origin (icosphere with `subdivisions` levels, clamped to 7, radial vertex normals); a
/// directional light of 1 lx travelling along −Z; an opaque black (0) plate at
/// z = +2·radius, 6·radius square, facing +Z, with a hole of radius `aperture` on the axis
/// ([`aperture_plate`], [`APERTURE_SEGMENTS`] segments; `aperture` is clamped to
/// [radius/1000, 2.5·radius]); a white (0.8) square screen 5·radius wide at
/// z = −`screen_distance`, facing +Z (the plate shades all of it but the light through the
/// hole). No camera.
///
/// The paraxial focus is f = n·R / (2(n − 1)) from the centre (Hecht, "Optics", §6.2).
/// Tessellation: the icosphere's flat triangles lie inside the sphere by at most the
/// sagitta ≈ e²/8R of an edge e ≈ 1.1·R/2ˢ; with the interpolated radial normals, rays
/// at 0.1R and 0.3R cross the axis within 2.3·10⁻⁴·f of the exact sphere's crossing at
/// s = 5 and 6.3·10⁻⁵·f at s = 6 (unit test below, n = 1.5). Use s ≥ 5.
/// Invalid `n`, `radius` or `screen_distance` (non-finite, ≤ 0) give non-finite or
/// degenerate geometry that [`SceneDesc::validate`] rejects.
pub fn focus_bench(
    n: f32,
    radius: f32,
    aperture: f32,
    screen_distance: f32,
    subdivisions: u32,
) -> SceneDesc {
    let r = f64::from(radius);
    // max/min, not clamp: clamp panics when the bounds are NaN (radius NaN).
    let hole = f64::from(aperture).max(r / 1000.0).min(2.5 * r);
    let mut s = SceneDesc {
        name: format!("Focus bench: ball lens n = {n}, R = {radius} m"),
        ..SceneDesc::default()
    };
    let glass = MaterialDesc::clear_glass(&format!("Glass IOR {n}"), n, 2.0 * radius);
    add_mesh(
        &mut s,
        "Sphere",
        icosphere(radius, subdivisions),
        glass,
        None,
    );
    let plate = aperture_plate(hole, 3.0 * r, APERTURE_SEGMENTS);
    let black = MaterialDesc::diffuse("Plate", Vec3::ZERO);
    let at = Some(Vec3::new(0.0, 0.0, 2.0 * radius));
    add_mesh(&mut s, "Aperture plate", plate, black, at);
    let screen = ground_plane(2.5 * radius, 2.5 * radius).transformed(quarter_turn_x(), Vec3::ZERO);
    let white = MaterialDesc::diffuse("Screen", Vec3::splat(0.8));
    let at = Some(Vec3::new(0.0, 0.0, -screen_distance));
    add_mesh(&mut s, "Screen", screen, white, at);
    s.lights.push(LightDesc::Directional {
        name: "Sun".into(),
        direction: Vec3::NEG_Z,
        color: Vec3::ONE,
        intensity: 1.0,
        spectrum: None,
    });
    s
}

/// A camera for [`focus_bench`] scenes: looks at the screen's centre from `distance` in
/// front of it, 30° off the axis (above); it sees past the plate when `distance`/2 exceeds
/// 3·radius.
pub fn focus_bench_camera(screen_distance: f32, distance: f32) -> CameraDesc {
    let target = Vec3::new(0.0, 0.0, -screen_distance);
    let eye = target + distance * Vec3::new(0.0, 0.5, 0.75f32.sqrt());
    camera(eye, target, 30.0, 1.0)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    #[test]
    fn aperture_plate_covers_the_square_minus_the_hole() {
        // Area = 4h² − (polygon area of the hole) exactly up to f32 rounding: the ring of
        // quad rings tile the square without gaps when the corners are vertices (1e-5 relative:
        // f32 positions of size ≤ 1 give ≤ 1e-7 relative error per triangle).
        let (hole, half) = (0.02, 0.3);
        let m = aperture_plate(hole, half, 250);
        assert_eq!(m.triangle_count() % (2 * 256), 0);
        assert!(m.triangle_count() > 2 * 256 * 10, "rings of compact quads");
        let mut area = 0.0;
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
            let n = (b - a).cross(c - a);
            assert!(n.z > 0.0, "faces +Z");
            area += n.z / 2.0;
        }
        let polygon = 256.0 / 2.0 * hole * hole * (2.0 * std::f64::consts::PI / 256.0).sin();
        let want = 4.0 * half * half - polygon;
        assert!((area / want - 1.0).abs() < 1e-5, "{area} vs {want}");
    }

    #[test]
    fn focus_bench_places_plate_sphere_and_screen() {
        let s = focus_bench(1.5, 0.01, 0.002, 0.02, 5);
        crate::authoring::scene::validate(&s).expect("valid");
        let z = |name: &str| {
            let m = s.meshes.iter().find(|m| m.name == name).expect(name);
            let z = m.positions.iter().map(|p| p.z);
            let (lo, hi) = z.fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), z| {
                (a.min(z), b.max(z))
            });
            0.5 * (lo + hi)
        };
        assert_eq!(
            (z("Sphere"), z("Aperture plate"), z("Screen")),
            (0.0, 0.02, -0.02)
        );
        // The sphere's vertices all lie on the sphere (f32: 1e-6 relative).
        let sphere = &s.meshes[0];
        for p in &sphere.positions {
            assert!((p.length() / 0.01 - 1.0).abs() < 1e-6);
        }
        // The screen faces +Z and is no wider than the plate, so the plate shades it.
        let screen = &s.meshes[2];
        let [a, b, c] = screen.indices[0].map(|i| screen.positions[i as usize]);
        assert!((b - a).cross(c - a).z > 0.0);
        let wide = screen.positions.iter().map(|p| p.x.abs().max(p.y.abs()));
        assert!(wide.fold(0.0, f32::max) < 0.03);
        assert!(
            matches!(s.lights[0], LightDesc::Directional { direction, .. } if direction == Vec3::NEG_Z)
        );
        // Bad input is rejected by validation, not a panic.
        let bad = focus_bench(1.5, f32::NAN, 0.002, 0.02, 5);
        assert!(crate::authoring::scene::validate(&bad).is_err());
    }

    /// Vector Snell's law (pbrt-v4 §9.3): `n` faces against `d`, `eta` = n_i / n_t.
    pub(crate) fn refract(d: DVec3, n: DVec3, eta: f64) -> DVec3 {
        let cos_i = -d.dot(n);
        let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
        eta * d + (eta * cos_i - (1.0 - sin2_t).sqrt()) * n
    }

    /// Nearest hit of `o + t·d` (t > 1e-9) on `m`: (t, interpolated unit normal); Möller &
    /// Trumbore (1997), brute force.
    pub(crate) fn hit_mesh(m: &TriMesh, o: DVec3, d: DVec3) -> Option<(f64, DVec3)> {
        let mut best: Option<(f64, DVec3)> = None;
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
            let (e1, e2) = (b - a, c - a);
            let p = d.cross(e2);
            let det = e1.dot(p);
            if det.abs() < 1e-15 {
                continue;
            }
            let s = o - a;
            let u = s.dot(p) / det;
            let q = s.cross(e1);
            let v = d.dot(q) / det;
            let dist = e2.dot(q) / det;
            if u < 0.0 || v < 0.0 || u + v > 1.0 || dist <= 1e-9 {
                continue;
            }
            if best.is_none_or(|(b, _)| dist < b) {
                let [na, nb, nc] = t.map(|i| m.normals[i as usize].as_dvec3());
                best = Some((dist, ((1.0 - u - v) * na + u * nb + v * nc).normalize()));
            }
        }
        best
    }

    /// z where a ray coming down −Z at (x, y) crosses closest to the axis after the lens
    /// `hit` (entry and exit through the same surface, index `n`).
    fn axis_crossing(hit: &dyn Fn(DVec3, DVec3) -> (f64, DVec3), x: f64, y: f64, n: f64) -> f64 {
        let (o, d) = (DVec3::new(x, y, 10.0), DVec3::NEG_Z);
        let (t, nrm) = hit(o, d);
        let (o, d) = (o + t * d, refract(d, nrm, 1.0 / n));
        let (t, nrm) = hit(o, d);
        let (o, d) = (o + t * d, refract(d, -nrm, n));
        let t = -(o.x * d.x + o.y * d.y) / (d.x * d.x + d.y * d.y);
        o.z + t * d.z
    }

    #[test]
    fn tessellated_ball_lens_focuses_within_half_a_percent_of_the_sphere() {
        // Rays at heights 0.1R and 0.3R, at azimuths off the icosahedron's symmetry
        // planes, through the icosphere (interpolated normals) and the exact sphere:
        // the axis crossings agree to 0.5 % of f = nR/(2(n − 1)) (the brief's tolerance).
        let (n, r) = (1.5, 1.0);
        let f = n * r / (2.0 * (n - 1.0));
        let sphere = |o: DVec3, d: DVec3| {
            let b = o.dot(d);
            let t = -b - (b * b - o.length_squared() + r * r).sqrt();
            let t = if t > 1e-9 {
                t
            } else {
                -b + (b * b - o.length_squared() + r * r).sqrt()
            };
            (t, (o + t * d).normalize())
        };
        for s in [5, 6] {
            let mesh = icosphere(r as f32, s);
            let on_mesh = |o: DVec3, d: DVec3| hit_mesh(&mesh, o, d).expect("hits");
            let mut worst: f64 = 0.0;
            for h in [0.1, 0.3] {
                for a in [0.3f64, 1.1, 2.0] {
                    let (x, y) = (h * a.cos(), h * a.sin());
                    let exact = axis_crossing(&sphere, x, y, n);
                    let tess = axis_crossing(&on_mesh, x, y, n);
                    assert!(exact < 0.0 && -exact > r && -exact < f, "{exact}");
                    worst = worst.max((tess - exact).abs() / f);
                }
            }
            eprintln!("icosphere s = {s}: worst focus error {:.2e} of f", worst);
            assert!(worst < 5e-3, "s = {s}: {worst}");
        }
    }
}
