//! The registry of rendering methods (`--method`): the closed enum [`Method`] and its one
//! `match` to each method's declaration ([`Method::caps`], the `CAPABILITIES` its module
//! holds). Everything that differs between methods outside their own modules (names, units,
//! photons, what they refuse) is read from the declaration; rendering is the one `match`
//! of [`super::Integrator::render_units`].
//!
//! Adding a method: its module with its `CAPABILITIES` and its render, a variant here and
//! its line in [`Method::caps`] and [`Method::ALL`], and its [`super::Integrator`] variant.

use super::capability::{Capabilities, Photons, Support, Units};
use super::{hybrid, path, photon_map, sppm, vcm, whitted};
use crate::error::Result;

/// The rendering method (`--method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Recursive ray tracing after Cropp & Zhang, "Light Refraction with Dispersion", §4:
    /// direct light from punctual lights, Fresnel-weighted reflection and refraction branches.
    Whitted,
    /// Unidirectional path tracing with next-event estimation and MIS.
    Path,
    /// Classic photon mapping (Jensen): direct light by shadow rays, a caustic map gathered
    /// at the first diffuse hit, a global map reached by final gathering.
    Photon,
    /// Stochastic progressive photon mapping in passes (Hachisuka & Jensen 2009, radius
    /// sequence of Knaus & Zwicker 2011).
    Sppm,
    /// The path tracer with a progressive caustic photon map for exactly the light paths it
    /// cannot sample (light → delta chain → first non-delta surface): [`hybrid`].
    Hybrid,
    /// Vertex connection and merging: bidirectional connections and photon merging under
    /// one multiple importance sampling ([`vcm`]).
    Vcm,
    /// Bidirectional path tracing: [`vcm`] without merging (unbiased).
    Bpt,
    /// `Path`, `Bpt`, `Hybrid`, `Vcm` or `Sppm` from the materials and the photon probes: a
    /// choice the render plan makes (`crate::plan::resolve_method`) before an
    /// [`super::Integrator`] exists; [`super::Integrator::new`] rejects it unresolved.
    Auto,
}

impl Method {
    /// Every method, in the order `--method` lists them.
    pub const ALL: [Method; 8] = [
        Method::Whitted,
        Method::Path,
        Method::Photon,
        Method::Sppm,
        Method::Hybrid,
        Method::Vcm,
        Method::Bpt,
        Method::Auto,
    ];

    /// What the method renders and how: its module's declaration.
    pub fn caps(self) -> &'static Capabilities {
        match self {
            Method::Whitted => &whitted::CAPABILITIES,
            Method::Path => &path::CAPABILITIES,
            Method::Photon => &photon_map::CAPABILITIES,
            Method::Sppm => &sppm::CAPABILITIES,
            Method::Hybrid => &hybrid::CAPABILITIES,
            Method::Vcm => &vcm::CAPABILITIES,
            Method::Bpt => &vcm::BPT_CAPABILITIES,
            Method::Auto => &AUTO,
        }
    }

    /// The method's command-line name, also the run name in reports and file names.
    pub fn name(self) -> &'static str {
        self.caps().name
    }

    /// What a method is good for, in a sentence for someone choosing how to light a gem.
    pub fn purpose(self) -> &'static str {
        self.caps().purpose
    }

    /// Parses `--method NAME` ([`crate::error::parse_name`]).
    pub fn parse(s: &str) -> Result<Method> {
        let names = Method::ALL.map(|m| (m.name(), m));
        crate::error::parse_name("--method", s, &names)
    }
}

/// `--method auto` before the plan resolves it: it can take whatever one of its choices
/// takes (the path tracer and the hybrid trace media and polarized light, SPPM stands in
/// for VCM under an orthographic camera), and counts samples until then.
const AUTO: Capabilities = Capabilities {
    name: "auto",
    purpose: "chosen from the scene",
    units: Units::Samples,
    photons: Photons::None,
    media: Support::Yes,
    orthographic: Support::Yes,
    polarization: Support::Yes,
    rayleigh_spectral: Support::Yes,
    lanes: Support::Yes,
    shards: Support::Yes,
    adaptive: Support::Yes,
    estimate_in_media: Support::Yes,
    progressive: Support::Yes,
    pixel_bytes: 0,
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::{Integrator, PhotonSettings};

    /// Every method has a declaration of its own (a new variant without one does not
    /// compile: [`Method::caps`] is exhaustive), a unique name that parses back, a
    /// purpose, and a reason with every "no".
    #[test]
    fn every_method_declares_itself() {
        for (i, m) in Method::ALL.iter().enumerate() {
            let caps = m.caps();
            assert_eq!(Method::parse(caps.name).unwrap(), *m);
            assert!(!caps.purpose.is_empty(), "{}", caps.name);
            for other in &Method::ALL[i + 1..] {
                assert_ne!(caps.name, other.name());
            }
            for s in [
                caps.media,
                caps.orthographic,
                caps.polarization,
                caps.rayleigh_spectral,
                caps.lanes,
                caps.shards,
                caps.adaptive,
                caps.estimate_in_media,
                caps.progressive,
            ] {
                if let Support::No(why) = s {
                    assert!(why.len() > 10, "{}: {why:?}", caps.name);
                }
            }
        }
    }

    /// Every method but `auto` makes an integrator that says it is that method; `auto`
    /// is refused unresolved.
    #[test]
    fn every_method_renders_as_itself() {
        let photon = PhotonSettings::default();
        for m in Method::ALL {
            match Integrator::new(m, 8, &photon) {
                Ok(i) => assert_eq!(i.method(), m),
                Err(e) => {
                    assert_eq!(m, Method::Auto, "{e}");
                    assert!(e.to_string().contains("auto"), "{e}");
                }
            }
        }
    }
}
