//! Integrators: how radiance along camera rays is estimated. A closed enum; each variant's
//! maths lives in its own module, and the per-hit step shared between them (and with photon
//! tracing) lives below them in [`crate::shading`].

pub mod path;
pub mod photon_map;
pub mod sppm;
pub mod whitted;

use crate::math::{Ray, Rng};
use crate::scene::Scene;
use crate::spectrum::Carrier;
#[allow(unused_imports)]
use glam::Vec3;

/// The rendering method (`--method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Recursive ray tracing after the seed paper §4: direct light from punctual lights,
    /// Fresnel-weighted reflection and refraction branches.
    Whitted,
    /// Unidirectional path tracing with next-event estimation and MIS.
    Path,
    /// Classic photon mapping (Jensen): direct light by shadow rays, a caustic map gathered
    /// at the first diffuse hit, a global map reached by final gathering.
    Photon,
    /// Stochastic progressive photon mapping in passes (Hachisuka & Jensen 2009, radius
    /// sequence of Knaus & Zwicker 2011).
    Sppm,
    /// `Sppm` when the scene has caustic paths, `Path` otherwise ([`Method::resolve`]); an
    /// unresolved `Auto` renders as `Path`.
    Auto,
}

impl Method {
    /// Resolves [`Method::Auto`] for `scene`: SPPM when light can reach a diffuse-like
    /// surface through specular ones (found by tracing a few thousand photons:
    /// [`crate::photon::trace::has_caustic_paths`]), the path tracer otherwise. Returns the
    /// method and the reason.
    pub fn resolve(self, scene: &Scene) -> (Method, Option<String>) {
        if self != Method::Auto {
            return (self, None);
        }
        let emitter = crate::photon::emit::PhotonEmitter::new(scene);
        if !emitter.is_empty() && crate::photon::trace::has_caustic_paths(scene, &emitter, 4096) {
            (
                Method::Sppm,
                Some("--method auto: light reaches diffuse surfaces through specular ones (caustics): SPPM".into()),
            )
        } else {
            (
                Method::Path,
                Some("--method auto: no caustic paths found: path tracer".into()),
            )
        }
    }
}

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
/// this depth (`tests/stiff_renders.rs`).
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
    pub roulette: crate::photon::trace::Roulette,
    /// Photons in a caustic-map estimate (photon).
    pub k_caustic: usize,
    /// Photons in a global-map estimate (photon, at final-gather hits).
    pub k_global: usize,
}

impl Default for PhotonSettings {
    fn default() -> Self {
        PhotonSettings {
            photons: 0,
            radius: None,
            alpha: 2.0 / 3.0,
            passes: 64,
            roulette: crate::photon::trace::Roulette::Throughput,
            k_caustic: 64,
            k_global: 64,
        }
    }
}

impl PhotonSettings {
    /// Rejects values the CLI's parsers reject too, for library callers: more than
    /// [`MAX_PHOTONS`] photons, no pass, α outside (0, 1), a radius that is not finite and
    /// positive. Errors name the flag and the value.
    pub fn check(&self) -> crate::error::Result<()> {
        let usage = |m: String| Err(crate::error::Error::Usage(m));
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
    pub fn check(&self, emitted: u64, max_depth: u32) -> crate::error::Result<()> {
        if self.stored.load(std::sync::atomic::Ordering::Relaxed) <= MAX_STORED_PHOTONS {
            return Ok(());
        }
        Err(crate::error::Error::Usage(format!(
            "--photons {emitted}: the photons would be stored more than {MAX_STORED_PHOTONS} \
             times (2 GiB; they bounce often in this scene): use fewer --photons or a smaller \
             --max-depth (now {max_depth})"
        )))
    }
}

/// Per-thread state an integrator carries along one camera sample.
pub struct Context {
    /// Random numbers for this pixel sample.
    pub rng: Rng,
    /// Rays traced so far (closest-hit and shadow).
    pub rays: u64,
}

/// Integrator settings.
#[derive(Debug, Clone, Copy)]
pub struct Integrator {
    /// Which method.
    pub method: Method,
    /// Maximum recursion depth (specular bounces count too); at most [`MAX_DEPTH`].
    pub max_depth: u32,
    /// Photon-mapping settings (ignored by Whitted and path).
    pub photon: PhotonSettings,
}

impl Integrator {
    /// Rejects settings outside the CLI's bounds (`--max-depth` in 1..=[`MAX_DEPTH`], and
    /// [`PhotonSettings::check`]) with an error naming the flag, for library callers.
    pub fn check(&self) -> crate::error::Result<()> {
        if !(1..=MAX_DEPTH).contains(&self.max_depth) {
            return Err(crate::error::Error::Usage(format!(
                "--max-depth {}: expected 1 to {MAX_DEPTH} bounces",
                self.max_depth
            )));
        }
        self.photon.check()
    }

    /// Radiance arriving along `ray` at the sample's wavelengths `lambda` (linear RGB when
    /// `C` is [`Vec3`]), for the per-sample methods; the photon methods need their maps or
    /// passes ([`crate::render`]) and fall back to the path tracer here.
    pub fn radiance<C: Carrier>(
        &self,
        scene: &Scene,
        ray: &Ray,
        lambda: C::Lambda,
        ctx: &mut Context,
    ) -> C {
        match self.method {
            Method::Whitted => whitted::radiance(scene, ray, self.max_depth, lambda, ctx),
            Method::Path | Method::Photon | Method::Sppm | Method::Auto => {
                path::radiance(scene, ray, self.max_depth, lambda, ctx)
            }
        }
    }
}
