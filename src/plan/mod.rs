//! The render plan: which stages of the pipeline a scene needs, decided from the loaded
//! scene (and the `--method` / `--spectral` flags) before rendering, each with a one-line
//! reason naming its evidence (material and mesh names, counts).
//!
//! Stages, in print order:
//! - **transport**: spectral (4 wavelengths, CIE film) or RGB — [`SpectralMode::resolve`].
//! - **photons**: a photon pass (SPPM / photon map) or not — [`Method::resolve`], whose
//!   `auto` choice rests on [`has_caustic_paths`] (fixed-seed probe photons; the same seed
//!   here, so the plan and the render always agree).
//! - **volumes**: Beer–Lambert attenuation, evaluated only for materials on triangles with a
//!   finite attenuation distance ([`crate::material::Material::transmittance_at`] returns 1
//!   otherwise).
//! - **textures**: images decoded by the loader vs images referenced by materials that
//!   triangles use (and, for glTF, images in the file).
//! - **acceleration**: triangles and meshes built into the backend (only meshes instanced by
//!   a node are loaded).
//! - **environment**: none, uniform (uniform sphere sampling) or a map (importance-sampled).
//! - **nested media**: contact probes at hits on triangles marked
//!   [`TriangleData::TOUCHES`] by `scene/contact.rs` (and `scene/thin.rs`).
//!
//! Costs ([`Plan::measure_costs`], for `--explain` and `iris info`) are measured on the
//! scene itself — a 32×24, 1 spp probe render with RGB and with spectral transport, and
//! 10 000 traced photons — or quoted from BENCHMARKS.md with the section named; nothing
//! else is claimed. [`Plan::text`] leaves timings out (it is what the snapshot test
//! compares); [`Plan::text_with_costs`] adds them.

use crate::app::SpectralMode;
use crate::converge::method_name;
use crate::integrator::Method;
use crate::light::env::Environment;
use crate::photon::emit::PhotonEmitter;
use crate::photon::trace::has_caustic_paths;
use crate::scene::{Scene, TriangleData};
use std::collections::BTreeSet;

mod costs;
pub use costs::{COST_PHOTONS, PROBE_REPEATS, PROBE_SIZE};
use std::fmt::Write as _;

/// Probe photons behind the caustic decision (the number `Method::resolve` uses).
pub const CAUSTIC_PROBE_PHOTONS: u32 = 4096;
/// One stage of the pipeline.
#[derive(Debug, Clone, PartialEq)]
pub struct Stage {
    /// Short name (`transport`, `photons`, …).
    pub name: &'static str,
    /// Whether the render runs it.
    pub used: bool,
    /// What was chosen and why, naming the evidence.
    pub reason: String,
    /// What the stage costs (measured or quoted with its source); `None` until
    /// [`Plan::measure_costs`].
    pub cost: Option<String>,
}

/// The plan for one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Stages in print order.
    pub stages: Vec<Stage>,
    /// Spectral transport.
    pub spectral: bool,
    /// The method that renders (`auto` resolved).
    pub method: Method,
    /// The `--method auto` decision, for the render notes.
    pub method_note: Option<String>,
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

/// Indices of the materials some triangle uses, ascending.
fn used_materials(scene: &Scene) -> BTreeSet<usize> {
    scene
        .triangle_material
        .iter()
        .map(|&m| m as usize)
        .collect()
}

impl Plan {
    /// Decides every stage for `scene` under the `--method` and `--spectral` flags.
    pub fn new(scene: &Scene, method: Method, spectral: SpectralMode) -> Plan {
        let used = used_materials(scene);
        let mats = |f: &dyn Fn(&crate::material::Material) -> bool| -> Vec<&str> {
            used.iter()
                .filter_map(|&i| scene.materials.get(i))
                .filter(|m| f(m))
                .map(|m| m.desc.name.as_str())
                .collect()
        };
        let spectral_on = spectral.resolve(scene);
        let (resolved, method_note) = method.resolve(scene);
        let mut stages = Vec::with_capacity(7);

        // Transport.
        let dispersive = mats(&|m| m.is_dispersive());
        let spectral_emitters = mats(&|m| m.emitter_shape().is_some());
        let spectral_lights = scene.light_shapes.iter().filter(|s| s.is_some()).count();
        let mut evidence = Vec::new();
        if !dispersive.is_empty() {
            evidence.push(format!("dispersive materials {}", names(dispersive)));
        }
        if !spectral_emitters.is_empty() {
            evidence.push(format!("spectral emitters {}", names(spectral_emitters)));
        }
        if spectral_lights > 0 {
            evidence.push(format!("{spectral_lights} lights naming a spectrum"));
        }
        let evidence = if evidence.is_empty() {
            "no dispersive material, spectral emitter or spectral light".to_string()
        } else {
            evidence.join("; ")
        };
        let reason = match (spectral, spectral_on) {
            (SpectralMode::On, _) => format!("spectral (--spectral on); {evidence}"),
            (SpectralMode::Off, _) => format!("RGB (--spectral off); {evidence}"),
            (SpectralMode::Auto, true) => format!("spectral: {evidence}"),
            (SpectralMode::Auto, false) => format!("RGB: {evidence}"),
        };
        stages.push(Stage {
            name: "transport",
            used: spectral_on,
            reason,
            cost: None,
        });

        // Photons.
        let emitter = PhotonEmitter::new(scene);
        let caustics = if method == Method::Auto {
            resolved == Method::Sppm
        } else {
            !emitter.is_empty() && has_caustic_paths(scene, &emitter, CAUSTIC_PROBE_PHOTONS)
        };
        let specular = mats(&|m| m.is_transmissive() || m.desc.metallic >= 1.0);
        let evidence = if caustics {
            format!(
                "caustic paths: probe photons ({CAUSTIC_PROBE_PHOTONS}) reach a diffuse \
                 surface after specular bounces only; transmissive or metallic materials {}",
                names(specular)
            )
        } else if specular.is_empty() {
            "no transmissive or metallic material on any triangle: no caustic paths".to_string()
        } else {
            format!(
                "no caustic path among {CAUSTIC_PROBE_PHOTONS} probe photons (transmissive or \
                 metallic materials {})",
                names(specular)
            )
        };
        let photons_used = matches!(resolved, Method::Sppm | Method::Photon);
        let how = if method == Method::Auto {
            format!("--method auto -> {}", method_name(resolved))
        } else {
            format!("--method {}", method_name(resolved))
        };
        stages.push(Stage {
            name: "photons",
            used: photons_used,
            reason: format!("{how}: {evidence}"),
            cost: None,
        });

        // Volumes.
        let attenuating: Vec<String> = used
            .iter()
            .filter_map(|&i| scene.materials.get(i))
            .filter(|m| m.desc.attenuation_distance.is_finite())
            .map(|m| format!("{} over {}", m.desc.name, m.desc.attenuation_distance))
            .collect();
        let clear = mats(&|m| m.is_volume() && !m.desc.attenuation_distance.is_finite()).len();
        stages.push(Stage {
            name: "volumes",
            used: !attenuating.is_empty(),
            reason: if attenuating.is_empty() {
                format!(
                    "Beer-Lambert never evaluated: no material on a triangle has a finite \
                     attenuation distance ({clear} clear volumetric materials)"
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
        });

        // Textures.
        let mut referenced = BTreeSet::new();
        for m in used.iter().filter_map(|&i| scene.materials.get(i)) {
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
        let decoded = scene.images.len();
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
        if scene.skipped_textures > 0 {
            let _ = write!(
                reason,
                "; {} texture slots of materials on no mesh left undecoded",
                scene.skipped_textures
            );
        }
        stages.push(Stage {
            name: "textures",
            used: !referenced.is_empty(),
            reason,
            cost: None,
        });

        // Acceleration.
        stages.push(Stage {
            name: "acceleration",
            used: true,
            reason: format!(
                "{} triangles in {} meshes (one per node instance and primitive, or OBJ group), {}",
                scene.triangle_count(),
                scene.meshes.len(),
                scene.backend_name()
            ),
            cost: None,
        });

        // Environment.
        let (env_used, reason) = match &scene.environment {
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
        };
        stages.push(Stage {
            name: "environment",
            used: env_used,
            reason,
            cost: None,
        });

        // Nested media.
        let mut touching = 0usize;
        let mut touching_meshes = BTreeSet::new();
        for (t, data) in scene.triangle_data.iter().enumerate() {
            if data.info & TriangleData::TOUCHES != 0 {
                touching += 1;
                touching_meshes.insert(scene.triangle_mesh[t] as usize);
            }
        }
        let volumetric = mats(&|m| m.is_volume()).len();
        stages.push(Stage {
            name: "nested media",
            used: touching > 0,
            reason: if touching > 0 {
                format!(
                    "contact probes on {touching} triangles of meshes {} (faces within the \
                     merge distance of another surface)",
                    names(
                        touching_meshes
                            .iter()
                            .filter_map(|&m| scene.meshes.get(m))
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
        });

        Plan {
            stages,
            spectral: spectral_on,
            method: resolved,
            method_note,
        }
    }

    /// The stage called `name`.
    pub fn stage(&self, name: &str) -> Option<&Stage> {
        self.stages.iter().find(|s| s.name == name)
    }

    /// The plan without timings (what the snapshot test compares).
    pub fn text(&self) -> String {
        self.render_text(false)
    }

    /// The plan with each stage's cost, when measured.
    pub fn text_with_costs(&self) -> String {
        self.render_text(true)
    }

    fn render_text(&self, costs: bool) -> String {
        let mut s = String::from("render plan:\n");
        let _ = writeln!(s, "  {:<13} {}", "method", method_name(self.method));
        for st in &self.stages {
            let _ = writeln!(
                s,
                "  {:<13} {:<9} {}",
                st.name,
                if st.used { "used" } else { "left out" },
                st.reason
            );
            if let (true, Some(c)) = (costs, &st.cost) {
                let _ = writeln!(s, "  {:<13} cost: {c}", "");
            }
        }
        s
    }
}
