//! What a lane carries, per channel: `M` = 3 linear RGB channels, or `M` = 4 sampled
//! wavelengths (hero wavelength spectral transport, [`crate::spectrum::Lambdas`], lane 0 the
//! hero), and the conversions of the scene's colours into it at a lane's wavelengths. Each
//! conversion is the scalar path's own ([`Carrier`] for [`Vec3`] or [`SampledSpectrum`]),
//! called per lane, so a kernel lane's values are the scalar path's for the same
//! wavelengths: colour inputs through [`Carrier::reflectance`], emission through
//! [`Carrier::emitted`] (an exact spectral shape where the emitter names one), the
//! environment through [`Carrier::illuminant`], and the film's conversion
//! [`Carrier::to_rgb`]. With `M` = 3 each is the identity on RGB and the lane's
//! wavelengths are not read.
//!
//! Units: channels of radiance (W·m⁻²·sr⁻¹, per nm in spectral transport) or of a
//! reflectance in [0, 1].

use crate::material::Material;
use crate::spectrum::{Carrier, EmitterShape, Lambdas, SampledSpectrum, SampledWavelengths};
use glam::Vec3;

/// `M` channels over `N` lanes: channel `c` of lane `i` at `[c][i]`.
pub type Channels<const N: usize, const M: usize> = [[f32; N]; M];

/// Whether `M` channels are wavelengths (4) rather than RGB (3).
#[inline(always)]
pub const fn spectral<const M: usize>() -> bool {
    M == 4
}

/// Wavelengths a lane holds before it is given a job (never read: a job samples its own).
pub fn unset() -> Lambdas {
    Lambdas::new(SampledWavelengths::sample_visible(0.5))
}

/// The first `M` of `v` (3 RGB channels or 4 wavelengths; `K` ≥ `M` where it is read).
#[inline(always)]
pub fn take<const M: usize, const K: usize>(v: [f32; K]) -> [f32; M] {
    std::array::from_fn(|c| v[c])
}

/// `rgb` in `M` channels: itself in RGB, `spectrum(rgb)` at the wavelengths in spectral
/// transport.
#[inline(always)]
fn convert<const M: usize>(rgb: [f32; 3], spectrum: impl Fn(Vec3) -> SampledSpectrum) -> [f32; M] {
    if spectral::<M>() {
        take(spectrum(Vec3::from_array(rgb)).to_lanes())
    } else {
        take(rgb)
    }
}

/// The reflectance of the colour `rgb` (in [0, 1]) at the wavelengths `l`.
#[inline(always)]
pub fn reflectance<const M: usize>(rgb: [f32; 3], l: &Lambdas) -> [f32; M] {
    convert(rgb, |c| SampledSpectrum::reflectance(c, l))
}

/// The radiance of an emitter whose RGB transport value is `rgb` (with the exact spectral
/// `shape` it names, if any) at the wavelengths `l`.
#[inline(always)]
pub fn emitted<const M: usize>(
    rgb: [f32; 3],
    shape: Option<&EmitterShape>,
    l: &Lambdas,
) -> [f32; M] {
    convert(rgb, |c| SampledSpectrum::emitted(c, shape, l))
}

/// The environment's radiance `rgb` at the wavelengths `l`.
#[inline(always)]
pub fn illuminant<const M: usize>(rgb: [f32; 3], l: &Lambdas) -> [f32; M] {
    convert(rgb, |c| SampledSpectrum::illuminant(c, l))
}

/// The transmittance of `m`'s volume over a length `x` at the wavelengths `l`
/// ([`Material::transmittance_at`]).
#[inline(always)]
pub fn transmittance<const M: usize>(m: &Material, x: f32, l: &Lambdas) -> [f32; M] {
    if spectral::<M>() {
        take(m.transmittance_at::<SampledSpectrum>(x, l).to_lanes())
    } else {
        take(m.transmittance_at::<Vec3>(x, &()).to_array())
    }
}

/// The film's linear RGB of the radiance `v` carried at the wavelengths `l`.
#[inline(always)]
pub fn to_rgb<const M: usize>(v: [f32; M], l: &Lambdas) -> Vec3 {
    if spectral::<M>() {
        SampledSpectrum::from_lanes(take(v)).to_rgb(l)
    } else {
        Vec3::from_array(take(v))
    }
}

/// Lane `i` of `v`.
#[inline(always)]
pub fn lane<const N: usize, const M: usize>(v: &Channels<N, M>, i: usize) -> [f32; M] {
    std::array::from_fn(|c| v[c][i])
}

/// Sets lane `i` of `v` to `x`.
#[inline(always)]
pub fn set_lane<const N: usize, const M: usize>(v: &mut Channels<N, M>, i: usize, x: [f32; M]) {
    (0..M).for_each(|c| v[c][i] = x[c]);
}
