//! Authored scenes stay as authored (issue 18, item 4): a file that brings its own light
//! gets no drop-in floor from `--ground auto` and no default studio; flags that ask
//! explicitly (`--ground on`, `--studio NAME`) still apply, and the notes say why nothing
//! was added.
//!
//! The scene is the peers' prism-and-slit view (`../shared/peers/make_scenes.py`,
//! `dispersion_view`), written here with the model library: an equilateral prism (IOR 1.6,
//! KHR dispersion 1) seen from its exit side, looking at a thin emissive slit 2 m before
//! its entry face at minimum deviation, with the file's own camera and nothing else. `--ground auto`
//! must not put a white floor under the prism (transmissive, nothing under it), lit by
//! the slit.

use crate::common;

use glam::{Mat3, Vec2, Vec3};
use iris::accel::Backend;
use iris::app::{PreviewOptions, RenderOptions};
use iris::authoring::shapes::{self, TriMesh};
use iris::authoring::{look_at, placed};
use iris::material::MaterialDesc;
use iris::prepare::{prepare, Authored, Note, Prepared};
use iris::scene::desc::SceneDesc;
use iris::studio::ground::{Floor, GROUND_MESH};
use iris::studio::{GroundMode, Studio};
use std::path::{Path, PathBuf};

/// Writes the prism-and-slit view (`make_scenes.py`'s `dispersion_view`, same numbers).
fn prism_and_slit(dir: &Path) -> PathBuf {
    let (ior, side) = (1.6f32, 0.5f32);
    let r3 = 3f32.sqrt();
    // Plan view (x, z): apex towards +z, centroid at the origin; 0.6 m tall from y = 0.
    let (apex, left, right) = (
        Vec2::new(0.0, side / r3),
        Vec2::new(-side / 2.0, -side / (2.0 * r3)),
        Vec2::new(side / 2.0, -side / (2.0 * r3)),
    );
    // `shapes::prism` runs along z with its apex at +y: a quarter turn about x stands it
    // up with the apex at +z.
    let prism = shapes::prism(side, 0.6).transformed(
        Mat3::from_rotation_x(std::f32::consts::FRAC_PI_2),
        Vec3::new(0.0, 0.3, 0.0),
    );
    // Minimum deviation for n = 1.6 through the 60° apex.
    let a = 60f32.to_radians();
    let th1 = (ior * (a / 2.0).sin()).asin();
    let dev = 2.0 * th1 - a;
    let ang_in = -std::f32::consts::FRAC_PI_6 + th1;
    let d_in = Vec3::new(ang_in.cos(), 0.0, ang_in.sin());
    let at = |p: Vec2| Vec3::new(p.x, 0.3, p.y);
    let entry = at((apex + left) / 2.0);
    // The slit: 12 × 300 mm, 2 m before the entry point, facing the prism.
    let centre = entry - 2.0 * d_in;
    let across = d_in.cross(Vec3::Y).normalize();
    let (w, h) = (0.012, 0.3);
    let mut corner = centre - 0.5 * w * across - Vec3::new(0.0, h / 2.0, 0.0);
    let (mut u, v) = (w * across, Vec3::new(0.0, h, 0.0));
    if u.cross(v).dot(d_in) < 0.0 {
        corner += u;
        u = -u;
    }
    let n = u.cross(v).normalize();
    let slit = TriMesh {
        positions: vec![corner, corner + u, corner + u + v, corner + v],
        normals: vec![n; 4],
        indices: vec![[0, 1, 2], [0, 2, 3]],
    };
    let ang_out = ang_in - dev;
    let d_out = Vec3::new(ang_out.cos(), 0.0, ang_out.sin());
    let exit = at((apex + right) / 2.0);
    let glass = MaterialDesc {
        dispersion: 1.0,
        ..MaterialDesc::clear_glass("DispersiveGlass", ior, 0.5)
    };
    let scene = SceneDesc {
        name: "prism and slit".into(),
        meshes: vec![
            placed("Prism", prism, 0, None),
            placed("Slit", slit, 1, None),
        ],
        materials: vec![glass, MaterialDesc::emitter("Slit", Vec3::splat(4.0))],
        cameras: vec![look_at(
            "view",
            exit + 1.2 * d_out,
            exit,
            Vec3::Y,
            24f32.to_radians(),
            None,
        )],
        ..Default::default()
    };
    let path = dir.join("prism_slit.glb");
    iris::authoring::write_glb(&path, &scene).expect("write the prism-and-slit scene");
    path
}

fn prepared(path: &Path, preview: PreviewOptions) -> Prepared {
    let opts = RenderOptions {
        size: Some((48, 36)),
        accel: Backend::Bvh,
        preview,
        ..RenderOptions::new(path, None)
    };
    prepare(path, &opts.prepare_options(None)).expect("prepare")
}

fn has_floor(p: &Prepared) -> bool {
    p.scene.meshes().iter().any(|m| m.name == GROUND_MESH)
}

fn ground(mode: GroundMode) -> PreviewOptions {
    PreviewOptions {
        ground: mode,
        ..Default::default()
    }
}

#[test]
fn a_lit_file_gets_no_floor_and_auto_picks_the_same_method() {
    let dir = common::scratch_dir("authored_prism");
    let path = prism_and_slit(&dir);
    let auto = prepared(&path, ground(GroundMode::Auto));
    let off = prepared(&path, ground(GroundMode::Off));
    let on = prepared(&path, ground(GroundMode::On));
    assert!(!has_floor(&auto), "{:?}", auto.notes());
    assert!(!has_floor(&off));
    assert!(has_floor(&on), "--ground on still adds the floor");
    assert_eq!(auto.scene.triangle_count(), off.scene.triangle_count());
    // The note says why: the file's own light (the slit emits), no studio, no floor.
    let evidence = Authored {
        punctual: 0,
        emissive: true,
        environment: false,
    };
    assert_eq!(
        auto.notes(),
        [Note::Authored {
            evidence,
            no_floor: true,
            no_studio: true
        }]
    );
    assert_eq!(
        off.notes(),
        [
            Note::Floor(Floor::Off),
            Note::Authored {
                evidence,
                no_floor: false,
                no_studio: true
            }
        ]
    );
    // The file's own camera: no framing note, the same camera either way.
    assert_eq!(auto.camera.world_from_camera, off.camera.world_from_camera);
    // `--method auto` decides on the scene as authored: the same as with no floor.
    let method = |p: &Prepared| {
        iris::plan::resolve_method(iris::integrator::Method::Auto, &p.scene, &common::PINHOLE)
    };
    let (m_auto, why_auto) = method(&auto);
    let (m_off, why_off) = method(&off);
    let (m_on, why_on) = method(&on);
    eprintln!("auto: {m_auto:?} {why_auto:?}\noff: {m_off:?} {why_off:?}\non: {m_on:?} {why_on:?}");
    assert_eq!(m_auto, m_off, "{why_auto:?} vs {why_off:?}");
    assert_eq!(why_auto, why_off);
    // No light was added: the slit is the only light.
    assert_eq!(auto.scene.lights().len(), off.scene.lights().len());
    assert!(auto.scene.environment().is_none());
    assert!(!auto.scene.default_lights());
}

#[test]
fn an_explicit_studio_lights_a_lit_file_too() {
    let dir = common::scratch_dir("authored_studio");
    let path = prism_and_slit(&dir);
    let plain = prepared(&path, ground(GroundMode::Off));
    let lit = prepared(
        &path,
        PreviewOptions {
            studio: Some(Studio::Jeweller),
            ground: GroundMode::Off,
            ..Default::default()
        },
    );
    assert_eq!(
        lit.notes(),
        [
            Note::StudioAdded {
                preset: Studio::Jeweller,
                keys: 2
            },
            Note::Floor(Floor::Off),
        ]
    );
    // The jeweller's two spot keys join the file's lights; its environment is added.
    assert_eq!(lit.scene.lights().len(), plain.scene.lights().len() + 2);
    assert!(lit.scene.environment().is_some());
    // `--studio none` asks for no studio: nothing changes, and the note still explains.
    let none = prepared(
        &path,
        PreviewOptions {
            studio: Some(Studio::None),
            ..Default::default()
        },
    );
    assert!(!has_floor(&none));
    assert_eq!(none.scene.lights().len(), plain.scene.lights().len());
    assert!(
        none.notes().iter().any(|n| matches!(
            n,
            Note::Authored {
                no_floor: true,
                no_studio: false,
                ..
            }
        )),
        "{:?}",
        none.notes()
    );
}

#[test]
fn the_command_line_and_info_print_the_authored_note() {
    let dir = common::scratch_dir("authored_cli");
    let path = prism_and_slit(&dir);
    let scene = path.to_str().unwrap();
    let want = "the file brings its own light (emissive surfaces): rendered as authored, no \
                studio or floor added (--studio NAME, --ground on to add)";
    let r = common::iris(
        &[
            "render", scene, "--method", "path", "--spp", "1", "--size", "16x12", "-q", "-o",
            "x.png",
        ],
        &dir,
    );
    let err = common::stderr(&r);
    assert!(r.status.success(), "{err}");
    assert!(err.contains(&format!("note: {want}")), "{err}");
    assert!(!err.contains("white floor"), "{err}");
    let info = common::iris(&["info", scene], &dir);
    let text = String::from_utf8_lossy(&info.stdout).into_owned();
    assert!(info.status.success(), "{}", common::stderr(&info));
    assert!(text.contains(&format!("note: {want}")), "{text}");
}
