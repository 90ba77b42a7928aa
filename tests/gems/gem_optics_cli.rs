//! `iris` on crystal and polarizer scenes from the command line (issue 34): bad optic axes
//! and indices are errors naming the file, the material and the field, with no output
//! written; the flags' bad values and conflicts are usage errors; an isotropic scene
//! renders bit-identically whether polarization is left to the plan or turned off; a
//! polarized render repeats itself exactly; `iris info` shows the optical character.

use crate::common;

use glam::Vec3;
use iris::authoring::shapes::{cuboid, ground_plane};
use iris::authoring::{look_at, placed};
use iris::material::MaterialDesc;
use iris::scene::desc::SceneDesc;
use serde_json::json;
use std::path::{Path, PathBuf};

/// A slab with material `extras`, over a lit floor, with a camera.
fn slab_file(dir: &Path, name: &str, extras: serde_json::Value) -> PathBuf {
    let mut slab = MaterialDesc::clear_glass("Crystal", 1.6, 0.01);
    slab.extras = Some(extras);
    let mut lamp = MaterialDesc::diffuse("Lamp", Vec3::ZERO);
    lamp.emissive = Vec3::splat(4.0);
    let mesh = |name: &str, geometry, material, y: f32| {
        placed(name, geometry, material, Some(Vec3::new(0.0, y, 0.0)))
    };
    let scene = SceneDesc {
        name: name.into(),
        meshes: vec![
            mesh("Slab", cuboid(Vec3::new(0.02, 0.005, 0.02)), 0, 0.005),
            mesh("Floor", ground_plane(0.1, 0.1), 1, 0.0),
            mesh("Lamp", ground_plane(0.05, 0.05), 2, 0.2),
        ],
        materials: vec![slab, MaterialDesc::diffuse("Floor", Vec3::splat(0.7)), lamp],
        lights: vec![],
        cameras: vec![look_at(
            "Camera",
            Vec3::new(0.0, 0.12, 0.08),
            Vec3::ZERO,
            Vec3::Y,
            0.6,
            None,
        )],
        ..SceneDesc::default()
    };
    let path = dir.join(format!("{name}.glb"));
    iris::authoring::glb::write_glb(&path, &scene).expect("write glb");
    path
}

fn render(dir: &Path, scene: &Path, out: &str, extra: &[&str]) -> std::process::Output {
    let scene = scene.to_str().unwrap();
    let mut args = vec![
        "render", scene, "--spp", "2", "--size", "32x24", "--quiet", "-o", out,
    ];
    args.extend_from_slice(extra);
    common::iris(&args, dir)
}

#[test]
fn bad_crystals_name_the_material_and_write_nothing() {
    let dir = common::scratch_dir("gem_optics_bad");
    for (case, extras, says) in [
        (
            "zero_axis",
            json!({"iris_crystal": {"stone": "calcite", "optic_axis": [0, 0, 0]}}),
            "optic_axis is zero",
        ),
        (
            "nan_axis",
            json!({"iris_crystal": {"n": [1.6, 1.5], "optic_axis": [0, "up", 0]}}),
            "optic_axis must be [x, y, z]",
        ),
        (
            "low_index",
            json!({"iris_crystal": {"n": [1.6, 0.8]}}),
            "index 2 = 0.8",
        ),
        (
            "huge_index",
            json!({"iris_crystal": {"n": [1.6, 1.65, 9.0]}}),
            "index 3 = 9",
        ),
        (
            "unknown_stone",
            json!({"iris_crystal": {"stone": "kryptonite"}}),
            "unknown stone",
        ),
        (
            "polarizer_zero",
            json!({"iris_polarizer": {"axis": [0, 0, 0]}}),
            "iris_polarizer.axis",
        ),
    ] {
        let scene = slab_file(&dir, case, extras);
        let out = dir.join(format!("{case}.png"));
        let o = render(&dir, &scene, out.to_str().unwrap(), &[]);
        let err = common::stderr(&o);
        assert!(!o.status.success(), "{case}: {err}");
        assert!(
            err.contains("Crystal") && err.contains(says),
            "{case}: {err}"
        );
        assert!(
            err.contains(&format!("{case}.glb")),
            "{case}: names the file: {err}"
        );
        assert!(!out.exists(), "{case}: no output");
    }
}

#[test]
fn polarization_flags_are_checked() {
    let dir = common::scratch_dir("gem_optics_flags");
    let calcite = slab_file(
        &dir,
        "calcite",
        json!({"iris_crystal": {"stone": "calcite"}}),
    );
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    for (flags, says) in [
        (&["--polarizer", "north"][..], "--polarizer"),
        (&["--polarizer", "400"][..], "-360 to 360"),
        (&["--polarization", "sometimes"][..], "--polarization"),
        (
            &["--polarizer", "10", "--polarization", "off"][..],
            "--polarizer needs polarized transport",
        ),
        (
            &["--polarization", "on", "--method", "sppm"][..],
            "--method sppm does not trace polarized light",
        ),
        (
            &["--polarization", "on", "--spectral", "off"][..],
            "polarized transport is spectral",
        ),
    ] {
        let o = render(&dir, &calcite, out, flags);
        let err = common::stderr(&o);
        assert!(
            !o.status.success() && err.contains(says),
            "{flags:?}: {err}"
        );
        assert!(!Path::new(out).exists(), "{flags:?}: no output");
    }
    // With another method named, automatic polarization steps aside and says so.
    let o = common::iris(&["info", calcite.to_str().unwrap()], &dir);
    let info = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(
        info.contains("optics calcite uniaxial −") && info.contains("birefringence 0.17"),
        "{info}"
    );
    assert!(
        info.contains("polarization  used      on: birefringent"),
        "{info}"
    );
    // What polarized paths do not have, and why, is in the plan.
    use iris::integrator::path::polarized::{WHY_NO_SPLIT, WHY_SINGLE_RAYS};
    let flat = info.split_whitespace().collect::<Vec<_>>().join(" ");
    for why in [WHY_NO_SPLIT, WHY_SINGLE_RAYS] {
        let why = why.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(flat.contains(&why), "{why}: {info}");
    }
    assert!(
        flat.contains("lanes left out polarized camera paths are single rays: the lanes step"),
        "{info}"
    );
}

#[test]
fn isotropic_scenes_render_the_same_with_the_mode_left_out() {
    let dir = common::scratch_dir("gem_optics_iso");
    let glass = slab_file(&dir, "glass", json!({}));
    let (a, b) = (dir.join("auto.exr"), dir.join("off.exr"));
    assert!(render(&dir, &glass, a.to_str().unwrap(), &[])
        .status
        .success());
    assert!(render(
        &dir,
        &glass,
        b.to_str().unwrap(),
        &["--polarization", "off"]
    )
    .status
    .success());
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    let o = common::iris(&["info", glass.to_str().unwrap()], &dir);
    let info = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(
        info.contains("polarization  left out  no birefringent material, no polarizer"),
        "{info}"
    );
    assert!(info.contains("optics isotropic"), "{info}");
}

#[test]
fn polarized_renders_repeat_exactly() {
    let dir = common::scratch_dir("gem_optics_repeat");
    let calcite = slab_file(
        &dir,
        "calcite",
        json!({"iris_crystal": {"stone": "calcite", "optic_axis": [1, 1, 0]}}),
    );
    let run = |name: &str, threads: &str| {
        let out = dir.join(name);
        let o = render(
            &dir,
            &calcite,
            out.to_str().unwrap(),
            &["--threads", threads, "--polarizer", "30"],
        );
        assert!(o.status.success(), "{}", common::stderr(&o));
        std::fs::read(out).unwrap()
    };
    let one = run("a.exr", "1");
    assert_eq!(one, run("b.exr", "1"));
    assert_eq!(one, run("c.exr", "2"));
}
