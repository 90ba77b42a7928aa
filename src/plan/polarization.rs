//! The polarization stage: whether light is traced with Stokes vectors
//! ([`crate::integrator::path::polarized`]) — only when the scene needs it, a birefringent
//! crystal ([`crate::material::CrystalDesc`]) or a polarizer on the camera
//! (`--polarizer`), like spectral transport for dispersion — and the method and transport
//! it then requires: spectral, and the path tracer or, where `--method auto` found the
//! caustics worth photons, the polarized hybrid (polarized caustic photons,
//! [`crate::photon::polarized`]).

use super::{Plan, SpectralMode, Stage};
use crate::error::{Error, Result};
use crate::integrator::capability::check_polarization;
use crate::integrator::Method;
use crate::scene::Scene;

/// `--polarization auto|on|off`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PolarizationMode {
    /// Polarized when a material is a crystal or a polarizer is on the camera.
    #[default]
    Auto,
    /// Always polarized.
    On,
    /// Never (crystals render with one index, their principal y one).
    Off,
}

impl PolarizationMode {
    /// Parses `--polarization auto|on|off`.
    pub fn parse(s: &str) -> Result<PolarizationMode> {
        let names = [
            ("auto", PolarizationMode::Auto),
            ("on", PolarizationMode::On),
            ("off", PolarizationMode::Off),
        ];
        crate::error::parse_name("--polarization", s, &names)
    }
}

pub use crate::integrator::path::polarized::Polarization;
use crate::integrator::path::polarized::{WHY_NO_SPLIT, WHY_SINGLE_RAYS};

/// What in the scene needs polarized transport: its crystal materials and polarizer
/// sheets, named (each material once, however many orientations it has).
fn crystals(scene: &Scene) -> Vec<String> {
    let mut names = Vec::new();
    for m in scene.materials() {
        let what = match (&m.desc.crystal, &m.desc.polarizer) {
            (Some(_), _) => format!("birefringent {}", m.desc.name),
            (None, Some(_)) => format!("polarizer sheet {}", m.desc.name),
            (None, None) => continue,
        };
        if !names.contains(&what) {
            names.push(what);
        }
    }
    names
}

/// Whether `scene` has what `--polarization auto` turns polarized transport on for (a
/// crystal or a polarizer sheet; a polarizer on the camera aside).
pub fn needs_polarization(scene: &Scene) -> bool {
    !crystals(scene).is_empty()
}

impl Plan {
    /// Decides the polarization stage under `--polarization mode` and `--polarizer`
    /// (degrees), given the `--method` and `--spectral` flags the plan was made with:
    /// polarized transport needs a method that declares it and spectral transport, which it
    /// takes when those were `auto`, and refuses scattering media
    /// ([`check_polarization`]). A usage error names the flags that conflict.
    pub fn decide_polarization(
        &mut self,
        scene: &Scene,
        (mode, polarizer_deg): (PolarizationMode, Option<f32>),
        (method, spectral): (Method, SpectralMode),
    ) -> Result<()> {
        let names = crystals(scene);
        let why = match (&names[..], polarizer_deg) {
            ([], None) => None,
            ([], Some(a)) => Some(format!("--polarizer {a}°")),
            (n, _) => Some(n.join(", ")),
        };
        // A method whose declaration has no polarized transport keeps automatic
        // polarization off (a polarizer on the camera still needs it).
        let other_method = !method.caps().polarization.is_yes();
        let on = match (mode, &why) {
            (PolarizationMode::Off, _) if polarizer_deg.is_some() => {
                return Err(Error::Usage(
                    "--polarizer needs polarized transport: drop --polarization off".into(),
                ))
            }
            (PolarizationMode::Off, _) => false,
            (PolarizationMode::On, _) => true,
            (PolarizationMode::Auto, _) if other_method && polarizer_deg.is_none() => false,
            (PolarizationMode::Auto, w) => w.is_some(),
        };
        let reason = match (on, mode, &why) {
            (true, PolarizationMode::On, None) => {
                format!("on (--polarization on): Stokes vectors; {WHY_NO_SPLIT}")
            }
            (true, _, Some(w)) => format!("on: {w}: Stokes vectors; {WHY_NO_SPLIT}"),
            (false, PolarizationMode::Off, Some(w)) => {
                format!("off (--polarization off): {w} rendered with one index")
            }
            (false, _, Some(w)) => format!(
                "off: --method {} {} ({w} rendered with one index)",
                method.name(),
                method
                    .caps()
                    .polarization
                    .why_not()
                    .unwrap_or("is not polarized")
            ),
            _ => "no birefringent material, no polarizer".to_string(),
        };
        self.stages.push(Stage {
            name: "polarization",
            used: on,
            reason,
            cost: None,
        });
        if !on {
            return Ok(());
        }
        check_polarization(method, scene, spectral != SpectralMode::Off)?;
        self.polarized_method();
        let pleochroic: Vec<String> = scene
            .materials()
            .iter()
            .filter(|m| {
                m.desc
                    .crystal
                    .is_some_and(|c| c.absorption(550.0) != [0.0; 3])
            })
            .map(|m| m.desc.name.clone())
            .collect();
        if let (Some(volumes), false) = (
            self.stages.iter_mut().find(|s| s.name == "volumes"),
            pleochroic.is_empty(),
        ) {
            volumes.used = true;
            volumes.reason = format!(
                "{}; pleochroic {} absorb each mode by the crystal table's spectra instead",
                volumes.reason,
                pleochroic.join(", ")
            );
        }
        if let Some(lanes) = self.stages.iter_mut().find(|s| s.name == "lanes") {
            lanes.used = false;
            lanes.reason = format!("polarized camera paths are single rays: {WHY_SINGLE_RAYS}");
        }
        self.spectral = true;
        self.polarization = Some(Polarization {
            polarizer: polarizer_deg.map(f32::to_radians),
        });
        Ok(())
    }

    /// The method under polarized transport: the path tracer and the hybrid stay; another
    /// method `--method auto` chose for its photons (SPPM, VCM, BPT, photon mapping: none
    /// traces polarized light) becomes the polarized hybrid, whose caustic photons carry
    /// Stokes vectors; the plan's note says which it had chosen.
    fn polarized_method(&mut self) {
        let to = match self.method {
            Method::Path | Method::Hybrid => return,
            Method::Whitted => Method::Path,
            _ => Method::Hybrid,
        };
        let note = match to {
            Method::Hybrid => format!(
                "hybrid: polarized transport; its caustic photons carry Stokes vectors \
                 (--method auto had chosen {})",
                self.method.name()
            ),
            _ => format!(
                "path: polarized transport (--method auto had chosen {})",
                self.method.name()
            ),
        };
        if let Some(photons) = self.stages.iter_mut().find(|s| s.name == "photons") {
            photons.used = to == Method::Hybrid;
            photons.reason = note.clone();
        }
        self.method_note = Some(note);
        self.method = to;
    }
}
