//! What a path carries: linear RGB ([`Vec3`]) or radiance at 4 sampled wavelengths
//! ([`SampledSpectrum`] with its [`Lambdas`]). The BSDFs and integrators are written once,
//! generic over [`Carrier`]; the renderer picks RGB for scenes that need nothing spectral
//! (`--spectral auto`), so those keep plain RGB transport, and spectral transport otherwise.
//!
//! Conventions:
//! - Colour inputs (base colour, tint, attenuation colour) become carriers through
//!   [`Carrier::reflectance`] (values in [0, 1]), emission through [`Carrier::illuminant`]
//!   (RGB (1,1,1) ↦ D65 with luminance 1); in RGB mode both are the identity.
//! - At a dispersive interface the path keeps only its hero wavelength
//!   ([`Carrier::keep_hero`]): the hero lane is multiplied by 4 and the others zeroed, which
//!   with the unchanged wavelength pdfs is exactly pbrt-v4's `TerminateSecondary` (pdf/4 on
//!   the hero) — but as a property of the carried value, so Whitted's branches may terminate
//!   independently and still add up. The path tracer's camera paths split into their 4
//!   wavelengths there instead ([`Carrier::lane_as_hero`], `crate::integrator::path`).
//! - At a ROUGH dispersive interface the path tracer keeps all 4 lanes instead, with
//!   spectral MIS over the wavelengths (Wilkie et al. 2014, "Hero Wavelength Spectral
//!   Sampling", §4; [`crate::shading::spectral_mis`]): [`Lambdas::hero_weight`] is then the
//!   posterior probability that each lane is the hero given the directions sampled so far,
//!   and [`Carrier::keep_hero`] multiplies the hero by 1/weight (4 while no rough dispersive
//!   vertex has been met, as above).
//! - [`Carrier::to_rgb`] is the film's conversion (spectrum → CIE XYZ → linear sRGB); it is
//!   the only place colour is converted.

use super::cie::d65_normalized;
use super::cie::xyz_to_linear_srgb;
use super::{RgbIlluminant, RgbReflectance, SampledSpectrum, SampledWavelengths, N_LAMBDA};
use glam::Vec3;
use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Sub};

/// The wavelengths of one camera sample, and whether the path kept only the hero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lambdas {
    /// The 4 sampled wavelengths and their pdfs (never terminated: see the module docs).
    pub wl: SampledWavelengths,
    /// The path went through a dispersive interface: only lane 0 carries radiance now.
    pub hero_only: bool,
    /// D65 (luminance 1) at the 4 wavelengths, looked up once per sample: every emission
    /// upsampling multiplies by it.
    pub d65: SampledSpectrum,
    /// Probability that lane j is the hero given the path so far (sums to 1; uniform 1/4
    /// until a rough dispersive vertex reweights it, [`crate::shading::spectral_mis`]). The
    /// lanes are rotations of the hero's sample number by j/4, so before any direction is
    /// sampled each lane is equally likely to be the one that chose them.
    pub hero_weight: [f32; N_LAMBDA],
    /// `Some(i)`: this path is the sub-path of a split sample that carries the sample's
    /// lane `i` alone in its lane 0, its lanes rotated by `i` ([`Carrier::lane_as_hero`]).
    /// `None` for a whole sample.
    pub sub_path: Option<u8>,
}

impl Lambdas {
    /// Wraps sampled wavelengths.
    pub fn new(wl: SampledWavelengths) -> Self {
        Lambdas {
            wl,
            hero_only: false,
            d65: SampledSpectrum::from_fn(&wl, d65_normalized),
            hero_weight: [1.0 / N_LAMBDA as f32; N_LAMBDA],
            sub_path: None,
        }
    }
}

/// The exact spectral shape of an emitter that names one (`iris_spectrum`: D65, blackbody,
/// sun): `filter(λ)·shape(λ)`, where the RGB transport uses `reference` = filter ×
/// sRGB(shape) for the same emitter at unit geometry. A value handed to
/// [`Carrier::emitted`] is `reference` × a geometric factor (distance falloff, 1/pdf, …),
/// which the spectral transport recovers and applies to the exact shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmitterShape {
    /// Spectral shape (luminance 1).
    pub shape: super::Spectrum,
    /// The RGB filter (glTF light colour × intensity, or emissive factor × strength).
    pub filter: Vec3,
    /// What the RGB transport uses for this emitter: filter × sRGB(shape).
    pub reference: Vec3,
}

/// A radiometric quantity carried along paths (see the module docs).
pub trait Carrier:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Mul<f32, Output = Self>
    + Div<f32, Output = Self>
    + AddAssign
    + MulAssign
    + MulAssign<f32>
    + DivAssign<f32>
{
    /// What the wavelengths of a sample are (nothing for RGB).
    type Lambda: Copy + Debug + Send + Sync;
    /// Zero everywhere.
    const ZERO: Self;
    /// One everywhere.
    const ONE: Self;
    /// Whether this carrier is spectral.
    const SPECTRAL: bool;

    /// The same value in every channel / lane.
    fn splat(v: f32) -> Self;
    /// Largest channel.
    fn max_element(self) -> f32;
    /// Channel-wise minimum.
    fn min(self, o: Self) -> Self;
    /// Channel-wise power.
    fn powf(self, e: f32) -> Self;
    /// Every channel finite.
    fn is_finite(self) -> bool;
    /// Mean over the channels.
    fn average(self) -> f32;
    /// `self + (o − self)·t`.
    fn lerp(self, o: Self, t: f32) -> Self {
        self + (o - self) * t
    }

    /// Wavelengths for one camera sample from a uniform `u`.
    fn sample_lambda(u: f32) -> Self::Lambda;
    /// A reflectance-like RGB colour (components in [0, 1]).
    fn reflectance(rgb: Vec3, l: &Self::Lambda) -> Self;
    /// An emitted RGB radiance (any non-negative values).
    fn illuminant(rgb: Vec3, l: &Self::Lambda) -> Self;
    /// Emitted radiance (or irradiance) `rgb` of an emitter with an optional exact spectral
    /// shape: RGB transport takes `rgb`; spectral transport takes the shape times the
    /// filter, scaled by `rgb`'s ratio to the shape's reference, or upsamples `rgb` as an
    /// illuminant when there is no shape.
    fn emitted(rgb: Vec3, shape: Option<&EmitterShape>, l: &Self::Lambda) -> Self;
    /// The film's conversion to linear sRGB.
    fn to_rgb(self, l: &Self::Lambda) -> Vec3;
    /// The hero wavelength in nm (`None` in RGB): what a dispersive interface refracts with.
    fn hero(l: &Self::Lambda) -> Option<f32>;
    /// Keeps the hero wavelength only (a dispersive interface); marks `l`. The hero lane is
    /// divided by its hero weight ([`Lambdas::hero_weight`]; 1/4 unless spectral MIS has
    /// reweighted it), which then becomes 1.
    fn keep_hero(self, l: &mut Self::Lambda) -> Self;
    /// The 4 wavelengths in nm (`None` in RGB).
    fn lanes_nm(l: &Self::Lambda) -> Option<[f32; 4]>;
    /// The hero weights ([`Lambdas::hero_weight`]; RGB: `[1, 0, 0, 0]`, unused).
    fn hero_weight(l: &Self::Lambda) -> [f32; 4];
    /// Sets the hero weights (no-op in RGB).
    fn set_hero_weight(l: &mut Self::Lambda, w: [f32; 4]);
    /// Whether the path kept only its hero wavelength ([`Carrier::keep_hero`]).
    fn is_hero_only(l: &Self::Lambda) -> bool;
    /// The channels / lanes as 4 floats (RGB: the 4th is 0), for compact storage.
    fn to_lanes(self) -> [f32; 4];
    /// Inverse of [`Carrier::to_lanes`].
    fn from_lanes(v: [f32; 4]) -> Self;
    /// The wavelengths of a sub-path that carries lane `i` of a sample alone (a path split
    /// into its wavelengths, [`crate::integrator::path`]): the lanes rotated so that lane
    /// `i` is the hero (lane 0), hero only, with hero weight 1. The sub-path's radiance
    /// in its lane 0 is the sample's lane `i`. Nothing for RGB.
    fn lane_as_hero(l: &Self::Lambda, i: usize) -> Self::Lambda;
    /// [`Lambdas::sub_path`] (`None` in RGB).
    fn sub_path(l: &Self::Lambda) -> Option<usize>;
    /// The wavelengths with lane `k` moved to lane 0 (lane j ← lane (j + k) mod 4), hero
    /// weights rotated with them, `hero_only` and `sub_path` kept: the same sample seen
    /// with lane `k` as the hero (SPPM's camera hero, `crate::integrator::path`; a whole
    /// sample's lanes only, never a sub-path's). Nothing for RGB.
    fn lanes_rotated(l: &Self::Lambda, k: usize) -> Self::Lambda;
    /// The values with lane `k` moved to lane 0 (lane j ← lane (j + k) mod 4,
    /// [`super::rotate_lanes`]), to go with [`Carrier::lanes_rotated`]. RGB values must not
    /// be rotated (`k` = 0 leaves them).
    fn rotated(self, k: usize) -> Self {
        Self::from_lanes(super::rotate_lanes(self.to_lanes(), k))
    }
}

impl Carrier for Vec3 {
    type Lambda = ();
    const ZERO: Self = Vec3::ZERO;
    const ONE: Self = Vec3::ONE;
    const SPECTRAL: bool = false;

    #[inline]
    fn splat(v: f32) -> Self {
        Vec3::splat(v)
    }
    #[inline]
    fn max_element(self) -> f32 {
        Vec3::max_element(self)
    }
    #[inline]
    fn min(self, o: Self) -> Self {
        Vec3::min(self, o)
    }
    #[inline]
    fn powf(self, e: f32) -> Self {
        Vec3::powf(self, e)
    }
    #[inline]
    fn is_finite(self) -> bool {
        Vec3::is_finite(self)
    }
    #[inline]
    fn average(self) -> f32 {
        self.element_sum() / 3.0
    }
    #[inline]
    fn sample_lambda(_u: f32) -> Self::Lambda {}
    #[inline]
    fn reflectance(rgb: Vec3, _l: &()) -> Self {
        rgb
    }
    #[inline]
    fn illuminant(rgb: Vec3, _l: &()) -> Self {
        rgb
    }
    #[inline]
    fn emitted(rgb: Vec3, _shape: Option<&EmitterShape>, _l: &()) -> Self {
        rgb
    }
    #[inline]
    fn to_rgb(self, _l: &()) -> Vec3 {
        self
    }
    #[inline]
    fn hero(_l: &()) -> Option<f32> {
        None
    }
    #[inline]
    fn keep_hero(self, _l: &mut ()) -> Self {
        self
    }
    #[inline]
    fn lanes_nm(_l: &()) -> Option<[f32; 4]> {
        None
    }
    #[inline]
    fn hero_weight(_l: &()) -> [f32; 4] {
        [1.0, 0.0, 0.0, 0.0]
    }
    #[inline]
    fn set_hero_weight(_l: &mut (), _w: [f32; 4]) {}
    #[inline]
    fn is_hero_only(_l: &()) -> bool {
        false
    }
    #[inline]
    fn to_lanes(self) -> [f32; 4] {
        [self.x, self.y, self.z, 0.0]
    }
    #[inline]
    fn from_lanes(v: [f32; 4]) -> Self {
        Vec3::new(v[0], v[1], v[2])
    }
    fn lane_as_hero(_l: &(), _i: usize) {}
    fn sub_path(_l: &()) -> Option<usize> {
        None
    }
    fn lanes_rotated(_l: &(), _k: usize) {}
}

impl Carrier for SampledSpectrum {
    type Lambda = Lambdas;
    const ZERO: Self = SampledSpectrum::zero();
    const ONE: Self = SampledSpectrum::one();
    const SPECTRAL: bool = true;

    #[inline]
    fn splat(v: f32) -> Self {
        SampledSpectrum::splat(v)
    }
    #[inline]
    fn max_element(self) -> f32 {
        self.max_value()
    }
    #[inline]
    fn min(self, o: Self) -> Self {
        let (a, b) = (self.values(), o.values());
        SampledSpectrum::new(std::array::from_fn(|i| a[i].min(b[i])))
    }
    #[inline]
    fn powf(self, e: f32) -> Self {
        self.map(|v| v.powf(e))
    }
    #[inline]
    fn is_finite(self) -> bool {
        self.values().iter().all(|v| v.is_finite())
    }
    #[inline]
    fn average(self) -> f32 {
        SampledSpectrum::average(&self)
    }
    fn sample_lambda(u: f32) -> Lambdas {
        Lambdas::new(SampledWavelengths::sample_visible(u))
    }
    fn reflectance(rgb: Vec3, l: &Lambdas) -> Self {
        if rgb.x == rgb.y && rgb.y == rgb.z {
            return SampledSpectrum::splat(rgb.x.clamp(0.0, 1.0));
        }
        RgbReflectance::new(rgb.to_array()).sample(&l.wl)
    }
    fn illuminant(rgb: Vec3, l: &Lambdas) -> Self {
        RgbIlluminant::sample_rgb(rgb.to_array(), &l.wl, l.d65)
    }
    fn emitted(rgb: Vec3, shape: Option<&EmitterShape>, l: &Lambdas) -> Self {
        let Some(sh) = shape else {
            return Self::illuminant(rgb, l);
        };
        let (r, f) = (sh.reference.max_element(), sh.filter.max_element());
        let k = rgb.max_element();
        if r.is_nan() || r <= 0.0 || f.is_nan() || f <= 0.0 || k.is_nan() || k <= 0.0 {
            return SampledSpectrum::zero();
        }
        Self::reflectance(sh.filter / f, l) * sh.shape.sample(&l.wl) * (f * k / r)
    }
    fn to_rgb(self, l: &Lambdas) -> Vec3 {
        Vec3::from_array(xyz_to_linear_srgb(self.to_xyz(&l.wl)))
    }
    #[inline]
    fn hero(l: &Lambdas) -> Option<f32> {
        Some(l.wl.hero())
    }
    fn keep_hero(self, l: &mut Lambdas) -> Self {
        if l.hero_only {
            return self;
        }
        l.hero_only = true;
        let mut v = [0.0; N_LAMBDA];
        let w0 = l.hero_weight[0];
        // The path's density marginalised over which lane is the hero was
        // Σ_j P_j / 4 = P_0 / (4 w_0); past a delta dispersive vertex only the hero could
        // have produced it (density P_0 / 4): a factor 1/w_0 (4 with uniform weights).
        v[0] = if w0 > 0.0 { self.values()[0] / w0 } else { 0.0 };
        l.hero_weight = [1.0, 0.0, 0.0, 0.0];
        SampledSpectrum::new(v)
    }
    #[inline]
    fn lanes_nm(l: &Lambdas) -> Option<[f32; 4]> {
        Some(l.wl.lambdas())
    }
    #[inline]
    fn hero_weight(l: &Lambdas) -> [f32; 4] {
        l.hero_weight
    }
    #[inline]
    fn set_hero_weight(l: &mut Lambdas, w: [f32; 4]) {
        l.hero_weight = w;
    }
    #[inline]
    fn is_hero_only(l: &Lambdas) -> bool {
        l.hero_only
    }
    #[inline]
    fn to_lanes(self) -> [f32; 4] {
        let v = self.values();
        [v[0], v[1], v[2], v[3]]
    }
    #[inline]
    fn from_lanes(v: [f32; 4]) -> Self {
        SampledSpectrum::new(v)
    }
    fn sub_path(l: &Lambdas) -> Option<usize> {
        l.sub_path.map(usize::from)
    }
    fn lane_as_hero(l: &Lambdas, i: usize) -> Lambdas {
        let mut hero_weight = [0.0; N_LAMBDA];
        hero_weight[0] = 1.0;
        Lambdas {
            hero_only: true,
            hero_weight,
            sub_path: Some(i as u8),
            ..Self::lanes_rotated(l, i)
        }
    }
    fn lanes_rotated(l: &Lambdas, k: usize) -> Lambdas {
        Lambdas {
            wl: l.wl.rotated(k),
            hero_only: l.hero_only,
            d65: SampledSpectrum::new(super::rotate_lanes(l.d65.values(), k)),
            hero_weight: super::rotate_lanes(l.hero_weight, k),
            sub_path: l.sub_path,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::EmissionSpectrum;

    /// A lane's sub-path sees that lane's wavelength as its hero, with its density and D65
    /// value, and the other lanes rotated with it.
    #[test]
    fn lane_as_hero_rotates_the_lanes() {
        let l = Lambdas::new(SampledWavelengths::sample_visible(0.61));
        for i in 0..N_LAMBDA {
            let h = <SampledSpectrum as Carrier>::lane_as_hero(&l, i);
            assert!(h.hero_only);
            assert_eq!(h.hero_weight, [1.0, 0.0, 0.0, 0.0]);
            for j in 0..N_LAMBDA {
                let k = (j + i) % N_LAMBDA;
                assert_eq!(h.wl.lambda(j), l.wl.lambda(k));
                assert_eq!(h.wl.lane_pdf(j), l.wl.lane_pdf(k));
                assert_eq!(h.d65.values()[j], l.d65.values()[k]);
            }
        }
    }

    /// A named emitter spectrum (2700 K) reaches the path as Planck's law itself, scaled by
    /// the RGB value's ratio to the reference, while the RGB transport keeps the RGB value;
    /// the upsampled sRGB colour of the same light differs by more than 5 % at some λ (so the
    /// test tells the two apart).
    #[test]
    fn emitted_uses_the_exact_shape() {
        let bb = EmissionSpectrum::Blackbody { kelvin: 2700.0 };
        let filter = Vec3::new(3.0, 3.0, 3.0);
        let sh = bb.emitter_shape(filter);
        assert_eq!(sh.reference, filter * bb.linear_srgb());
        let l = Lambdas::new(SampledWavelengths::sample_uniform((450.0 - 360.0) / 470.0));
        let rgb = sh.reference * 2.0;
        let v = SampledSpectrum::emitted(rgb, Some(&sh), &l).values();
        let up = SampledSpectrum::illuminant(rgb, &l).values();
        let mut differs = false;
        for (i, lam) in l.wl.lambdas().into_iter().enumerate() {
            let want = 2.0 * 3.0 * bb.spectrum().eval(lam);
            assert!(
                (v[i] - want).abs() <= 1e-4 * want,
                "{lam} nm: {} vs {want}",
                v[i]
            );
            differs |= (up[i] - want).abs() > 0.05 * want;
        }
        assert!(differs, "upsampled {up:?} vs exact {v:?}");
        assert_eq!(Vec3::emitted(rgb, Some(&sh), &()), rgb);
    }
}
