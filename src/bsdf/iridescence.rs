//! What KHR_materials_iridescence and KHR_materials_anisotropy add to a reflection lobe,
//! resolved at a shading point ([`LobeExtensions`]), and how the thin film's reflectance
//! replaces the lobe's Fresnel term in either transport.
//!
//! - Spectral transport: the film reflectance ([`super::interference`]) is evaluated exactly
//!   at each of the path's 4 wavelengths (`Iridescence::lanes`, nm).
//! - RGB transport: each channel is the film's reflectance spectrum integrated against the
//!   CIE 1931 matching functions under D65 and converted to linear sRGB, the spectrum being
//!   sampled at [`RGB_NODES`] wavelengths 380–780 nm (12.5 nm apart) and reconstructed
//!   piecewise linearly (constant beyond the ends); the weights of the nodes are that
//!   reconstruction integrated at 1 nm against D65·(XYZ→sRGB)·x̄ȳz̄, normalised per channel
//!   so that a constant reflectance gives itself (grey stays grey). This is what the film
//!   shows under a white (D65) light in spectral transport, up to the reconstruction
//!   error, which the test `rgb_iridescence_matches_spectral_integral` bounds (≤ 0.01 per
//!   channel). A substrate whose index differs per channel (a coloured metal, a coloured
//!   specular) evaluates the spectrum once per channel with that channel's index.
//!
//! The lobe's Fresnel F becomes mix(F, R_film, factor) (the extension's
//! "iridescence_fresnel" mix). Substrates: a dielectric's index comes from its F0
//! (n = (1+√F0)/(1−√F0), so the plain KHR_materials_ior F0 gives back `ior`), a glTF
//! metal's from its base colour taken as F0 the same way (real index, the extension's
//! reference: `Fresnel0ToIor(baseColor)`), a measured metal uses its complex index.

use super::interference;
use crate::spectrum::cie;
use crate::spectrum::Carrier;
use std::sync::OnceLock;

/// Wavelength nodes of the RGB integration (380, 392.5, …, 780 nm).
pub const RGB_NODES: usize = 33;
const NODE_START: f32 = 380.0;
const NODE_STEP: f32 = 12.5;

/// KHR_materials_iridescence at a shading point (textures applied).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iridescence {
    /// Mix weight of the film's Fresnel, in [0, 1].
    pub factor: f32,
    /// Film index of refraction (relative to the outside).
    pub ior: f32,
    /// Film thickness in nm (> 0).
    pub thickness: f32,
    /// The path's 4 wavelengths in nm (spectral transport), `None` in RGB transport.
    pub lanes: Option<[f32; 4]>,
}

/// The film and brushed-surface extensions of one lobe: both off is [`LobeExtensions::NONE`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LobeExtensions {
    /// The thin film, if its factor and thickness are both > 0.
    pub iridescence: Option<Iridescence>,
    /// KHR_materials_anisotropy strength in [0, 1] (0 = isotropic); the shading frame's x
    /// axis is then the anisotropy direction.
    pub anisotropy: f32,
}

impl LobeExtensions {
    /// No film, isotropic.
    pub const NONE: LobeExtensions = LobeExtensions {
        iridescence: None,
        anisotropy: 0.0,
    };
}

impl Default for LobeExtensions {
    fn default() -> Self {
        LobeExtensions::NONE
    }
}

impl Iridescence {
    /// The film's reflectance at incidence cosine `cos` over a substrate of index
    /// `eta` + i`kappa` (per channel or lane).
    pub fn reflectance<C: Carrier>(&self, cos: f32, eta: C, kappa: C) -> C {
        let (n, k) = (eta.to_lanes(), kappa.to_lanes());
        let r = |i: usize, nm: f32| {
            interference::reflectance(cos, self.ior, self.thickness, n[i], k[i], nm)
        };
        match self.lanes {
            Some(nm) if C::SPECTRAL => C::from_lanes(std::array::from_fn(|i| r(i, nm[i]))),
            _ => {
                let w = rgb_weights();
                let spectrum =
                    |c: usize| -> [f32; RGB_NODES] { std::array::from_fn(|j| r(c, node_nm(j))) };
                let weigh = |c: usize, s: &[f32; RGB_NODES]| -> f32 {
                    w[c].iter()
                        .zip(s)
                        .map(|(a, b)| a * b)
                        .sum::<f32>()
                        .clamp(0.0, 1.0)
                };
                let s0 = spectrum(0);
                let same = |c: usize| n[c] == n[0] && k[c] == k[0];
                let r0 = weigh(0, &s0);
                let r1 = weigh(1, &if same(1) { s0 } else { spectrum(1) });
                let r2 = weigh(2, &if same(2) { s0 } else { spectrum(2) });
                C::from_lanes([r0, r1, r2, 0.0])
            }
        }
    }

    /// `plain` mixed with the film's reflectance by the factor.
    pub fn mix<C: Carrier>(&self, plain: C, cos: f32, eta: C, kappa: C) -> C {
        plain.lerp(self.reflectance(cos, eta, kappa), self.factor)
    }
}

/// Substrate indices from normal-incidence reflectances, channel by channel
/// ([`interference::f0_to_ior`]).
pub fn ior_from_f0<C: Carrier>(f0: C) -> C {
    C::from_lanes(f0.to_lanes().map(interference::f0_to_ior))
}

fn node_nm(j: usize) -> f32 {
    NODE_START + NODE_STEP * j as f32
}

/// Per-channel (linear sRGB) weights of the RGB nodes; see the module doc.
pub fn rgb_weights() -> &'static [[f32; RGB_NODES]; 3] {
    static W: OnceLock<[[f32; RGB_NODES]; 3]> = OnceLock::new();
    W.get_or_init(|| {
        let mut w = [[0f64; RGB_NODES]; 3];
        for l in 360..=830 {
            let nm = l as f32;
            let rgb = cie::xyz_to_linear_srgb(cie::cmf(nm));
            let e = f64::from(cie::d65(nm));
            for (j, hat) in hats(nm) {
                for c in 0..3 {
                    w[c][j] += hat * e * f64::from(rgb[c]);
                }
            }
        }
        w.map(|row| {
            let sum: f64 = row.iter().sum();
            row.map(|x| (x / sum) as f32)
        })
    })
}

/// The piecewise-linear reconstruction's weights at `nm`: (node, weight), weights sum to 1.
fn hats(nm: f32) -> [(usize, f64); 2] {
    let x = ((nm - NODE_START) / NODE_STEP).clamp(0.0, (RGB_NODES - 1) as f32);
    let j = (x.floor() as usize).min(RGB_NODES - 2);
    let t = f64::from(x - j as f32);
    [(j, 1.0 - t), (j + 1, t)]
}

/// The exact spectral colour reference for tests: the film reflectance integrated at 1 nm
/// against D65 and the matching functions into linear sRGB, normalised per channel like
/// [`rgb_weights`].
#[cfg(test)]
pub(crate) fn rgb_reference(r: impl Fn(f32) -> f32) -> [f32; 3] {
    let mut acc = [0f64; 3];
    let mut norm = [0f64; 3];
    for l in 360..=830 {
        let nm = l as f32;
        let rgb = cie::xyz_to_linear_srgb(cie::cmf(nm));
        let e = f64::from(cie::d65(nm));
        for c in 0..3 {
            acc[c] += e * f64::from(rgb[c]) * f64::from(r(nm));
            norm[c] += e * f64::from(rgb[c]);
        }
    }
    std::array::from_fn(|c| (acc[c] / norm[c]) as f32)
}
