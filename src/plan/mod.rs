//! The render plan: which stages of the pipeline a scene needs, decided from the loaded
//! scene (and the `--method` / `--spectral` flags) before rendering, each with a one-line
//! reason naming its evidence (material and mesh names, counts).
//!
//! Stages, in print order:
//! - **transport**: spectral (4 wavelengths, CIE film) or RGB — [`SpectralMode::resolve`].
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
//! - **environment**: none, uniform (uniform sphere sampling) or a map (importance-sampled).
//! - **nested media**: contact probes at hits on triangles marked
//!   [`TriangleData::TOUCHES`] by `scene/contact.rs` (and `scene/thin.rs`).
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
    /// Spectral transport when a material is dispersive or a light or emissive material names
    /// a spectrum (`iris_spectrum`), RGB otherwise.
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
                scene
                    .materials
                    .iter()
                    .any(|m| m.is_dispersive() || m.emitter_shape().is_some())
                    || scene.light_shapes.iter().any(Option::is_some)
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
/// 2. the caustic lights (punctual and emissive, [`crate::integrator::caustic`]) put no
///    power through delta chains onto a non-delta surface ([`caustic::probe_share`] = 0): the
///    caustics come from the environment (or glossy chains), which the hybrid leaves to the
///    path tracer → **SPPM**, whose photons carry them;
/// 3. the caustic share s of the caustic lights' power at first non-delta hits is below
///    [`AUTO_HYBRID_BELOW`] → **hybrid** (the path tracer for everything it reaches, the
///    map only for L S+ D);
/// 4. otherwise → **SPPM**.
///
/// [`AUTO_HYBRID_BELOW`] is 0 (the hybrid is not chosen) on the measurements so far: at
/// equal time (20 s, 2 shared cores, against 150–300 s SPPM references) SPPM was ahead of
/// the hybrid on every caustic scene of the repository, from s ≈ 0 (ruby, relative error
/// 0.171 vs 0.200) and 2.4 % (glass of water, 0.081 vs 0.090) to 2.9 % (fig4_5_1
/// caustics, RMSE 0.27 vs 0.39) and 37 % (gem caustics, 0.37 vs 2.3): the hybrid's
/// indirect light gathers the concentrated caustic map at later camera vertices, and in
/// spectral scenes its path-traced part shares the pass's wavelengths.
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
    let share = caustic::probe_share(scene, CAUSTIC_PROBE_PHOTONS);
    let (method, why) = if share <= 0.0 {
        (
            Method::Sppm,
            "caustics only from the environment or glossy surfaces (the lamps and punctual \
             lights put no power through specular chains onto a diffuse surface): SPPM"
                .to_string(),
        )
    } else if share < AUTO_HYBRID_BELOW {
        (
            Method::Hybrid,
            format!(
                "caustics carry {:.2} % of the light reaching diffuse surfaces (under {:.2} %): \
                 path tracer + caustic map (hybrid)",
                100.0 * share,
                100.0 * AUTO_HYBRID_BELOW
            ),
        )
    } else {
        (
            Method::Sppm,
            format!(
                "caustics carry {:.2} % of the light reaching diffuse surfaces ({}): SPPM",
                100.0 * share,
                if AUTO_HYBRID_BELOW > 0.0 {
                    format!(
                        "the hybrid is chosen under {:.2} %",
                        100.0 * AUTO_HYBRID_BELOW
                    )
                } else {
                    "the hybrid, behind SPPM at equal time so far, is not chosen".to_string()
                }
            ),
        )
    };
    (method, Some(format!("--method auto: {why}")))
}

/// The caustic share of first-hit power under which `--method auto` picks the hybrid over
/// SPPM ([`resolve_method`]; 0 = never, from the measurements cited there).
pub const AUTO_HYBRID_BELOW: f64 = 0.0;

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
