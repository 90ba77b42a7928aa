//! `iris info`: what Iris reads from a scene file (meshes, triangles, materials with their
//! KHR values, lights, cameras, the environment, warnings) and the render plan that
//! `iris render FILE` would follow with default flags, with its costs measured. Values are
//! printed in the file's units (lights: candela / lux, as KHR_lights_punctual).
//!
//! Each section of the text is written by its own function, in the order printed: header,
//! meshes, materials, lights (with the file's environment), cameras, warnings, render plan.
//! With `--stone` / `--metal` the description is the one after those overrides (as
//! `iris render` sees it); without, a file with no transmissive material gets a note
//! suggesting `--stone` and naming the materials it would change.

use crate::accel::Backend;
use crate::camera::Camera;
use crate::error::Result;
use crate::integrator::Method;
use crate::material::MaterialDesc;
use crate::plan::SpectralMode;
use crate::prepare::looks::{self, LookFlag};
use crate::scene::desc::{CameraDesc, EnvironmentDesc, LightDesc, Projection, SceneDesc};
use std::fmt::Write as _;
use std::path::Path;

/// `iris info`: a human-readable description of the scene.
pub fn info_command(path: &Path) -> Result<String> {
    info_command_with(path, &[])
}

/// `iris info` with `--stone` / `--metal` flags: the scene as `iris render` with those flags
/// sees it ([`crate::prepare::looks`]).
pub fn info_command_with(path: &Path, flags: &[LookFlag]) -> Result<String> {
    let mut desc = crate::load::load_scene(path)?;
    let applied = looks::apply(&mut desc, flags)?;
    let mut s = String::new();
    write_header(&mut s, path, &desc);
    write_meshes(&mut s, &desc);
    write_materials(&mut s, &desc.materials);
    write_lights(&mut s, &desc);
    write_cameras(&mut s, &desc.cameras);
    write_warnings(&mut s, &desc.warnings);
    match info_plan(path, flags) {
        Ok(plan) => s.push_str(&plan),
        Err(e) => {
            let _ = writeln!(s, "render plan: unavailable ({e})");
        }
    }
    for a in &applied {
        let _ = writeln!(s, "note: {a}");
    }
    if flags.is_empty() {
        if let Some(hint) = stone_hint(&desc) {
            let _ = writeln!(s, "note: {hint}");
        }
    }
    Ok(s)
}

/// The `--stone` suggestion for a file whose meshes use no transmissive material (an
/// artist's gem with a viewer's placeholder material), naming the materials a bare
/// `--stone diamond` would change; `None` when some mesh is transmissive.
fn stone_hint(desc: &SceneDesc) -> Option<String> {
    let used: Vec<&MaterialDesc> = desc
        .materials
        .iter()
        .enumerate()
        .filter(|(i, _)| desc.meshes.iter().any(|m| m.material == Some(*i)))
        .map(|(_, m)| m)
        .filter(|m| !looks::is_emitter(m))
        .collect();
    if used
        .iter()
        .any(|m| m.transmission > 0.0 && m.metallic < 1.0)
    {
        return None;
    }
    let mut names: Vec<&str> = used.iter().take(4).map(|m| m.name.as_str()).collect();
    if desc.meshes.iter().any(|m| m.material.is_none()) {
        names.push("the default material");
    }
    if used.len() > 4 {
        names.push("…");
    }
    let one = match used.len() {
        0 | 1 => String::new(),
        _ => " (`--stone diamond=NAME` for one of them, `--metal gold=NAME` for a setting)"
            .to_string(),
    };
    Some(format!(
        "no transmissive material: if this is a gem, `--stone diamond` makes {} a diamond{one}; \
         stones: {}",
        names.join(", "),
        looks::stone_names()
    ))
}

/// `FILE: N meshes, T triangles`, then what was compressed, if anything.
fn write_header(s: &mut String, path: &Path, desc: &SceneDesc) {
    let tris: usize = desc.meshes.iter().map(|m| m.indices.len()).sum();
    let _ = writeln!(
        s,
        "{}: {} meshes, {} triangles",
        path.display(),
        desc.meshes.len(),
        tris
    );
    let c = desc.compressed;
    if c.draco_primitives > 0 || c.meshopt_views > 0 {
        let _ = writeln!(
            s,
            "geometry: {} primitives Draco-compressed, {} meshopt-compressed buffer views",
            c.draco_primitives, c.meshopt_views
        );
    }
}

/// `meshes:`, one line per mesh: triangle count and material name.
fn write_meshes(s: &mut String, desc: &SceneDesc) {
    let _ = writeln!(s, "meshes:");
    for m in &desc.meshes {
        let mat = m
            .material
            .and_then(|i| desc.materials.get(i))
            .map_or("default material", |x| &x.name);
        let _ = writeln!(s, "  {}: {} triangles, {}", m.name, m.indices.len(), mat);
    }
}

/// `materials:`, one line per material ([`write_material`]).
fn write_materials(s: &mut String, materials: &[MaterialDesc]) {
    let _ = writeln!(s, "materials:");
    for m in materials {
        write_material(s, m);
    }
}

/// One material's line: the metallic-roughness values, then only the KHR extensions and
/// Iris extras that differ from their defaults.
fn write_material(s: &mut String, m: &MaterialDesc) {
    let ior = crate::material::describe_ior(m);
    let _ = write!(
        s,
        "  {}: base [{:.3} {:.3} {:.3} {:.3}] metallic {} roughness {} ior {} transmission {}",
        m.name,
        m.base_color.x,
        m.base_color.y,
        m.base_color.z,
        m.base_color.w,
        m.metallic,
        m.roughness,
        ior,
        m.transmission
    );
    if m.thickness > 0.0 || m.attenuation_distance.is_finite() {
        let _ = write!(
            s,
            " volume(thickness {} attenuation [{:.3} {:.3} {:.3}] over {})",
            m.thickness,
            m.attenuation_color.x,
            m.attenuation_color.y,
            m.attenuation_color.z,
            m.attenuation_distance
        );
    }
    let extensions = m.describe_extensions();
    if !extensions.is_empty() {
        let _ = write!(s, " {extensions}");
    }
    if let Some(metal) = m.conductor {
        let (n, k) = metal.eta_k(crate::spectrum::ior::LAMBDA_D);
        let _ = write!(
            s,
            " measured metal {} (n {n:.3}, k {k:.3} at 587.6 nm)",
            metal.name()
        );
    }
    if let Some(optics) = crate::material::crystal::describe_optics(m) {
        let _ = write!(s, " {optics}");
    }
    if let Some(a) = m.polarizer {
        let _ = write!(
            s,
            " polarizer sheet (axis [{:.3} {:.3} {:.3}])",
            a.x, a.y, a.z
        );
    }
    if m.priority != 0 {
        let _ = write!(s, " priority {}", m.priority);
    }
    if m.specular != 1.0 || m.specular_color != glam::Vec3::ONE {
        let _ = write!(
            s,
            " specular {} color {:?}",
            m.specular,
            m.specular_color.to_array()
        );
    }
    let l = &m.layers;
    if l.clearcoat > 0.0 {
        let _ = write!(
            s,
            " clearcoat {} roughness {}",
            l.clearcoat, l.clearcoat_roughness
        );
    }
    if l.sheen_color != glam::Vec3::ZERO {
        let _ = write!(
            s,
            " sheen {:?} roughness {}",
            l.sheen_color.to_array(),
            l.sheen_roughness
        );
    }
    if l.diffuse_transmission > 0.0 {
        let _ = write!(
            s,
            " diffuse transmission {} color {:?}",
            l.diffuse_transmission,
            l.diffuse_transmission_color.to_array()
        );
    }
    if m.emissive != glam::Vec3::ZERO {
        let _ = write!(s, " emissive {:?}", m.emissive.to_array());
    }
    if let Some(spectrum) = m.emission_spectrum {
        let _ = write!(s, " {}", spectrum_note(spectrum));
    }
    let _ = writeln!(s);
}

/// `lights:`: the emissive meshes, a note when the file has no light at all, each punctual
/// light ([`light_line`]) and the file's environment.
fn write_lights(s: &mut String, desc: &SceneDesc) {
    let _ = writeln!(s, "lights:");
    let emitters = desc
        .meshes
        .iter()
        .filter(|m| {
            m.material
                .and_then(|i| desc.materials.get(i))
                .is_some_and(|x| x.emissive.max_element() > 0.0)
        })
        .count();
    if emitters > 0 {
        let _ = writeln!(s, "  {emitters} emissive meshes (sampled as area lights)");
    }
    if desc.lights.is_empty() && emitters == 0 && desc.environment.is_none() {
        let _ = writeln!(
            s,
            "  none (renders use the studio lighting of --studio, default soft, or --env)"
        );
    }
    for l in &desc.lights {
        let line = light_line(l);
        match l.spectrum() {
            Some(spectrum) => {
                let _ = writeln!(s, "  {line}, {}", spectrum_note(spectrum));
            }
            None => {
                let _ = writeln!(s, "  {line}");
            }
        }
    }
    write_environment(s, desc.environment.as_ref());
}

/// A punctual light in the file's units: kind, name, intensity (cd or lx) and placement.
fn light_line(l: &LightDesc) -> String {
    match l {
        LightDesc::Point {
            name,
            position,
            intensity,
            ..
        } => format!(
            "point \"{name}\" {intensity} cd at {:?}",
            position.to_array()
        ),
        LightDesc::Spot {
            name,
            position,
            intensity,
            outer_cone,
            ..
        } => format!(
            "spot \"{name}\" {intensity} cd at {:?}, outer cone {:.1}°",
            position.to_array(),
            outer_cone.to_degrees()
        ),
        LightDesc::Directional {
            name,
            direction,
            intensity,
            ..
        } => format!(
            "directional \"{name}\" {intensity} lx toward {:?}",
            direction.to_array()
        ),
    }
}

/// The file's environment (under `lights:`), if it names one.
fn write_environment(s: &mut String, environment: Option<&EnvironmentDesc>) {
    match environment {
        Some(EnvironmentDesc::Uniform(c)) => {
            let _ = writeln!(
                s,
                "  environment (file): uniform {:?} (--env overrides)",
                c.to_array()
            );
        }
        Some(EnvironmentDesc::Map(p)) => {
            let _ = writeln!(
                s,
                "  environment (file): map {} (--env overrides)",
                p.display()
            );
        }
        Some(EnvironmentDesc::Sky(p)) => {
            let _ = writeln!(
                s,
                "  environment (file): sky, sun at elevation {}°, azimuth {}°, turbidity {} \
                 (--env overrides)",
                p.elevation, p.azimuth, p.turbidity
            );
        }
        None => {}
    }
}

/// `cameras:`, one line per camera (index, name, projection), or how renders frame the
/// model without one.
fn write_cameras(s: &mut String, cameras: &[CameraDesc]) {
    let _ = writeln!(s, "cameras:");
    if cameras.is_empty() {
        let _ = writeln!(
            s,
            "  none (renders frame the model automatically; --view front|top|side|threequarter)"
        );
    }
    for (i, c) in cameras.iter().enumerate() {
        let p = match c.projection {
            Projection::Perspective { yfov, .. } => {
                format!("perspective yfov {:.1}°", yfov.to_degrees())
            }
            Projection::Orthographic { xmag, ymag } => format!("orthographic {xmag}×{ymag}"),
        };
        let _ = writeln!(s, "  {i} \"{}\": {p}", c.name);
    }
}

/// `warnings:` and the loader's warnings, only when there are any.
fn write_warnings(s: &mut String, warnings: &[String]) {
    if !warnings.is_empty() {
        let _ = writeln!(s, "warnings:");
        for w in warnings {
            let _ = writeln!(s, "  {w}");
        }
    }
}

/// The render plan of `iris render SCENE` with default flags and `flags` (auto method, auto spectral,
/// the file's environment), with its costs measured, and what the preparation decided (the
/// notes `iris render` and `iris converge` print), for `iris info`.
fn info_plan(path: &Path, flags: &[LookFlag]) -> Result<String> {
    let (w, h) = crate::plan::PROBE_SIZE;
    let prepared = crate::prepare::prepare(
        path,
        &crate::prepare::PrepareOptions {
            accel: Backend::Auto,
            size: Some((w, h)),
            looks: flags.to_vec(),
            ..Default::default()
        },
    )?;
    let (scene, cam) = (&prepared.scene, &prepared.camera);
    let mut plan = crate::plan::Plan::new(scene, &cam.projection, Method::Auto, SpectralMode::Auto);
    plan.decide_polarization(
        scene,
        (Default::default(), None),
        (Method::Auto, SpectralMode::Auto),
    )?;
    // `iris render`'s default output is a PNG under --denoise auto.
    let denoise = crate::denoise::mode::choose(Default::default(), Path::new("render.png"))?;
    plan.stages.push(denoise.stage());
    // And its default budget: the error target or the time limit ends it.
    let budget = super::budget::Budget::default();
    let adaptive = super::adaptive::choose(
        super::adaptive::AdaptiveFlags {
            mode: Default::default(),
            open: budget.open,
            target: budget
                .target_error
                .map(|_| super::budget::default_target(true)),
            shard: false,
            media: scene.has_media(),
        },
        plan.method,
    )?;
    plan.stages.push(adaptive.stage());
    plan.add_file_counts(path);
    plan.measure_costs(scene, &Camera::new(cam, w, h), 0)?;
    let mut s = format!(
        "{}  (the plan for --method auto, `iris render`'s default method)\n",
        plan.text_with_costs()
    );
    for n in prepared.notes() {
        let _ = writeln!(s, "note: {n}");
    }
    Ok(s)
}

/// `spectrum D65 (sRGB [1.000 1.000 1.000])`: an emitter's `iris_spectrum` and the colour
/// the RGB renderer gives it (luminance 1, before the file's colour filter).
fn spectrum_note(spectrum: crate::spectrum::EmissionSpectrum) -> String {
    let c = spectrum.linear_srgb();
    format!(
        "spectrum {spectrum} (sRGB [{:.3} {:.3} {:.3}])",
        c.x, c.y, c.z
    )
}
