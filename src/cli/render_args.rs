//! `iris render`'s flags (also flattened into `iris turntable`) and the material overrides
//! (`--stone`, `--metal`) shared by render, converge and info: clap structs and their
//! conversion into [`crate::app::RenderOptions`]. Units are the flags' own (seconds,
//! pixels, metres); every bound is checked while parsing ([`super::parse`]).

use super::parse::*;
use crate::accel::Backend;
use crate::app::{self, RenderOptions};
use crate::app::{BudgetFlags, SpectralMode};
use crate::integrator::{CausticMode, Method, PhotonSettings};
use crate::measure::MeasureOptions;
use crate::output::{DisplayOptions, Exposure, ToneMap};
use crate::photon::trace::Roulette;
use crate::sampler::SamplerKind;
use std::path::PathBuf;

/// `--exposure`, `--tonemap`: how an 8-bit PNG is made from the linear image (render and
/// the commands that flatten its flags, merge).
#[derive(clap::Args, Clone)]
pub struct PngArgs {
    /// PNG exposure: `auto` (log-average luminance to 0.18) or stops in [-64, 64], e.g. -1.5.
    #[arg(long, default_value = "auto", value_parser = parse_exposure, allow_hyphen_values = true)]
    pub exposure: Exposure,
    /// PNG tone map: aces, reinhard, clamp.
    #[arg(long, default_value = "aces", value_parser = ToneMap::parse)]
    pub tonemap: ToneMap,
}

impl PngArgs {
    /// The display options the flags give.
    pub fn display(&self) -> DisplayOptions {
        DisplayOptions {
            exposure: self.exposure,
            tonemap: self.tonemap,
        }
    }
}

/// `--stone`, `--metal`, `--metal-roughness`: material overrides for render, converge, info.
#[derive(clap::Args, Clone, Default)]
pub struct LookArgs {
    /// Make materials a stone (repeatable): NAME is diamond, sapphire, ruby, emerald,
    /// cubic-zirconia, quartz, crown-glass, calcite, zircon, peridot, tourmaline,
    /// tanzanite, topaz, moissanite or rutile (the birefringent ones with their optic axis
    /// along the model's +Y; docs/gem-optics.md). Without =SELECTOR it changes the stones
    /// (transmissive volumes; in a file with none, closed surfaces) no other
    /// --stone/--metal names; NAME=* changes every material but the lights;
    /// NAME=MATERIAL changes that material (a mesh name if no material has it),
    /// NAME=material:MATERIAL or NAME=mesh:MESH say which.
    #[arg(long, value_name = "NAME[=SELECTOR]")]
    pub stone: Vec<String>,
    /// Make materials a measured metal (repeatable), for settings: gold, silver, platinum,
    /// copper, rose-gold, spectral n and k (see docs/stones-and-metals.md); selectors as
    /// for --stone.
    #[arg(long, value_name = "NAME[=SELECTOR]")]
    pub metal: Vec<String>,
    /// GGX perceptual roughness of every --metal surface, 0 (polished mirror, the default)
    /// to 1.
    #[arg(long, default_value_t = 0.0, value_parser = parse_unit, allow_hyphen_values = true)]
    pub metal_roughness: f32,
}

impl LookArgs {
    /// The flags, stones first, each in the order given.
    pub fn flags(&self) -> crate::Result<Vec<crate::prepare::looks::LookFlag>> {
        use crate::prepare::looks::LookFlag;
        let stones = self.stone.iter().map(|a| LookFlag::stone(a));
        let metals = self
            .metal
            .iter()
            .map(|a| LookFlag::metal(a, self.metal_roughness));
        stones.chain(metals).collect()
    }
}

/// `iris render`: every flag of one render.
#[derive(clap::Args, Clone)]
pub struct RenderArgs {
    /// Scene file (.gltf, .glb, .obj).
    pub scene: PathBuf,
    /// Output image (.png or .exr); default `<scene stem>.png` here.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Image size WxH, e.g. 800x600 (default 800 wide at the camera's aspect): at most 2^26
    /// pixels (8192x8192) and 8 GiB of per-pixel buffers (about 55 M pixels, e.g.
    /// 8192x6400; for `--method sppm` about 19 M pixels, e.g. 4096x4096).
    #[arg(long, value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Samples per pixel, 1 to 1000000: the render stops there (or earlier at --time or
    /// --target-error). Without --spp and --passes the render is open-ended: it stops at
    /// --time / --target-error, by default at the estimated error 0.01 of a PNG's picture
    /// (0.03 relative for an EXR) or after 120 s, whichever comes first, and rewrites the
    /// output as it goes.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub spp: Option<u32>,
    /// Rendering method: auto (the default: from probe photons, the path tracer when no light
    /// reaches a diffuse surface through specular ones, BPT instead in an enclosed room, VCM
    /// for rough glass or where caustics carry 4 % or more of the light, else the hybrid; the
    /// reason is printed), whitted (recursive ray tracing, after Cropp & Zhang's paper §4), path
    /// (path tracing with next-event estimation and MIS), photon (classic photon mapping:
    /// caustic + global maps, final gather), sppm (stochastic progressive photon mapping:
    /// passes, converges), hybrid (the path tracer plus a progressive caustic photon map for
    /// light that reaches a diffuse surface through specular ones only; one pass per
    /// sample, converges), vcm (vertex connection and merging: light and camera subpaths
    /// connected and merged under one multiple importance sampling; one pass per sample,
    /// converges; perspective cameras), bpt (bidirectional path tracing: vcm without
    /// merging, unbiased).
    #[arg(long, value_parser = Method::parse)]
    pub method: Option<Method>,
    /// Maximum number of bounces (reflections and refractions) per path, 1 to 1024 (also
    /// the Whitted tracer's recursion depth and the photons stored per photon path); a
    /// camera path's random walk through a scattering medium counts once (1: single
    /// scattering).
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=i64::from(crate::integrator::MAX_DEPTH)))]
    pub max_depth: u32,
    /// Intersection backend: auto (Embree when compiled in), embree, bvh.
    #[arg(long, default_value = "auto", value_parser = Backend::parse)]
    pub accel: Backend,
    /// Random seed (same seed, scene and backend → same image).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Numbers driving the camera paths: zsobol (Owen-scrambled Sobol' per pixel in Morton
    /// order, blue-noise error; the default) or independent (a PCG stream per sample).
    #[arg(long, default_value = "zsobol", value_parser = SamplerKind::parse)]
    pub sampler: SamplerKind,
    /// Worker threads, 0 to 1024 (0 = one per core).
    #[arg(long, default_value_t = 0, value_parser = parse_threads())]
    pub threads: usize,
    /// Camera name or index from the file.
    #[arg(long)]
    pub camera: Option<String>,
    /// A camera at the eye EX,EY,EZ looking at TX,TY,TZ (scene units, world space, +Y up)
    /// with a vertical field of view of FOV degrees (0.1 to 170), e.g. `0,0.3,1:0,0,0:35`;
    /// replaces the file's camera (not with --camera or --view). `iris view` prints it.
    #[arg(long, value_name = "EX,EY,EZ:TX,TY,TZ:FOV", value_parser = parse_look_at, allow_hyphen_values = true)]
    pub camera_look_at: Option<crate::prepare::look_at::LookAt>,
    /// The model turned about the vertical axis through its centre by 360°·F/N, as frame F
    /// of `iris turntable --frames N` (0 ≤ F < N ≤ 10000), e.g. `--turn 90/360`.
    #[arg(long, value_name = "F/N", value_parser = parse_turn)]
    pub turn: Option<crate::prepare::turntable::Spin>,
    /// PNG exposure and tone map.
    #[command(flatten)]
    pub png: PngArgs,
    /// Environment light: `none`, a grey value or `R,G,B` radiance, an equirectangular
    /// .exr/.hdr map (+Y up; the image centre looks along −Z), or a computed clear sky and
    /// its sun, `sky:elevation=DEG[,azimuth=DEG,turbidity=T]` (elevation −10 to 90, azimuth
    /// from −Z towards +X, default 0, turbidity 1 to 10, default 2). Default: the scene
    /// file's `iris_environment` (glTF scene extras), else none.
    #[arg(long, allow_hyphen_values = true)]
    pub env: Option<String>,
    /// Fog filling the scene's air (its bounding box), `none` to clear the file's: a
    /// density `D` (grey extinction per scene unit, m⁻¹ in metric files) or comma-separated
    /// `density=D`, `rayleigh=S` (σ_s at 550 nm, falling as λ⁻⁴, Rayleigh phase),
    /// `color=R:G:B` (multiple-scattering albedo, default white) and `g=G` (Henyey–Greenstein
    /// anisotropy in (−1, 1)). Default: the scene file's `iris_fog` (glTF scene extras),
    /// else none. Only `--method path` (and `auto`) render media.
    #[arg(long, allow_hyphen_values = true)]
    pub fog: Option<String>,
    /// Spectral transport (4 wavelengths per sample, CIE colour): `auto` when a material is
    /// dispersive or a light names a spectrum, `on` always, `off` never (RGB, dispersive
    /// materials use n_d).
    #[arg(long, default_value = "auto", value_parser = SpectralMode::parse)]
    pub spectral: SpectralMode,
    /// Polarized transport (Stokes vectors; docs/gem-optics.md): `auto` when a material
    /// is a birefringent crystal or `--polarizer` is given, `on` always, `off` never
    /// (crystals then render with one index). Needs spectral transport and the path tracer
    /// or the hybrid (`auto` takes the hybrid where it would have chosen a photon method).
    #[arg(long, default_value = "auto", value_parser = crate::plan::PolarizationMode::parse)]
    pub polarization: crate::plan::PolarizationMode,
    /// A linear polarizer in front of the camera, its transmission axis ANGLE degrees
    /// (−360 to 360) from the image's horizontal, counter-clockwise.
    #[arg(long, value_parser = super::parse::parse_polarizer, allow_hyphen_values = true)]
    pub polarizer: Option<f32>,
    /// Studio lighting (not with `--env`): `soft` (grey, broad softboxes; the default for a
    /// file with no light of its own), `jeweller` (dark, small bright strips: fire),
    /// `bright` (white high-key), or `none` (plain directional key and fill). A file that
    /// brings its own light gets a studio only when this flag names one (added to the
    /// file's lights).
    #[arg(long, value_parser = crate::studio::Studio::parse)]
    pub studio: Option<crate::studio::Studio>,
    /// White floor under the model: `auto` (for a transmissive model with nothing under
    /// it, in a file that brings no light of its own), `on` or `off`.
    #[arg(long, default_value = "auto", value_parser = crate::studio::GroundMode::parse)]
    pub ground: crate::studio::GroundMode,
    /// SPPM passes, 1 to 10000000 (with --time or --target-error, whichever comes first).
    /// Given alone or with --spp, the other count is 4 spp or 64 passes.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=10_000_000))]
    pub passes: Option<u32>,
    /// Time budget in seconds (more than 0, at most 10000000): every method stops after the
    /// round of samples (SPPM: the pass) that crosses it, with at least one sample per pixel.
    /// Without --spp/--passes it is the whole budget (no error target unless given);
    /// otherwise the first limit reached ends the render. Default without any budget flag:
    /// 120.
    #[arg(long, value_parser = parse_seconds, allow_hyphen_values = true)]
    pub time: Option<f64>,
    /// Photons per SPPM or hybrid pass or in total for `--method photon`, 1 to 16777216 (2^24).
    /// Default: SPPM one per pixel; the hybrid with `--caustics map` the count a pilot finds
    /// fastest to converge (1/64 to 4 per pixel, named in the last line), with `light` or
    /// `mixed` one per pixel; photon mapping 500000. A pass or map that would store more than
    /// 2^26 photons (2 GiB) stops with an error.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=crate::integrator::MAX_PHOTONS))]
    pub photons: Option<u64>,
    /// Initial SPPM / hybrid / VCM gather radius, largest photon-map radius, in scene units (default: from
    /// the pixel footprint): finite and > 0 (no memory depends on it).
    #[arg(long, value_parser = parse_radius, allow_hyphen_values = true)]
    pub radius: Option<f32>,
    /// SPPM / hybrid / VCM radius reduction α in (0, 1): r²ᵢ₊₁ = r²ᵢ (i+α)/(i+1) (Knaus & Zwicker 2011).
    #[arg(long, default_value_t = 2.0 / 3.0, value_parser = parse_alpha, allow_hyphen_values = true)]
    pub alpha: f32,
    /// Write the image so far at the checkpoints (1, 2, 4, … samples, or passes for SPPM)
    /// that are at least K samples or passes after the last one written; K from 1 to
    /// 10000000. Without it, an open-ended render (no --spp/--passes) rewrites the image at
    /// the checkpoints at most every 2 s.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=10_000_000))]
    pub checkpoint: Option<u32>,
    /// Photon Russian roulette rule: throughput (survivors keep their power), lobe (Cropp &
    /// Zhang's rule: diffuse / reflect / refract by the material's colours; `seed` is the
    /// former name of lobe).
    #[arg(long, default_value = "throughput", value_parser = Roulette::parse)]
    pub photon_rr: Roulette,
    /// How `--method hybrid` counts its caustics: map (the caustic photon map everywhere),
    /// light (light tracing splatted onto the image wherever the caustic light is seen
    /// directly, the map where it is seen through glass or mirrors) or mixed (light tracing
    /// for the caustic itself, the map for its later diffuse bounces, where seen directly).
    /// An orthographic camera keeps the map.
    #[arg(long, default_value = "map", value_parser = CausticMode::parse)]
    pub caustics: CausticMode,
    /// Reference EXR (same size as the render; sets the size if --size is not given): error
    /// against it at every checkpoint (1, 2, 4, … samples or passes).
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Write error against time as CSV: a "load" row, a "build" row, one "render" row per
    /// checkpoint.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Plot error against time, log-log (.png or .svg): against --reference if given, else
    /// the half-buffer estimate.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Stop once the estimated error of the image as written (from two half images, from 8
    /// samples or passes on) is at or below E, finite and > 0. For a PNG: the display RMSE
    /// of the picture as a viewer sees it (after exposure, tone map and clipping, denoised
    /// when the PNG is; values in [0, 1]); for an EXR: the relative RMSE of the linear
    /// values. Upper bound: --time, --spp or --passes, whichever comes first; given alone,
    /// 120 s. Default without any budget flag: 0.01 for a PNG, 0.03 for an EXR.
    #[arg(long, value_parser = parse_target, allow_hyphen_values = true)]
    pub target_error: Option<f64>,
    /// No progress bar.
    #[arg(short, long)]
    pub quiet: bool,
    /// Frame the model automatically from this view: threequarter (front-right, 35° above;
    /// the default for files without a camera), front, top, side. Replaces the file's
    /// camera; not with --camera.
    #[arg(long, value_parser = crate::framing::View::parse)]
    pub view: Option<crate::framing::View>,
    /// What camera rays that see no surface show: `env` (the default: the environment, or
    /// black), a colour (white, black, grey, #rrggbb, or R,G,B sRGB values in [0, 1]), or
    /// `transparent` (PNG with alpha, EXR with an A channel). The environment still lights
    /// the model; pixels count as covered when the camera ray hits a surface (glass too).
    #[arg(long, value_parser = crate::output::Background::parse)]
    pub background: Option<crate::output::Background>,
    /// `--stone`, `--metal`, `--metal-roughness`.
    #[command(flatten)]
    pub looks: LookArgs,
    /// Print the render plan to stderr before rendering: which stages the scene needs
    /// (spectral or RGB, photons, volumes, textures, acceleration, environment, nested
    /// media, denoise), why, and what each costs (a 32x24 probe render, 10 000 photons).
    #[arg(long)]
    pub explain: bool,
    /// Render only shard I of N (1 ≤ I ≤ N, counted from 1 like Slurm array indices) and
    /// write a partial image (-o PART.exr) for `iris merge`: with --spp/--passes T the
    /// units ⌊(I−1)T/N⌋..⌊I·T/N⌋; without, a segment of the Sobol' block until --time or
    /// --target-error (each per shard). Written only at the end.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<crate::app::shard::Shard>,
    /// Denoising with Intel Open Image Denoise (albedo and normals of the first
    /// non-specular surface seen through glass as auxiliary images): `auto` denoises a PNG
    /// and leaves an EXR raw, `on` denoises a PNG or adds the denoised image to an EXR as
    /// the layer `denoised` (channels denoised.R, .G, .B), `off` never.
    #[arg(long, default_value = "auto", value_parser = crate::denoise::DenoiseMode::parse)]
    pub denoise: crate::denoise::DenoiseMode,
    /// Adaptive sampling: converged 16×16 tiles rest while the noisy ones take samples
    /// (from 32 samples per pixel on, never below a quarter of the image's; a tile also
    /// rests below half the error target).
    /// `auto` turns it on when the time limit or the error target ends the render (no
    /// --spp/--passes), `on` always, `off` never; never for SPPM or a shard.
    #[arg(long, default_value = "auto", value_parser = crate::app::adaptive::AdaptiveMode::parse)]
    pub adaptive: crate::app::adaptive::AdaptiveMode,
}

impl RenderArgs {
    /// The render options (measurement and drop-in preview included) these flags ask for.
    pub fn options(&self) -> crate::Result<RenderOptions> {
        let a = self.clone();
        let budget = BudgetFlags {
            method: a.method,
            spp: a.spp,
            passes: a.passes,
            time: a.time.map(std::time::Duration::from_secs_f64),
            target_error: a.target_error,
        }
        .resolve();
        let options = RenderOptions {
            scene: a.scene,
            output: a.output,
            size: a.size,
            spp: budget.spp,
            method: budget.method,
            max_depth: a.max_depth,
            time_limit: budget.time_limit,
            checkpoint: a.checkpoint,
            watch: budget.open,
            photon: PhotonSettings {
                photons: a.photons.unwrap_or(0),
                radius: a.radius,
                alpha: a.alpha,
                passes: budget.passes,
                roulette: a.photon_rr,
                caustic_mode: a.caustics,
                ..PhotonSettings::default()
            },
            accel: a.accel,
            seed: a.seed,
            sampler: a.sampler,
            threads: a.threads,
            camera: a.camera,
            look_at: a.camera_look_at,
            display: a.png.display(),
            quiet: a.quiet,
            env: a
                .env
                .as_deref()
                .map(crate::light::env::Environment::parse_arg)
                .transpose()?,
            fog: a.fog.as_deref().map(parse_fog).transpose()?,
            spectral: a.spectral,
            polarization: a.polarization,
            polarizer: a.polarizer,
            measure: MeasureOptions {
                reference: a.reference,
                report: a.report,
                plot: a.plot,
                target_error: budget.target_error,
                default_target: budget.default_target,
            },
            preview: app::PreviewOptions {
                studio: a.studio,
                ground: a.ground,
                view: a.view,
                background: a.background.unwrap_or_default(),
            },
            looks: a.looks.flags()?,
            explain: a.explain,
            denoise: a.denoise,
            adaptive: a.adaptive,
            spin: a.turn,
            exr_copy: None,
            shard: a.shard,
        };
        Ok(options)
    }
}

/// `--fog SPEC` or `--fog none` ([`crate::volume::fog`]).
fn parse_fog(spec: &str) -> crate::error::Result<Option<crate::volume::Medium>> {
    if spec.trim().eq_ignore_ascii_case("none") {
        return Ok(None);
    }
    crate::volume::fog::parse(spec)
        .map(Some)
        .map_err(|why| crate::error::Error::Usage(format!("--fog {spec}: {why}")))
}
