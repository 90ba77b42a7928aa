//! Turntables (issue 19, item 3): `iris turntable SCENE --frames N -o DIR`.
//!
//! Scenes are written here with the model library: an L-shaped opaque model (no
//! symmetry about the vertical axis), a cube and a hexagonal prism centred on it, lit by
//! two directional lights of the file (one straight down, one from the camera's side and
//! above), with the file's own camera and `--ground on` (a floor that must not turn). Every
//! render is tiny and bounded by counts (Whitted, 2 spp, `--denoise off`, 48×36).

use crate::common;

use common::{entries, iris, stderr};
use glam::{DVec2, Vec3};
use iris::authoring::lathe::{Lathe, ProfilePoint};
use iris::authoring::shapes::{cuboid, TriMesh};
use iris::authoring::{look_at, placed};
use iris::image::ImageRgb;
use iris::material::MaterialDesc;
use iris::scene::desc::{LightDesc, MeshDesc, SceneDesc};
use std::path::{Path, PathBuf};

const SIZE: &str = "48x36";

/// The flags of every render here (with `--ground on`: the floor must stay put).
const FLAGS: [&str; 10] = [
    "--size",
    SIZE,
    "--method",
    "whitted",
    "--spp",
    "2",
    "--denoise",
    "off",
    "--ground",
    "on",
];

fn part(name: &str, geometry: TriMesh, material: usize, at: Vec3) -> MeshDesc {
    placed(name, geometry, material, Some(at))
}

/// Writes `dir/<name>.glb`: `meshes` standing on y = 0 under the two lights, seen by the
/// file's camera (or none).
fn write_scene(dir: &Path, name: &str, meshes: Vec<MeshDesc>, camera: bool) -> PathBuf {
    let scene = SceneDesc {
        name: name.into(),
        meshes,
        materials: vec![
            MaterialDesc::diffuse("Red", Vec3::new(0.8, 0.1, 0.1)),
            MaterialDesc::diffuse("Green", Vec3::new(0.1, 0.7, 0.2)),
        ],
        lights: vec![
            LightDesc::Directional {
                name: "Down".into(),
                direction: Vec3::NEG_Y,
                color: Vec3::ONE,
                intensity: 3.0,
                spectrum: None,
            },
            LightDesc::Directional {
                name: "Front".into(),
                direction: Vec3::new(0.0, -1.0, -1.0),
                color: Vec3::ONE,
                intensity: 2.0,
                spectrum: None,
            },
        ],
        cameras: camera
            .then(|| {
                look_at(
                    "Cam",
                    Vec3::new(0.0, 1.6, 3.2),
                    Vec3::new(0.0, 0.3, 0.0),
                    Vec3::Y,
                    0.7,
                    Some(4.0 / 3.0),
                )
            })
            .into_iter()
            .collect(),
        ..Default::default()
    };
    let path = dir.join(format!("{name}.glb"));
    iris::authoring::write_glb(&path, &scene).expect("write scene");
    path
}

/// An L of two red bars and a green block off to one side: no turn but 360° maps it
/// onto itself.
fn l_shape(dir: &Path, camera: bool) -> PathBuf {
    let meshes = vec![
        part(
            "Bar",
            cuboid(Vec3::new(0.6, 0.15, 0.15)),
            0,
            Vec3::new(0.0, 0.15, 0.0),
        ),
        part(
            "Post",
            cuboid(Vec3::new(0.15, 0.45, 0.15)),
            0,
            Vec3::new(0.45, 0.45, 0.0),
        ),
        part(
            "Block",
            cuboid(Vec3::splat(0.15)),
            1,
            Vec3::new(-0.4, 0.15, 0.45),
        ),
    ];
    write_scene(dir, "l_shape", meshes, camera)
}

/// A hexagonal prism (radius 0.5, 0.6 tall) centred on the vertical axis, flat caps.
fn hexagon() -> TriMesh {
    let point = |r: f64, y: f64, n: (f64, f64)| ProfilePoint {
        r,
        y,
        normal: DVec2::new(n.0, n.1),
    };
    let (r, h) = (0.5, 0.6);
    let lathe = Lathe::new(6);
    let mut mesh = TriMesh::default();
    lathe.band(
        &mut mesh,
        &[point(0.0, 0.0, (0.0, -1.0)), point(r, 0.0, (0.0, -1.0))],
    );
    lathe.band(
        &mut mesh,
        &[point(r, 0.0, (1.0, 0.0)), point(r, h, (1.0, 0.0))],
    );
    lathe.band(
        &mut mesh,
        &[point(r, h, (0.0, 1.0)), point(0.0, h, (0.0, 1.0))],
    );
    mesh
}

/// Runs `iris` with `args` then [`FLAGS`] and `extra` in `dir`; asserts success.
fn run(dir: &Path, args: &[&str], extra: &[&str]) -> String {
    let mut all: Vec<&str> = args.to_vec();
    all.extend(FLAGS);
    all.extend(["-q"]);
    all.extend(extra);
    let o = iris(&all, dir);
    assert!(o.status.success(), "iris {all:?}: {}", stderr(&o));
    stderr(&o)
}

/// Runs `iris` with `args` in `dir`, expecting failure; returns stderr.
fn fails(dir: &Path, args: &[&str]) -> String {
    let o = iris(args, dir);
    assert!(!o.status.success(), "iris {args:?} should fail");
    stderr(&o)
}

fn png(path: &Path) -> image::RgbImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8()
}

fn exr(path: &Path) -> ImageRgb {
    iris::output::read_exr(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `iris turntable SCENE --frames N [--frame F] -o OUT` with [`FLAGS`] and `extra`.
fn turntable(
    dir: &Path,
    scene: &str,
    frames: u32,
    frame: Option<u32>,
    out: &str,
    extra: &[&str],
) -> String {
    let (n, f) = (frames.to_string(), frame.map(|f| f.to_string()));
    let mut args = vec!["turntable", scene, "--frames", &n, "-o", out];
    if let Some(f) = &f {
        args.extend(["--frame", f]);
    }
    run(dir, &args, extra)
}

#[test]
fn frame_zero_is_the_still_and_frames_are_reproducible() {
    let dir = common::scratch_dir("turntable_still");
    let scene = l_shape(&dir, true);
    let scene = scene.to_str().unwrap();
    // A still at a given exposure, and its linear EXR (whose numbers no exposure touches).
    run(
        &dir,
        &["render", scene, "-o", "still.png"],
        &["--exposure", "0.5"],
    );
    run(&dir, &["render", scene, "-o", "still.exr"], &[]);
    turntable(
        &dir,
        scene,
        8,
        Some(0),
        "a",
        &["--exr", "--exposure", "0.5"],
    );
    // Frame 0 is the file as it is: the same bytes as the still, PNG and EXR.
    let read = |p: &str| std::fs::read(dir.join(p)).unwrap();
    assert_eq!(read("a/frame_0000.png"), read("still.png"));
    assert_eq!(read("a/frame_0000.exr"), read("still.exr"));
    // `--frame F` writes only that frame (no probe, no partial, no animation).
    assert_eq!(
        entries(&dir.join("a")),
        ["frame_0000.exr", "frame_0000.png"]
    );
    // With `--exposure auto` (the default) the EXR is the same and the PNG's exposure is
    // the whole turn's, as the note says.
    let notes = turntable(&dir, scene, 8, Some(0), "d", &["--exr"]);
    assert!(
        notes.contains("exposure locked for the whole turn at"),
        "{notes}"
    );
    assert_eq!(read("d/frame_0000.exr"), read("still.exr"));
    // The same frame twice gives the same bytes; the turn alone decides a frame (frame 2
    // of 8 and frame 1 of 4 are both 90°).
    for (frames, frame, out) in [(8, 2, "a"), (8, 2, "b"), (4, 1, "c")] {
        turntable(&dir, scene, frames, Some(frame), out, &[]);
    }
    assert_eq!(read("a/frame_0002.png"), read("b/frame_0002.png"));
    assert_eq!(read("a/frame_0002.png"), read("c/frame_0001.png"));
    assert_ne!(read("a/frame_0002.png"), read("d/frame_0000.png"));
}

#[test]
fn the_model_turns_and_the_floor_and_lights_do_not() {
    let dir = common::scratch_dir("turntable_turn");
    let scene = l_shape(&dir, true);
    let scene = scene.to_str().unwrap();
    let notes = run_all(&dir, scene);
    assert!(
        notes.contains("turntable frame 0 of 4 (0–3): the model (3 meshes) turned 0°"),
        "{notes}"
    );
    let frames: Vec<image::RgbImage> = (0..4)
        .map(|f| png(&dir.join(format!("out/frame_{f:04}.png"))))
        .collect();
    let (w, h) = frames[0].dimensions();
    // A quarter turn of the L changes much of the picture …
    let changed = |a: &image::RgbImage, b: &image::RgbImage| {
        a.pixels()
            .zip(b.pixels())
            .filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > 12))
            .count()
    };
    for f in 1..4 {
        let n = changed(&frames[0], &frames[f]);
        assert!(n as u32 > w * h / 30, "frame {f}: only {n} pixels changed");
    }
    // … but not the floor near the camera, far from the model and its shadows: the bottom
    // corners are the same in every frame, bit for bit (and lit: not background), so the
    // exposure (`--exposure auto`, locked for the turn) did not move either.
    for f in &frames[1..] {
        for (x, y) in (0..6).flat_map(|x| (h - 4..h).flat_map(move |y| [(x, y), (w - 1 - x, y)])) {
            assert_eq!(f.get_pixel(x, y), frames[0].get_pixel(x, y), "({x}, {y})");
            assert!(
                frames[0].get_pixel(x, y).0[0] > 40,
                "floor lit at ({x}, {y})"
            );
        }
    }
    // A whole turn (frame N of N, only through the library) is frame 0.
    let opts = |frame| iris::app::RenderOptions {
        size: Some((48, 36)),
        spp: 2,
        denoise: iris::denoise::DenoiseMode::Off,
        preview: iris::app::PreviewOptions {
            ground: iris::studio::GroundMode::On,
            ..Default::default()
        },
        spin: Some(iris::prepare::turntable::Spin::new(frame, 4).unwrap()),
        ..iris::app::RenderOptions::new(
            Path::new(scene),
            Some(&dir.join(format!("lib{frame}.exr"))),
        )
    };
    let full = iris::app::render_command(&opts(4)).expect("render 360°");
    let zero = iris::app::render_command(&opts(0)).expect("render 0°");
    assert_eq!(full.image, zero.image);
    assert_eq!(full.image, exr(&dir.join("lib0.exr")));
}

/// The whole turntable of the L: 4 frames, then the animation.
fn run_all(dir: &Path, scene: &str) -> String {
    let o = iris(
        &[
            &["turntable", scene, "--frames", "4", "-o", "out"][..],
            &FLAGS[..],
            &["--gif"],
        ]
        .concat(),
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    stderr(&o)
}

/// The largest channel difference between two linear images, relative to the brightest
/// channel of `a`, and the share of pixels that differ by more than `tol` of it.
fn compare(a: &ImageRgb, b: &ImageRgb, tol: f32) -> (f32, f64) {
    let peak = a
        .data
        .iter()
        .map(|p| p.max_element())
        .fold(0.0f32, f32::max);
    let diffs: Vec<f32> = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(p, q)| (*p - *q).abs().max_element() / peak)
        .collect();
    let over = diffs.iter().filter(|&&d| d > tol).count();
    (
        diffs.iter().copied().fold(0.0, f32::max),
        over as f64 / diffs.len() as f64,
    )
}

#[test]
fn models_symmetric_under_a_turn_look_the_same_after_it() {
    let dir = common::scratch_dir("turntable_symmetry");
    let cube = write_scene(
        &dir,
        "cube",
        vec![part(
            "Cube",
            cuboid(Vec3::splat(0.35)),
            0,
            Vec3::new(0.0, 0.35, 0.0),
        )],
        true,
    );
    let hex = write_scene(
        &dir,
        "hexagon",
        vec![part("Hex", hexagon(), 1, Vec3::ZERO)],
        true,
    );
    // The cube a quarter turn on (frame 9 of 36, exact cos and sin): its faces land on
    // each other exactly, only the diagonals that split them into triangles change.
    // The hexagon a sixth of a turn on (frame 6 of 36, a general angle): its corners land
    // on each other within f32 rounding (~1e-7 m).
    for (scene, frame) in [(&cube, 9), (&hex, 6)] {
        let s = scene.to_str().unwrap();
        let stem = scene.file_stem().unwrap().to_str().unwrap();
        for f in [0, 3, frame] {
            turntable(&dir, s, 36, Some(f), stem, &["--exr"]);
        }
        let read = |f: u32| exr(&dir.join(format!("{stem}/frame_{f:04}.exr")));
        let (a, b) = (read(0), read(frame));
        // Equal up to float rounding: a hit point moved by an ulp shades the same to
        // ~1e-6 of the peak; a camera sample grazing an edge may fall on the other side
        // (one of 2 samples: half the pixel), allowed for at most 2 % of the pixels.
        let (worst, share) = compare(&a, &b, 1e-4);
        assert!(
            share <= 0.02,
            "{stem}: {:.2} % of pixels differ (worst {worst})",
            100.0 * share
        );
        // And the model is really there and turned: a frame a twelfth of a turn off (30°,
        // frame 3) is not the same picture.
        let c = read(3);
        let (_, moved) = compare(&a, &c, 1e-2);
        assert!(
            moved > 0.02,
            "{stem}: 30° changed only {:.2} % of pixels",
            100.0 * moved
        );
    }
}

#[test]
fn assemble_checks_every_frame_then_writes_the_animation() {
    let dir = common::scratch_dir("turntable_assemble");
    let scene = l_shape(&dir, true);
    let scene = scene.to_str().unwrap();
    for f in [0, 1, 3] {
        turntable(&dir, scene, 4, Some(f), "out", &[]);
    }
    std::fs::write(dir.join("out/frame_0002.partial.png"), b"half").unwrap();
    let before = entries(&dir.join("out"));
    let assemble = [
        "turntable",
        scene,
        "--frames",
        "4",
        "-o",
        "out",
        "--assemble",
        "--gif",
    ];
    let err = fails(&dir, &assemble);
    assert!(
        err.contains("1 of the 4 frames missing in out: 2 (frame_NNNN.png"),
        "{err}"
    );
    assert!(
        err.contains("only partly rendered (still running or interrupted): 2"),
        "{err}"
    );
    assert_eq!(entries(&dir.join("out")), before, "nothing written");
    std::fs::remove_file(dir.join("out/frame_0002.partial.png")).unwrap();
    turntable(&dir, scene, 4, Some(2), "out", &[]);
    let o = iris(&assemble, &dir);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("4 frames 48x36 at 12 fps"),
        "{}",
        stderr(&o)
    );
    let frames: Vec<image::RgbImage> = (0..4)
        .map(|f| png(&dir.join(format!("out/frame_{f:04}.png"))))
        .collect();

    // The APNG: 4 frames of 48×36 shown 1/12 s each, looping, each exactly its frame file.
    let file = std::fs::File::open(dir.join("out/turntable.png")).unwrap();
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    let actl = reader.info().animation_control.expect("an APNG");
    assert_eq!((actl.num_frames, actl.num_plays), (4, 0));
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    for (f, want) in frames.iter().enumerate() {
        let info = reader.next_frame(&mut buf).expect("frame");
        assert_eq!((info.width, info.height), (48, 36));
        let fc = reader.info().frame_control.expect("fcTL");
        assert_eq!((fc.delay_num, fc.delay_den), (1, 12));
        assert_eq!(
            &buf[..info.buffer_size()],
            want.as_raw().as_slice(),
            "frame {f}"
        );
    }
    assert!(reader.next_frame(&mut buf).is_err(), "no fifth frame");

    // The GIF: 4 frames of 48×36, 8 cs each (1/12 s rounded), close to the frames.
    let file = std::fs::File::open(dir.join("out/turntable.gif")).unwrap();
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(std::io::BufReader::new(file)).unwrap();
    let mut n = 0;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!((frame.width, frame.height, frame.delay), (48, 36, 8));
        let want = &frames[n];
        let err: f64 = frame
            .buffer
            .chunks_exact(4)
            .zip(want.pixels())
            .map(|(g, p)| {
                (0..3)
                    .map(|c| f64::from(g[c].abs_diff(p.0[c])))
                    .sum::<f64>()
            })
            .sum::<f64>()
            / (48.0 * 36.0 * 3.0);
        // 256 colours for a few dozen distinct ones: close to lossless here.
        assert!(err < 4.0, "GIF frame {n}: mean error {err} levels");
        n += 1;
    }
    assert_eq!(n, 4);
}

#[test]
fn auto_method_and_framing_are_decided_once_for_every_frame() {
    let dir = common::scratch_dir("turntable_auto");
    // A bare gem: no camera (framed automatically), the jeweller studio, a floor and
    // `--method auto` (the hybrid for a stone under a studio).
    let gem = dir.join("gem.glb");
    let o = iris(
        &[
            "gem", "--cut", "pear", "--stone", "ruby", "--bare", "-o", "gem.glb",
        ],
        &dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let g = gem.to_str().unwrap();
    let flags = ["--size", "32x24", "--spp", "2", "--denoise", "off", "-q"];
    let all = iris(
        &[&["turntable", g, "--frames", "3", "-o", "all"][..], &flags].concat(),
        &dir,
    );
    assert!(all.status.success(), "{}", stderr(&all));
    // A lone job for frame 2 takes frame 0's method and camera: the same bytes.
    let one = iris(
        &[
            &["turntable", g, "--frames", "3", "--frame", "2", "-o", "one"][..],
            &flags,
        ]
        .concat(),
        &dir,
    );
    assert!(one.status.success(), "{}", stderr(&one));
    assert!(
        stderr(&one).contains("chosen on frame 0's scene, for every frame"),
        "{}",
        stderr(&one)
    );
    let read = |p: &str| std::fs::read(dir.join(p)).unwrap();
    assert_eq!(read("all/frame_0002.png"), read("one/frame_0002.png"));
    assert_eq!(entries(&dir.join("one")), ["frame_0002.png"]);

    // The camera is the same in every frame and every frame's model is inside it.
    let prep = |frame| {
        iris::prepare::prepare(
            &gem,
            &iris::prepare::PrepareOptions {
                size: Some((32, 24)),
                spin: Some(iris::prepare::turntable::Spin::new(frame, 12).unwrap()),
                ..Default::default()
            },
        )
        .expect("prepare")
    };
    let zero = prep(0);
    for frame in [1, 3, 5, 7] {
        let p = prep(frame);
        assert_eq!(p.camera, zero.camera, "frame {frame}");
        let model = model_points(&p.scene);
        let (lo, hi) = iris::framing::projected_box(&model, &p.camera, 32.0 / 24.0).unwrap();
        assert!(
            lo.min_element() > -0.85 && hi.max_element() < 0.85,
            "frame {frame}: {lo} {hi}"
        );
        assert_ne!(model, model_points(&zero.scene), "frame {frame} turned");
        // The floor is the same floor.
        assert_eq!(floor_points(&p.scene), floor_points(&zero.scene));
        assert_eq!(
            format!("{:?}", p.scene.lights()),
            format!("{:?}", zero.scene.lights())
        );
    }
    let notes: Vec<String> = zero.notes().iter().map(ToString::to_string).collect();
    assert!(
        notes
            .iter()
            .any(|n| n.contains("framed on the bounding cylinder of the whole turn")),
        "{notes:?}"
    );
}

/// The vertices of a built scene's triangles that are (`floor`) or are not the floor.
fn points(scene: &iris::scene::Scene, floor: bool) -> Vec<Vec3> {
    let g = scene
        .meshes()
        .iter()
        .position(|m| m.name == iris::studio::ground::GROUND_MESH);
    scene
        .triangles()
        .iter()
        .filter(|t| (Some(t.mesh as usize) == g) == floor)
        .flat_map(|t| t.vertices.map(|i| scene.positions()[i as usize]))
        .collect()
}

fn model_points(scene: &iris::scene::Scene) -> Vec<Vec3> {
    points(scene, false)
}

fn floor_points(scene: &iris::scene::Scene) -> Vec<Vec3> {
    let p = points(scene, true);
    assert_eq!(p.len(), 6, "a two-triangle floor");
    p
}

#[test]
fn bad_flags_are_clear_errors_that_write_nothing() {
    let dir = common::scratch_dir("turntable_errors");
    let scene = l_shape(&dir, true);
    let s = scene.to_str().unwrap();
    let err = fails(&dir, &["turntable", s, "--frames", "0", "-o", "out"]);
    assert!(err.contains("--frames") && err.contains("0"), "{err}");
    let err = fails(
        &dir,
        &["turntable", s, "--frames", "4", "--frame", "4", "-o", "out"],
    );
    assert!(
        err.contains("--frame 4: out of range for --frames 4 (frames are numbered 0 to 3)"),
        "{err}"
    );
    std::fs::write(dir.join("file"), b"x").unwrap();
    let err = fails(
        &dir,
        &[
            "turntable",
            s,
            "--frames",
            "4",
            "--frame",
            "1",
            "-o",
            "file",
        ],
    );
    assert!(
        err.contains("file: cannot write output: -o: not a directory"),
        "{err}"
    );
    let err = fails(
        &dir,
        &[
            "turntable",
            s,
            "--frames",
            "4",
            "-o",
            "nowhere",
            "--assemble",
        ],
    );
    assert!(
        err.contains("nowhere is not a directory of frames"),
        "{err}"
    );
    let err = fails(
        &dir,
        &[
            "turntable",
            s,
            "--frames",
            "4",
            "-o",
            "out",
            "--report",
            "r.csv",
        ],
    );
    assert!(err.contains("not with iris turntable"), "{err}");
    let err = fails(
        &dir,
        &[
            "turntable",
            s,
            "--frames",
            "4",
            "--frame",
            "1",
            "--assemble",
            "-o",
            "out",
        ],
    );
    assert!(err.contains("cannot be used with"), "{err}");
    let err = fails(&dir, &["turntable", s, "--frames", "4"]);
    assert!(err.contains("--output <DIR>"), "{err}");
    let err = fails(
        &dir,
        &["turntable", s, "--frames", "4", "-o", "out", "--fps", "0"],
    );
    assert!(err.contains("--fps"), "{err}");
    // Nothing was written: no frame directory, the scene and the file only.
    assert_eq!(entries(&dir), ["file", "l_shape.glb"]);
}

#[test]
fn an_interrupted_frame_is_not_kept_and_nothing_is_assembled() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    // A guard against hangs, not a speed test.
    const HANG: Duration = Duration::from_secs(120);
    let dir = common::scratch_dir("turntable_interrupt");
    let scene = l_shape(&dir, true);
    // A first frame that would take hours, watched at every checkpoint: its partial file
    // appears once the render is under way (the signal handler is installed by then).
    let child = Command::new(env!("CARGO_BIN_EXE_iris"))
        .args([
            "turntable",
            scene.to_str().unwrap(),
            "--frames",
            "3",
            "-o",
            "out",
        ])
        .args(["--size", "64x48", "--method", "path", "--spp", "1000000"])
        .args(["--checkpoint", "1", "--threads", "2", "-q"])
        .current_dir(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start iris");
    let t = Instant::now();
    while !dir.join("out/frame_0000.partial.png").is_file() {
        assert!(t.elapsed() < HANG, "no checkpoint written after {HANG:?}");
        std::thread::sleep(Duration::from_millis(20));
    }
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(kill.success());
    let out = child.wait_with_output().expect("wait for iris");
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert!(
        err.contains(
            "interrupted (Ctrl-C or SIGTERM) during frame 0: its partial image was removed"
        ),
        "{err}"
    );
    // No frame, no partial frame, no animation.
    assert!(
        entries(&dir.join("out")).is_empty(),
        "{:?}",
        entries(&dir.join("out"))
    );
}
