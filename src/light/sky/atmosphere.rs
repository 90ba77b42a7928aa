//! Single scattering of sunlight in a spherical, exponential atmosphere of air (Rayleigh)
//! and aerosol (Mie), spectral: what [`super::Sky`] integrates into its map and its sun.
//!
//! Frames and units: positions in metres from the Earth's centre, +Y up at the observer,
//! who stands on the ground at (0, R_E + 1 m, 0). Directions are unit world vectors
//! pointing away from the observer (a view direction looks at the sky along it; the sun
//! direction points at the sun). Wavelengths in nm. Coefficients in m⁻¹; column densities
//! (∫ρ ds) in metres; phase functions per steradian. Radiance comes out per unit of the
//! sun's extraterrestrial spectral irradiance (the caller scales it).
//!
//! The model (Bruneton & Neyret 2008, "Precomputed Atmospheric Scattering", §2 and their
//! constants; Nishita et al. 1993 for single scattering):
//! - Earth radius R_E = 6360 km, top of the atmosphere R_A = 6420 km;
//! - air: density e^(−h/8 km), scattering β_R(λ) = 13.5·10⁻⁶ (550/λ)⁴ m⁻¹ at sea level
//!   (Rayleigh's λ⁻⁴ law through Bruneton & Neyret's 550-nm value; their 680/440-nm values
//!   5.8 and 33.1 follow from it within 0.5 %), no absorption; phase 3(1 + μ²)/(16π);
//! - aerosol: density e^(−h/1.2 km), optical depth at 550 nm from the turbidity T
//!   (Preetham et al. 1999: T = (τ_R + τ_M)/τ_R, so τ_M(550) = (T − 1) τ_R(550)),
//!   Ångström exponent 1.3 for its wavelength dependence, single-scattering albedo 0.9
//!   (extinction = scattering / 0.9), Cornette–Shanks phase with g = 0.76;
//! - no ozone (its Chappuis band deepens the blue of a twilight zenith; left out), no
//!   multiple scattering (the sky is somewhat darker and bluer near the horizon than a
//!   multiply scattered one).
//!
//! Single scattering along a view ray from the observer to the top of the atmosphere
//! (or the ground), midpoint rule with [`VIEW_STEPS`] steps, the sun's column density from
//! each point with [`SUN_STEPS`] steps; points in the Earth's shadow get no sunlight. Both
//! rays start where the air is densest, so the rule runs over u with t = L u² (steps
//! growing from the start: the first of a horizontal ray is a few metres, not tens of
//! kilometres).

use glam::DVec3;
use std::f64::consts::PI;

/// Earth radius, m.
pub const EARTH_RADIUS: f64 = 6_360e3;
/// Top of the atmosphere, m from the Earth's centre.
pub const TOP_RADIUS: f64 = 6_420e3;
/// Air's density scale height, m.
pub const RAYLEIGH_HEIGHT: f64 = 8e3;
/// Aerosol's density scale height, m.
pub const MIE_HEIGHT: f64 = 1.2e3;
/// Air's sea-level scattering coefficient at 550 nm, m⁻¹.
pub const RAYLEIGH_550: f64 = 13.5e-6;
/// Ångström exponent of the aerosol's optical depth.
pub const ANGSTROM: f64 = 1.3;
/// Aerosol single-scattering albedo (scattering / extinction).
pub const MIE_ALBEDO: f64 = 0.9;
/// Aerosol's Cornette–Shanks asymmetry.
pub const MIE_G: f64 = 0.76;
/// Steps along a view ray.
pub const VIEW_STEPS: usize = 32;
/// Steps along the ray to the sun.
pub const SUN_STEPS: usize = 16;
/// The observer's height above the ground, m.
const OBSERVER_HEIGHT: f64 = 1.0;

/// An atmosphere of a given turbidity.
#[derive(Debug, Clone, Copy)]
pub struct Atmosphere {
    /// Aerosol sea-level scattering coefficient at 550 nm, m⁻¹.
    mie_550: f64,
}

/// Sea-level scattering coefficients (m⁻¹) of air and aerosol at a list of wavelengths
/// (the aerosol's extinction is its scattering / [`MIE_ALBEDO`]).
#[derive(Debug, Clone)]
pub struct Coefficients {
    rayleigh: Vec<f64>,
    mie: Vec<f64>,
}

/// Column densities (∫ρ ds, m) of air and aerosol along a path.
#[derive(Debug, Clone, Copy, Default)]
struct Columns {
    air: f64,
    aerosol: f64,
}

impl Atmosphere {
    /// The atmosphere of turbidity `t` ≥ 1 (1: air only).
    pub fn new(t: f64) -> Self {
        let tau_r = RAYLEIGH_550 * RAYLEIGH_HEIGHT;
        Atmosphere {
            mie_550: (t - 1.0).max(0.0) * tau_r / MIE_HEIGHT,
        }
    }

    /// Air's sea-level scattering coefficient at `lambda` nm, m⁻¹.
    pub fn rayleigh(lambda: f64) -> f64 {
        RAYLEIGH_550 * (550.0 / lambda).powi(4)
    }

    /// Aerosol's sea-level scattering coefficient at `lambda` nm, m⁻¹.
    pub fn mie(&self, lambda: f64) -> f64 {
        self.mie_550 * (lambda / 550.0).powf(-ANGSTROM)
    }

    /// Vertical optical depth of the whole atmosphere at `lambda` nm in a plane-parallel
    /// approximation (β·H for each constituent, extinction).
    pub fn zenith_optical_depth(&self, lambda: f64) -> f64 {
        let column = Columns {
            air: RAYLEIGH_HEIGHT,
            aerosol: MIE_HEIGHT,
        };
        optical_depth(Self::rayleigh(lambda), self.mie(lambda), column)
    }

    /// The sun's direct transmittance to the observer at each of `lambdas` (nm), for the
    /// unit direction `sun`; 0 below the horizon (the ground blocks it).
    pub fn sun_transmittance(&self, sun: DVec3, lambdas: &[f64]) -> Vec<f64> {
        let start = observer();
        match columns_to_top(start, sun, SUN_STEPS * 4) {
            Some(c) => lambdas
                .iter()
                .map(|&l| (-optical_depth(Self::rayleigh(l), self.mie(l), c)).exp())
                .collect(),
            None => vec![0.0; lambdas.len()],
        }
    }

    /// The scattering and extinction coefficients at `lambdas` (nm), for
    /// [`Self::single_scatter`].
    pub fn coefficients(&self, lambdas: &[f64]) -> Coefficients {
        Coefficients {
            rayleigh: lambdas.iter().map(|&l| Self::rayleigh(l)).collect(),
            mie: lambdas.iter().map(|&l| self.mie(l)).collect(),
        }
    }

    /// Singly scattered radiance arriving at the observer from unit direction `view`, per
    /// unit extraterrestrial solar irradiance, at the wavelengths of `k`
    /// ([`Self::coefficients`]), for the unit sun direction `sun`. 0 for a view ray that
    /// starts into the ground.
    pub fn single_scatter(&self, view: DVec3, sun: DVec3, k: &Coefficients) -> Vec<f64> {
        let mut out = vec![0.0; k.rayleigh.len()];
        let start = observer();
        let Some(len) = ray_length(start, view) else {
            return out;
        };
        let mu = view.dot(sun);
        let (pr, pm) = (rayleigh_phase(mu), cornette_shanks(mu, MIE_G));
        let mut to_point = Columns::default();
        for i in 0..VIEW_STEPS {
            let (t, ds) = quadratic_step(len, i, VIEW_STEPS);
            let p = start + view * t;
            let (air, aerosol) = densities(p);
            // The view segment up to this point, the half step included.
            let seg = Columns {
                air: to_point.air + 0.5 * air * ds,
                aerosol: to_point.aerosol + 0.5 * aerosol * ds,
            };
            to_point.air += air * ds;
            to_point.aerosol += aerosol * ds;
            let Some(to_sun) = columns_to_top(p, sun, SUN_STEPS) else {
                continue;
            };
            let both = Columns {
                air: seg.air + to_sun.air,
                aerosol: seg.aerosol + to_sun.aerosol,
            };
            for (o, (&br, &bm)) in out.iter_mut().zip(k.rayleigh.iter().zip(&k.mie)) {
                let scatter = br * air * pr + bm * aerosol * pm;
                *o += (-optical_depth(br, bm, both)).exp() * scatter * ds;
            }
        }
        out
    }
}

/// Optical depth of the column densities `c` for the sea-level scattering coefficients
/// `rayleigh` and `mie` (the aerosol's extinction is its scattering / [`MIE_ALBEDO`]).
fn optical_depth(rayleigh: f64, mie: f64, c: Columns) -> f64 {
    rayleigh * c.air + mie / MIE_ALBEDO * c.aerosol
}

/// The observer's position.
fn observer() -> DVec3 {
    DVec3::new(0.0, EARTH_RADIUS + OBSERVER_HEIGHT, 0.0)
}

/// Relative densities (air, aerosol) at `p`.
fn densities(p: DVec3) -> (f64, f64) {
    let h = (p.length() - EARTH_RADIUS).max(0.0);
    ((-h / RAYLEIGH_HEIGHT).exp(), (-h / MIE_HEIGHT).exp())
}

/// Distance from `p` along unit `d` to the top of the atmosphere; `None` if the ray meets
/// the ground first.
fn ray_length(p: DVec3, d: DVec3) -> Option<f64> {
    if hits_sphere(p, d, EARTH_RADIUS) {
        return None;
    }
    let b = p.dot(d);
    let c = p.length_squared() - TOP_RADIUS * TOP_RADIUS;
    let disc = b * b - c;
    (disc >= 0.0).then(|| -b + disc.sqrt()).filter(|t| *t > 0.0)
}

/// Whether the ray from `p` along unit `d` meets the sphere of radius `r` ahead.
fn hits_sphere(p: DVec3, d: DVec3, r: f64) -> bool {
    let b = p.dot(d);
    let c = p.length_squared() - r * r;
    b < 0.0 && b * b - c > 0.0
}

/// Column densities from `p` along unit `d` to the top of the atmosphere in `steps`
/// midpoint steps; `None` in the Earth's shadow.
fn columns_to_top(p: DVec3, d: DVec3, steps: usize) -> Option<Columns> {
    let len = ray_length(p, d)?;
    let mut c = Columns::default();
    for i in 0..steps {
        let (t, ds) = quadratic_step(len, i, steps);
        let (air, aerosol) = densities(p + d * t);
        c.air += air * ds;
        c.aerosol += aerosol * ds;
    }
    Some(c)
}

/// Step `i` of `n` over [0, `len`] with t = len·u², u at the step's midpoint: the point's
/// distance t and its length dt = 2·len·u/n.
fn quadratic_step(len: f64, i: usize, n: usize) -> (f64, f64) {
    let u = (i as f64 + 0.5) / n as f64;
    (len * u * u, 2.0 * len * u / n as f64)
}

/// Rayleigh's phase function, sr⁻¹, for the cosine `mu` of the scattering angle.
pub fn rayleigh_phase(mu: f64) -> f64 {
    3.0 * (1.0 + mu * mu) / (16.0 * PI)
}

/// Cornette & Shanks (1992)'s phase function, sr⁻¹, asymmetry `g`.
pub fn cornette_shanks(mu: f64, g: f64) -> f64 {
    let g2 = g * g;
    3.0 * (1.0 - g2) * (1.0 + mu * mu)
        / (8.0 * PI * (2.0 + g2) * (1.0 + g2 - 2.0 * g * mu).powf(1.5))
}
