//! `--env sky:elevation=DEG[,azimuth=DEG,turbidity=T]`: a clear sky and its sun from single
//! Rayleigh and Mie scattering ([`atmosphere`]), computed spectrally and converted to
//! linear sRGB through the CIE 1931 observer, so a low sun turns the light orange and the
//! sky overhead stays blue.
//!
//! What a [`Sky`] holds:
//! - an equirectangular map ([`MAP_WIDTH`] × [`MAP_HEIGHT`], computed [`COARSE`]× coarser
//!   and interpolated) of the sky's radiance above
//!   the horizon and, below it, a grey ground of albedo [`GROUND_ALBEDO`] lit by the sun
//!   and the sky (Lambertian: L = ρ E_h / π); it is sampled as any `--env` map;
//! - the sun, which the scene gets as a directional light (`sky sun`, added by
//!   [`crate::prepare`]) whose irradiance is the extraterrestrial
//!   sun's through the atmosphere along its direction (none below the horizon). The sun's
//!   disc itself is not in the map (a directional light is not seen directly); its aureole,
//!   the aerosol's forward scattering, is.
//!
//! Frames: +Y up; the sun's azimuth is measured from −Z (the map's centre, where a glTF
//! camera with no rotation looks) towards +X, its elevation from the horizon.
//!
//! Units: the extraterrestrial sun is a 5772 K blackbody (the Sun's effective temperature)
//! scaled so that its luminance-weighted irradiance is π: a white Lambertian surface facing
//! it above the atmosphere would have radiance 1 (luminance Y), about what `--exposure 0`
//! shows well. Everything else follows from the atmosphere, so a sunset is darker than noon
//! at the same exposure, as it should be.

pub mod atmosphere;

use crate::error::Result;
use crate::image::ImageRgb;
use crate::light::env::map::EnvMap;
use crate::light::env::mapping::uv_to_dir;
use crate::spectrum::cie;
use atmosphere::Atmosphere;
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// Map width in texels (0.18° per texel).
pub const MAP_WIDTH: u32 = 2048;
/// Map height in texels.
pub const MAP_HEIGHT: u32 = 1024;
/// The scattering integral is computed on a grid this many times coarser in each
/// direction (0.7°) and interpolated bilinearly onto the map: the sky is smooth at that
/// scale, but a nearest-texel map of the coarse grid shows steps near the horizon.
pub const COARSE: u32 = 4;
/// The ground's albedo below the horizon.
pub const GROUND_ALBEDO: f32 = 0.3;
/// The Sun's effective temperature, K (IAU 2015 Resolution B3 nominal value).
pub const SUN_KELVIN: f32 = 5772.0;
/// Wavelengths the spectra are integrated over: 380, 390, …, 780 nm.
const LAMBDAS: usize = 41;

/// The largest |azimuth| accepted, degrees: one turn either way, the range of
/// `--polarizer`. Beyond it an angle is a mistake rather than a direction (1e30° has lost
/// every digit that would say where the sun is).
pub const AZIMUTH_LIMIT: f32 = 360.0;

/// The parameters of `--env sky:…`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkyParams {
    /// The sun's elevation above the horizon, degrees, in [−10, 90].
    pub elevation: f32,
    /// The sun's azimuth from −Z towards +X, degrees, in [−360, 360] ([`AZIMUTH_LIMIT`]).
    pub azimuth: f32,
    /// Preetham's turbidity, in [1, 10] (1: air alone; 2: a clear day).
    pub turbidity: f32,
}

impl SkyParams {
    /// Parses the part after `sky:` of an `--env` value or of a glTF scene's
    /// `extras.iris_environment`: `elevation=DEG` (required), `azimuth=DEG` (default 0),
    /// `turbidity=T` (default 2), comma-separated, each at most once. The error is the
    /// reason, for the caller to prefix with the flag or the file's element.
    pub fn parse(rest: &str) -> std::result::Result<SkyParams, String> {
        let (mut elevation, mut azimuth, mut turbidity) = (None, None, None);
        for part in rest.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let (key, value) = part
                .split_once('=')
                .ok_or_else(|| format!("{part:?} is not KEY=VALUE"))?;
            let v: f32 = value
                .trim()
                .parse()
                .ok()
                .filter(|v: &f32| v.is_finite())
                .ok_or_else(|| format!("{key}={value:?} is not a finite number"))?;
            let slot = match key.trim() {
                "elevation" => &mut elevation,
                "azimuth" => &mut azimuth,
                "turbidity" => &mut turbidity,
                k => {
                    return Err(format!(
                        "unknown key {k:?} (accepted: elevation, azimuth, turbidity)"
                    ))
                }
            };
            if slot.replace(v).is_some() {
                return Err(format!("{} is given twice", key.trim()));
            }
        }
        let elevation = elevation.ok_or("elevation=DEG is required")?;
        let p = SkyParams {
            elevation,
            azimuth: azimuth.unwrap_or(0.0),
            turbidity: turbidity.unwrap_or(2.0),
        };
        if !(-10.0..=90.0).contains(&p.elevation) {
            return Err(format!(
                "elevation {} is outside −10 … 90 degrees",
                p.elevation
            ));
        }
        if !(1.0..=10.0).contains(&p.turbidity) {
            return Err(format!("turbidity {} is outside 1 … 10", p.turbidity));
        }
        if p.azimuth.abs() > AZIMUTH_LIMIT {
            return Err(format!(
                "azimuth {} is outside −{AZIMUTH_LIMIT} … {AZIMUTH_LIMIT} degrees",
                p.azimuth
            ));
        }
        Ok(p)
    }

    /// Unit direction towards the sun.
    pub fn sun_direction(&self) -> DVec3 {
        let (e, a) = (
            f64::from(self.elevation).to_radians(),
            f64::from(self.azimuth).to_radians(),
        );
        DVec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos())
    }
}

/// A computed sky: its map and its sun.
#[derive(Debug, Clone)]
pub struct Sky {
    /// What it was computed from.
    pub params: SkyParams,
    /// Radiance above the horizon, the lit ground below it (linear sRGB, scene units).
    pub map: EnvMap,
    /// The sun's irradiance at normal incidence (linear sRGB, scene units) and the unit
    /// direction towards it; `None` below the horizon.
    pub sun: Option<(Vec3, Vec3)>,
}

impl Sky {
    /// Computes the sky of `params` (a fraction of a second on 2 cores).
    pub fn new(params: SkyParams) -> Result<Sky> {
        let atm = Atmosphere::new(f64::from(params.turbidity));
        let sun = params.sun_direction();
        let lambdas: Vec<f64> = (0..LAMBDAS).map(|i| 380.0 + 10.0 * i as f64).collect();
        let e0 = solar_spectrum(&lambdas);
        let (cw, ch) = (
            (MAP_WIDTH / COARSE) as usize,
            (MAP_HEIGHT / COARSE) as usize / 2,
        );
        let coefficients = atm.coefficients(&lambdas);
        // The coarse grid over the upper half: texel centres of a cw × 2ch map.
        let coarse: Vec<Vec3> = (0..cw * ch)
            .into_par_iter()
            .map(|i| {
                let (x, y) = (i % cw, i / cw);
                let uv = glam::Vec2::new(
                    (x as f32 + 0.5) / cw as f32,
                    (y as f32 + 0.5) / (2 * ch) as f32,
                );
                let view = uv_to_dir(uv).as_dvec3();
                let l = atm.single_scatter(view, sun, &coefficients);
                to_rgb(&lambdas, |k| l[k] * e0[k])
            })
            .collect();
        let (w, h) = (MAP_WIDTH as usize, MAP_HEIGHT as usize);
        let mut data: Vec<Vec3> = (0..w * h)
            .into_par_iter()
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if y >= h / 2 {
                    return Vec3::ZERO;
                }
                // Bilinear in the coarse grid's texel-centre coordinates; u wraps, v clamps.
                let fx = (x as f32 + 0.5) / COARSE as f32 - 0.5;
                let fy = ((y as f32 + 0.5) / COARSE as f32 - 0.5).clamp(0.0, (ch - 1) as f32);
                let (x0, y0) = (fx.floor(), fy.floor());
                let (tx, ty) = (fx - x0, fy - y0);
                let xi = |d: i64| (x0 as i64 + d).rem_euclid(cw as i64) as usize;
                let y1 = (y0 as usize + 1).min(ch - 1);
                let row = |yy: usize| coarse[yy * cw + xi(0)].lerp(coarse[yy * cw + xi(1)], tx);
                row(y0 as usize).lerp(row(y1), ty)
            })
            .collect();
        let t = atm.sun_transmittance(sun, &lambdas);
        let sun_rgb = to_rgb(&lambdas, |k| t[k] * e0[k]);
        let sun_light =
            (sun.y > 0.0 && sun_rgb.max_element() > 0.0).then(|| (sun_rgb, sun.as_vec3()));
        // The ground: ρ/π × (the sun's and the sky's irradiance on a horizontal plane).
        let horizontal = sky_irradiance(&data, w, h) + sun_rgb * sun.y.max(0.0) as f32;
        let ground = horizontal * (GROUND_ALBEDO / std::f32::consts::PI);
        data[w * (h / 2)..].fill(ground);
        let image = ImageRgb {
            width: MAP_WIDTH,
            height: MAP_HEIGHT,
            data,
        };
        let map = EnvMap::from_image(image, std::path::Path::new("--env sky"))?;
        Ok(Sky {
            params,
            map,
            sun: sun_light,
        })
    }
}

/// The extraterrestrial solar spectral irradiance at `lambdas`: a [`SUN_KELVIN`] blackbody
/// scaled so that its CIE luminance Y is π (module docs).
fn solar_spectrum(lambdas: &[f64]) -> Vec<f64> {
    let shape: Vec<f64> = lambdas
        .iter()
        .map(|&l| f64::from(cie::blackbody_normalized(l as f32, SUN_KELVIN)))
        .collect();
    let y = f64::from(to_xyz(lambdas, |k| shape[k])[1]);
    shape.iter().map(|s| s * std::f64::consts::PI / y).collect()
}

/// CIE XYZ of the spectrum `s(k)` sampled at `lambdas` (10 nm apart), normalised as
/// [`cie::spectrum_to_xyz`] (Y of a flat spectrum of 1 is 1).
fn to_xyz(lambdas: &[f64], s: impl Fn(usize) -> f64) -> [f32; 3] {
    let mut acc = [0.0f64; 3];
    for (k, &l) in lambdas.iter().enumerate() {
        let m = cie::cmf(l as f32);
        let v = s(k) * 10.0;
        for c in 0..3 {
            acc[c] += f64::from(m[c]) * v;
        }
    }
    acc.map(|a| (a / f64::from(cie::CIE_Y_INTEGRAL)) as f32)
}

/// Linear sRGB of the spectrum `s(k)` at `lambdas`, negative components (out of gamut)
/// clamped to 0.
fn to_rgb(lambdas: &[f64], s: impl Fn(usize) -> f64) -> Vec3 {
    Vec3::from(cie::xyz_to_linear_srgb(to_xyz(lambdas, s))).max(Vec3::ZERO)
}

/// Irradiance on a horizontal plane from the map's texels above the horizon:
/// Σ L cos θ ΔΩ over the texels of the upper half.
fn sky_irradiance(data: &[Vec3], w: usize, h: usize) -> Vec3 {
    let dphi = 2.0 * std::f32::consts::PI / w as f32;
    let dtheta = std::f32::consts::PI / h as f32;
    let mut sum = Vec3::ZERO;
    for y in 0..h / 2 {
        let (t0, t1) = (y as f32 * dtheta, (y + 1) as f32 * dtheta);
        // ∫ cos θ sin θ dθ over the row = (sin² t1 − sin² t0)/2.
        let weight = 0.5 * (t1.sin().powi(2) - t0.sin().powi(2)) * dphi;
        for x in 0..w {
            sum += data[y * w + x] * weight;
        }
    }
    sum
}
