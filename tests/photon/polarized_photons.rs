//! Polarized photons (issue 34): the hybrid's caustic photons carry Stokes vectors through
//! polarizer sheets and birefringent crystals ([`iris::photon::polarized`]), checked against
//! a closed form and against the polarized path tracer where both converge.
//!
//! - Malus's law in photons: a point light shines through two ideal polarizer sheets at θ
//!   onto a white floor. No camera path can reach a point light through a sheet, so the
//!   floor under the sheets is lit by the caustic map alone; it must receive ½ cos²θ of the
//!   light the bare floor receives by next-event estimation (same scene without sheets).
//!   Tolerance 3 %: the map's estimate over ~10⁴ photons per pixel block is good to ~1 %,
//!   and the sheets are ideal (no Fresnel), so nothing else differs.
//! - A calcite retarder between crossed polarizers under an area light: with its optic axis
//!   at 45° to both sheets the slab splits the light the first sheet polarized into two
//!   modes with D at ±45°, of which the second sheet passes half each — a quarter of what
//!   the slab alone passes; with the axis along the first sheet only one mode is excited
//!   and the second sheet stops it. The polarized hybrid (the floor's light through the
//!   stack is all in its map) and the polarized path tracer (which reaches the area light
//!   through the stack by BSDF sampling) must agree within 4 % on the slab alone and on the
//!   45° stack, each over its own bare floor: at 1024 paths and 256 passes of 5·10⁴
//!   photons their differences measured 0.6–1.4 %, mostly the hybrid's light through the
//!   crystal being sampled at one hero wavelength a pass.
//!
use crate::common;

use common::optics::{build, crystal, emitter, glass, luminance, mean, ortho, settings, sheet};
use common::{mesh, white_lambert};
use glam::{Mat3, Vec3};
use iris::authoring::shapes::{cuboid, ground_plane, icosphere};
use iris::camera::Camera;
use iris::integrator::path::polarized::Polarization;
use iris::integrator::{CausticSettings, Integrator, PhotonSettings};
use iris::material::{CrystalOptics, MaterialDesc};
use iris::scene::desc::{CameraDesc, LightDesc, MeshDesc, SceneDesc};
use iris::scene::Scene;

/// Calcite's principal indices at 589 nm (no dispersion here: the walk-off does not matter).
const CALCITE: [f32; 3] = [1.6584, 1.6584, 1.4864];

/// The polarized hybrid with `photons` a pass, its map's radius chosen from the first pass.
fn hybrid(photons: u64) -> Integrator {
    Integrator::Hybrid {
        max_depth: 32,
        caustics: CausticSettings {
            photons,
            ..PhotonSettings::default().caustics()
        },
        polarization: Some(Polarization { polarizer: None }),
    }
}

/// The mean luminance of `integrator`'s render of `scene` through `cam`, `size`² pixels
/// at `spp` (passes for the hybrid).
fn render(integrator: &Integrator, scene: &Scene, cam: &CameraDesc, size: u32, spp: u32) -> f32 {
    let img = integrator
        .render(scene, &Camera::new(cam, size, size), &settings(size, spp))
        .expect("render")
        .0;
    luminance(mean(&img))
}

/// A horizontal square of half-size `half` at `centre`, material `m`.
fn square(name: &str, half: f32, centre: Vec3, m: usize) -> MeshDesc {
    mesh(
        name,
        ground_plane(half, half).transformed(Mat3::IDENTITY, centre),
        m,
    )
}

/// A unit vector ⊥ the light's central ray (1, −1, 0)/√2 in the Malus scene, at `deg` from
/// +z toward (1, 1, 0)/√2: a sheet's axis as the light crossing it sees it (the sheets
/// pass the axis's part ⊥ the ray, so an axis at an angle to the ray would change θ).
fn across(deg: f32) -> Vec3 {
    let a = deg.to_radians();
    Vec3::Z * a.cos() + Vec3::new(1.0, 1.0, 0.0).normalize() * a.sin()
}

#[test]
fn malus_law_holds_for_photons_through_two_sheets() {
    // The light at (−2, 3, 0) shines through the sheets (at x ≈ −1) onto the floor around
    // x = 1, which the camera sees from straight above.
    let scene = |theta: Option<f32>| {
        let mut meshes = vec![square("floor", 3.0, Vec3::ZERO, 0)];
        if theta.is_some() {
            meshes.push(square("a", 0.25, Vec3::new(-1.0, 2.0, 0.0), 1));
            meshes.push(square("b", 0.25, Vec3::new(-0.9, 1.9, 0.0), 2));
        }
        let t = theta.unwrap_or(0.0);
        build(
            SceneDesc {
                source: "malus photons".into(),
                meshes,
                materials: vec![white_lambert(), sheet(Vec3::Z), sheet(across(t))],
                lights: vec![LightDesc::Point {
                    name: "lamp".into(),
                    position: Vec3::new(-2.0, 3.0, 0.0),
                    color: Vec3::ONE,
                    intensity: 10.0,
                    range: None,
                    spectrum: None,
                }],
                ..Default::default()
            },
            None,
        )
    };
    let cam = ortho(
        Vec3::new(1.0, 5.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::Z,
        0.25,
    );
    let bare = render(&hybrid(40_000), &scene(None), &cam, 16, 24);
    assert!(bare > 0.01, "the bare floor is lit: {bare}");
    for deg in [0.0f32, 30.0, 45.0, 90.0] {
        let through = render(&hybrid(40_000), &scene(Some(deg)), &cam, 16, 24);
        let expect = 0.5 * deg.to_radians().cos().powi(2);
        let ratio = through / bare;
        eprintln!("malus photons {deg}°: {ratio:.4} (½cos²θ = {expect:.4})");
        assert!(
            (ratio - expect).abs() <= 0.03 * expect.max(0.1),
            "{deg}°: the floor under the sheets gets {ratio} of the bare floor, not {expect}"
        );
    }
}

/// Under a 2 × 2 light at y = 3 over a white floor: with `sheets` = `Some(true)` the crossed
/// stack (sheet along x at y = 1.6, a calcite slab from y = 1.15 to 1.45 with its optic axis
/// along `axis`, sheet along z at y = 1.0), `Some(false)` the slab alone, `None` the bare
/// floor.
fn stack(sheets: Option<bool>, axis: Option<Vec3>) -> Scene {
    let mut meshes = vec![
        square("floor", 4.0, Vec3::ZERO, 0),
        square("light", 1.0, Vec3::new(0.0, 3.0, 0.0), 1),
    ];
    if let Some(with_sheets) = sheets {
        let slab = cuboid(Vec3::new(1.5, 0.15, 1.5)).transformed(Mat3::IDENTITY, Vec3::Y * 1.3);
        meshes.push(mesh("slab", slab, 3));
        if with_sheets {
            meshes.push(square("polarizer", 1.5, Vec3::new(0.0, 1.6, 0.0), 2));
            meshes.push(square("analyzer", 1.5, Vec3::new(0.0, 1.0, 0.0), 4));
        }
    }
    let c = crystal(
        "calcite",
        CrystalOptics::Indices(CALCITE),
        axis.unwrap_or(Vec3::X),
    );
    build(
        SceneDesc {
            source: "crossed stack".into(),
            meshes,
            materials: vec![
                white_lambert(),
                emitter(),
                sheet(Vec3::X),
                c,
                sheet(Vec3::Z),
            ],
            ..Default::default()
        },
        None,
    )
}

#[test]
fn a_calcite_retarder_between_crossed_sheets_agrees_with_the_path_tracer() {
    // The camera sees the floor under the stack from low on the side, clear of it.
    let d = Vec3::new(3.0, 1.0, 0.0).normalize();
    let cam = ortho(d * 8.0, Vec3::ZERO, Vec3::Y, 0.2);
    let size = 24;
    let path = Integrator::Path {
        max_depth: 32,
        dispersion: iris::integrator::path::Dispersion::ALL,
        polarization: Some(Polarization { polarizer: None }),
    };
    let (path_spp, passes) = (1024, 256);
    let diagonal = Some(Vec3::new(1.0, 0.0, 1.0).normalize());
    // Each method's light through a configuration over its own bare floor (the hybrid's
    // passes share their wavelengths, so its ratios are taken at the same passes).
    let ratios = |integrator: &Integrator, spp: u32| {
        let bare = render(integrator, &stack(None, None), &cam, size, spp);
        assert!(bare > 0.01, "the bare floor is lit: {bare}");
        let through = |sheets: bool, axis: Option<Vec3>| {
            render(integrator, &stack(Some(sheets), axis), &cam, size, spp) / bare
        };
        [
            through(false, diagonal),
            through(true, diagonal),
            through(true, Some(Vec3::X)),
        ]
    };
    let [p_slab, p45, p0] = ratios(&path, path_spp);
    let [h_slab, h45, h0] = ratios(&hybrid(50_000), passes);
    eprintln!(
        "over the bare floor: slab alone path {p_slab:.4} hybrid {h_slab:.4}; crossed stack \
         with the axis at 45° path {p45:.4} hybrid {h45:.4}, along the polarizer path {p0:.4} \
         hybrid {h0:.4}"
    );
    for (what, p, h) in [("the slab", p_slab, h_slab), ("the 45° stack", p45, h45)] {
        assert!(
            (h / p - 1.0).abs() < 0.04,
            "{what}: hybrid {h} against path {p}"
        );
    }
    // The crossed sheets pass a quarter of what the slab alone passes (the Fresnel
    // transmittances of the two modes differ by ~2 %, oblique rays a little more).
    assert!(
        (0.22..0.26).contains(&(p45 / p_slab)),
        "the 45° stack passes {} of the slab's light, not about ¼",
        p45 / p_slab
    );
    assert!(
        p0 < 0.05 * p45 && h0 < 0.05 * h45,
        "the axis along the polarizer leaves the crossed stack dark: path {p0}, hybrid {h0}"
    );
}

/// Rough black glass (n = 1.5, α = 0.25) lit through a polarizer sheet with its axis `axis` by a
/// 2 × 2 light 60° from the normal on the +x side; the camera looks from 60° on the −x side
/// through its polarizer, so what it sees is the glossy reflection, s-polarized mostly.
fn glossy_through_sheet(axis: Vec3) -> Scene {
    // Black glass: what refracts in is absorbed within a millimetre, so the floor shows its
    // rough surface's reflection alone.
    let rough = iris::material::MaterialDesc {
        roughness: 0.5,
        attenuation_distance: 0.001,
        attenuation_color: Vec3::splat(0.01),
        ..common::optics::glass(1.5)
    };
    let r = Vec3::new(60f32.to_radians().sin(), 60f32.to_radians().cos(), 0.0);
    let facing = Mat3::from_quat(glam::Quat::from_rotation_arc(Vec3::Y, -r));
    let slab = cuboid(Vec3::new(3.0, 0.1, 3.0)).transformed(Mat3::IDENTITY, Vec3::Y * -0.1);
    build(
        SceneDesc {
            source: "glossy through a sheet".into(),
            meshes: vec![
                mesh("floor", slab, 0),
                mesh(
                    "light",
                    ground_plane(1.0, 1.0).transformed(facing, r * 3.0),
                    1,
                ),
                mesh(
                    "sheet",
                    ground_plane(1.2, 1.2).transformed(facing, r * 2.1),
                    2,
                ),
            ],
            materials: vec![rough, emitter(), sheet(axis)],
            ..Default::default()
        },
        None,
    )
}

#[test]
fn polarized_photons_reflect_off_rough_glass_as_camera_paths_see_it() {
    // The caustic map's gather at a polarizing surface (Mueller matrices at the microfacet
    // normal, the photon's Stokes vector in its own basis) against the polarized path
    // tracer, which finds the light through the sheet by sampling the glossy lobe. The
    // sheet passes s (along z) or p (in the plane of incidence, ⊥ the light's central
    // ray); the camera looks through nothing, or a polarizer along s or p (its image
    // horizontal is z). Each pair must agree within 5 % (their noise here is ~1 %).
    let cam_dir = Vec3::new(60f32.to_radians().sin(), -60f32.to_radians().cos(), 0.0);
    let cam = ortho(-cam_dir * 6.0, Vec3::ZERO, Vec3::Y, 0.3);
    assert!(Camera::new(&cam, 8, 8).basis().0.z.abs() > 0.999);
    let p_axis = Vec3::new(60f32.to_radians().cos(), -60f32.to_radians().sin(), 0.0);
    let size = 16;
    let mut seen = Vec::new();
    for (sheet_name, axis) in [("s", Vec3::Z), ("p", p_axis)] {
        let scene = glossy_through_sheet(axis);
        for camera in [None, Some(0.0f32), Some(90.0)] {
            let polarization = Polarization {
                polarizer: camera.map(f32::to_radians),
            };
            let path = Integrator::Path {
                max_depth: 8,
                dispersion: iris::integrator::path::Dispersion::ALL,
                polarization: Some(polarization),
            };
            let hybrid = Integrator::Hybrid {
                max_depth: 8,
                caustics: CausticSettings {
                    photons: 50_000,
                    ..PhotonSettings::default().caustics()
                },
                polarization: Some(polarization),
            };
            let p = render(&path, &scene, &cam, size, 512);
            let h = render(&hybrid, &scene, &cam, size, 128);
            eprintln!("sheet {sheet_name}, camera {camera:?}: path {p:.5} hybrid {h:.5}");
            seen.push((sheet_name, camera, p, h));
        }
    }
    let most = seen.iter().map(|s| s.2).fold(0.0, f32::max);
    assert!(most > 1e-3, "the reflection is seen: {seen:?}");
    for (sheet_name, camera, p, h) in &seen {
        assert!(
            (h - p).abs() < 0.05 * p.max(0.05 * most),
            "sheet {sheet_name}, camera {camera:?}: hybrid {h} against path {p}"
        );
    }
}

#[test]
fn the_polarized_hybrid_is_the_same_on_one_thread_or_two() {
    // Fixed photon chunks and per-photon streams: the map, and so the image, is a function
    // of the seed alone (the crystal and the sheets exercise every polarized branch).
    let scene = stack(Some(true), Some(Vec3::new(1.0, 0.0, 1.0).normalize()));
    let d = Vec3::new(3.0, 1.0, 0.0).normalize();
    let cam = Camera::new(&ortho(d * 8.0, Vec3::ZERO, Vec3::Y, 0.2), 12, 12);
    let image = |threads: usize| {
        let s = iris::render::RenderSettings {
            threads,
            ..settings(12, 6)
        };
        hybrid(20_000).render(&scene, &cam, &s).expect("render").0
    };
    let (one, two) = (image(1), image(2));
    assert!(mean(&one).length() > 0.0, "the floor is lit");
    assert!(one.data == two.data, "one thread and two differ");
}

/// Issue 48 item 4: a light inside a crystal, under the polarized hybrid. No camera path
/// reaches a light inside a crystal, so the floor's light through it is all the caustic
/// map's, traced by photons that start inside the crystal in no mode.
///
/// - A point light at the centre of a ball (radius 0.5, centre 1 above a white floor); the
///   camera sees the floor from above, 20 × 20 round the ball (light down to 84° from the
///   vertical). Every ray leaves the lossless ball nearly along a radius (what the wall
///   reflects crosses the centre and leaves on the other side), so the floor gets the
///   light the bare floor gets (no ball, next-event estimation). For an isotropic
///   "crystal" (three equal indices, one mode) the icosphere's facets turn rays by about
///   a degree. In calcite with its optic axis vertical the extraordinary light leaves
///   bent toward the axis (the walk-off), but the set-up is symmetric under y ↦ −y, so as
///   much turns down as up, and near the horizontal, where rays miss the window, the
///   walk-off vanishes.
/// - An area light (a small emissive square) in the ball, the floor seen to one side:
///   a crystal of three equal indices is glass of that index for every photon (a glass
///   with a trace of dispersion, whose photons keep their hero wavelength alone from the
///   ball on, as the crystal's do, so both maps see the same wavelength each pass).
///
/// Tolerance 3 %: at 64 passes of 5000 photons the map's mean over the window is good to
/// about 1 %, but the crystal's photons carry one hero wavelength a pass, whose
/// luminance weight varies from pass to pass (about 1 % over 64 passes).
#[test]
fn a_light_inside_a_crystal_lights_the_floor_through_it() {
    let centre = Vec3::new(0.0, 1.0, 0.0);
    let lamp = LightDesc::Point {
        name: "lamp".into(),
        position: centre,
        color: Vec3::ONE,
        intensity: 10.0,
        range: None,
        spectrum: None,
    };
    let scene = |ball: Option<&MaterialDesc>, area: bool| {
        let mut meshes = vec![square("floor", 10.0, Vec3::ZERO, 0)];
        let bright = MaterialDesc {
            emissive: Vec3::splat(1000.0),
            ..emitter()
        };
        let mut materials = vec![white_lambert(), bright];
        if area {
            meshes.push(square("bulb", 0.1, centre, 1));
        }
        if let Some(m) = ball {
            let shell = icosphere(0.5, 4).transformed(Mat3::IDENTITY, centre);
            meshes.push(mesh("ball", shell, 2));
            materials.push(m.clone());
        }
        let lights = if area { Vec::new() } else { vec![lamp.clone()] };
        build(
            SceneDesc {
                source: "light in a crystal".into(),
                meshes,
                materials,
                lights,
                ..Default::default()
            },
            None,
        )
    };
    let floor = |scene: &Scene, cam: &CameraDesc| render(&hybrid(5_000), scene, cam, 32, 64);
    let iso = crystal("one index", CrystalOptics::Indices([1.6; 3]), Vec3::Y);
    let calcite = crystal("calcite", CrystalOptics::Indices(CALCITE), Vec3::Y);
    let check = |what: &str, ratio: f32| {
        eprintln!("{what}: {ratio:.4}");
        assert!((ratio - 1.0).abs() <= 0.03, "{what}: {ratio}");
    };
    let above = ortho(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO, Vec3::Z, 10.0);
    let bare = floor(&scene(None, false), &above);
    assert!(bare > 0.01, "the bare floor is lit: {bare}");
    for m in [&iso, &calcite] {
        let lit = floor(&scene(Some(m), false), &above);
        check(
            &format!("point light in {} over the bare floor", m.name),
            lit / bare,
        );
    }
    let side = ortho(
        Vec3::new(3.0, 5.0, 0.0),
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::Z,
        2.0,
    );
    // A trace of dispersion makes the glass's photons carry their hero wavelength alone,
    // as the crystal's do, so the two maps share each pass's wavelength.
    let hero_glass = MaterialDesc {
        dispersion: 0.001,
        ..glass(1.6)
    };
    let in_glass = floor(&scene(Some(&hero_glass), true), &side);
    assert!(
        in_glass > 0.01,
        "the floor is lit through glass: {in_glass}"
    );
    let in_iso = floor(&scene(Some(&iso), true), &side);
    check("area light in one index over glass", in_iso / in_glass);
}
