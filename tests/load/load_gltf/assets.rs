//! The shared third-party assets (MANIFEST.md): all load, triangle counts, and the
//! dispersion / volume / IOR values the renderer depends on.

use super::{common, gltf_files, load, material, triangles};
use glam::Vec3;

/// Every shared glTF asset loads; "in scene" triangle counts from MANIFEST.md §1.
#[test]
fn shared_assets_load_with_manifest_triangle_counts() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let mut files = Vec::new();
    gltf_files(&assets, &mut files);
    files.sort();
    assert!(
        files.len() >= 20,
        "expected the 20 glTF assets, found {}",
        files.len()
    );
    for file in &files {
        let desc = load(file);
        assert!(triangles(&desc) > 0, "{}", file.display());
        for mesh in &desc.meshes {
            let n = mesh.positions.len();
            assert!(
                mesh.normals.is_empty() || mesh.normals.len() == n,
                "{}",
                mesh.name
            );
            assert!(mesh.uvs.is_empty() || mesh.uvs.len() == n, "{}", mesh.name);
            assert!(
                mesh.indices.iter().flatten().all(|&i| (i as usize) < n),
                "{}",
                mesh.name
            );
            assert!(
                mesh.material.is_none_or(|m| m < desc.materials.len()),
                "{}",
                mesh.name
            );
        }
        println!(
            "{}: {} triangles, warnings {:?}",
            file.display(),
            triangles(&desc),
            desc.warnings
        );
    }
    let expected = [
        ("khronos/Box/Box.glb", 12),
        ("khronos/BoxTextured/BoxTextured.glb", 12),
        ("khronos/Cube/glTF/Cube.gltf", 12),
        ("khronos/Suzanne/glTF/Suzanne.gltf", 3_936),
        ("khronos/DispersionTest/DispersionTest.glb", 51_827),
        ("khronos/CompareDispersion/CompareDispersion.glb", 66),
        ("khronos/CompareIor/CompareIor.glb", 2_562),
        (
            "khronos/CompareTransmission/CompareTransmission.glb",
            11_778,
        ),
        ("khronos/CompareVolume/CompareVolume.glb", 11_778),
        ("khronos/TransmissionTest/TransmissionTest.glb", 128_775),
        ("khronos/AttenuationTest/AttenuationTest.glb", 292),
        (
            "khronos/TransmissionRoughnessTest/TransmissionRoughnessTest.glb",
            77_792,
        ),
        ("khronos/GlassVaseFlowers/GlassVaseFlowers.glb", 14_036),
        (
            "khronos/GlassHurricaneCandleHolder/GlassHurricaneCandleHolder.glb",
            4_126,
        ),
        ("khronos/GlassBrokenWindow/GlassBrokenWindow.glb", 987),
        ("khronos/SunglassesKhronos/SunglassesKhronos.glb", 13_396),
        ("gems/DiamondLowPoly/diamond.glb", 96),
        ("sketchfab/LowPolyGlassTable/glass-table.glb", 592),
        (
            "blender-io-roundtrip/15_transmission/15_transmission.gltf",
            4_800,
        ),
        ("blender-io-roundtrip/17_ior/17_ior.gltf", 60),
    ];
    for (rel, tris) in expected {
        assert_eq!(triangles(&load(&assets.join(rel))), tris, "{rel}");
    }
}

#[test]
fn dispersion_test_has_the_ior_dispersion_grid() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let desc = load(&assets.join("khronos/DispersionTest/DispersionTest.glb"));
    let iors = [
        ("1.0", 1.0),
        ("1.33", 1.33),
        ("1.50", 1.5),
        ("1.76", 1.76),
        ("2.42", 2.42),
    ];
    let dispersions = [0.0, 0.5, 1.0, 2.0, 5.0];
    let mut prisms = 0;
    for (ior_text, ior) in iors {
        for (column, dispersion) in dispersions.iter().enumerate() {
            // The node (not the material) carries the grid name, e.g. "Prism_IOR2.42_D5".
            let node = format!("\"Prism_IOR{ior_text}_D{}\"", column + 1);
            let mesh = desc
                .meshes
                .iter()
                .find(|m| m.name.contains(&node))
                .expect("prism node");
            let m = &desc.materials[mesh.material.expect("prism material")];
            assert!((m.ior - ior).abs() < 1e-6, "{}: ior {}", m.name, m.ior);
            assert_eq!(m.dispersion, *dispersion, "{}", m.name);
            assert_eq!(m.transmission, 1.0);
            assert!((m.thickness - 0.018478).abs() < 1e-6);
            assert_eq!(m.roughness, 0.0);
            assert_eq!(m.attenuation_distance, f32::INFINITY);
            assert_eq!(mesh.indices.len(), 320);
            prisms += 1;
        }
    }
    assert_eq!(prisms, 25);
    // The 1.5 row has no KHR_materials_ior: the default applies.
    assert_eq!(material(&desc, "Mat_IOR_1.50_D5").ior, 1.5);
    assert_eq!(material(&desc, "Mat_IOR_2.42_D5").dispersion, 5.0);
    assert!(desc.warnings.is_empty(), "{:?}", desc.warnings);
}

#[test]
fn compare_dispersion_attenuation_and_defaults() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let desc = load(&assets.join("khronos/CompareDispersion/CompareDispersion.glb"));
    let (with, without) = (
        material(&desc, "Dispersion"),
        material(&desc, "No Dispersion"),
    );
    assert_eq!((with.dispersion, without.dispersion), (5.0, 0.0));
    for m in [with, without] {
        assert!((m.ior - 2.42).abs() < 1e-6);
        assert_eq!(m.attenuation_distance, 1.0);
        assert_eq!(m.attenuation_color, Vec3::ONE);
        assert_eq!(m.thickness, 0.5);
        assert!(m.transmission_texture.is_some());
    }
    assert!(!desc.images.is_empty());
    for image in &desc.images {
        assert_eq!(image.rgba8.len(), (image.width * image.height * 4) as usize);
    }

    let desc = load(&assets.join("khronos/AttenuationTest/AttenuationTest.glb"));
    let m = material(&desc, "R5_Attenuation_0.25");
    assert_eq!(m.attenuation_color, Vec3::new(0.1, 0.5, 0.9));
    assert_eq!(m.attenuation_distance, 4.0);

    let desc = load(&assets.join("khronos/Box/Box.glb"));
    assert!(desc
        .materials
        .iter()
        .all(|m| m.attenuation_distance == f32::INFINITY));
    assert!(desc
        .materials
        .iter()
        .all(|m| m.ior == 1.5 && m.dispersion == 0.0));

    let desc = load(&assets.join("blender-io-roundtrip/17_ior/17_ior.gltf"));
    assert_eq!(material(&desc, "ior_2_no_transmission").ior, 1.5);
    assert_eq!(material(&desc, "ior_2").ior, 2.0);
    assert_eq!(material(&desc, "ior_1.45").ior, 1.45);
}

#[test]
fn unsupported_extensions_are_warned_once() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    // A real clearcoat file (Sketchfab's low-poly diamond: clearcoat 1) is read, not listed.
    let diamond = load(&assets.join("gems/DiamondLowPoly/diamond.glb"));
    assert!(
        diamond.warnings.iter().all(|w| !w.contains("clearcoat")),
        "{:?}",
        diamond.warnings
    );
    assert!(diamond.materials.iter().any(|m| m.layers.clearcoat == 1.0));
    let (rel, ext) = ("khronos/TransmissionTest/TransmissionTest.glb", "KHR_xmp");
    let desc = load(&assets.join(rel));
    assert_eq!(
        desc.warnings.iter().filter(|w| w.contains(ext)).count(),
        1,
        "{rel}: {:?}",
        desc.warnings
    );
}
