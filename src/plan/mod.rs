//! The render plan: which stages of the pipeline a scene needs, decided from the loaded
//! scene (and the `--method` / `--spectral` flags) before rendering, each with a one-line
//! reason naming its evidence (material and mesh names, counts).
//!
//! Stages, in print order:
//! - **transport**: spectral (4 wavelengths, CIE colour) or RGB — [`SpectralMode::resolve`]
//!   (dispersive materials, measured metals, named emission spectra).
//! - **photons**: a photon pass (SPPM / photon map / the hybrid's caustic map) or not —
//!   [`resolve_method`], whose `auto` choice among path, hybrid and SPPM rests on
//!   [`has_caustic_paths`] and the caustic share of the hybrid's probe (fixed-seed probe
//!   photons; the same seeds here, so the plan and the render always agree).
//! - **volumes**: Beer–Lambert attenuation, evaluated only for materials on triangles with a
//!   finite attenuation distance ([`crate::material::Material::transmittance_at`] returns 1
//!   otherwise).
//! - **textures**: images decoded by the loader vs images referenced by materials that
//!   triangles use (and, for glTF, images in the file).
//! - **acceleration**: triangles and meshes built into the backend (only meshes instanced by
//!   a node are loaded).
//! - **lanes**: whether the path tracer and the hybrid trace their camera paths in packets
//!   of 8 or 16 ([`crate::integrator::path::LaneWidth`]); other methods and the BVH trace
//!   single rays.
//! - **environment**: none, uniform (uniform sphere sampling) or a map (importance-sampled).
//! - **nested media**: contact probes at hits on triangles marked
//!   [`crate::scene::Triangle::TOUCHES`] by `scene/contact.rs` (and `scene/thin.rs`).
//! - **denoise**: added by the caller that knows the output ([`crate::app::RenderJob`],
//!   `iris info` for the default PNG), not by [`Plan::new`]:
//!   [`crate::denoise::DenoiseChoice::stage`].
//!
//! Costs ([`Plan::measure_costs`], for `--explain` and `iris info`) are measured on the
//! scene itself — a 32×24, 1 spp probe render with RGB and with spectral transport, and
//! 10 000 traced photons — or quoted from BENCHMARKS.md with the section named; nothing
//! else is claimed. [`Plan::text`] leaves timings out (it is what the snapshot test
//! compares); [`Plan::text_with_costs`] adds them.

use crate::integrator::{caustic, Method};
use crate::scene::Scene;

mod costs;
mod stages;
pub use costs::{COST_PHOTONS, PROBE_REPEATS, PROBE_SIZE};
use std::fmt::Write as _;

/// `--spectral auto|on|off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpectralMode {
    /// Spectral transport when a material is dispersive or a measured metal (`--metal`:
    /// its colour is n(λ), k(λ)), or a light or emissive material names a spectrum
    /// (`iris_spectrum`); RGB otherwise.
    #[default]
    Auto,
    /// Always spectral.
    On,
    /// Always RGB (dispersive materials use n_d).
    Off,
}

impl SpectralMode {
    /// Parses `--spectral auto|on|off` ([`crate::error::parse_name`]).
    pub fn parse(s: &str) -> crate::error::Result<SpectralMode> {
        let names = [
            ("auto", SpectralMode::Auto),
            ("on", SpectralMode::On),
            ("off", SpectralMode::Off),
        ];
        crate::error::parse_name("--spectral", s, &names)
    }

    /// Whether to render `scene` spectrally.
    pub fn resolve(self, scene: &Scene) -> bool {
        match self {
            SpectralMode::On => true,
            SpectralMode::Off => false,
            SpectralMode::Auto => {
                scene.materials().iter().any(|m| {
                    m.is_dispersive()
                        || m.emitter_shape().is_some()
                        || m.conductor().is_some()
                        || m.desc.is_iridescent()
                }) || scene.lights().iter().any(|l| l.shape.is_some())
            }
        }
    }
}

/// Resolves [`Method::Auto`] for `scene` among the path tracer, the hybrid and SPPM, from
/// two fixed-seed photon probes (the same seeds here and in the stages, so the plan and the
/// render always agree). Returns the method and the reason. The rule:
/// 1. no light reaches a diffuse-like surface through specular ones
///    ([`crate::photon::trace::has_caustic_paths`], all lights) → **path**: nothing the path
///    tracer cannot sample;
/// 2. a transmissive material is rough ([`rough_glass`]): light focused through rough glass
///    (L G+ D) is neither the path tracer's strength (a point or spot light is reached only
///    by next-event estimation at the last rough interface: fireflies) nor the hybrid's
///    caustic map's (delta chains only) → **SPPM**, whose photons carry every chain;
/// 3. the caustic share s — of the lights' power arriving at first non-delta hits, the part
///    that came through delta bounces ([`caustic::probe_share`]) — is below
///    [`AUTO_HYBRID_BELOW`] → **hybrid**: the path tracer for everything it reaches, the
///    caustic map only for the L S+ D paths;
/// 4. otherwise (the caustics are the picture: a stone under a narrow spot, a beam through a
///    prism) → **SPPM**.
///
/// Measured (BENCHMARKS.md "Converging faster", 20 s each, 2 cores, relative MSE against
/// long references, hybrid vs SPPM): the hybrid ahead on the gallery's studio-lit stones
/// (s < 0.2 %: oval ruby 0.0070 vs 0.035, round diamond 0.095 vs 0.19, bare diamond 0.90
/// vs 2.9), the prism beam of Fig. 5.3.1 (s ≈ 0: 2.8e-5 vs 1.0e-4) and the point-light
/// caustic sphere (s = 3.2 %: 2.7e-3 vs 4.2e-3); SPPM ahead on DispersionTest (s = 4.9 %:
/// 5.8e-3 vs 5.3e-3), the Cornell box with water (s = 18 %: 0.020 vs 0.0023: the floor seen
/// through the water is all caustic, where SPPM's per-pixel radii beat the map's global
/// one), the stone under a 3° spot (s = 38 %: 1.7 vs 0.19) and CompareDispersion's rough
/// spheres (12.9 vs 6.4). Hence [`AUTO_HYBRID_BELOW`] = 4 %.
pub fn resolve_method(method: Method, scene: &Scene) -> (Method, Option<String>) {
    if method != Method::Auto {
        return (method, None);
    }
    let emitter = crate::photon::emit::PhotonEmitter::new(scene);
    if emitter.is_empty()
        || !crate::photon::trace::has_caustic_paths(scene, &emitter, CAUSTIC_PROBE_PHOTONS)
    {
        return (
            Method::Path,
            Some("--method auto: no caustic paths found: path tracer".into()),
        );
    }
    let why = if let Some(name) = rough_glass(scene) {
        (
            Method::Sppm,
            format!(
                "rough transmissive material {name} focuses light the path tracer reaches only \
                 by chance and the hybrid's caustic map does not carry: SPPM"
            ),
        )
    } else {
        let share = caustic::probe_share(scene, CAUSTIC_PROBE_PHOTONS);
        if share < AUTO_HYBRID_BELOW {
            (
                Method::Hybrid,
                format!(
                    "caustics carry {:.2} % of the light reaching diffuse surfaces (under {:.0} %): \
                     path tracer + caustic map (hybrid)",
                    100.0 * share,
                    100.0 * AUTO_HYBRID_BELOW
                ),
            )
        } else {
            (
                Method::Sppm,
                format!(
                    "caustics carry {:.2} % of the light reaching diffuse surfaces (the hybrid \
                     is chosen under {:.0} %): SPPM",
                    100.0 * share,
                    100.0 * AUTO_HYBRID_BELOW
                ),
            )
        }
    };
    (why.0, Some(format!("--method auto: {}", why.1)))
}

/// The first transmissive material with a rough surface (GGX roughness factor above
/// [`ROUGH_GLASS`]), by its label (`material N "name"`), if any.
fn rough_glass(scene: &Scene) -> Option<String> {
    scene
        .materials()
        .iter()
        .enumerate()
        .find(|(_, m)| m.is_transmissive() && m.desc.roughness > ROUGH_GLASS)
        .map(|(_, m)| m.desc.name.clone())
}

/// Roughness above which a transmissive material counts as rough glass for `--method auto`.
pub const ROUGH_GLASS: f32 = 0.05;

/// The caustic share under which `--method auto` picks the hybrid over SPPM
/// ([`resolve_method`], from the measurements cited there).
pub const AUTO_HYBRID_BELOW: f64 = 0.04;

/// Probe photons behind the caustic decision (the number [`resolve_method`] uses).
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

impl Plan {
    /// Decides every stage for `scene` under the `--method` and `--spectral` flags.
    pub fn new(scene: &Scene, method: Method, spectral: SpectralMode) -> Plan {
        let ev = stages::Evidence::new(scene);
        let spectral_on = spectral.resolve(scene);
        let (resolved, method_note) = resolve_method(method, scene);
        Plan {
            stages: vec![
                stages::transport(&ev, spectral, spectral_on),
                stages::photons(&ev, method, resolved, method_note.as_deref()),
                stages::volumes(&ev),
                stages::textures(&ev),
                stages::acceleration(scene),
                stages::lanes(scene, resolved),
                stages::environment(scene),
                stages::nested_media(&ev),
            ],
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
        let _ = writeln!(s, "  {:<13} {}", "method", self.method.name());
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
