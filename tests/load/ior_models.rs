//! IOR models end to end (issue 4, item 3): file → description → validation → the
//! render [`Material`]'s `spectrum::IorModel`. glTF extras (`iris_glass`, `cauchy`),
//! KHR_materials_dispersion, the `ior: 0` mode, MTL `iris_glass`, the shared DispersionTest
//! asset and the `iris info` lines. Wavelengths in nm.

use crate::common;
// The glTF fixture documents of `load_gltf` (tests/load/load_gltf/fixtures.rs).
use crate::load_gltf::fixtures;

use fixtures::{cube_doc, write_json};
use iris::load::load_scene;
use iris::material::Material;
use iris::material::MaterialDesc;
use iris::scene::desc::SceneDesc;
use iris::spectrum::ior::{LAMBDA_C, LAMBDA_D, LAMBDA_F};
use iris::spectrum::IorModel;
use iris::LoadErrorKind;
use serde_json::{json, Value};
use std::path::PathBuf;

/// Writes the cube with `materials` (the cube uses material 0) and returns its path.
fn gltf_with(test: &str, materials: Value) -> PathBuf {
    let dir = common::scratch_dir(test);
    let mut doc = cube_doc();
    doc["extensionsUsed"] = json!(["KHR_materials_ior", "KHR_materials_dispersion"]);
    doc["materials"] = materials;
    write_json(&dir, "scene.gltf", &doc)
}

fn loaded(test: &str, materials: Value) -> SceneDesc {
    let path = gltf_with(test, materials);
    load_scene(&path).unwrap_or_else(|e| panic!("{test}: {e}"))
}

fn render_material(desc: &SceneDesc, index: usize) -> Material {
    Material::new(desc.materials[index].clone())
}

/// Loads and expects an error of `kind` naming the file and `material 0 "Glass"`.
fn expect_material_error(test: &str, materials: Value, kind: LoadErrorKind) -> String {
    let path = gltf_with(test, materials);
    let e = match load_scene(&path) {
        Ok(_) => panic!("{test}: loaded but should fail"),
        Err(e) => e,
    };
    let text = e.to_string();
    assert_eq!(e.kind, kind, "{test}: {text}");
    assert!(text.contains("scene.gltf"), "{test}: no file in {text}");
    assert!(
        text.contains("material 0 \"Glass\""),
        "{test}: no material in {text}"
    );
    text
}

#[test]
fn iris_glass_n_bk7_gives_the_catalogue_n_d() {
    let desc = loaded(
        "ior_bk7",
        json!([{"name": "Glass", "extras": {"iris_glass": "n-bk7"},
                "extensions": {"KHR_materials_ior": {"ior": 1.52}}}]),
    );
    let m = render_material(&desc, 0);
    // SCHOTT quotes n_d = 1.5168 (4 decimals): half a unit in the last place is 5e-5.
    let n = m.ior_model().ior(LAMBDA_D);
    assert!((n - 1.5168).abs() < 5e-5, "n_d = {n}");
    assert!((m.ior() - 1.5168).abs() < 5e-5, "RGB ior {}", m.ior());
    assert!(m.is_dispersive());
    // Catalogue V_d = 64.17; the fit's own Abbe number agrees to the quoted 2 decimals.
    let v = m.ior_model().abbe_number();
    assert!((v - 64.17).abs() < 0.01, "Abbe {v}");
    // Normal dispersion: blue bends more.
    assert!(m.ior_model().ior(LAMBDA_F) > n && n > m.ior_model().ior(LAMBDA_C));
}

#[test]
fn cauchy_extras_win_over_khr_dispersion() {
    let desc = loaded(
        "ior_cauchy_vs_khr",
        json!([{"name": "Glass", "extras": {"cauchy": {"b": 1.5, "c": 0.0042}},
                "extensions": {"KHR_materials_ior": {"ior": 1.6},
                               "KHR_materials_dispersion": {"dispersion": 0.36}}}]),
    );
    assert!(desc.warnings.is_empty(), "{:?}", desc.warnings);
    let m = render_material(&desc, 0);
    assert_eq!(*m.ior_model(), IorModel::Cauchy { b: 1.5, c: 0.0042 });
    // n(486.13) = 1.5 + 0.0042 / 0.48613² = 1.517772; the KHR model would give ≈ 1.61.
    let n_f = m.ior_model().ior(LAMBDA_F);
    assert!((n_f - 1.517_772).abs() < 1e-5, "n_F = {n_f}");
    let expected_d = 1.5 + 0.0042 / (0.58756f32 * 0.58756);
    assert!((m.ior() - expected_d).abs() < 1e-6, "{}", m.ior());
}

#[test]
fn khr_dispersion_reproduces_the_spec_numbers() {
    let desc = loaded(
        "ior_khr",
        json!([{"name": "Glass", "extensions": {"KHR_materials_ior": {"ior": 2.42},
                "KHR_materials_dispersion": {"dispersion": 0.36}}}]),
    );
    let m = render_material(&desc, 0);
    let model = *m.ior_model();
    assert_eq!(
        model,
        IorModel::KhrDispersion {
            n_d: 2.42,
            dispersion: 0.36
        }
    );
    // The spec: dispersion 20/V_d, so Abbe 55.6 ↔ 0.36. Computed from n_F, n_C the
    // formula's constant 523655 nm² reproduces V_d to ~3e-5 relative.
    let v = model.abbe_number();
    assert!((v - 20.0 / 0.36).abs() < 0.01, "Abbe {v}");
    // n_F − n_C = (n_d − 1)/V_d; f32 n near 2.4 is good to ~3e-7, so 1e-4 is loose.
    let spread = model.ior(LAMBDA_F) - model.ior(LAMBDA_C);
    assert!((spread - 1.42 / (20.0 / 0.36)).abs() < 1e-4, "{spread}");
    // RGB transport uses the KHR ior itself.
    assert_eq!(m.ior(), 2.42);
}

#[test]
fn ior_zero_disables_dispersion() {
    let desc = loaded(
        "ior_zero",
        json!([{"name": "Glass", "extras": {"iris_glass": "diamond"},
                "extensions": {"KHR_materials_ior": {"ior": 0.0},
                               "KHR_materials_dispersion": {"dispersion": 1.0}}}]),
    );
    let m = render_material(&desc, 0);
    assert_eq!(*m.ior_model(), IorModel::Constant(f32::INFINITY));
    assert!(!m.is_dispersive());
    assert_eq!(m.ior(), f32::INFINITY);
    let warning = desc.warnings.join("\n");
    assert!(
        warning.contains("material 0 \"Glass\"") && warning.contains("ior 0"),
        "{warning}"
    );
}

#[test]
fn bad_glass_extras_name_file_and_material() {
    let text = expect_material_error(
        "ior_unknown_glass",
        json!([{"name": "Glass", "extras": {"iris_glass": "unobtainium"}}]),
        LoadErrorKind::InvalidValue,
    );
    assert!(
        text.contains("unobtainium") && text.contains("N-BK7") && text.contains("sapphire"),
        "{text}"
    );
    let text = expect_material_error(
        "ior_glass_type",
        json!([{"name": "Glass", "extras": {"iris_glass": 7}}]),
        LoadErrorKind::InvalidValue,
    );
    assert!(text.contains("must be a string"), "{text}");
    let text = expect_material_error(
        "ior_glass_and_cauchy",
        json!([{"name": "Glass", "extras": {"iris_glass": "water",
                "cauchy": {"b": 1.5, "c": 0.0042}}}]),
        LoadErrorKind::InvalidValue,
    );
    assert!(text.contains("both"), "{text}");
}

#[test]
fn mtl_iris_glass_and_its_errors() {
    let dir = common::scratch_dir("ior_mtl");
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gem\nf 1 2 3\nusemtl ice\nf 1 3 2\n";
    let mtl = "newmtl gem\nillum 7\niris_glass N-SF11\n\nnewmtl ice\nillum 7\nNi 1.31\n# iris_glass water\n";
    std::fs::write(dir.join("a.obj"), obj).expect("write");
    std::fs::write(dir.join("m.mtl"), mtl).expect("write");
    let desc = load_scene(&dir.join("a.obj")).unwrap_or_else(|e| panic!("{e}"));
    let find = |name: &str| -> &MaterialDesc {
        let quoted = format!("\"{name}\"");
        desc.materials
            .iter()
            .find(|m| m.name.contains(&quoted))
            .expect("material")
    };
    let (gem, ice) = (find("gem"), find("ice"));
    // The glass name makes illum 7 a dielectric without `Ni`; n_d comes from the model.
    assert_eq!(gem.transmission, 1.0);
    let gem = Material::new(gem.clone());
    // SCHOTT N-SF11: n_d = 1.78472, quoted to 5 decimals.
    assert!((gem.ior() - 1.78472).abs() < 5e-5, "{}", gem.ior());
    // The comment form wins over `Ni 1.31` for refraction: the water model's own n_d
    // (Daimon & Masumura 20 °C, ≈ 1.3334; the catalogue value is the spectrum module's test).
    let ice = Material::new(ice.clone());
    let water = IorModel::named("water").expect("catalogue").n_d();
    assert_eq!(ice.ior(), water);
    assert!((1.332..1.335).contains(&water), "{water}");
    assert!(ice.is_dispersive());

    std::fs::write(dir.join("m.mtl"), "newmtl gem\nKd 1\niris_glass BK8\n").expect("write");
    let e = load_scene(&dir.join("a.obj")).expect_err("unknown glass");
    let text = e.to_string();
    assert_eq!(e.kind, LoadErrorKind::InvalidValue, "{text}");
    assert!(
        text.contains("m.mtl") && text.contains("\"gem\" (line 3)") && text.contains("BK8"),
        "{text}"
    );
}

#[test]
fn info_prints_the_ior_model() {
    let path = gltf_with(
        "ior_info",
        json!([{"name": "Glass", "extras": {"iris_glass": "bk7"}},
               {"name": "Gem", "extensions": {"KHR_materials_ior": {"ior": 2.42},
                "KHR_materials_dispersion": {"dispersion": 0.36}}}]),
    );
    let text = iris::app::info_command(&path).expect("info");
    assert!(
        text.contains("ior Sellmeier N-BK7 (n_d 1.5168, Abbe 64.2)"),
        "{text}"
    );
    assert!(
        text.contains("ior 2.42, KHR dispersion 0.36 (Abbe 55.6)"),
        "{text}"
    );
}

#[test]
fn dispersion_test_columns_resolve_to_khr_models() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let desc = load_scene(&assets.join("khronos/DispersionTest/DispersionTest.glb"))
        .unwrap_or_else(|e| panic!("{e}"));
    // Columns D1..D5 carry dispersion 0, 0.5, 1, 2, 5 (checked with `iris info`).
    let dispersions = [0.0f32, 0.5, 1.0, 2.0, 5.0];
    let mut checked = 0;
    for (ior_text, n_d) in [
        ("1.33", 1.33f32),
        ("1.50", 1.5),
        ("1.76", 1.76),
        ("2.42", 2.42),
    ] {
        for (column, &d) in dispersions.iter().enumerate() {
            let name = format!("\"Mat_IOR_{ior_text}_D{}\"", column + 1);
            let m = desc
                .materials
                .iter()
                .find(|m| m.name.ends_with(&name))
                .unwrap_or_else(|| panic!("{name}"));
            let model = *Material::new(m.clone()).ior_model();
            if d == 0.0 {
                assert_eq!(model, IorModel::Constant(n_d), "{name}");
                continue;
            }
            assert_eq!(
                model,
                IorModel::KhrDispersion { n_d, dispersion: d },
                "{name}"
            );
            // V_d = 20/D to 0.01 % (the formula's 523655 constant is rounded).
            let v = model.abbe_number();
            assert!((v / (20.0 / d) - 1.0).abs() < 1e-4, "{name}: Abbe {v}");
            checked += 1;
        }
    }
    assert_eq!(checked, 16);
    // n_d = 1: the formula's (n_d − 1) factor vanishes, so the model is not dispersive.
    let air = desc
        .materials
        .iter()
        .find(|m| m.name.ends_with("\"Mat_IOR_1.0_D5\""))
        .expect("IOR 1 prism");
    assert_eq!(air.dispersion, 5.0);
    assert!(!Material::new(air.clone()).is_dispersive());
}

/// Nested-media priority: glTF `extras.iris_priority` and MTL `iris_priority` load as
/// integers (default 0); non-integers and out-of-range values are errors naming the file,
/// the material and (MTL) the line.
#[test]
fn iris_priority_loads_and_rejects_bad_values() {
    let desc = loaded(
        "priority_gltf",
        json!([{"name": "Glass", "extras": {"iris_priority": 3}}, {"name": "Plain"}]),
    );
    assert_eq!(
        (desc.materials[0].priority, desc.materials[1].priority),
        (3, 0)
    );
    for bad in [json!(1.5), json!("high"), json!(2_000_000)] {
        let text = expect_material_error(
            "priority_gltf_bad",
            json!([{"name": "Glass", "extras": {"iris_priority": bad}}]),
            LoadErrorKind::InvalidValue,
        );
        assert!(
            text.contains("iris_priority") && text.contains("Glass"),
            "{text}"
        );
    }
    let dir = common::scratch_dir("priority_mtl");
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\n";
    std::fs::write(dir.join("a.obj"), obj).expect("write");
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl glass\nillum 7\nNi 1.5\niris_priority 2\n",
    )
    .unwrap();
    let desc = load_scene(&dir.join("a.obj")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(desc.materials[0].priority, 2);
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl glass\nillum 7\nNi 1.5\niris_priority x\n",
    )
    .unwrap();
    let text = load_scene(&dir.join("a.obj")).unwrap_err().to_string();
    assert!(
        text.contains("m.mtl") && text.contains("glass") && text.contains("line 4"),
        "{text}"
    );
}
