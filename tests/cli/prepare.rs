//! One scene preparation (issue 16): `iris render`, `iris converge` and `iris info` describe
//! and render the same scene for the same file and flags. Before, `iris converge` on a file
//! with no light rendered the plain key and fill with no floor, while `iris render` showed
//! the studio and a floor: three commands prepared the scene three ways. The preparation's
//! decisions are data ([`Note`]): each `--env`/`--studio`/`--ground`/`--background`/`--view`
//! variation is checked to decide what it says, in the library and on the command line.

use crate::common;

use glam::Vec3;
use iris::accel::Backend;
use iris::app::converge::ConvergeOptions;
use iris::app::{PreviewOptions, RenderOptions};
use iris::framing::View;
use iris::integrator::Method;
use iris::light::env::Environment;
use iris::output::Background;
use iris::prepare::camera_choice::AutoCamera;
use iris::prepare::{prepare, Note, Prepared};
use iris::scene::Scene;
use iris::studio::ground::Floor;
use iris::studio::{GroundMode, Studio};
use std::path::{Path, PathBuf};

/// A round diamond with no camera, light or floor: every drop-in decision is taken.
fn bare() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gems/round_diamond_bare.glb")
}

/// Lines starting with `note: ` on stderr.
fn notes(stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .filter_map(|l| l.strip_prefix("note: ").map(String::from))
        .collect()
}

/// What a command renders, in comparable form: lights, triangles, bounds, the environment
/// (its radiance in the six axis directions) and the camera.
#[derive(Debug, PartialEq)]
struct Seen {
    lights: Vec<iris::light::PunctualLight>,
    default_lights: bool,
    triangles: usize,
    positions: Vec<Vec3>,
    bounds: (Vec3, Vec3),
    subject_bounds: (Vec3, Vec3),
    environment: Option<Vec<Vec3>>,
    camera: glam::Mat4,
}

fn seen(scene: &Scene, camera: &iris::scene::desc::CameraDesc) -> Seen {
    let dirs = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    Seen {
        lights: scene.lights().to_vec(),
        default_lights: scene.default_lights(),
        triangles: scene.triangle_count(),
        positions: scene.positions().to_vec(),
        bounds: scene.bounds(),
        subject_bounds: scene.subject_bounds(),
        environment: scene
            .environment()
            .as_ref()
            .map(|e| dirs.iter().map(|&d| e.eval(d)).collect()),
        camera: camera.world_from_camera,
    }
}

fn seen_prepared(p: &Prepared) -> Seen {
    seen(&p.scene, &p.camera)
}

#[test]
fn render_and_converge_options_prepare_the_same_scene() {
    let path = bare();
    let dir = common::scratch_dir("prepare_lib");
    let render = RenderOptions {
        size: Some((48, 27)),
        accel: Backend::Bvh,
        ..RenderOptions::new(&path, Some(&dir.join("r.png")))
    };
    let converge = ConvergeOptions {
        scene: path.clone(),
        methods: vec![Method::Path],
        time: std::time::Duration::from_secs(1),
        reference: None,
        out_dir: dir.join("c"),
        size: Some((48, 27)),
        seed: 0,
        sampler: Default::default(),
        threads: 0,
        accel: Backend::Bvh,
        quiet: true,
        looks: Vec::new(),
    };
    let a = prepare(&path, &render.prepare_options(None)).expect("render's preparation");
    let b = prepare(&path, &converge.prepare_options(None)).expect("converge's preparation");
    assert_eq!(a.notes(), b.notes());
    assert_eq!(seen_prepared(&a), seen_prepared(&b), "render and converge");
    // `iris info` plans the default preparation (at its probe size; same aspect here).
    let (scene, camera) =
        iris::app::default_preview_scene(&path, Backend::Bvh, (48, 27)).expect("info's");
    assert_eq!(seen(&scene, &camera), seen_prepared(&a), "render and info");
    assert_eq!(a.size, b.size);
    assert_eq!(a.scene.triangle_count(), b.scene.triangle_count());
    assert_eq!(a.scene.lights().len(), b.scene.lights().len());
    assert_eq!(
        a.scene.environment().is_some(),
        b.scene.environment().is_some()
    );
    assert_eq!(
        a.camera.world_from_camera, b.camera.world_from_camera,
        "same framing"
    );
    // And it is the drop-in preview: the studio (jeweller, the default for a gem) lights the stone and a floor is added.
    let n = a
        .notes()
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("\n");
    assert!(n.contains("studio `jeweller`"), "{n}");
    assert!(n.contains("white floor added"), "{n}");
    assert_eq!(
        a.notes(),
        [
            Note::Studio {
                preset: Studio::Jeweller,
                keys: 2
            },
            Note::Floor(Floor::UnderGlass),
            Note::Camera(AutoCamera::NoCamera),
        ]
    );
    assert!(
        a.scene.environment().is_some(),
        "the studio's softbox environment"
    );
    // The same preparation twice is the same scene (nothing depends on call order).
    let c = prepare(&path, &converge.prepare_options(None)).expect("again");
    assert_eq!(c.notes(), b.notes());
    assert_eq!(c.scene.positions(), b.scene.positions());
}

#[test]
fn cli_converge_notes_the_preparation_render_notes() {
    let dir = common::scratch_dir("prepare_cli");
    let scene = bare();
    let scene = scene.to_str().unwrap();
    let r = common::iris(
        &[
            "render", scene, "--method", "path", "--spp", "1", "--size", "32x18", "-q", "-o",
            "r.png",
        ],
        &dir,
    );
    let r_err = common::stderr(&r);
    assert!(r.status.success(), "{r_err}");
    let c = common::iris(
        &[
            "converge",
            scene,
            "--methods",
            "path",
            "--time",
            "0.1",
            "--size",
            "32x18",
            "-q",
            "-o",
            "out",
        ],
        &dir,
    );
    let c_err = common::stderr(&c);
    assert!(c.status.success(), "{c_err}");
    let (rn, cn) = (notes(&r_err), notes(&c_err));
    // Lights, floor and camera: three preparation notes, each also in render's.
    assert_eq!(cn.len(), 3, "{cn:?}");
    for n in &cn {
        assert!(rn.contains(n), "converge: {n:?}\nrender: {rn:?}");
    }
    assert!(cn.iter().any(|n| n.contains("studio")), "{cn:?}");
    assert!(cn.iter().any(|n| n.contains("floor added")), "{cn:?}");
    // `iris info` prints the same preparation notes.
    let info = common::iris(&["info", scene], &dir);
    assert!(info.status.success(), "{}", common::stderr(&info));
    let info_text = String::from_utf8_lossy(&info.stdout).into_owned();
    assert_eq!(notes(&info_text), cn, "{info_text}");
}

/// A flag variation: the command-line flags and the library options they stand for.
struct Variation {
    flags: &'static [&'static str],
    env: Option<Option<Environment>>,
    preview: PreviewOptions,
}

fn variations() -> Vec<Variation> {
    let p = PreviewOptions::default;
    vec![
        Variation {
            flags: &[],
            env: None,
            preview: p(),
        },
        Variation {
            flags: &["--studio", "jeweller"],
            env: None,
            preview: PreviewOptions {
                studio: Some(Studio::Jeweller),
                ..p()
            },
        },
        Variation {
            flags: &["--studio", "none"],
            env: None,
            preview: PreviewOptions {
                studio: Some(Studio::None),
                ..p()
            },
        },
        Variation {
            flags: &["--env", "0.5"],
            env: Some(Some(Environment::Uniform {
                radiance: Vec3::splat(0.5),
            })),
            preview: p(),
        },
        Variation {
            flags: &["--env", "none"],
            env: Some(None),
            preview: p(),
        },
        Variation {
            flags: &["--ground", "on"],
            env: None,
            preview: PreviewOptions {
                ground: GroundMode::On,
                ..p()
            },
        },
        Variation {
            flags: &["--ground", "off", "--studio", "bright"],
            env: None,
            preview: PreviewOptions {
                ground: GroundMode::Off,
                studio: Some(Studio::Bright),
                ..p()
            },
        },
        Variation {
            flags: &["--background", "transparent", "--view", "top"],
            env: None,
            preview: PreviewOptions {
                background: Background::Transparent,
                view: Some(View::Top),
                ..p()
            },
        },
    ]
}

#[test]
fn each_variation_prepares_what_it_says_in_the_library_and_on_the_command_line() {
    let path = bare();
    let dir = common::scratch_dir("prepare_variations");
    let studio = |preset, keys| Note::Studio { preset, keys };
    let no_camera = Note::Camera(AutoCamera::NoCamera);
    let expected = [
        vec![
            studio(Studio::Jeweller, 2),
            Note::Floor(Floor::UnderGlass),
            no_camera,
        ],
        vec![
            studio(Studio::Jeweller, 2),
            Note::Floor(Floor::UnderGlass),
            no_camera,
        ],
        vec![Note::KeyFill, Note::Floor(Floor::UnderGlass), no_camera],
        vec![Note::Floor(Floor::UnderGlass), no_camera],
        vec![Note::KeyFill, Note::Floor(Floor::UnderGlass), no_camera],
        vec![
            studio(Studio::Jeweller, 2),
            Note::Floor(Floor::On),
            no_camera,
        ],
        vec![
            studio(Studio::Bright, 1),
            Note::Floor(Floor::Off),
            no_camera,
        ],
        vec![
            studio(Studio::Jeweller, 2),
            Note::Floor(Floor::CoversBackground),
            Note::Camera(AutoCamera::View {
                view: View::Top,
                over_file_camera: false,
            }),
        ],
    ];
    let mut floorless: Option<Seen> = None;
    for (v, want) in variations().iter().zip(expected) {
        let render = RenderOptions {
            size: Some((32, 18)),
            accel: Backend::Bvh,
            env: v.env.clone(),
            ..RenderOptions::new(&path, None)
        };
        let render = RenderOptions {
            preview: v.preview,
            ..render
        };
        let p = prepare(&path, &render.prepare_options(None)).expect("prepare");
        assert_eq!(p.notes(), want, "{:?}", v.flags);
        let s = seen_prepared(&p);
        // The lights say the same as the notes: the key and fill, a studio's keys, or only
        // the environment.
        let keys = want.iter().find_map(|n| match n {
            Note::Studio { keys, .. } => Some(*keys),
            _ => None,
        });
        let key_fill = want.contains(&Note::KeyFill);
        assert_eq!(s.default_lights, key_fill, "{:?}", v.flags);
        let n_lights = keys.unwrap_or(if key_fill { 2 } else { 0 });
        assert_eq!(s.lights.len(), n_lights, "{:?}", v.flags);
        assert_eq!(s.environment.is_some(), !key_fill, "{:?}", v.flags);
        // A floor adds two triangles; the subject bounds stay the stone's either way.
        let floor = want.contains(&Note::Floor(Floor::On))
            || want.contains(&Note::Floor(Floor::UnderGlass));
        let stone = floorless.get_or_insert_with(|| {
            let v = prepare(
                &path,
                &RenderOptions {
                    preview: PreviewOptions {
                        ground: GroundMode::Off,
                        ..PreviewOptions::default()
                    },
                    ..render.clone()
                }
                .prepare_options(None),
            )
            .expect("floorless");
            seen_prepared(&v)
        });
        let floor_triangles = if floor { 2 } else { 0 };
        assert_eq!(
            s.triangles,
            stone.triangles + floor_triangles,
            "{:?}",
            v.flags
        );
        assert_eq!(s.subject_bounds, stone.bounds, "{:?}", v.flags);
        if v.preview.view.is_none() {
            // Framing never fits the floor: the same camera with or without it.
            assert_eq!(s.camera, stone.camera, "{:?}", v.flags);
        }
        // `iris render` with these flags prints these notes, in this order (among the
        // render's own: method, spectral transport).
        let mut args = vec![
            "render",
            path.to_str().unwrap(),
            "--method",
            "whitted",
            "--spp",
            "1",
            "--size",
            "32x18",
            "--accel",
            "bvh",
            "-q",
            "-o",
            "v.exr",
        ];
        args.extend(v.flags);
        let r = common::iris(&args, &dir);
        let err = common::stderr(&r);
        assert!(r.status.success(), "{:?}: {err}", v.flags);
        let printed = notes(&err);
        let want_text: Vec<String> = want.iter().map(ToString::to_string).collect();
        let in_order: Vec<&String> = printed.iter().filter(|n| want_text.contains(n)).collect();
        assert_eq!(
            in_order,
            want_text.iter().collect::<Vec<_>>(),
            "{:?}: {printed:?}",
            v.flags
        );
    }
}

#[test]
fn info_plans_the_scene_render_plans() {
    // `iris info` plans `iris render FILE --method auto` at the probe size with the
    // default budget (an error target, so adaptive sampling is on): the stage lines
    // (without the measured costs, which are timings) are the same.
    let dir = common::scratch_dir("prepare_info");
    let scene = bare();
    let scene = scene.to_str().unwrap();
    let plan_lines = |text: &str| -> Vec<String> {
        text.lines()
            .skip_while(|l| !l.starts_with("render plan:"))
            .take_while(|l| l.starts_with("render plan:") || l.starts_with("  "))
            // Costs are timings; info's last line says which method the plan is for.
            .filter(|l| !l.trim_start().starts_with("cost:") && !l.starts_with("  ("))
            .map(String::from)
            .collect()
    };
    let info = common::iris(&["info", scene], &dir);
    assert!(info.status.success(), "{}", common::stderr(&info));
    let info_text = String::from_utf8_lossy(&info.stdout).into_owned();
    let r = common::iris(
        &[
            "render",
            scene,
            "--explain",
            "--method",
            "auto",
            "--size",
            "32x24",
            // A PNG's default target (a display error), as `iris info` plans for.
            "--target-error",
            "0.01",
            "--time",
            "0.1",
            "-q",
            "-o",
            "x.png",
        ],
        &dir,
    );
    let r_err = common::stderr(&r);
    assert!(r.status.success(), "{r_err}");
    let (a, b) = (plan_lines(&info_text), plan_lines(&r_err));
    assert!(a.len() >= 8, "{info_text}");
    assert_eq!(a, b, "info:\n{info_text}\nrender:\n{r_err}");
}

/// A description loaded once renders as its file does (`RenderJob::with_loaded`, the
/// Python module's `Scene`), with flags that act at preparation (`--stone`, the camera);
/// and a render cancelled through its hooks (`RunHooks::cancel`, Ctrl-C in the module)
/// ends at once, interrupted, instead of running to its time limit.
#[test]
fn a_loaded_description_renders_as_its_file_and_a_cancelled_render_stops() {
    use iris::app::{RenderJob, RunHooks};
    let ruby = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/ruby.glb");
    let desc = iris::load::load_scene(&ruby).unwrap();
    let hooks = |cancel| RunHooks {
        write_image: false,
        progress: None,
        cancel,
    };
    for flags in [
        &[][..],
        &["--stone=sapphire", "--camera-look-at=0.3,0.2,0.3:0,0,0:30"],
    ] {
        let mut args: Vec<String> = ["--size=24x16", "--spp=2", "--method=path", "--quiet"]
            .iter()
            .chain(flags)
            .map(|s| s.to_string())
            .collect();
        args.push(ruby.display().to_string());
        let opts = iris::cli::parse_render(&args).unwrap();
        let file = RenderJob::new(&opts)
            .unwrap()
            .run_with(hooks(Default::default()));
        let loaded = RenderJob::with_loaded(&opts, desc.clone(), Default::default())
            .unwrap()
            .run_with(hooks(Default::default()));
        assert_eq!(
            file.unwrap().image.data,
            loaded.unwrap().image.data,
            "{flags:?}"
        );
    }
    let args = [
        "--size=64x40",
        "--time=60",
        "--quiet",
        &ruby.display().to_string(),
    ]
    .map(String::from);
    let opts = iris::cli::parse_render(&args).unwrap();
    let cancel = iris::render::guard::Cancel::new();
    cancel.cancel();
    let start = std::time::Instant::now();
    let s = RenderJob::with_loaded(&opts, desc, Default::default())
        .unwrap()
        .run_with(hooks(cancel))
        .unwrap();
    assert!(s.stats.interrupted() && start.elapsed().as_secs() < 30);
    assert!(iris::cli::render_flags()
        .iter()
        .any(|f| f == "camera-look-at"));
}
