//! `--stone` and `--metal` (issue 18 item 6): the override changes exactly the selected
//! materials of the scene description, errors name what the file has, and an artist's gem
//! with a placeholder material (the shared `DiamondLowPoly/diamond.glb`) becomes a
//! transmissive, dispersive diamond that the plan renders spectrally with a caustic method.
//!
//! The generated test file has four materials and five meshes:
//! `Placeholder` (opaque cyan) on mesh `Gem`; `Setting` (grey metal) on meshes `Prong` and
//! `Setting`; `Floor` on mesh `Plinth`; the emissive `Lamp` on mesh `Panel`. The mesh
//! named like a material it does not alone use makes `=Setting` ambiguous.

use crate::common;

use glam::{Vec3, Vec4};
use iris::authoring::placed;
use iris::authoring::shapes::{cuboid, icosphere};
use iris::integrator::Method;
use iris::material::MaterialDesc;
use iris::plan::{Plan, SpectralMode};
use iris::prepare::looks::{apply, Applied, LookFlag};
use iris::prepare::{prepare, PrepareOptions};
use iris::scene::desc::SceneDesc;
use iris::spectrum::Metal;
use std::path::{Path, PathBuf};

/// Writes the test file (see the module docs) into `dir`.
fn ring_file(dir: &Path) -> PathBuf {
    let mesh = |name: &str, geometry, material, x: f32| {
        placed(name, geometry, material, Some(Vec3::new(x, 0.0, 0.0)))
    };
    let mut placeholder = MaterialDesc::diffuse("Placeholder", Vec3::new(0.0, 0.67, 0.8));
    placeholder.roughness = 0.0;
    let mut setting = MaterialDesc::diffuse("Setting", Vec3::splat(0.7));
    setting.metallic = 1.0;
    let mut lamp = MaterialDesc::diffuse("Lamp", Vec3::ZERO);
    lamp.emissive = Vec3::splat(5.0);
    let scene = SceneDesc {
        name: "ring".into(),
        // The gem is 6.5 mm across (the size of `iris gem`'s stone); the rest is larger.
        meshes: vec![
            mesh("Gem", icosphere(0.00325, 2), 0, 0.0),
            mesh("Prong", cuboid(Vec3::splat(0.001)), 1, 0.01),
            mesh("Setting", cuboid(Vec3::new(0.01, 0.001, 0.01)), 1, 0.03),
            mesh("Plinth", cuboid(Vec3::new(0.05, 0.002, 0.05)), 2, 0.0),
            mesh("Panel", cuboid(Vec3::new(0.01, 0.0005, 0.01)), 3, -0.05),
        ],
        materials: vec![
            placeholder,
            setting,
            MaterialDesc::diffuse("Floor", Vec3::splat(0.8)),
            lamp,
        ],
        lights: vec![],
        ..SceneDesc::default()
    };
    let path = dir.join("ring.glb");
    iris::authoring::glb::write_glb(&path, &scene).expect("write ring.glb");
    path
}

/// The loaded, validated description of the test file.
fn ring(name: &str) -> SceneDesc {
    let dir = common::scratch_dir(name);
    iris::load::load_scene(&ring_file(&dir)).expect("load ring.glb")
}

fn stone(arg: &str) -> LookFlag {
    LookFlag::stone(arg).expect("a valid --stone")
}

fn metal(arg: &str) -> LookFlag {
    LookFlag::metal(arg, 0.0).expect("a valid --metal")
}

/// The materials of the meshes, by mesh.
fn mesh_materials(d: &SceneDesc) -> Vec<Option<usize>> {
    d.meshes.iter().map(|m| m.material).collect()
}

/// Apart from the materials listed as changed, the description is what it was: the other
/// materials equal, the geometry and every mesh's material index as before unless listed.
fn assert_only(before: &SceneDesc, after: &SceneDesc, changed: &[usize]) {
    for (i, (a, b)) in before.materials.iter().zip(&after.materials).enumerate() {
        assert_eq!(a == b, !changed.contains(&i), "material {i}: {a:?} → {b:?}");
    }
    for (a, b) in before.meshes.iter().zip(&after.meshes) {
        assert_eq!(
            (&a.name, &a.positions, &a.indices),
            (&b.name, &b.positions, &b.indices)
        );
    }
    assert_eq!(before.meshes.len(), after.meshes.len());
    assert_eq!(before.lights, after.lights);
}

/// No material of the ring is a transmissive volume, so `--stone` without a selector takes
/// the closed surfaces: the gem and the plinth (a box), not the named setting or the lamp.
#[test]
fn a_bare_flag_changes_every_material_the_others_do_not_name() {
    let before = ring("looks_bare");
    let mut d = before.clone();
    let applied = apply(&mut d, &[stone("diamond"), metal("gold=material:Setting")]).unwrap();
    // The emissive Lamp (3) stays a light.
    assert_only(&before, &d, &[0, 1, 2]);
    assert_eq!(d.materials.len(), 4, "no material added");
    assert_eq!(mesh_materials(&d), mesh_materials(&before));
    for i in [0, 2] {
        let m = &d.materials[i];
        assert_eq!(
            (m.ior, m.transmission, m.metallic),
            (2.417, 1.0, 0.0),
            "{m:?}"
        );
        assert!((m.dispersion - 20.0 / 55.0).abs() < 1e-6 && m.thickness > 0.0);
        assert_eq!((m.base_color, m.conductor), (Vec4::ONE, None));
    }
    assert_eq!(d.materials[1].conductor, Some(Metal::Gold));
    assert_eq!(
        (d.materials[1].metallic, d.materials[1].roughness),
        (1.0, 0.0)
    );
    assert!(d.materials[0]
        .name
        .ends_with("\"Placeholder\" (--stone diamond)"));
    assert_eq!(
        applied,
        vec![
            Applied {
                flag: "--stone diamond".into(),
                materials: vec![
                    before.materials[0].name.clone(),
                    before.materials[2].name.clone()
                ],
                meshes: 2,
                scope: Some("no selector: the stones; =* for every material"),
            },
            Applied {
                flag: "--metal gold=material:Setting".into(),
                materials: vec![before.materials[1].name.clone()],
                meshes: 2,
                scope: None,
            },
        ]
    );
}

#[test]
fn a_material_selector_changes_that_material_alone() {
    let before = ring("looks_material");
    let mut d = before.clone();
    apply(&mut d, &[stone("ruby=Placeholder")]).unwrap();
    assert_only(&before, &d, &[0]);
    assert_eq!(mesh_materials(&d), mesh_materials(&before));
    let ruby = &d.materials[0];
    assert_eq!((ruby.ior, ruby.transmission), (1.77, 1.0));
    // The gem is 6.5 mm across, as `iris gem`'s stone: the same 4 mm colour distance.
    assert!(
        (ruby.attenuation_distance - 0.004).abs() < 0.0002,
        "{}",
        ruby.attenuation_distance
    );
    assert!(ruby.attenuation_color.x > ruby.attenuation_color.y);
}

#[test]
fn a_mesh_selector_gives_the_mesh_a_material_of_its_own() {
    let before = ring("looks_mesh");
    let mut d = before.clone();
    // `Gem` names only a mesh: a bare NAME falls back to meshes.
    apply(
        &mut d,
        &[metal("platinum=mesh:Setting"), stone("emerald=Gem")],
    )
    .unwrap();
    assert_only(&before, &d, &[]);
    assert_eq!(d.materials.len(), 6);
    let m = mesh_materials(&d);
    assert_eq!(
        m[1], before.meshes[1].material,
        "Prong keeps the shared Setting"
    );
    assert_eq!(d.materials[m[2].unwrap()].conductor, Some(Metal::Platinum));
    let gem = &d.materials[m[0].unwrap()];
    assert_eq!((gem.ior, gem.transmission), (1.583, 1.0));
    assert_eq!(m[3], before.meshes[3].material);
}

/// A stone on a model 100 times larger keeps the colour saturation: the attenuation
/// distance scales with the model (the largest bounding-box side of its meshes).
#[test]
fn coloured_stones_scale_their_colour_with_the_model() {
    let mut d = ring("looks_scale");
    for p in d.meshes[0].positions.iter_mut() {
        *p *= 100.0;
    }
    apply(&mut d, &[stone("sapphire=Placeholder")]).unwrap();
    let dist = d.materials[0].attenuation_distance;
    assert!((dist - 0.4).abs() < 0.02, "{dist}");
}

#[test]
fn errors_name_the_choices() {
    let d = ring("looks_errors");
    let err = |flags: &[LookFlag]| {
        apply(&mut d.clone(), flags)
            .expect_err("an error")
            .to_string()
    };
    let e = LookFlag::stone("glass")
        .expect_err("unknown stone")
        .to_string();
    assert!(e.contains("emerald") && e.contains("cubic-zirconia"), "{e}");
    let e = LookFlag::metal("brass", 0.0)
        .expect_err("unknown metal")
        .to_string();
    assert!(e.contains("rose-gold") && e.contains("platinum"), "{e}");
    assert!(LookFlag::metal("gold", 1.5).is_err());
    assert!(LookFlag::stone("ruby=").is_err());
    let e = err(&[stone("ruby=Topaz")]);
    for name in [
        "\"Placeholder\"",
        "\"Setting\"",
        "\"Floor\"",
        "\"Gem\"",
        "\"Plinth\"",
        "ring.glb",
    ] {
        assert!(e.contains(name), "{name} missing from: {e}");
    }
    let e = err(&[metal("gold=Setting")]);
    assert!(
        e.contains("material:Setting") && e.contains("mesh:Setting"),
        "{e}"
    );
    let e = err(&[stone("diamond"), metal("gold")]);
    assert!(e.contains("only one"), "{e}");
    let e = err(&[
        stone("ruby=Placeholder"),
        stone("sapphire=material:placeholder"),
    ]);
    assert!(e.contains("both name material"), "{e}");
}

/// A birefringent stone is a crystal, held to a crystal's rule (issue 48): on an open mesh
/// `--stone calcite` is refused naming the file, the material and the flag, as an
/// `extras.iris_crystal` there is; an isotropic stone (diamond) on it is not a crystal and
/// is accepted.
#[test]
fn a_birefringent_stone_on_an_open_mesh_is_refused_as_a_crystal() {
    let mut d = ring("looks_open_crystal");
    let gem = d
        .meshes
        .iter()
        .position(|m| m.name.contains("Gem"))
        .unwrap();
    d.meshes[gem].indices.pop();
    let e = apply(&mut d.clone(), &[stone("calcite=Placeholder")])
        .expect_err("an open crystal")
        .to_string();
    for needle in [
        "ring.glb",
        "Placeholder",
        "--stone calcite",
        "birefringent crystal",
        "surface is open: 3 edges",
        "even after welding",
    ] {
        assert!(e.contains(needle), "{needle} missing from: {e}");
    }
    apply(&mut d, &[stone("diamond=Placeholder")]).expect("diamond is isotropic");
}

/// The CLI takes the flags on render and info, and fails with the names on a bad one.
#[test]
fn cli_takes_the_flags() {
    let dir = common::scratch_dir("looks_cli");
    let file = ring_file(&dir);
    let f = file.to_str().unwrap();
    let out = common::iris(
        &[
            "info",
            f,
            "--stone",
            "diamond=Gem",
            "--metal",
            "gold=material:Setting",
        ],
        &dir,
    );
    assert!(out.status.success(), "{}", common::stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("measured metal gold"), "{text}");
    assert!(text.contains("transport     used      spectral"), "{text}");
    let out = common::iris(&["render", f, "--stone", "opal", "-o", "x.png"], &dir);
    assert!(!out.status.success());
    assert!(
        common::stderr(&out).contains("crown-glass"),
        "{}",
        common::stderr(&out)
    );
    assert!(!dir.join("x.png").exists());
    // Without a flag, `iris info` on an opaque file suggests the stone.
    let out = common::iris(&["info", f], &dir);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("--stone diamond") && text.contains("\"Placeholder\""),
        "{text}"
    );
}

/// The shared Sketchfab diamond: opaque cyan as exported (RGB, path tracer: nothing to
/// refract); with `--stone diamond` its one material is transmissive and dispersive, the
/// plan renders spectrally and `--method auto` picks a caustic-capable method (hybrid or
/// SPPM), decided by the plan's probes, not by rendering.
#[test]
fn the_sketchfab_diamond_becomes_a_diamond() {
    let Some(root) = common::shared_assets() else {
        return;
    };
    let path = root.join("gems/DiamondLowPoly/diamond.glb");
    let opts = |looks: Vec<LookFlag>| PrepareOptions {
        size: Some((32, 24)),
        looks,
        ..Default::default()
    };
    let plain = prepare(&path, &opts(vec![])).expect("prepare");
    let plan = Plan::new(
        &plain.scene,
        &common::PINHOLE,
        Method::Auto,
        SpectralMode::Auto,
    );
    assert!(
        !plan.spectral && plan.method == Method::Path,
        "{}",
        plan.text()
    );
    let info = iris::app::info_command(&path).expect("info");
    assert!(
        info.contains("--stone diamond") && info.contains("material 0 \"material\""),
        "{info}"
    );

    let stoned = prepare(&path, &opts(vec![stone("diamond")])).expect("prepare");
    let used: Vec<_> = stoned
        .scene
        .triangles()
        .iter()
        .map(|t| stoned.scene.material(t.material()))
        .filter(|m| m.desc.name.contains("--stone"))
        .collect();
    assert!(!used.is_empty());
    assert!(used
        .iter()
        .all(|m| m.is_transmissive() && m.is_volume() && m.is_dispersive()));
    let plan = Plan::new(
        &stoned.scene,
        &common::PINHOLE,
        Method::Auto,
        SpectralMode::Auto,
    );
    assert!(plan.spectral, "{}", plan.text());
    assert!(
        matches!(plan.method, Method::Hybrid | Method::Sppm),
        "{}",
        plan.text()
    );
    assert_eq!(stoned.looks.len(), 1);
    assert_eq!(stoned.looks[0].meshes, 1);
}

/// A gem of glass on an open floor plane, a lamp: `--stone sapphire` without a selector
/// changes the stone alone (the floor stays a floor, and the birefringent sapphire is not
/// refused for the floor's open surface); `=*` changes every material but the light,
/// and a birefringent stone on the open floor is then refused naming it.
#[test]
fn a_bare_stone_flag_changes_the_stones_and_star_every_material() {
    let dir = common::scratch_dir("looks_stones");
    let mesh = |name: &str, geometry, material| placed(name, geometry, material, None);
    let scene = SceneDesc {
        name: "gem on a floor".into(),
        meshes: vec![
            mesh("Gem", icosphere(0.00325, 2), 0),
            mesh(
                "Floor",
                iris::authoring::shapes::ground_plane(0.05, 0.05),
                1,
            ),
            mesh("Panel", cuboid(Vec3::new(0.01, 0.0005, 0.01)), 2),
        ],
        materials: vec![
            MaterialDesc::clear_glass("Glass", 1.5, 0.0065),
            MaterialDesc::diffuse("Floor", Vec3::splat(0.8)),
            MaterialDesc::emitter("Lamp", Vec3::splat(5.0)),
        ],
        lights: vec![],
        ..SceneDesc::default()
    };
    let path = dir.join("gem_on_floor.glb");
    iris::authoring::glb::write_glb(&path, &scene).expect("write");
    let before = iris::load::load_scene(&path).expect("load");
    let mut d = before.clone();
    let applied = apply(&mut d, &[stone("sapphire")]).expect("stones only");
    assert_only(&before, &d, &[0]);
    assert!(d.materials[0].crystal.is_some(), "sapphire is birefringent");
    assert!(
        applied[0].to_string().contains("the stones"),
        "{}",
        applied[0]
    );
    let mut d = before.clone();
    apply(&mut d, &[stone("diamond=*")]).expect("every material");
    assert_only(&before, &d, &[0, 1]);
    let mut d = before.clone();
    let e = apply(&mut d, &[stone("sapphire=*")])
        .unwrap_err()
        .to_string();
    assert!(e.contains("Floor") && e.contains("open"), "{e}");
}
