//! Integrator settings and their bounds: the command line's photon flags
//! ([`PhotonSettings`]), the parts each photon method uses ([`PhotonMapSettings`],
//! [`SppmSettings`]), and the photon store budget. Radii are in scene units; counts are
//! photons emitted unless named stored.

use crate::error::{Error, Result};
use crate::photon::trace::Roulette;

/// Most photons emitted per SPPM pass or in total for `--method photon` (`--photons`):
/// 2^24 ≈ 16.8 M. Every emitted photon may be stored at several surfaces (32 bytes each),
/// so this bounds the photon map's memory before anything is traced; SPPM's default of one
/// photon per pixel is capped here too.
pub const MAX_PHOTONS: u64 = 1 << 24;

/// Most photons stored in one photon map or one SPPM pass (2^26 ≈ 67 M, 2 GiB at 32 bytes
/// each): a scene whose photons bounce so often that `--photons` emitted photons would
/// store more stops tracing and fails with an error naming `--photons` and `--max-depth`.
pub const MAX_STORED_PHOTONS: u64 = 1 << 26;

/// Largest `--max-depth`: bounces per path, recursion depth of the Whitted tracer and
/// non-delta bounces (hence stored photons) per photon. Equal to the delta bounce cap of
/// camera and photon paths ([`crate::shading::MAX_DELTA_BOUNCES`]). The old bound, 100 000,
/// crashed the Whitted tracer with a stack overflow in a closed mirror box (so did 2048 on
/// a 2 MiB stack); the render workers' stacks ([`crate::render::WORKER_STACK`]) hold 4×
/// this depth (`tests/optics/stiff_renders.rs`).
pub const MAX_DEPTH: u32 = 1024;

/// Photon-mapping settings (`--method photon` and `sppm`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhotonSettings {
    /// Photons per pass (SPPM) or in total (photon); 0 = one per pixel (SPPM, at most
    /// [`MAX_PHOTONS`]) or 500 000. At most [`MAX_PHOTONS`].
    pub photons: u64,
    /// Initial (SPPM) or largest (photon) gather radius in scene units; `None` = from the
    /// pixel footprint at the visible points.
    pub radius: Option<f32>,
    /// SPPM radius-reduction parameter α ∈ (0, 1) (Knaus & Zwicker 2011: r²ᵢ₊₁ = r²ᵢ (i+α)/(i+1)).
    pub alpha: f32,
    /// SPPM passes.
    pub passes: u32,
    /// Photon Russian roulette rule.
    pub roulette: Roulette,
    /// Photons in a caustic-map estimate (photon).
    pub k_caustic: usize,
    /// Photons in a global-map estimate (photon, at final-gather hits).
    pub k_global: usize,
    /// How the hybrid estimates its caustic paths (`--caustics`).
    pub caustic_mode: CausticMode,
}

/// How the hybrid (`--method hybrid`) estimates the caustic-origin paths
/// ([`super::caustic`], [`super::light_trace`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CausticMode {
    /// The caustic map, gathered at every camera path's first non-delta vertex D₁ (the
    /// default: on the caustic-sphere and gem scenes it matched or beat the light-traced
    /// modes in relMSE at equal time and equal passes; BENCHMARKS.md, "Light-traced
    /// caustics").
    #[default]
    Map,
    /// Where D₁ is seen directly, light tracing of every caustic-origin photon vertex
    /// (L S+ D and its later diffuse bounces); the map where D₁ is seen through delta
    /// bounces.
    Light,
    /// Where D₁ is seen directly, light tracing of the L S+ D vertices (the caustic itself)
    /// and the map's later-bounce photons for the rest; the whole map where D₁ is seen
    /// through delta bounces.
    Mixed,
}

impl CausticMode {
    /// Parses `--caustics map|light|mixed` ([`crate::error::parse_name`]).
    pub fn parse(s: &str) -> Result<CausticMode> {
        let names = [
            ("map", CausticMode::Map),
            ("light", CausticMode::Light),
            ("mixed", CausticMode::Mixed),
        ];
        crate::error::parse_name("--caustics", s, &names)
    }
}

impl Default for PhotonSettings {
    fn default() -> Self {
        PhotonSettings {
            photons: 0,
            radius: None,
            alpha: 2.0 / 3.0,
            passes: 64,
            roulette: Roulette::Throughput,
            k_caustic: 64,
            k_global: 64,
            caustic_mode: CausticMode::default(),
        }
    }
}

impl PhotonSettings {
    /// Rejects values the CLI's parsers reject too, for library callers: more than
    /// [`MAX_PHOTONS`] photons, no pass, α outside (0, 1), a radius that is not finite and
    /// positive. Errors name the flag and the value.
    pub fn check(&self) -> Result<()> {
        let usage = |m: String| Err(Error::Usage(m));
        if self.photons > MAX_PHOTONS {
            return usage(format!(
                "--photons {}: at most {MAX_PHOTONS} photons (per SPPM pass, or in total for --method photon)",
                self.photons
            ));
        }
        if self.passes == 0 {
            return usage("--passes 0: at least 1 pass".into());
        }
        if !(self.alpha > 0.0 && self.alpha < 1.0) {
            return usage(format!(
                "--alpha {}: expected α strictly between 0 and 1",
                self.alpha
            ));
        }
        if let Some(r) = self.radius.filter(|r| !(r.is_finite() && *r > 0.0)) {
            return usage(format!("--radius {r}: expected a finite radius > 0"));
        }
        Ok(())
    }
}

/// The photons stored by the parallel chunks of one SPPM pass or one photon map, counted
/// against [`MAX_STORED_PHOTONS`]: chunks stop tracing once it is crossed and the pass
/// fails ([`StoreBudget::check`]); under the budget nothing changes (the same photons, in
/// the same order).
#[derive(Debug, Default)]
pub struct StoreBudget {
    stored: std::sync::atomic::AtomicU64,
}

impl StoreBudget {
    /// Counts `n` photons just stored; false once the total is over the budget.
    pub fn add(&self, n: usize) -> bool {
        let n = n as u64;
        let total = self
            .stored
            .fetch_add(n, std::sync::atomic::Ordering::Relaxed)
            .saturating_add(n);
        total <= MAX_STORED_PHOTONS
    }

    /// An error naming `--photons` (the `emitted` count) and `--max-depth` if the budget
    /// was crossed.
    pub fn check(&self, emitted: u64, max_depth: u32) -> Result<()> {
        if self.stored.load(std::sync::atomic::Ordering::Relaxed) <= MAX_STORED_PHOTONS {
            return Ok(());
        }
        Err(Error::Usage(format!(
            "--photons {emitted}: the photons would be stored more than {MAX_STORED_PHOTONS} \
             times (2 GiB; they bounce often in this scene): use fewer --photons or a smaller \
             --max-depth (now {max_depth})"
        )))
    }
}

/// What classic photon mapping (`--method photon`) uses of the photon flags.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhotonMapSettings {
    /// Photons emitted in total; 0 = 500 000. At most [`MAX_PHOTONS`].
    pub photons: u64,
    /// Largest gather radius in scene units; `None` = 16 pixel footprints at the scene's
    /// centre.
    pub radius: Option<f32>,
    /// Photon Russian roulette rule.
    pub roulette: Roulette,
    /// Photons in a caustic-map estimate.
    pub k_caustic: usize,
    /// Photons in a global-map estimate (at final-gather hits).
    pub k_global: usize,
}

/// What SPPM (`--method sppm`) uses of the photon flags.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SppmSettings {
    /// Photons per pass; 0 = one per pixel (at most [`MAX_PHOTONS`]).
    pub photons: u64,
    /// Initial gather radius in scene units; `None` = 2 pixel footprints at the median
    /// visible point of the first pass.
    pub radius: Option<f32>,
    /// Radius-reduction parameter α ∈ (0, 1) (Knaus & Zwicker 2011).
    pub alpha: f32,
    /// Passes.
    pub passes: u32,
    /// Photon Russian roulette rule.
    pub roulette: Roulette,
    /// Spectral transport: camera paths keep their 4 wavelengths at rough dispersive
    /// interfaces with spectral MIS under their own hero (`crate::integrator::path`'s
    /// `own_hero`; on by default); off keeps the hero only there, for comparisons.
    pub spectral_mis: bool,
}

/// What the hybrid (`--method hybrid`) uses of the photon flags: its caustic map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CausticSettings {
    /// Caustic-light photons emitted per pass (one pass per camera sample per pixel);
    /// 0 = one per pixel (at most [`MAX_PHOTONS`]). Only those reaching a non-delta surface
    /// through delta bounces are stored.
    pub photons: u64,
    /// Initial gather radius in scene units; `None` = from the pixel footprint at the first
    /// pass's caustic photons ([`super::caustic`]).
    pub radius: Option<f32>,
    /// Radius-reduction parameter α ∈ (0, 1) (Knaus & Zwicker 2011).
    pub alpha: f32,
    /// Map only, or light tracing where the caustic is seen directly ([`CausticMode`]).
    pub mode: CausticMode,
    /// In spectral transport, the camera paths split into their 4 wavelengths at their
    /// first smooth dispersive interface ([`super::path::Dispersion::SPLIT`]; on by
    /// default), rather than keeping the hero only (for comparisons).
    pub split: bool,
}

impl CausticSettings {
    /// What the hybrid's camera paths keep of their wavelengths ([`Self::split`]).
    pub fn dispersion(&self) -> super::path::Dispersion {
        match self.split {
            true => super::path::Dispersion::SPLIT,
            false => super::path::Dispersion::HERO,
        }
    }

    /// [`PhotonSettings::check`] on the fields this method uses.
    pub fn check(&self) -> Result<()> {
        PhotonSettings {
            photons: self.photons,
            radius: self.radius,
            alpha: self.alpha,
            ..PhotonSettings::default()
        }
        .check()
    }
}

impl PhotonSettings {
    /// The part `--method hybrid` uses.
    pub fn caustics(&self) -> CausticSettings {
        CausticSettings {
            photons: self.photons,
            radius: self.radius,
            alpha: self.alpha,
            mode: self.caustic_mode,
            split: true,
        }
    }

    /// The part `--method vcm` (`merge`) and `--method bpt` use.
    pub fn vcm(&self, merge: bool) -> super::vcm::VcmSettings {
        super::vcm::VcmSettings {
            radius: self.radius,
            alpha: self.alpha,
            merge,
        }
    }

    /// The part `--method photon` uses.
    pub fn photon_map(&self) -> PhotonMapSettings {
        PhotonMapSettings {
            photons: self.photons,
            radius: self.radius,
            roulette: self.roulette,
            k_caustic: self.k_caustic,
            k_global: self.k_global,
        }
    }

    /// The part `--method sppm` uses.
    pub fn sppm(&self) -> SppmSettings {
        SppmSettings {
            photons: self.photons,
            radius: self.radius,
            alpha: self.alpha,
            passes: self.passes,
            roulette: self.roulette,
            spectral_mis: true,
        }
    }
}

impl PhotonMapSettings {
    /// [`PhotonSettings::check`] on the fields this method uses.
    pub fn check(&self) -> Result<()> {
        PhotonSettings {
            photons: self.photons,
            radius: self.radius,
            ..PhotonSettings::default()
        }
        .check()
    }
}

impl SppmSettings {
    /// [`PhotonSettings::check`] on the fields this method uses.
    pub fn check(&self) -> Result<()> {
        PhotonSettings {
            photons: self.photons,
            radius: self.radius,
            alpha: self.alpha,
            passes: self.passes,
            ..PhotonSettings::default()
        }
        .check()
    }
}

/// Rejects a `--max-depth` outside 1..=[`MAX_DEPTH`] with an error naming the flag.
pub fn check_depth(max_depth: u32) -> Result<()> {
    if !(1..=MAX_DEPTH).contains(&max_depth) {
        return Err(Error::Usage(format!(
            "--max-depth {max_depth}: expected 1 to {MAX_DEPTH} bounces"
        )));
    }
    Ok(())
}
