//! The node graph (glTF 2.0 §3.5): scene choice, world transforms, and what nodes carry —
//! meshes, KHR_lights_punctual lights, cameras.
//!
//! - Scene: `scene` if set, else scene 0, else every node that is nobody's child.
//! - World matrix of a node: `parent · local`, local = `matrix` or `T·R·S` (§3.5.2).
//! - Lights (KHR_lights_punctual): position = world translation; direction = world image
//!   of the node's −Z, normalised; intensity and colour are copied unchanged (candela for
//!   point/spot, lux for directional; node scale does not affect intensity); the light's
//!   `extras.iris_spectrum` is read as for materials (`material::iris_spectrum`).
//! - Cameras look down local −Z with +Y up (§3.10); `world_from_camera` keeps the view
//!   direction and up vector but has scale and shear removed (Gram–Schmidt, right-handed).
//! - Environment: the chosen scene's `extras.iris_environment` (an Iris convention) is a
//!   path to an equirectangular `.exr`/`.hdr` map relative to the glTF file's directory
//!   (a plain path, not a URI), a grey radiance `g` or `[r, g, b]` (finite, ≥ 0), or a
//!   computed sky `"sky:elevation=DEG[,azimuth=DEG,turbidity=T]"` (as `--env`,
//!   [`crate::light::sky`]). The map must exist; it is decoded later, when the renderer
//!   builds the environment. Other extras keys are ignored.
//! - Fog: the chosen scene's `extras.iris_fog` is a fog specification as `--fog` takes it
//!   (`"density=0.2,g=0.5"`, `"rayleigh=0.05"`; [`crate::volume::fog`]).
//! - The graph is walked without recursion; a cycle (depth beyond the node count) is a
//!   `Parse` error and runaway instancing a `TooLarge` error, so hostile files end cleanly.
//! - EXT_mesh_gpu_instancing: a node's mesh is placed once per instance
//!   ([`super::instancing`]); each placement is a mesh named `… primitive P instance I`.

use super::instancing::instance_transforms;
use super::mesh::{instantiate, read_primitive, Primitive};
use super::{label, Ctx, Warnings, MAX_TRIANGLES};
use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::{CameraDesc, EnvironmentDesc, LightDesc, Projection, SceneDesc};
use glam::{Mat4, Vec3};
use gltf::json::validation::Checked;
use gltf::khr_lights_punctual::Kind;
use std::collections::HashMap;
use std::rc::Rc;

/// Most node instances a scene may expand to (nodes shared by several parents multiply).
const MAX_NODE_VISITS: usize = 1 << 20;

/// Flattens the chosen scene into `desc.meshes`, `desc.lights` and `desc.cameras`.
pub(super) fn read_scene_graph(
    ctx: &Ctx<'_>,
    desc: &mut SceneDesc,
    warnings: &mut Warnings,
) -> Result<(), LoadError> {
    desc.name = chosen_scene(ctx)
        .and_then(|s| s.name().map(str::to_owned))
        .unwrap_or_default();
    desc.environment = read_environment(ctx)?;
    desc.fog = read_fog(ctx)?;
    let node_count = ctx.doc.nodes().len();
    let mut stack: Vec<(gltf::Node<'_>, Mat4, usize)> = root_nodes(ctx.doc)
        .into_iter()
        .rev()
        .map(|n| (n, Mat4::IDENTITY, 0))
        .collect();
    let mut primitives: HashMap<(usize, usize), Rc<Primitive>> = HashMap::new();
    let (mut visits, mut triangles, mut vertices) = (0usize, 0usize, 0usize);

    while let Some((node, parent, depth)) = stack.pop() {
        let node_label = label("node", node.index(), node.name());
        visits += 1;
        if visits > MAX_NODE_VISITS {
            return Err(ctx.error(
                node_label,
                LoadErrorKind::TooLarge,
                "the node graph expands to over 2^20 node instances",
            ));
        }
        if depth > node_count {
            return Err(ctx.error(
                node_label,
                LoadErrorKind::Parse,
                "the node hierarchy contains a cycle",
            ));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());

        if let Some(mesh) = node.mesh() {
            let mesh_label = format!("{node_label} {}", label("mesh", mesh.index(), mesh.name()));
            let instances = instance_transforms(ctx, &node, world, &node_label)?;
            for prim in mesh.primitives() {
                let element = format!("{mesh_label} primitive {}", prim.index());
                let read = match primitives.get(&(mesh.index(), prim.index())) {
                    Some(read) => Rc::clone(read),
                    None => {
                        let read = Rc::new(read_primitive(ctx, &prim, &element)?);
                        if let Primitive::Triangles(local) = read.as_ref() {
                            if let Some((decoded, declared)) = local.extra_points {
                                warnings.draco_points.push(format!(
                                    "{element} ({decoded} points, accessors say {declared})"
                                ));
                            }
                        }
                        primitives.insert((mesh.index(), prim.index()), Rc::clone(&read));
                        read
                    }
                };
                match read.as_ref() {
                    Primitive::Triangles(local) => {
                        for (i, at) in instances.iter().enumerate() {
                            triangles = triangles.saturating_add(local.triangle_count());
                            vertices = vertices.saturating_add(local.vertex_count());
                            if triangles > MAX_TRIANGLES || vertices > MAX_TRIANGLES {
                                return Err(ctx.error(
                                    element,
                                    LoadErrorKind::TooLarge,
                                    format!(
                                        "the scene exceeds {MAX_TRIANGLES} triangles or vertices"
                                    ),
                                ));
                            }
                            let name = if instances.len() > 1 {
                                format!("{element} instance {i}")
                            } else {
                                element.clone()
                            };
                            desc.meshes.push(instantiate(local, at, name));
                        }
                    }
                    Primitive::Skipped(mode) => warnings
                        .skipped_primitives
                        .push(format!("{element} ({mode})")),
                    Primitive::NoPosition => warnings.no_position.push(element),
                }
            }
        }
        if let Some(light) = node.light() {
            desc.lights
                .push(light_desc(ctx, &node, &node_label, &light, &world)?);
        }
        if let Some(camera) = node.camera() {
            desc.cameras.push(camera_desc(
                ctx,
                &node,
                &node_label,
                camera.index(),
                &world,
            )?);
        }
        let children: Vec<_> = node.children().collect();
        stack.extend(
            children
                .into_iter()
                .rev()
                .map(|child| (child, world, depth + 1)),
        );
    }
    Ok(())
}

/// The root nodes of the scene to render.
fn root_nodes(doc: &gltf::Document) -> Vec<gltf::Node<'_>> {
    if let Some(scene) = doc.default_scene().or_else(|| doc.scenes().next()) {
        return scene.nodes().collect();
    }
    let mut is_child = vec![false; doc.nodes().len()];
    for node in doc.nodes() {
        for child in node.children() {
            if let Some(flag) = is_child.get_mut(child.index()) {
                *flag = true;
            }
        }
    }
    doc.nodes()
        .filter(|n| !is_child.get(n.index()).copied().unwrap_or(true))
        .collect()
}

/// The scene the file asks for (`scene`), else its first; `None` if it has none.
fn chosen_scene<'a>(ctx: &Ctx<'a>) -> Option<gltf::Scene<'a>> {
    ctx.doc.default_scene().or_else(|| ctx.doc.scenes().next())
}

/// The chosen scene's label and the value of its extras key `key`
/// ([`super::extras::extras_key`]), if it has one.
fn scene_key(ctx: &Ctx<'_>, key: &str) -> Result<Option<(String, serde_json::Value)>, LoadError> {
    let Some(scene) = chosen_scene(ctx) else {
        return Ok(None);
    };
    let name = label("scene", scene.index(), scene.name());
    let value = super::extras::extras_key(ctx, scene.extras(), &name, key)?;
    Ok(value.map(|v| (name, v)))
}

/// The chosen scene's `extras.iris_fog`: a fog specification string as `--fog` takes
/// ([`crate::volume::fog`]).
fn read_fog(ctx: &Ctx<'_>) -> Result<Option<crate::volume::Medium>, LoadError> {
    let Some((scene, value)) = scene_key(ctx, "iris_fog")? else {
        return Ok(None);
    };
    let element = format!("{scene} extras.iris_fog");
    let spec = value.as_str().ok_or_else(|| {
        ctx.error(
            &element,
            LoadErrorKind::InvalidValue,
            format!("{value} is not a fog specification string"),
        )
    })?;
    crate::volume::fog::parse(spec).map(Some).map_err(|why| {
        ctx.error(
            &element,
            LoadErrorKind::InvalidValue,
            format!("{spec:?}: {why}"),
        )
    })
}

/// The chosen scene's `extras.iris_environment`, checked (see the module docs).
fn read_environment(ctx: &Ctx<'_>) -> Result<Option<EnvironmentDesc>, LoadError> {
    let Some((scene, value)) = scene_key(ctx, "iris_environment")? else {
        return Ok(None);
    };
    let value = &value;
    let element = format!("{scene} extras.iris_environment");
    let err = |kind, detail: String| ctx.error(element.as_str(), kind, detail);
    let radiance = |v: &serde_json::Value| {
        v.as_f64()
            .map(|x| x as f32)
            .filter(|x| x.is_finite() && *x >= 0.0)
    };
    use serde_json::Value;
    let env = match value {
        Value::String(s) if s.starts_with("sky:") => {
            let params = crate::light::sky::SkyParams::parse(&s["sky:".len()..])
                .map_err(|why| err(LoadErrorKind::InvalidValue, format!("{s:?}: {why}")))?;
            EnvironmentDesc::Sky(params)
        }
        Value::String(file) if !file.is_empty() => {
            let path = ctx.base_dir.join(file);
            let ext = path
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            if !matches!(ext.as_deref(), Some("exr" | "hdr")) {
                return Err(err(
                    LoadErrorKind::Unsupported,
                    format!("{file:?}: environment maps must be .exr or .hdr (equirectangular)"),
                ));
            }
            let kind = match ext.as_deref() {
                Some("exr") => crate::fileio::Input::Exr,
                _ => crate::fileio::Input::Image,
            };
            if let Err(e) = ctx.files.check(&path, kind) {
                return Err(err(e.kind, format!("{}: {e}", path.display())));
            }
            EnvironmentDesc::Map(path)
        }
        Value::Number(_) => {
            let g = radiance(value).ok_or_else(|| {
                err(
                    LoadErrorKind::InvalidValue,
                    format!("grey radiance must be finite and ≥ 0, found {value}"),
                )
            })?;
            EnvironmentDesc::Uniform(Vec3::splat(g))
        }
        Value::Array(items) if items.len() == 3 => {
            let rgb: Option<Vec<f32>> = items.iter().map(radiance).collect();
            let rgb = rgb.ok_or_else(|| {
                err(
                    LoadErrorKind::InvalidValue,
                    format!("[r, g, b] must be finite numbers ≥ 0, found {value}"),
                )
            })?;
            EnvironmentDesc::Uniform(Vec3::new(rgb[0], rgb[1], rgb[2]))
        }
        _ => {
            return Err(err(
                LoadErrorKind::InvalidValue,
                format!("expected a .exr/.hdr file name, \"sky:elevation=DEG,…\", a grey value or [r, g, b], found {value}"),
            ))
        }
    };
    Ok(Some(env))
}

/// The first of the given names, else `fallback`.
fn pick_name(names: &[Option<&str>], fallback: String) -> String {
    names
        .iter()
        .flatten()
        .next()
        .map_or(fallback, |n| (*n).to_string())
}

fn light_desc(
    ctx: &Ctx<'_>,
    node: &gltf::Node<'_>,
    node_label: &str,
    light: &gltf::khr_lights_punctual::Light<'_>,
    world: &Mat4,
) -> Result<LightDesc, LoadError> {
    let name = pick_name(
        &[light.name(), node.name()],
        format!("light {}", light.index()),
    );
    let position = world.transform_point3(Vec3::ZERO);
    let color = Vec3::from(light.color());
    let intensity = light.intensity();
    let spectrum = super::material::iris_spectrum(
        ctx,
        light.extras(),
        &label("light", light.index(), light.name()),
    )?;
    let direction = || {
        crate::math::unit_direction(world.as_dmat4().transform_vector3(glam::DVec3::NEG_Z))
            .map_err(|why| {
                ctx.error(
                    format!(
                        "{node_label} {}",
                        label("light", light.index(), light.name())
                    ),
                    LoadErrorKind::InvalidValue,
                    format!(
                        "the node transform gives the light no direction: its −Z {why}                          (a zero or non-finite scale)"
                    ),
                )
            })
    };
    Ok(match light.kind() {
        Kind::Point => LightDesc::Point {
            name,
            position,
            color,
            intensity,
            range: light.range(),
            spectrum,
        },
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => LightDesc::Spot {
            name,
            position,
            direction: direction()?,
            color,
            intensity,
            range: light.range(),
            inner_cone: inner_cone_angle,
            outer_cone: outer_cone_angle,
            spectrum,
        },
        Kind::Directional => LightDesc::Directional {
            name,
            direction: direction()?,
            color,
            intensity,
            spectrum,
        },
    })
}

fn camera_desc(
    ctx: &Ctx<'_>,
    node: &gltf::Node<'_>,
    node_label: &str,
    index: usize,
    world: &Mat4,
) -> Result<CameraDesc, LoadError> {
    let json = ctx.doc.as_json().cameras.get(index);
    let camera_name = json.and_then(|c| c.name.as_deref());
    let element = format!("{node_label} {}", label("camera", index, camera_name));
    let json = json.ok_or_else(|| {
        ctx.error(
            element.as_str(),
            LoadErrorKind::IndexOutOfRange,
            "no such camera",
        )
    })?;
    // Read from the JSON: the typed accessor unwraps a projection object that may be absent.
    let projection = match (&json.type_, &json.perspective, &json.orthographic) {
        (Checked::Valid(gltf::json::camera::Type::Perspective), Some(p), _) => {
            Projection::Perspective {
                yfov: p.yfov,
                aspect: p.aspect_ratio,
            }
        }
        (Checked::Valid(gltf::json::camera::Type::Orthographic), _, Some(o)) => {
            Projection::Orthographic {
                xmag: o.xmag,
                ymag: o.ymag,
            }
        }
        _ => {
            return Err(ctx.error(
                element,
                LoadErrorKind::Parse,
                "camera type has no matching perspective/orthographic object",
            ))
        }
    };
    let world_from_camera = rigid(world).ok_or_else(|| {
        ctx.error(
            element.as_str(),
            LoadErrorKind::InvalidValue,
            "the node transform is degenerate (zero scale); cannot orient the camera",
        )
    })?;
    Ok(CameraDesc {
        name: pick_name(&[camera_name, node.name()], format!("camera {index}")),
        projection,
        world_from_camera,
    })
}

/// `m` without scale or shear: keeps the −Z (view) axis and the +Y (up) axis direction,
/// makes X = Y × Z, keeps the translation. The axes are normalised safely
/// ([`crate::math::unit_direction`]), so any finite non-zero scale works; `None` if the
/// axes are degenerate (a zero scale, or Y along Z).
fn rigid(m: &Mat4) -> Option<Mat4> {
    let unit = |v: Vec3| crate::math::unit_direction(v.as_dvec3()).ok();
    let z = unit(m.z_axis.truncate())?;
    let y_in = unit(m.y_axis.truncate())?;
    let y = (y_in - z * y_in.dot(z)).try_normalize()?;
    let x = y.cross(z);
    Some(Mat4::from_cols(
        x.extend(0.0),
        y.extend(0.0),
        z.extend(0.0),
        m.w_axis.truncate().extend(1.0),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn rigid_removes_scale_and_keeps_orientation() {
        let rot = Quat::from_rotation_y(0.7);
        let m = Mat4::from_scale_rotation_translation(
            Vec3::new(2.0, 3.0, 0.5),
            rot,
            Vec3::new(1.0, 2.0, 3.0),
        );
        let r = rigid(&m).unwrap_or(Mat4::ZERO);
        let expected = Mat4::from_rotation_translation(rot, Vec3::new(1.0, 2.0, 3.0));
        assert!(r.abs_diff_eq(expected, 1e-5));
        assert!(rigid(&Mat4::from_scale(Vec3::ZERO)).is_none());
    }
}
