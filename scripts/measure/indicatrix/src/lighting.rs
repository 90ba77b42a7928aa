//! indicatrix's studio lighting, and the same lighting written as an equirectangular map.
//!
//! Both presets used here (`tent`, `ring`) are one illuminant spectrum times a scalar,
//! wavelength-independent field over directions (`rig.rs`: `DirectionLighting::Scaled` for
//! the light tent, `DirectionLighting::Rig` for the studio rig, whose every term multiplies
//! the same `spec_power`), and indicatrix white-balances that illuminant to D65 (von Kries,
//! Bradford). So the lighting a camera sees in direction `d` is exactly grey:
//! `k * g(d) * (1, 1, 1)` in linear sRGB, `g(d)` = the rig's radiance at any wavelength /
//! the illuminant's power there, `k` = the luminance indicatrix's tracer gives a unit `g`
//! (measured by [`calibrate`], by tracing rays that miss the stone).
//!
//! What a map cannot hold: the light tent darkens the directions round the observer (a
//! 16° head shadow round the direction from the stone to the eye, per pixel). The map puts
//! it round +Y, the eye of the face-up camera seen from the stone's centre; from the edge of
//! the stone the eye is atan(1 / distance) off +Y (0.6° at the 100 girdle radii used here).

use glam::Vec3;
use indicatrix::{
    geometry::GpuFacetPlane,
    optics::{
        materials::GemMaterial,
        raytracer::{
            DEFAULT_HEAD_SHADOW_DEG, EnvironmentSource, LightingPreset, Ray, build_plane_soa,
            hash_u32, head_shadow_cosines, sample_studio_environment_with_rig_shadow_tray,
            studio_spec_power, trace_spectral_ray_with_finish_soa,
        },
    },
    optics::studio_rig::StudioRig,
    render_setup::Backdrop,
};

/// A lighting set-up of indicatrix's studio.
#[derive(Clone, Copy, Debug)]
pub struct Lighting {
    pub name: &'static str,
    pub preset: LightingPreset,
    pub backdrop: Backdrop,
    /// Key light azimuth and elevation, degrees.
    pub light_yaw_deg: f32,
    pub light_pitch_deg: f32,
    pub exposure: f32,
}

impl Lighting {
    /// `tent`: the desktop viewer's defaults (light tent + black cards, white paper tray,
    /// key light at 48° azimuth, 72° elevation). `ring`: "Gem Studio Ring Lights" (the
    /// analytic studio rig: dark charcoal backdrop, key and fill softboxes, 16 pinpoint ring
    /// lights), its own ground, same light pose.
    pub fn by_name(name: &str) -> Self {
        let (name, preset, backdrop) = match name {
            "tent" => ("tent", LightingPreset::LightTent, Backdrop::White),
            "ring" => ("ring", LightingPreset::RingLights, Backdrop::AsLit),
            other => panic!("unknown lighting {other:?} (tent, ring)"),
        };
        Self {
            name,
            preset,
            backdrop,
            light_yaw_deg: 48.0,
            light_pitch_deg: 72.0,
            exposure: 1.0,
        }
    }

    pub fn yaw(&self) -> f32 {
        self.light_yaw_deg.to_radians()
    }

    pub fn pitch(&self) -> f32 {
        self.light_pitch_deg.to_radians()
    }

    /// Tray radiance at exposure 1 (0 = the preset's own ground).
    pub fn tray(&self) -> f32 {
        self.backdrop.resolve(self.preset, self.yaw(), self.pitch())
    }

    pub fn studio(&self) -> EnvironmentSource<'static> {
        self.preset
            .studio(self.exposure, self.yaw(), self.pitch())
            .with_backdrop(self.tray())
    }

    pub fn describe(&self) -> String {
        format!(
            "indicatrix {:?} ({}), backdrop {:?} (tray radiance {:.4}), key light yaw {}° pitch {}°, exposure {}, head shadow {}°",
            self.preset,
            self.preset.label(),
            self.backdrop,
            self.tray(),
            self.light_yaw_deg,
            self.light_pitch_deg,
            self.exposure,
            DEFAULT_HEAD_SHADOW_DEG
        )
    }

    /// `g(dir)`: the rig's radiance towards `dir` divided by the illuminant's power, seen by
    /// an observer in direction `observer` from the stone.
    pub fn g(&self, rig: &StudioRig, dir: Vec3, observer: Vec3, lambda: f32) -> f32 {
        sample_studio_environment_with_rig_shadow_tray(
            dir,
            lambda,
            self.preset,
            self.exposure,
            rig,
            observer,
            head_shadow_cosines(DEFAULT_HEAD_SHADOW_DEG),
            self.tray(),
        ) / studio_spec_power(self.preset, lambda)
    }
}

/// Result of [`calibrate`].
pub struct Calibration {
    /// Luminance (CIE Y) indicatrix gives a unit `g`.
    pub k: f32,
    /// Chromaticity of the traced environment (D65 is 0.3127, 0.3290).
    pub xy: (f32, f32),
    /// Largest relative spread of `g` over 400..700 nm at a few directions (0: one spectrum).
    pub spectral_spread: f32,
}

/// Measures `k` by tracing `samples` camera rays that miss the stone towards two
/// directions, through the real tracer (white balance and XYZ integration included).
pub fn calibrate(lighting: &Lighting, planes: &[GpuFacetPlane], samples: u32) -> Calibration {
    let soa = build_plane_soa(planes);
    let material = GemMaterial::diamond();
    let env = lighting.studio();
    let rig = StudioRig::new(lighting.yaw(), lighting.pitch());
    let mut ks = Vec::new();
    let mut xyz_first = Vec3::ZERO;
    for dir in [Vec3::new(0.4, 0.35, 0.85), Vec3::new(-0.7, -0.4, 0.3)] {
        let dir = dir.normalize();
        let ray = Ray {
            origin: dir * 50.0,
            dir,
        };
        let mut sum = Vec3::ZERO;
        for i in 0..samples {
            let seed = hash_u32(i ^ 0x1234_5678);
            let hero = (i as f32 + 0.5) / samples as f32;
            sum += trace_spectral_ray_with_finish_soa(
                ray, planes, &soa, &[], &material, 12, env, seed, hero, None,
            );
        }
        let xyz = sum / samples as f32;
        if xyz_first == Vec3::ZERO {
            xyz_first = xyz;
        }
        ks.push(xyz.y / lighting.g(&rig, dir, -dir, 560.0));
    }
    let mut spread = 0.0f32;
    for dir in [Vec3::Y, Vec3::new(0.3, 0.9, 0.1), Vec3::new(0.0, -1.0, 0.0), Vec3::X] {
        let dir = dir.normalize();
        let g0 = lighting.g(&rig, dir, Vec3::Y, 560.0);
        for lambda in [400.0, 450.0, 500.0, 600.0, 650.0, 700.0] {
            let g = lighting.g(&rig, dir, Vec3::Y, lambda);
            if g0 > 0.0 {
                spread = spread.max((g / g0 - 1.0).abs());
            }
        }
    }
    let s = xyz_first.x + xyz_first.y + xyz_first.z;
    println!(
        "calibration {}: k = {:.6} and {:.6} at two directions ({} samples each)",
        lighting.name, ks[0], ks[1], samples
    );
    Calibration {
        k: 0.5 * (ks[0] + ks[1]),
        xy: (xyz_first.x / s, xyz_first.y / s),
        spectral_spread: spread,
    }
}

/// Which equirectangular convention to bake in.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Convention {
    /// Iris (src/light/env/mapping.rs): u = 0.5 + atan2(x, -z) / 2π, v = acos(y) / π,
    /// nearest texel.
    Iris,
    /// indicatrix's `EnvironmentMap`: u = atan2(x, z) / 2π, v = acos(y) / π, bilinear.
    Indicatrix,
}

fn uv_to_dir(conv: Convention, u: f32, v: f32) -> Vec3 {
    let theta = std::f32::consts::PI * v;
    let (st, ct) = theta.sin_cos();
    match conv {
        Convention::Iris => {
            let phi = 2.0 * std::f32::consts::PI * (u - 0.5);
            let (sp, cp) = phi.sin_cos();
            Vec3::new(st * sp, ct, -st * cp)
        }
        Convention::Indicatrix => {
            let phi = 2.0 * std::f32::consts::PI * u;
            let (sp, cp) = phi.sin_cos();
            Vec3::new(st * sp, ct, st * cp)
        }
    }
}

/// The lighting as a `width` × `width / 2` grey map (linear sRGB radiance, row 0 = +Y),
/// each texel the mean of `ss` × `ss` directions over it (Iris looks texels up without
/// filtering, so a texel holds the mean over its area).
pub fn bake(lighting: &Lighting, k: f32, width: usize, ss: usize, conv: Convention) -> Vec<f32> {
    let height = width / 2;
    let rig = StudioRig::new(lighting.yaw(), lighting.pitch());
    let threads = std::thread::available_parallelism().map_or(2, usize::from);
    let mut out = vec![0.0f32; width * height];
    std::thread::scope(|scope| {
        for (t, chunk) in out.chunks_mut(width * height.div_ceil(threads)).enumerate() {
            let rig = &rig;
            scope.spawn(move || {
                let row0 = t * height.div_ceil(threads);
                for (i, texel) in chunk.iter_mut().enumerate() {
                    let (x, y) = (i % width, row0 + i / width);
                    let mut sum = 0.0;
                    for sy in 0..ss {
                        for sx in 0..ss {
                            let u = (x as f32 + (sx as f32 + 0.5) / ss as f32) / width as f32;
                            let v = (y as f32 + (sy as f32 + 0.5) / ss as f32) / height as f32;
                            sum += lighting.g(rig, uv_to_dir(conv, u, v), Vec3::Y, 560.0);
                        }
                    }
                    *texel = k * sum / (ss * ss) as f32;
                }
            });
        }
    });
    out
}
