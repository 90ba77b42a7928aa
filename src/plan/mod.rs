//! The render plan: which stages of the pipeline a scene needs, decided from the loaded
//! scene (and the `--method` / `--spectral` flags) before rendering, each with a one-line
//! reason naming its evidence (material and mesh names, counts).
//!
//! Stages, in print order:
//! - **transport**: spectral (4 wavelengths, CIE colour) or RGB — [`SpectralMode::resolve`]
//!   (dispersive materials, measured metals, named emission spectra).
//! - **photons**: a photon pass (SPPM / photon map / the hybrid's caustic map / VCM's light
//!   subpaths) or not — [`resolve_method`] (`method.rs`), whose `auto` choice among path,
//!   BPT, hybrid, VCM and SPPM rests on fixed-seed photon probes (the same seeds here, so
//!   the plan and the render always agree).
//! - **volumes**: Beer–Lambert attenuation, evaluated only for materials on triangles that
//!   absorb ([`crate::material::Material::absorbs`]: a finite attenuation distance and a
//!   colour other than white; [`crate::material::Material::transmittance_at`] returns 1
//!   otherwise).
//! - **textures**: images decoded by the loader vs images referenced by materials that
//!   triangles use (and, for glTF, images in the file).
//! - **acceleration**: triangles and meshes built into the backend (only meshes instanced by
//!   a node are loaded).
//! - **lanes**: whether the path tracer and the hybrid trace their camera paths in packets
//!   of 8 or 16 ([`crate::integrator::path::LaneWidth`]); other methods and the BVH trace
//!   single rays; for the path tracer, whether the structure-of-arrays kernel renders its
//!   camera paths and why not (`IRIS_KERNEL=scalar`: never;
//!   [`crate::integrator::path::kernel`]).
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

use crate::integrator::Method;
use crate::scene::desc::Projection;
use crate::scene::Scene;

mod costs;
mod method;
mod polarization;
mod stages;
pub use costs::{COST_PHOTONS, PROBE_REPEATS, PROBE_SIZE};
pub use method::{
    resolve_method, AUTO_ENCLOSED_FROM, AUTO_HYBRID_BELOW, CAUSTIC_PROBE_PHOTONS, ROUGH_GLASS,
};
pub use polarization::{needs_polarization, Polarization, PolarizationMode};
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

    /// Whether to render `scene` spectrally with `method`. A Rayleigh medium asks for
    /// spectral transport except under a method whose declaration says no
    /// ([`crate::integrator::capability::Capabilities::rayleigh_spectral`]: the hybrid,
    /// whose paths and photons would then keep one wavelength each in it, colour noise,
    /// [`crate::shading::media::keep_hero_in`]): there RGB's three channels carry the λ⁻⁴
    /// law at their dominant wavelengths, unless something else needs spectra.
    pub fn resolve(self, scene: &Scene, method: Method) -> bool {
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
                    || (chromatic_media(scene) && method.caps().rayleigh_spectral.is_yes())
            }
        }
    }
}

/// Whether a scattering medium's coefficients follow a spectral law RGB only approximates
/// (Rayleigh's λ⁻⁴, [`crate::volume::Medium::wants_spectral`]).
pub(super) fn chromatic_media(scene: &Scene) -> bool {
    let fog = scene.fog().is_some_and(|f| f.medium.wants_spectral());
    fog || scene
        .materials()
        .iter()
        .any(|m| m.medium().is_some_and(|med| med.wants_spectral()))
}

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
    /// Polarized transport ([`Plan::decide_polarization`]); `None`: left out.
    pub polarization: Option<Polarization>,
}

impl Plan {
    /// Decides every stage for `scene`, seen through a camera of `projection`, under the
    /// `--method` and `--spectral` flags.
    pub fn new(
        scene: &Scene,
        projection: &Projection,
        method: Method,
        spectral: SpectralMode,
    ) -> Plan {
        let ev = stages::Evidence::new(scene);
        let (resolved, method_note) = resolve_method(method, scene, projection);
        let spectral_on = spectral.resolve(scene, resolved);
        Plan {
            stages: vec![
                stages::transport(&ev, (spectral, spectral_on), resolved),
                stages::photons(&ev, method, resolved, method_note.as_deref()),
                stages::volumes(&ev),
                stages::media(scene),
                stages::textures(&ev),
                stages::acceleration(scene),
                stages::lanes(
                    scene,
                    resolved,
                    (
                        matches!(projection, Projection::Perspective { .. }),
                        spectral_on,
                    ),
                ),
                stages::environment(scene),
                stages::nested_media(&ev),
            ],
            spectral: spectral_on,
            method: resolved,
            method_note,
            polarization: None,
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
