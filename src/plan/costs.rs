//! What each stage of a [`Plan`] costs on its scene, for `--explain` and `iris info`:
//! measured on the scene itself (a [`PROBE_SIZE`], 1 spp probe render with RGB and with
//! spectral transport, fastest of [`PROBE_REPEATS`]; [`COST_PHOTONS`] traced photons; the
//! acceleration build time) or quoted from BENCHMARKS.md with the section named. Times are
//! wall-clock milliseconds on this machine; nothing else is claimed.

use super::Plan;
use crate::camera::Camera;
use crate::error::Result;
use crate::integrator::capability::Photons;
use crate::integrator::{Integrator, Method};
use crate::photon::emit::PhotonEmitter;
use crate::photon::trace::{trace, Roulette, TraceSettings};
use crate::render::RenderSettings;
use crate::scene::Scene;
use glam::Vec3;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Photons traced to time a photon pass.
pub const COST_PHOTONS: u32 = 10_000;
/// Timed probe renders per transport (the fastest counts).
pub const PROBE_REPEATS: u32 = 3;
/// Probe render size for the transport cost.
pub const PROBE_SIZE: (u32, u32) = (32, 24);

impl Plan {
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
    /// 1 spp probe render with RGB and with spectral transport (the plan's method when it
    /// traces no photons, else the path tracer; fastest of [`PROBE_REPEATS`] each), and 10 000 traced
    /// photons.
    pub fn measure_costs(&mut self, scene: &Scene, camera: &Camera, threads: usize) -> Result<()> {
        let method = match self.method.caps().photons {
            Photons::None => self.method,
            _ => Method::Path,
        };
        let probe = |spectral: bool| -> Result<f64> {
            let (w, h) = PROBE_SIZE;
            let integrator = Integrator::new(method, 64, &Default::default())?;
            let settings = RenderSettings {
                sampler: Default::default(),
                width: w,
                height: h,
                spp: 1,
                seed: 0,
                threads,
                quiet: true,
                spectral,
                time_limit: None,
                adaptive: None,
                cancel: Default::default(),
                kernel: Default::default(),
            };
            let start = Instant::now();
            integrator.render(scene, camera, &settings)?;
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
                    method.name(),
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
                    scene.accel_build_time().as_secs_f64() * 1e3
                ),
                "lanes" => "not measured here; BENCHMARKS.md 'Lanes: 8 or 16 camera paths per \
                            packet': 0.90-1.03x the time of single rays on the caustic \
                            sphere, a diamond and CompareDispersion"
                    .into(),
                "nested media" => "BENCHMARKS.md 'Path tracer on real scenes': 0.45 us per probe on Embree, \
                      8.4 us on the BVH, at each hit on a marked triangle"
                    .into(),
                _ => "not measured".into(),
            });
        }
        Ok(())
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
    let numbers = crate::photon::emit::PhotonNumbers::new(0x0C05_7000);
    for i in 0..COST_PHOTONS {
        let mut rng = crate::math::Rng::new(&[0x0C05_7000, i as u64]);
        let aim = crate::photon::emit::DEFAULT_AIM;
        if let Some(ph) = emitter.emit_index(scene, &numbers, i as u64, aim) {
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
    let bytes = crate::fileio::input::read(path, crate::fileio::Input::Scene).ok()?;
    let g = gltf::Gltf::from_slice_without_validation(&bytes).ok()?;
    Some((g.document.images().len(), g.document.meshes().len()))
}
