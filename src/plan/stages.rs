//! The stages of the render plan, one function each: what the scene holds that decides the
//! stage, and the reason line naming that evidence (material and mesh names, counts). The
//! order and meaning of the stages are the parent module's.

use super::{SpectralMode, Stage, CAUSTIC_PROBE_PHOTONS};
use crate::integrator::capability::Photons;
use crate::integrator::path::LaneWidth;
use crate::integrator::Method;
use crate::light::env::Environment;
use crate::material::Material;
use crate::photon::emit::{PhotonEmitter, DEFAULT_AIM};
use crate::photon::probe::has_caustic_paths;
use crate::scene::{Scene, Triangle};
use std::collections::BTreeSet;
use std::fmt::Write as _;

/// The scene and the materials some triangle uses (ascending): what every stage looks at.
pub(super) struct Evidence<'a> {
    pub scene: &'a Scene,
    used: BTreeSet<usize>,
}

impl<'a> Evidence<'a> {
    pub fn new(scene: &'a Scene) -> Self {
        let used = scene
            .triangles()
            .iter()
            .map(|t| t.material() as usize)
            .collect();
        Evidence { scene, used }
    }

    /// The materials some triangle uses.
    fn materials(&self) -> impl Iterator<Item = &'a Material> + '_ {
        self.used
            .iter()
            .filter_map(|&i| self.scene.materials().get(i))
    }

    /// Names of the used materials for which `f` holds.
    fn mats(&self, f: impl Fn(&Material) -> bool) -> Vec<&'a str> {
        self.materials()
            .filter(|m| f(m))
            .map(|m| m.desc.name.as_str())
            .collect()
    }
}

/// Up to three names (as the loader gives them), then "and N more".
fn names<'a>(list: impl IntoIterator<Item = &'a str>) -> String {
    let all: Vec<&str> = list.into_iter().collect();
    let mut s: Vec<String> = all.iter().take(3).map(|n| n.to_string()).collect();
    if all.len() > 3 {
        s.push(format!("and {} more", all.len() - 3));
    }
    s.join(", ")
}

/// Transport: spectral or RGB, and the materials and lights that decide it.
pub(super) fn transport(
    ev: &Evidence,
    (spectral, spectral_on): (SpectralMode, bool),
    method: Method,
) -> Stage {
    let (scene, mats) = (ev.scene, |f: &dyn Fn(&Material) -> bool| ev.mats(f));
    let dispersive = mats(&|m: &Material| m.is_dispersive());
    let metals = mats(&|m: &Material| m.conductor().is_some());
    let spectral_emitters = mats(&|m: &Material| m.emitter_shape().is_some());
    let spectral_lights = scene.lights().iter().filter(|l| l.shape.is_some()).count();
    let iridescent = mats(&|m: &Material| m.desc.is_iridescent());
    let mut evidence = Vec::new();
    if !iridescent.is_empty() {
        evidence.push(format!("iridescent materials {}", names(iridescent)));
    }
    if !dispersive.is_empty() {
        evidence.push(format!("dispersive materials {}", names(dispersive)));
    }
    if !metals.is_empty() {
        evidence.push(format!("measured metals {}", names(metals)));
    }
    if !spectral_emitters.is_empty() {
        evidence.push(format!("spectral emitters {}", names(spectral_emitters)));
    }
    if spectral_lights > 0 {
        evidence.push(format!("{spectral_lights} lights naming a spectrum"));
    }
    if super::chromatic_media(scene) {
        evidence.push(match method.caps().rayleigh_spectral.why_not() {
            Some(why) => format!(
                "a medium scattering by Rayleigh's λ⁻⁴ law, which --method {} {why}",
                method.name()
            ),
            None => "a medium scattering by Rayleigh's λ⁻⁴ law".into(),
        });
    }
    let evidence = if evidence.is_empty() {
        "no dispersive material, spectral emitter, spectral light or Rayleigh medium".to_string()
    } else {
        evidence.join("; ")
    };
    let reason = match (spectral, spectral_on) {
        (SpectralMode::On, _) => format!("spectral (--spectral on); {evidence}"),
        (SpectralMode::Off, _) => format!("RGB (--spectral off); {evidence}"),
        (SpectralMode::Auto, true) => format!("spectral: {evidence}"),
        (SpectralMode::Auto, false) => format!("RGB: {evidence}"),
    };
    Stage {
        name: "transport",
        used: spectral_on,
        reason,
        cost: None,
    }
}

/// Photons: whether the method traces photons, and the caustic evidence.
/// `why` is the `--method auto` decision's reason ([`super::resolve_method`]), appended.
pub(super) fn photons(ev: &Evidence, method: Method, resolved: Method, why: Option<&str>) -> Stage {
    let (scene, mats) = (ev.scene, |f: &dyn Fn(&Material) -> bool| ev.mats(f));
    let emitter = PhotonEmitter::new(scene);
    let caustics = if method == Method::Auto {
        // Auto picks these only on a caustic path found by the same probe.
        matches!(resolved, Method::Hybrid | Method::Vcm | Method::Sppm)
    } else {
        !emitter.is_empty() && has_caustic_paths(scene, &emitter, CAUSTIC_PROBE_PHOTONS)
    };
    let specular = mats(&crate::photon::aim::is_caustic_maker);
    let aimed = match emitter.targets().spheres().len() {
        0 => String::new(),
        n => format!(
            ", {:.0} % aimed at {n} bounding sphere(s) of the caustic makers",
            DEFAULT_AIM.fraction() * 100.0
        ),
    };
    let evidence = if caustics {
        format!(
            "caustic paths: probe photons ({CAUSTIC_PROBE_PHOTONS}{aimed}) reach a diffuse \
                     surface after specular bounces only; transmissive or metallic materials {}",
            names(specular)
        )
    } else if specular.is_empty() {
        "no transmissive or metallic material on any triangle: no caustic paths".to_string()
    } else {
        format!(
            "no caustic path among {CAUSTIC_PROBE_PHOTONS} probe photons{aimed} (transmissive \
                     or metallic materials {})",
            names(specular)
        )
    };
    let photons_used = resolved.caps().photons != Photons::None;
    let how = if method == Method::Auto {
        format!("--method auto -> {}", resolved.name())
    } else {
        format!("--method {}", resolved.name())
    };
    Stage {
        name: "photons",
        used: photons_used,
        reason: match why
            .filter(|_| resolved != Method::Path)
            .and_then(|w| w.strip_prefix("--method auto: "))
            .map(|w| w.strip_prefix("no caustic paths found; ").unwrap_or(w))
        {
            Some(w) => format!("{how}: {evidence}; {w}"),
            None => format!("{how}: {evidence}"),
        },
        cost: None,
    }
}

/// Volumes: the materials on triangles with Beer–Lambert attenuation ([`Material::absorbs`]).
pub(super) fn volumes(ev: &Evidence) -> Stage {
    let mats = |f: &dyn Fn(&Material) -> bool| ev.mats(f);
    let attenuating: Vec<String> = ev
        .materials()
        .filter(|m| m.absorbs())
        .map(|m| format!("{} over {}", m.desc.name, m.desc.attenuation_distance))
        .collect();
    let clear = mats(&|m: &Material| m.is_volume() && !m.absorbs()).len();
    Stage {
        name: "volumes",
        used: !attenuating.is_empty(),
        reason: if attenuating.is_empty() {
            format!(
                "Beer-Lambert never evaluated: no material on a triangle absorbs (a finite \
                         attenuation distance with a colour other than white; {clear} clear \
                         volumetric materials)"
            )
        } else {
            let n = attenuating.len();
            let mut list: Vec<String> = attenuating.into_iter().take(3).collect();
            if n > 3 {
                list.push(format!("and {} more", n - 3));
            }
            format!("Beer-Lambert attenuation in {}", list.join(", "))
        },
        cost: None,
    }
}

/// Scattering media: what scatters, and how the path tracer treats it.
pub(super) fn media(scene: &Scene) -> Stage {
    let used = scene.has_media();
    Stage {
        name: "media",
        used,
        reason: if used {
            format!(
                "volumetric path tracing (free-flight sampling with spectral MIS, next-event \
                 estimation from inside media, shadow rays through index-matched boundaries) \
                 in {}",
                crate::shading::media::summary(scene)
            )
        } else {
            "no scattering medium and no fog: rays cross air and volumes without sampling \
             distances"
                .into()
        },
        cost: None,
    }
}

/// Textures: decoded images against the images materials on triangles reference.
pub(super) fn textures(ev: &Evidence) -> Stage {
    let scene = ev.scene;
    let mut referenced = BTreeSet::new();
    for m in ev.materials() {
        let d = &m.desc;
        for t in [
            d.base_color_texture,
            d.metallic_roughness_texture,
            d.emissive_texture,
            d.transmission_texture,
        ]
        .into_iter()
        .flatten()
        {
            referenced.insert(t.image);
        }
    }
    let decoded = scene.images().len();
    let mut reason = format!(
        "{} of {decoded} decoded images referenced by materials on triangles",
        referenced.len()
    );
    if decoded > referenced.len() {
        let _ = write!(
            reason,
            "; {} decoded for materials whose triangles validation removed",
            decoded - referenced.len()
        );
    }
    if scene.skipped_textures() > 0 {
        let _ = write!(
            reason,
            "; {} texture slots of materials on no mesh left undecoded",
            scene.skipped_textures()
        );
    }
    Stage {
        name: "textures",
        used: !referenced.is_empty(),
        reason,
        cost: None,
    }
}

/// Acceleration: triangles and meshes in the backend.
pub(super) fn acceleration(scene: &Scene) -> Stage {
    Stage {
        name: "acceleration",
        used: true,
        reason: format!(
            "{} triangles in {} meshes (one per node instance and primitive, or OBJ group), {}",
            scene.triangle_count(),
            scene.meshes().len(),
            scene.backend_name()
        ),
        cost: None,
    }
}

/// Lanes: whether the method's camera paths run in packets
/// ([`crate::integrator::path::LaneWidth`], where its declaration says so,
/// [`crate::integrator::capability::Capabilities::lanes`]) and why not otherwise.
pub(super) fn lanes(scene: &Scene, method: Method, (perspective, spectral): (bool, bool)) -> Stage {
    let plain = plain_lanes(scene, method);
    let hybrid = method == Method::Hybrid;
    if !(method == Method::Path || hybrid) || !crate::integrator::path::kernel::requested() {
        return plain;
    }
    match crate::integrator::path::kernel::plan_text(scene, (perspective, spectral), hybrid) {
        Ok(reason) if hybrid => Stage {
            used: true,
            reason: format!(
                "camera paths (with --caustics map, unpolarized): {reason}; the caustic map \
                 gathered at each path's first diffuse vertex (on the scalar vertex's \
                 surface), light closing a D S+ L chain left to the map. Otherwise: {}",
                plain.reason
            ),
            ..plain
        },
        Ok(reason) => Stage {
            used: true,
            reason,
            ..plain
        },
        Err(why) => Stage {
            reason: format!(
                "{}; not the structure-of-arrays kernel: {why}",
                plain.reason
            ),
            ..plain
        },
    }
}

/// The lanes stage of the scalar vertex (what renders outside the kernel's class, or with
/// `IRIS_KERNEL=scalar`).
fn plain_lanes(scene: &Scene, method: Method) -> Stage {
    let width = LaneWidth::choose(scene);
    let caps = method.caps();
    let (used, reason) = match (caps.lanes.why_not(), width) {
        (_, Err(e)) => (false, format!("single rays ({e})")),
        (None, Ok(LaneWidth::Scalar)) => (
            false,
            format!(
                "single rays: {} has no packet traversal (or IRIS_LANES=off)",
                scene.backend_name()
            ),
        ),
        (None, Ok(w)) => {
            let n = w.lanes();
            let queries = match scene.accel() {
                crate::accel::Accel::Bvh(_) => "the BVH answers lane by lane".to_string(),
                #[allow(unreachable_patterns)]
                _ => format!("rtcIntersect{n} / rtcOccluded{n}"),
            };
            let photons = if caps.photons != Photons::None {
                "; its photons on single rays (packets do not pay on them: BENCHMARKS.md, \
                 \"Photon passes in lanes\")"
            } else {
                ""
            };
            (
                true,
                format!(
                    "{n} camera paths per packet ({queries}), shading per lane; the image is \
                     the single-ray image{photons}"
                ),
            )
        }
        (Some(why), Ok(_)) => (
            false,
            format!(
                "single rays: --method {} {why} (the path tracer and the hybrid's camera \
                 paths run in lanes)",
                method.name()
            ),
        ),
    };
    Stage {
        name: "lanes",
        used,
        reason,
        cost: None,
    }
}

/// Environment: none, uniform or an importance-sampled map.
pub(super) fn environment(scene: &Scene) -> Stage {
    let (env_used, reason) = match &scene.environment() {
        None => (
            false,
            "none (no iris_environment in the file, no --env)".into(),
        ),
        Some(Environment::Uniform { radiance }) => (
            true,
            format!(
                "uniform radiance [{:.3} {:.3} {:.3}], uniform sphere sampling",
                radiance.x, radiance.y, radiance.z
            ),
        ),
        Some(Environment::Map(m)) => (
            true,
            format!(
                "map {}x{}, importance-sampled by luminance x solid angle",
                m.width(),
                m.height()
            ),
        ),
        Some(Environment::Sky(sky)) => (
            true,
            format!(
                "sky at sun elevation {}°, azimuth {}°, turbidity {} (single Rayleigh and \
                 Mie scattering, spectral): map {}x{}, importance-sampled, and the sun as a \
                 directional light",
                sky.params.elevation,
                sky.params.azimuth,
                sky.params.turbidity,
                sky.map.width(),
                sky.map.height()
            ),
        ),
    };
    Stage {
        name: "environment",
        used: env_used,
        reason,
        cost: None,
    }
}

/// Nested media: triangles marked for contact probes.
pub(super) fn nested_media(ev: &Evidence) -> Stage {
    let (scene, mats) = (ev.scene, |f: &dyn Fn(&Material) -> bool| ev.mats(f));
    let mut touching = 0usize;
    let mut touching_meshes = BTreeSet::new();
    for t in scene.triangles() {
        if t.has(Triangle::TOUCHES) {
            touching += 1;
            touching_meshes.insert(t.mesh as usize);
        }
    }
    let volumetric = mats(&|m: &Material| m.is_volume()).len();
    Stage {
        name: "nested media",
        used: touching > 0,
        reason: if touching > 0 {
            format!(
                "contact probes on {touching} triangles of meshes {} (faces within the \
                         merge distance of another surface)",
                names(
                    touching_meshes
                        .iter()
                        .filter_map(|&m| scene.meshes().get(m))
                        .map(|m| m.name.as_str())
                )
            )
        } else {
            format!(
                "no triangle touches another surface ({volumetric} volumetric materials \
                         on triangles): no contact probes"
            )
        },
        cost: None,
    }
}
