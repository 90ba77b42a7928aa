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
use crate::camera::Camera;
use crate::converge::method_name;
use crate::envmap::Environment;
use crate::error::Result;
use crate::integrator::{Integrator, Method};
use crate::photon::emit::PhotonEmitter;
use crate::photon::trace::{has_caustic_paths, trace, Roulette, TraceSettings};
use crate::render::{render_progressive, RenderSettings};
use crate::scene::{Scene, TriangleData};
use glam::Vec3;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Probe photons behind the caustic decision (the number `Method::resolve` uses).
pub const CAUSTIC_PROBE_PHOTONS: u32 = 4096;
/// Photons traced to time a photon pass.
pub const COST_PHOTONS: u32 = 10_000;
/// Timed probe renders per transport (the fastest counts).
pub const PROBE_REPEATS: u32 = 3;
/// Probe render size for the transport cost.
pub const PROBE_SIZE: (u32, u32) = (32, 24);

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

    /// Adds the glTF file's own counts (images, meshes) to the textures and acceleration
    /// reasons, parsing only the JSON (no buffers, no images). Other formats: unchanged.
    pub fn add_file_counts(&mut self, path: &Path) {
        let Some((images, meshes)) = gltf_counts(path) else {
            return;
        };
        if let Some(s) = self.stages.iter_mut().find(|s| s.name == "textures") {
            let _ = write!(s.reason, "; {images} images in the file");
        }
        if let Some(s) = self.stages.iter_mut().find(|s| s.name == "acceleration") {
            let _ = write!(
                s.reason,
                "; {meshes} meshes in the file (meshes no node instances are not loaded)"
            );
        }
    }

    /// Measures (or quotes, with the source) what each stage costs on this scene: a 32×24,
    /// 1 spp probe render with RGB and with spectral transport (path tracer, or the plan's
    /// method when it is Whitted; fastest of [`PROBE_REPEATS`] each), and 10 000 traced
    /// photons.
    pub fn measure_costs(&mut self, scene: &Scene, camera: &Camera, threads: usize) -> Result<()> {
        let method = if self.method == Method::Whitted {
            Method::Whitted
        } else {
            Method::Path
        };
        let probe = |spectral: bool| -> Result<f64> {
            let (w, h) = PROBE_SIZE;
            let integrator = Integrator {
                method,
                max_depth: 64,
                photon: Default::default(),
            };
            let settings = RenderSettings {
                width: w,
                height: h,
                spp: 1,
                seed: 0,
                threads,
                quiet: true,
                spectral,
                time_limit: None,
            };
            let start = Instant::now();
            render_progressive(scene, camera, &integrator, &settings, None)?;
            Ok(start.elapsed().as_secs_f64() * 1e3)
        };
        // Warm-up of both (thread pool, caches), then the fastest of three alternating runs
        // each: single millisecond-scale runs on a shared machine vary by 2x and more.
        probe(false)?;
        probe(true)?;
        let (mut rgb, mut spectral) = (f64::INFINITY, f64::INFINITY);
        for _ in 0..PROBE_REPEATS {
            rgb = rgb.min(probe(false)?);
            spectral = spectral.min(probe(true)?);
        }
        let emitter = PhotonEmitter::new(scene);
        let photons = (!emitter.is_empty()).then(|| time_photons(scene, &emitter));
        let backend = scene.backend_name();
        for s in &mut self.stages {
            s.cost = Some(match s.name {
                "transport" => format!(
                    "probe {}x{}, 1 spp, {}, fastest of {PROBE_REPEATS}: RGB {rgb:.1} ms, \
                     spectral {spectral:.1} ms (x{:.2})",
                    PROBE_SIZE.0,
                    PROBE_SIZE.1,
                    method_name(method),
                    spectral / rgb.max(1e-6)
                ),
                "photons" => match photons {
                    Some(ms) => format!(
                        "tracing {COST_PHOTONS} photons on one thread: {ms:.1} ms (a pass; SPPM also builds \
                         and gathers its map)"
                    ),
                    None => "no light emits: no photons to trace".into(),
                },
                "volumes" => "not measured (one colour power per segment inside a medium)".into(),
                "textures" => "not measured; BENCHMARKS.md 'Scene load and acceleration-structure build': texture \
                               decoding dominates loading where there are textures \
                               (GlassHurricaneCandleHolder: 3.4 MB of images, 158 ms)"
                    .into(),
                "acceleration" => format!(
                    "built in {:.1} ms ({backend})",
                    scene.accel_build_time.as_secs_f64() * 1e3
                ),
                "environment" => "not measured".into(),
                _ => "BENCHMARKS.md 'Path tracer on real scenes': 0.45 us per probe on Embree, \
                      8.4 us on the BVH, at each hit on a marked triangle"
                    .into(),
            });
        }
        Ok(())
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

/// Milliseconds to trace [`COST_PHOTONS`] photons (fixed seed, depth 8, the caustic probe's
/// settings).
fn time_photons(scene: &Scene, emitter: &PhotonEmitter) -> f64 {
    let settings = TraceSettings {
        max_depth: 8,
        roulette: Roulette::Throughput,
    };
    let start = Instant::now();
    let mut vertices = 0u64;
    for i in 0..COST_PHOTONS {
        let mut rng = crate::math::Rng::new(&[0x0C05_7000, i as u64]);
        if let Some(ph) = emitter.emit_from(scene, &mut rng) {
            trace::<Vec3>(scene, &ph, (), &settings, &mut rng, |_, _| vertices += 1);
        }
    }
    std::hint::black_box(vertices);
    start.elapsed().as_secs_f64() * 1e3
}

/// (images, meshes) declared in a .gltf/.glb file's JSON, or `None` for other formats or a
/// file the glTF parser rejects.
fn gltf_counts(path: &Path) -> Option<(usize, usize)> {
    let ext = path.extension()?.to_string_lossy().to_ascii_lowercase();
    if ext != "gltf" && ext != "glb" {
        return None;
    }
    let bytes = std::fs::read(path).ok()?;
    let g = gltf::Gltf::from_slice_without_validation(&bytes).ok()?;
    Some((g.document.images().len(), g.document.meshes().len()))
}
