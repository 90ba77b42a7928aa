//! The KHR_materials_sheen lobe: the "Charlie" microfiber distribution and visibility of
//! Estevez & Kulla 2017 ("Production Friendly Microfacet Sheen BRDF", SIGGRAPH course
//! notes, §2–3), as the extension's implementation notes write them, and its directional
//! albedo E(μ, α) for the albedo-scaling layering.
//!
//! Frame: local shading frame, z = normal; the lobe is two-sided reflection (|cos θ|).
//! `alpha` is the extension's `alphaG = sheenRoughness` (the spec text, not its square),
//! clamped to [`MIN_ALPHA`, 1] because D → a delta at the horizon as α → 0 (the same clamp
//! Filament and three.js apply).
//!
//! f_sheen(wo, wi) = sheenColor · D(h) · G / (4 |cos θo| |cos θi|), with
//! D(h) = (2 + 1/α) · sin^(1/α) θh / (2π) and G = 1 / (1 + Λ(μo) + Λ(μi)) (Estevez & Kulla
//! eq. 3 and their fitted Λ, §3). F = 1.
//!
//! Table: E(μ, α) = ∫ f_sheen(wo, wi)|cos θi| dωi for sheenColor = 1 on a grid of `N_MU`
//! nodes uniform in √μ over [0, 1] (μ = |cos θo|) by `N_ALPHA` nodes uniform in α over
//! [`MIN_ALPHA`, 1], bilinear in (√μ, α). Each node is a deterministic midpoint quadrature
//! over (cos θi, φi) ∈ [0, 1] × [0, π] (doubled: wo lies in the xz plane), `Q`×`Q` points;
//! the integrand D·G/(4μo) is smooth for α ≥ [`MIN_ALPHA`]. The table is stored in
//! `sheen_table.bin` (u16 little endian, E·65535, index `ia · N_MU + im`, 1 KiB) and
//! embedded like `super::energy`'s; `IRIS_REGEN_SHEEN_TABLE=1 cargo test --release --lib
//! sheen_table_file_is_current` rewrites it; the tests check it against the quadrature and
//! against a Monte Carlo estimate of the albedo (`super::layers_tests`).

use super::albedo_table;
use std::f32::consts::PI;
use std::sync::OnceLock;

/// Smallest sheen α (the microfibres are never perfectly aligned).
pub const MIN_ALPHA: f32 = 0.07;
/// Nodes in √μ over [0, 1].
const N_MU: usize = 32;
/// Nodes in α over [MIN_ALPHA, 1].
const N_ALPHA: usize = 16;
/// Quadrature points per axis per node.
const Q: usize = 192;
/// Smallest μo a node is evaluated at (the lobe is 0/0 at μo = 0).
const MU_MIN: f32 = 1e-3;
/// Number of table entries.
const LEN: usize = N_MU * N_ALPHA;

/// The embedded table (see the module doc).
static TABLE_FILE: &[u8] = include_bytes!("sheen_table.bin");
/// The decoded table, built on first lookup.
static TABLE: OnceLock<Vec<f32>> = OnceLock::new();

/// Clamps a sheen roughness to the range the lobe and its table use.
#[inline]
pub fn clamp_alpha(alpha: f32) -> f32 {
    if alpha.is_nan() {
        return 1.0;
    }
    alpha.clamp(MIN_ALPHA, 1.0)
}

/// Charlie distribution D(θh) = (2 + 1/α) · sin^(1/α) θh / (2π) (Estevez & Kulla eq. 3),
/// from cos θh; normalised so that ∫ D cos θh dω = 1.
#[inline]
pub fn d(alpha: f32, cos_h: f32) -> f32 {
    let inv = 1.0 / alpha;
    let sin2 = (1.0 - cos_h * cos_h).max(0.0);
    (2.0 + inv) * sin2.powf(0.5 * inv) / (2.0 * PI)
}

/// Estevez & Kulla's fitted exponent L(x) (§3, the extension's `l(x, alphaG)`): the fit's
/// coefficients interpolated by (1 − α)².
#[inline]
fn l(x: f32, alpha: f32) -> f32 {
    let t = (1.0 - alpha) * (1.0 - alpha);
    let mix = |a: f32, b: f32| a + (b - a) * t;
    let (a, b, c) = (
        mix(21.5473, 25.3245),
        mix(3.82987, 3.32435),
        mix(0.19823, 0.16801),
    );
    let (dd, e) = (mix(-1.97760, -1.27393), mix(-4.32054, -4.85967));
    a / (1.0 + b * x.powf(c)) + dd * x + e
}

/// Λ(μ) of the Charlie visibility: exp L(μ) below μ = 0.5, mirrored above it
/// (Estevez & Kulla §3).
#[inline]
fn lambda(mu: f32, alpha: f32) -> f32 {
    let mu = mu.abs();
    if mu < 0.5 {
        l(mu, alpha).exp()
    } else {
        (2.0 * l(0.5, alpha) - l(1.0 - mu, alpha)).exp()
    }
}

/// The sheen lobe for a white sheen colour, f = D·G/(4|cos θo||cos θi|), for a reflection
/// pair (`wo.z`, `wi.z` on the same side, `cos_h` = |n·h| of their half vector).
#[inline]
pub fn f_white(alpha: f32, mu_o: f32, mu_i: f32, cos_h: f32) -> f32 {
    let (mu_o, mu_i) = (mu_o.abs(), mu_i.abs());
    if mu_o == 0.0 || mu_i == 0.0 {
        return 0.0;
    }
    let g = 1.0 / (1.0 + lambda(mu_o, alpha) + lambda(mu_i, alpha));
    d(alpha, cos_h) * g / (4.0 * mu_o * mu_i)
}

/// Directional albedo of the white sheen lobe at μo by the deterministic quadrature of the
/// module doc with `q`×`q` points.
pub(crate) fn albedo_quadrature(mu: f32, alpha: f32, q: usize) -> f32 {
    let mu = mu.max(MU_MIN);
    let so = (1.0 - mu * mu).max(0.0).sqrt();
    let mut acc = 0.0f64;
    for i in 0..q {
        let ci = (i as f32 + 0.5) / q as f32;
        let si = (1.0 - ci * ci).max(0.0).sqrt();
        for j in 0..q {
            let phi = PI * (j as f32 + 0.5) / q as f32;
            // h ∝ wo + wi with wo = (so, 0, mu), wi = (si cos φ, si sin φ, ci).
            let h = glam::Vec3::new(so + si * phi.cos(), si * phi.sin(), mu + ci);
            let cos_h = h.z / h.length();
            acc += (f_white(alpha, mu, ci, cos_h) * ci) as f64;
        }
    }
    // dω = dcos θ dφ over [0, 1] × [0, 2π]; the grid covers half of φ.
    (acc * 2.0 * PI as f64 / (q * q) as f64) as f32
}

fn mu_node(im: usize) -> f32 {
    let t = im as f32 / (N_MU - 1) as f32;
    t * t
}

fn alpha_node(ia: usize) -> f32 {
    MIN_ALPHA + (1.0 - MIN_ALPHA) * ia as f32 / (N_ALPHA - 1) as f32
}

/// Generates the table in the file format.
pub(crate) fn generate_file() -> Vec<u8> {
    let mut out = Vec::with_capacity(2 * LEN);
    for ia in 0..N_ALPHA {
        for im in 0..N_MU {
            let e = albedo_quadrature(mu_node(im), alpha_node(ia), Q);
            out.extend_from_slice(&albedo_table::quantise(e).to_le_bytes());
        }
    }
    out
}

/// Decodes the embedded table ([`albedo_table::decode`]).
fn load() -> Vec<f32> {
    albedo_table::decode(TABLE_FILE, LEN, generate_file)
}

/// Path of the table file in the source tree (tests).
#[cfg(test)]
pub(crate) const TABLE_PATH: &str =
    concat!(env!("CARGO_MANIFEST_DIR"), "/src/bsdf/sheen_table.bin");

/// Largest difference between the embedded table and a fresh computation (tests).
#[cfg(test)]
pub(crate) fn max_file_deviation() -> f32 {
    let fresh = generate_file();
    TABLE_FILE
        .chunks_exact(2)
        .zip(fresh.chunks_exact(2))
        .map(|(a, b)| {
            let a = u16::from_le_bytes([a[0], a[1]]) as f32;
            let b = u16::from_le_bytes([b[0], b[1]]) as f32;
            (a - b).abs() / 65535.0
        })
        .fold(
            if TABLE_FILE.len() == 2 * LEN {
                0.0
            } else {
                1.0
            },
            f32::max,
        )
}

/// Interpolated directional albedo E(μ, α) of the white sheen lobe (module doc); μ and α
/// are clamped to the table.
pub fn albedo(mu: f32, alpha: f32) -> f32 {
    let t = TABLE.get_or_init(load);
    let x = mu.abs().min(1.0).sqrt() * (N_MU - 1) as f32;
    let y = (clamp_alpha(alpha) - MIN_ALPHA) / (1.0 - MIN_ALPHA) * (N_ALPHA - 1) as f32;
    let im = (x as usize).min(N_MU - 2);
    let ia = (y as usize).min(N_ALPHA - 2);
    let (fm, fa) = (x - im as f32, y - ia as f32);
    let at = |ia: usize, im: usize| t[ia * N_MU + im];
    let lo = at(ia, im) * (1.0 - fm) + at(ia, im + 1) * fm;
    let hi = at(ia + 1, im) * (1.0 - fm) + at(ia + 1, im + 1) * fm;
    lo * (1.0 - fa) + hi * fa
}
