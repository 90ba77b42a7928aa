//! One test per validation rule, on small descriptions built in code.

use super::validate;
use crate::error::LoadErrorKind;
use crate::material::{AlphaMode, ExplicitIor, ImageDesc, MaterialDesc, TextureRef};
use crate::scene::desc::*;
use crate::spectrum::EmissionSpectrum;
use glam::{Vec2, Vec3, Vec4};
use std::sync::Arc;

/// One unit right triangle (mesh "tri", material "glass"), valid as is.
pub(super) fn scene() -> SceneDesc {
    SceneDesc {
        source: "scene.test".into(),
        meshes: vec![MeshDesc {
            name: "mesh 0 \"tri\"".into(),
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2]],
            material: Some(0),
            ..MeshDesc::default()
        }],
        materials: vec![MaterialDesc {
            name: "material 0 \"glass\"".into(),
            ..MaterialDesc::default()
        }],
        ..SceneDesc::default()
    }
}

pub(super) fn err_kind(desc: SceneDesc) -> (LoadErrorKind, String) {
    match validate(desc) {
        Ok(_) => panic!("expected an error"),
        Err(e) => (e.kind, e.to_string()),
    }
}

pub(super) fn warnings(desc: SceneDesc) -> (SceneDesc, String) {
    let d = validate(desc).expect("valid");
    let w = d.warnings.join("\n");
    (d, w)
}

#[test]
fn valid_scene_passes_unchanged() {
    let (d, w) = warnings(scene());
    assert_eq!(d.meshes[0].indices, vec![[0, 1, 2]]);
    assert!(w.is_empty(), "{w}");
}

#[test]
fn index_out_of_range_names_mesh() {
    let mut d = scene();
    d.meshes[0].indices.push([0, 1, 7]);
    let (k, msg) = err_kind(d);
    assert_eq!(k, LoadErrorKind::IndexOutOfRange);
    assert!(
        msg.contains("scene.test") && msg.contains("\"tri\" triangle 1"),
        "{msg}"
    );
}

#[test]
fn per_vertex_array_length() {
    let mut d = scene();
    d.meshes[0].normals = vec![Vec3::Z];
    assert_eq!(err_kind(d).0, LoadErrorKind::Parse);
    let mut d = scene();
    d.meshes[0].uvs = vec![Vec2::ZERO; 4];
    let (k, msg) = err_kind(d);
    assert_eq!(k, LoadErrorKind::Parse);
    assert!(msg.contains("\"tri\""), "{msg}");
}

#[test]
fn material_and_texture_indices() {
    let mut d = scene();
    d.meshes[0].material = Some(3);
    let (k, msg) = err_kind(d);
    assert_eq!(k, LoadErrorKind::IndexOutOfRange);
    assert!(msg.contains("\"tri\""), "{msg}");
    let mut d = scene();
    d.materials[0].emissive_texture = Some(TextureRef::new(0, 0));
    let (k, msg) = err_kind(d);
    assert_eq!(k, LoadErrorKind::IndexOutOfRange);
    assert!(
        msg.contains("\"glass\"") && msg.contains("emissiveTexture"),
        "{msg}"
    );
}

#[test]
fn image_size_must_match() {
    let mut d = scene();
    d.images.push(ImageDesc {
        name: "image 0 \"a.png\"".into(),
        width: 2,
        height: 2,
        rgba8: Arc::new(vec![0; 15]),
    });
    let (k, msg) = err_kind(d);
    assert_eq!(k, LoadErrorKind::MissingBuffer);
    assert!(msg.contains("a.png"), "{msg}");
}

#[test]
fn non_finite_positions_drop_their_triangles() {
    let mut d = scene();
    // A second triangle on a NaN vertex and a third on an infinite one.
    d.meshes[0].positions.push(Vec3::new(0.0, f32::NAN, 0.0));
    d.meshes[0]
        .positions
        .push(Vec3::new(f32::INFINITY, 0.0, 0.0));
    d.meshes[0].indices.extend([[0, 3, 1], [1, 4, 2]]);
    let (d, w) = warnings(d);
    assert_eq!(d.meshes[0].indices, vec![[0, 1, 2]]);
    assert!(d.meshes[0].positions.iter().all(|p| p.is_finite()));
    assert!(
        w.contains("scene.test: mesh 0 \"tri\": 2 non-finite vertex position(s); 2 triangle(s)"),
        "{w}"
    );
    // Every triangle bad: the mesh is removed, and with nothing left that is an error.
    let mut d = scene();
    d.meshes[0].positions[2] = Vec3::new(0.0, f32::NAN, 0.0);
    let (k, msg) = err_kind(d);
    assert_eq!(k, LoadErrorKind::NoTriangles);
    assert!(msg.contains("scene.test"), "{msg}");
}

#[test]
fn bad_normals_and_uvs_are_repaired() {
    let mut d = scene();
    d.meshes[0].normals = vec![Vec3::Z, Vec3::new(f32::INFINITY, 0.0, 0.0), Vec3::Z];
    d.meshes[0].uvs = vec![Vec2::ZERO, Vec2::new(f32::NAN, 1.0), Vec2::ONE];
    let (d, w) = warnings(d);
    // The bad normal is replaced by the face normal (+z for the CCW triangle in z = 0).
    assert_eq!(d.meshes[0].normals, vec![Vec3::Z; 3]);
    assert_eq!(d.meshes[0].uvs[1], Vec2::ZERO);
    assert!(
        w.contains("normals") && w.contains("texture coordinate"),
        "{w}"
    );
}

#[test]
fn degenerate_triangles_dropped_and_empty_meshes_removed() {
    let mut d = scene();
    d.meshes[0].indices.push([0, 0, 1]);
    d.meshes[0].positions.push(Vec3::new(2.0, 0.0, 0.0)); // collinear with 0 and 1
    d.meshes[0].indices.push([0, 1, 3]);
    d.meshes.push(MeshDesc {
        name: "flat".into(),
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
        indices: vec![[0, 1, 2]],
        ..MeshDesc::default()
    });
    let (d, w) = warnings(d);
    assert_eq!(d.meshes.len(), 1);
    assert_eq!(d.meshes[0].indices, vec![[0, 1, 2]]);
    assert!(
        w.contains("mesh 0 \"tri\": dropped 2 degenerate")
            && w.contains("flat: dropped 1 degenerate")
            && w.contains("removed: flat"),
        "{w}"
    );
    // Tiny but valid triangles survive (area computed in f64).
    let mut d = scene();
    d.meshes[0].positions = vec![Vec3::ZERO, Vec3::X * 1e-25, Vec3::Y * 1e-25];
    assert_eq!(validate(d).expect("valid").meshes[0].indices.len(), 1);
}

#[test]
fn no_triangles() {
    let mut d = scene();
    d.meshes[0].indices = vec![[1, 1, 2]];
    let (k, msg) = err_kind(d);
    assert_eq!(k, LoadErrorKind::NoTriangles);
    assert!(msg.contains("scene.test"), "{msg}");
    let mut d = scene();
    d.meshes.clear();
    assert_eq!(err_kind(d).0, LoadErrorKind::NoTriangles);
}

#[test]
fn too_large() {
    // 2^28 real triangles would take gigabytes: check the counting rule directly.
    let src = std::path::Path::new("big.obj");
    let max = super::MAX_ELEMENTS;
    assert!(super::check_counts(src, max, max).is_ok());
    for (t, v) in [(max + 1, 3), (1, max + 1)] {
        let e = super::check_counts(src, t, v).expect_err("too large");
        assert_eq!(e.kind, LoadErrorKind::TooLarge);
        assert!(e.to_string().contains("big.obj"));
    }
}

#[test]
fn ior_rules() {
    for bad in [f32::NAN, f32::INFINITY, -1.5] {
        let mut d = scene();
        d.materials[0].ior = bad;
        let (k, msg) = err_kind(d);
        assert_eq!(k, LoadErrorKind::InvalidIor);
        assert!(msg.contains("\"glass\""), "{msg}");
    }
    for fine in [0.0, 1.0, 2.42] {
        let mut d = scene();
        d.materials[0].ior = fine;
        let (_, w) = warnings(d);
        assert!(w.is_empty(), "{w}");
    }
    let mut d = scene();
    d.materials[0].ior = 0.75;
    let (_, w) = warnings(d);
    assert!(w.contains("\"glass\"") && w.contains("bubble"), "{w}");
}

#[test]
fn cauchy_rules() {
    let mut d = scene();
    d.materials[0].ior_model = Some(ExplicitIor::Cauchy { b: 1.5, c: 0.0042 });
    assert!(validate(d).is_ok());
    for (b, c) in [
        (0.0, 0.0),
        (1.5, -0.1),
        (f32::NAN, 0.0),
        (1.5, f32::INFINITY),
    ] {
        let mut d = scene();
        d.materials[0].ior_model = Some(ExplicitIor::Cauchy { b, c });
        assert_eq!(err_kind(d).0, LoadErrorKind::InvalidIor, "b={b} c={c}");
    }
}

#[test]
fn glass_names_resolve_or_fail_naming_the_material() {
    use crate::spectrum::IorModel;
    let mut d = scene();
    d.materials[0].ior_model = Some(ExplicitIor::Glass("n-bk7".into()));
    let (d, w) = warnings(d);
    assert!(w.is_empty(), "{w}");
    let model = d.materials[0].spectral_ior().expect("known");
    assert_eq!(model, IorModel::named("N-BK7").expect("catalogue"));
    let mut d = scene();
    d.materials[0].ior_model = Some(ExplicitIor::Glass("BK-7x".into()));
    let (k, msg) = err_kind(d);
    assert_eq!(k, LoadErrorKind::InvalidIor);
    assert!(
        msg.contains("\"glass\"") && msg.contains("BK-7x") && msg.contains("N-SF11"),
        "{msg}"
    );
}

#[test]
fn ior_zero_disables_dispersion_with_a_warning() {
    use crate::spectrum::IorModel;
    let explicit = [
        None,
        Some(ExplicitIor::Glass("diamond".into())),
        Some(ExplicitIor::Cauchy { b: 1.5, c: 0.0042 }),
    ];
    for model in explicit {
        let mut d = scene();
        d.materials[0].ior = 0.0;
        d.materials[0].dispersion = 0.36;
        d.materials[0].ior_model = model.clone();
        let (d, w) = warnings(d);
        assert!(
            w.contains("\"glass\"") && w.contains("ior 0"),
            "{model:?}: {w}"
        );
        let resolved = d.materials[0].spectral_ior().expect("resolves");
        assert_eq!(resolved, IorModel::Constant(f32::INFINITY), "{model:?}");
        assert!(!resolved.is_dispersive());
    }
}

#[test]
fn non_finite_material_values_are_errors() {
    let cases: [fn(&mut MaterialDesc); 5] = [
        |m| m.roughness = f32::NAN,
        |m| m.base_color.w = f32::NAN,
        |m| m.emissive.y = f32::INFINITY,
        |m| m.specular_color.x = f32::NAN,
        |m| m.alpha_mode = AlphaMode::Mask(f32::NAN),
    ];
    for (i, set) in cases.iter().enumerate() {
        let mut d = scene();
        set(&mut d.materials[0]);
        let (k, msg) = err_kind(d);
        assert_eq!(k, LoadErrorKind::InvalidValue, "case {i}");
        assert!(msg.contains("\"glass\""), "{msg}");
    }
    let mut d = scene();
    d.materials[0].roughness = f32::NAN;
    assert!(err_kind(d).1.contains("roughness"));
}

#[test]
fn out_of_range_factors_are_clamped_with_warning() {
    let mut d = scene();
    let m = &mut d.materials[0];
    m.roughness = 1.5;
    m.metallic = -0.5;
    m.base_color = Vec4::new(2.0, 0.5, 0.5, 1.0);
    m.attenuation_color = Vec3::new(0.5, 1.2, 0.5);
    m.specular_color = Vec3::new(-1.0, 2.0, 1.0);
    let (d, w) = warnings(d);
    let m = &d.materials[0];
    assert_eq!((m.roughness, m.metallic, m.base_color.x), (1.0, 0.0, 1.0));
    assert_eq!(m.attenuation_color.y, 1.0);
    assert_eq!(m.specular_color, Vec3::new(0.0, 2.0, 1.0));
    assert!(
        w.contains("\"glass\"") && w.contains("roughness 1.5 → 1"),
        "{w}"
    );
}

#[test]
fn volume_and_emission_ranges() {
    let cases: [fn(&mut MaterialDesc); 6] = [
        |m| m.attenuation_distance = 0.0,
        |m| m.attenuation_distance = -1.0,
        |m| m.attenuation_distance = f32::NAN,
        |m| m.thickness = -0.1,
        |m| m.dispersion = -1.0,
        |m| m.emissive = Vec3::new(1.0, -1.0, 0.0),
    ];
    for (i, set) in cases.iter().enumerate() {
        let mut d = scene();
        set(&mut d.materials[0]);
        assert_eq!(err_kind(d).0, LoadErrorKind::InvalidValue, "case {i}");
    }
    let mut d = scene();
    d.materials[0].attenuation_distance = f32::INFINITY;
    assert!(validate(d).is_ok());
}

#[test]
fn emission_spectrum_rules() {
    let mut d = scene();
    d.materials[0].emissive = Vec3::splat(2.0);
    d.materials[0].emission_spectrum = Some(EmissionSpectrum::Blackbody { kelvin: 3200.0 });
    let (_, w) = warnings(d);
    assert!(!w.contains("iris_spectrum"), "{w}");
    for kelvin in [500.0, 50_000.0, f32::NAN] {
        let mut d = scene();
        d.materials[0].emissive = Vec3::splat(2.0);
        d.materials[0].emission_spectrum = Some(EmissionSpectrum::Blackbody { kelvin });
        let (k, msg) = err_kind(d);
        assert_eq!(k, LoadErrorKind::InvalidValue);
        assert!(
            msg.contains("\"glass\"") && msg.contains("iris_spectrum"),
            "{msg}"
        );
    }
    // Not emissive: the spectrum does nothing, which is worth a warning, not an error.
    let mut d = scene();
    d.materials[0].emission_spectrum = Some(EmissionSpectrum::D65);
    let (_, w) = warnings(d);
    assert!(
        w.contains("\"glass\": iris_spectrum D65 has no effect"),
        "{w}"
    );
}
