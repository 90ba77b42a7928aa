//! Two scenes for spectral rendering, shipped (CC0) in `assets/scenes/`: Fig. 5.3.1 of
//! Cropp & Zhang, "Light Refraction with Dispersion" (a narrow white beam through a 60°
//! prism onto a screen) and a diamond.
//!
//! Units are metres, +Y up, linear RGB, real-world sizes; emitters are black diffuse quads
//! with the radiance below, emitting from their front face (as in [`super::demos`]). Every
//! mesh's vertices are in world space (no node translation). Geometry is computed in `f64`
//! with `+ − × ÷ √` only and rounded to `f32` once, so the files are bit-identical on every
//! platform.
//!
//! **`fig5_3_1_prism_beam.glb`** (top view: beam in the plane y = [`BEAM_Y`]):
//! - prism: upright equilateral N-BK7 prism (side [`PRISM_SIDE`], height 0.1 m, apex
//!   towards +Z, centroid on the Y axis) standing 1 mm above a black stand 0.3 m tall;
//!   material `extras.iris_glass: "N-BK7"`, fallback `KHR_materials_ior` 1.5168 (n_d),
//!   transmission 1, volume thickness 0.1;
//! - beam: a 2 × 40 mm emitter (radiance [`BEAM_RADIANCE`]) at the back of a closed black
//!   tube (4 × 8 cm, 1 m long) whose front is a black baffle (20 × 20 cm) with a 2 × 40 mm
//!   slit; emitter centre → slit centre is the beam axis, which meets the prism's left face
//!   at (−side/3, [`BEAM_Y`], 0) at the incidence of minimum deviation for n_d = 1.5168:
//!   sin θ₁ = n_d · sin 30°, θ₁ = 49.32° (deviation D = 2θ₁ − 60° = 38.65°; the ray
//!   inside runs parallel to the base, along +X). Divergence ≈ (2 + 2) mm / 1 m = 4 mrad
//!   full angle, so the white beam is ≈ 16 mm wide at the screen;
//! - screen: white (0.85) quad 0.8 × 0.7 m standing on the floor, perpendicular to the
//!   587.6 nm exit ray, centre [`SCREEN_DISTANCE`] along it from the exit point. The
//!   486.1–656.3 nm spread there is ≈ 0.71° × 3 m ≈ 37 mm;
//! - room: dark grey floor (0.3), black (0.05) stand, tube and baffle, a dim directional
//!   fill of [`FILL_LUX`] lx; no environment (black);
//! - camera: 0.9 m behind and 0.35 m above the exit point, 0.3 m to the +Z side, looking
//!   along the exit beam towards the screen (yfov 40°, 16:9).
//!
//! The emitter-behind-a-slit (not a spot light with a tiny cone) is deliberate: it is an
//! area light, so a path can reach it and both integrators (and a photon mapper) see the
//! same source, and the beam's width and divergence follow from the slit geometry as in
//! the lab, instead of from a delta light's cone.
//!
//! **`diamond.glb`**: a round brilliant ([`Brilliant`] with table 53 %, crown 34.5°,
//! pavilion 40.75°, Ø 6.5 mm ≈ 1 ct) lying on a pavilion main (table tilted 40.75° towards
//! +Z) 0.1 mm above a dark grey (0.1) floor; material `KHR_materials_ior` 2.42,
//! `KHR_materials_dispersion` 0.36 (Abbe ≈ 55), clear volume; seven 1 × 1 cm emitters of
//! radiance [`GEM_LIGHT_RADIANCE`] 12 cm away, ringed 25° and 40° around the table normal,
//! and a faint uniform environment (`iris_environment: 0.02`); camera 6 cm from the
//! stone's vertex centroid, 30° off the table normal (towards +Y), yfov 10°.

use super::parts::push_material;
use crate::authoring::gem::Brilliant;
use crate::authoring::lathe::sin_cos;
use crate::authoring::scene::placed;
use crate::authoring::shapes::{cuboid, ground_plane, push_flat_facing_away, TriMesh};
use crate::material::MaterialDesc;
use crate::scene::desc::LightDesc;
use crate::scene::desc::{CameraDesc, EnvironmentDesc, SceneDesc};
use glam::{DVec3, Vec3};

/// Side of the prism's equilateral cross-section, metres.
pub const PRISM_SIDE: f64 = 0.1;
/// Height of the beam plane (the prism's mid-height), metres.
pub const BEAM_Y: f64 = 0.351;
/// Refractive index the beam geometry is laid out for: N-BK7 at 587.6 nm (n_d; SCHOTT
/// data sheet N-BK7, 2017).
pub const N_D_BK7: f64 = 1.5168;
/// Distance from the prism's exit point to the screen centre along the exit ray, metres.
pub const SCREEN_DISTANCE: f64 = 3.0;
/// Radiance of the beam's emitter.
pub const BEAM_RADIANCE: f32 = 200_000.0;
/// Illuminance of the dim directional fill, lux.
pub const FILL_LUX: f32 = 0.06;
/// Radiance of each of the diamond's small lights.
pub const GEM_LIGHT_RADIANCE: f32 = 300.0;

/// Pushes the planar convex polygon `pts` (any winding) facing away from `inside`, with
/// its flat normal; fanned from the first vertex.
fn push_facing_away(mesh: &mut TriMesh, pts: Vec<DVec3>, inside: DVec3) {
    let n = (pts[1] - pts[0]).cross(pts[2] - pts[0]).normalize();
    push_flat_facing_away(mesh, pts, n, inside);
}

/// Pushes the rectangle centred at `c` with half axes `u`, `v`, facing `u × v`.
fn push_rect(mesh: &mut TriMesh, c: DVec3, u: DVec3, v: DVec3) {
    let n = u.cross(v).normalize();
    push_facing_away(
        mesh,
        vec![c - u - v, c + u - v, c + u + v, c - u + v],
        c - n,
    );
}

/// The upright prism: equilateral cross-section of side `side` in the XZ plane, apex at
/// +Z, centroid on the Y axis, from y = `y0` to `y0 + height`. Flat normals, outward.
pub fn upright_prism(side: f64, y0: f64, height: f64) -> TriMesh {
    let h = side * 3.0f64.sqrt() / 2.0;
    let corners = [
        (-side / 2.0, -h / 3.0),
        (side / 2.0, -h / 3.0),
        (0.0, 2.0 * h / 3.0),
    ];
    let at = |(x, z): (f64, f64), y: f64| DVec3::new(x, y, z);
    let inside = DVec3::new(0.0, y0 + height / 2.0, 0.0);
    let mut mesh = TriMesh::default();
    for y in [y0, y0 + height] {
        push_facing_away(
            &mut mesh,
            corners.iter().map(|&c| at(c, y)).collect(),
            inside,
        );
    }
    for k in 0..3 {
        let (a, b) = (corners[k], corners[(k + 1) % 3]);
        let quad = vec![at(a, y0), at(b, y0), at(b, y0 + height), at(a, y0 + height)];
        push_facing_away(&mut mesh, quad, inside);
    }
    mesh
}

/// The beam of [`fig5_3_1_prism_beam`] at minimum deviation for [`N_D_BK7`]: the entry
/// and exit points on the prism and the incoming and outgoing unit directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamLayout {
    /// Where the beam axis meets the prism's left face.
    pub entry: DVec3,
    /// Where it leaves the right face.
    pub exit: DVec3,
    /// Incoming direction.
    pub dir_in: DVec3,
    /// Outgoing direction at 587.6 nm.
    pub dir_out: DVec3,
}

impl BeamLayout {
    /// Minimum deviation through a 60° prism: the inside ray is parallel to the base, so
    /// θ₁ = θ₂ with sin θ₁ = n sin(A/2) and the ray turns by D/2 = θ₁ − A/2 at each face
    /// (Born & Wolf, "Principles of Optics", §4.7.2). The inside ray runs along +X through
    /// the centroid.
    pub fn minimum_deviation() -> Self {
        let (sin30, cos30) = (0.5, 3.0f64.sqrt() / 2.0);
        let sin1 = N_D_BK7 * sin30;
        let cos1 = (1.0 - sin1 * sin1).sqrt();
        // Half deviation D/2 = θ₁ − 30°.
        let cos_half = cos1 * cos30 + sin1 * sin30;
        let sin_half = sin1 * cos30 - cos1 * sin30;
        let x = PRISM_SIDE / 3.0;
        BeamLayout {
            entry: DVec3::new(-x, BEAM_Y, 0.0),
            exit: DVec3::new(x, BEAM_Y, 0.0),
            dir_in: DVec3::new(cos_half, 0.0, sin_half),
            dir_out: DVec3::new(cos_half, 0.0, -sin_half),
        }
    }
}

/// Adds a mesh with a new material.
fn mesh(s: &mut SceneDesc, name: &str, geometry: TriMesh, material: MaterialDesc) {
    let material = push_material(s, material);
    mesh_with(s, name, geometry, material);
}

/// Adds a mesh using material index `material`.
fn mesh_with(s: &mut SceneDesc, name: &str, geometry: TriMesh, material: usize) {
    s.meshes.push(placed(name, geometry, material, None));
}

/// Fig. 5.3.1: a narrow white beam through a 60° N-BK7 prism at minimum deviation onto a
/// white screen 3 m away.
pub fn fig5_3_1_prism_beam() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Fig. 5.3.1: white beam through a 60° prism onto a screen".into(),
        ..SceneDesc::default()
    };
    let beam = BeamLayout::minimum_deviation();
    let black = push_material(&mut s, MaterialDesc::diffuse("Black", Vec3::splat(0.05)));
    mesh(
        &mut s,
        "Floor",
        ground_plane(4.0, 4.0).transformed(glam::Mat3::IDENTITY, Vec3::new(1.0, 0.0, -0.5)),
        MaterialDesc::diffuse("Floor", Vec3::splat(0.3)),
    );
    let stand = cuboid(Vec3::new(0.06, 0.15, 0.06))
        .transformed(glam::Mat3::IDENTITY, Vec3::new(0.0, 0.15, 0.0));
    mesh_with(&mut s, "Stand", stand, black);
    let glass = MaterialDesc::named_glass("Prism N-BK7", "N-BK7", N_D_BK7 as f32, 0.1);
    mesh(
        &mut s,
        "Prism",
        upright_prism(PRISM_SIDE, BEAM_Y - 0.05, 0.1),
        glass,
    );

    // Beam frame: w along the beam, u × v = w with v = +Y.
    let w = beam.dir_in;
    let v = DVec3::Y;
    let u = v.cross(w);
    let slit = beam.entry - 0.5 * w;
    let lamp = slit - 1.0 * w;
    let mut emitter = TriMesh::default();
    push_rect(&mut emitter, lamp, 0.001 * u, 0.02 * v);
    let emitter_material = MaterialDesc::emitter("Beam emitter", Vec3::splat(BEAM_RADIANCE));
    mesh(&mut s, "Beam emitter", emitter, emitter_material);
    // Baffle: a 20 × 20 cm plate around a 2 × 40 mm slit (four strips, symmetric about the
    // slit centre), facing the lamp and the prism alike (opaque both ways).
    let (sw, sh, bw) = (0.001, 0.02, 0.1);
    let mut baffle = TriMesh::default();
    for side in [-1.0, 1.0] {
        let mid = (sw + bw) / 2.0;
        push_rect(
            &mut baffle,
            slit + side * mid * u,
            (bw - sw) / 2.0 * u,
            bw * v,
        );
        push_rect(
            &mut baffle,
            slit + side * (sh + bw) / 2.0 * v,
            sw * u,
            (bw - sh) / 2.0 * v,
        );
    }
    mesh_with(&mut s, "Slit baffle", baffle, black);
    // Lamp tube from 1 mm behind the emitter to the baffle: four walls and a back cap.
    let mut tube = TriMesh::default();
    let (tw, th) = (0.02, 0.04);
    let back = lamp - 0.001 * w;
    let mid = (back + slit) / 2.0;
    let half_len = (slit - back).length() / 2.0 * w;
    push_rect(&mut tube, mid + tw * u, half_len, th * v);
    push_rect(&mut tube, mid - tw * u, th * v, half_len);
    push_rect(&mut tube, mid + th * v, tw * u, half_len);
    push_rect(&mut tube, mid - th * v, half_len, tw * u);
    push_rect(&mut tube, back, th * v, tw * u);
    mesh_with(&mut s, "Lamp tube", tube, black);

    // Screen perpendicular to the exit ray, facing back along it, standing on the floor.
    let centre = beam.exit + SCREEN_DISTANCE * beam.dir_out;
    let n = -beam.dir_out;
    let su = v.cross(n);
    let mut screen = TriMesh::default();
    push_rect(
        &mut screen,
        DVec3::new(centre.x, 0.35, centre.z),
        0.4 * su,
        0.35 * v,
    );
    mesh(
        &mut s,
        "Screen",
        screen,
        MaterialDesc::diffuse("Screen", Vec3::splat(0.85)),
    );

    // A punctual fill: the path tracer gives each punctual light its own share of the
    // light samples, while emitters share theirs by power (the beam's would take 99 %).
    s.lights.push(LightDesc::Directional {
        name: "Fill".into(),
        direction: Vec3::new(0.5, -1.0, -0.2),
        color: Vec3::ONE,
        intensity: FILL_LUX,
        spectrum: None,
    });

    let side = DVec3::new(beam.dir_out.z, 0.0, -beam.dir_out.x);
    let eye = beam.exit - 0.9 * beam.dir_out - 0.3 * side + DVec3::new(0.0, 0.35, 0.0);
    let target = beam.exit + 0.6 * beam.dir_out + DVec3::new(0.0, -0.1, 0.0);
    s.cameras.push(look(eye, target, 40.0, 16.0 / 9.0));
    s
}

/// A camera from `eye` to `target` (f64), vertical field `yfov` degrees.
fn look(eye: DVec3, target: DVec3, yfov: f64, aspect: f32) -> CameraDesc {
    super::parts::camera(eye.as_vec3(), target.as_vec3(), yfov, aspect)
}

/// The diamond's cut: Tolkowsky ideal with a 53 % table, Ø 6.5 mm.
pub fn diamond_cut() -> Brilliant {
    Brilliant {
        table: 0.53,
        ..Brilliant::ideal(0.0065)
    }
}

/// A round brilliant diamond (IOR 2.42, dispersion 0.36) on a dark floor under four
/// small lights.
pub fn diamond() -> SceneDesc {
    let mut s = SceneDesc {
        name: "Diamond, round brilliant".into(),
        environment: Some(EnvironmentDesc::Uniform(Vec3::splat(0.02))),
        ..SceneDesc::default()
    };
    mesh(
        &mut s,
        "Floor",
        ground_plane(0.15, 0.15),
        MaterialDesc::diffuse("Floor", Vec3::splat(0.1)),
    );
    let stone = diamond_cut().resting(0.0001);
    let n = stone.positions.len() as f64;
    let centre = stone.positions.iter().map(|p| p.as_dvec3()).sum::<DVec3>() / n;
    let mut material = MaterialDesc::clear_glass("Diamond IOR 2.42", 2.42, 0.004);
    material.dispersion = 0.36;
    mesh(&mut s, "Diamond", stone, material);

    // Table normal after resting: n = (0, cos 40.75°, sin 40.75°); e = the unit vector
    // perpendicular to it in the YZ plane, towards +Y. A well-cut stone returns light that
    // enters the crown near its normal, so the lights ring the table normal: 25° and 40°
    // off it, at azimuths (about n, from e) 90° apart, 12 cm from the stone, facing it;
    // none near azimuth 180°, 30° off, where the table mirrors the camera.
    let (st, ct) = sin_cos(40.75f64.to_radians());
    let n = DVec3::new(0.0, ct, st);
    let e = DVec3::new(0.0, st, -ct);
    let f = n.cross(e);
    let ring = [
        (25.0, 0.0),
        (25.0, 90.0),
        (25.0, 270.0),
        (40.0, 45.0),
        (40.0, 135.0),
        (40.0, 225.0),
        (40.0, 315.0),
    ];
    for (i, (off, azimuth)) in ring.into_iter().enumerate() {
        let (so, co) = sin_cos(f64::to_radians(off));
        let (sa, ca) = sin_cos(f64::to_radians(azimuth));
        let dir = co * n + so * (ca * e + sa * f);
        let at = centre + 0.12 * dir;
        let u = DVec3::Y.cross(dir).normalize();
        let v = dir.cross(u);
        // u × v = dir, so (v, u) faces −dir, towards the stone.
        let mut quad = TriMesh::default();
        push_rect(&mut quad, at, 0.005 * v, 0.005 * u);
        let name = format!("Light {}", i + 1);
        let light = MaterialDesc::emitter(&name, Vec3::splat(GEM_LIGHT_RADIANCE));
        mesh(&mut s, &name, quad, light);
    }

    // The camera sits 30° from the table normal, towards +Y (elevation 49.25° + 30° =
    // 79.25°, towards +Z).
    let eye = centre + 0.06 * (sin_cos(30f64.to_radians()).1 * n + 0.5 * e);
    s.cameras.push(look(eye, centre, 10.0, 1.0));
    s
}
