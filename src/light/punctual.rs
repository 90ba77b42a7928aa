//! Punctual lights (KHR_lights_punctual) and their incident illumination at a point.
//!
//! Units follow the glTF spec: point and spot intensities in candela (lm/sr), directional
//! illuminance in lux (lm/m²). `sample_li` returns the **irradiance at normal incidence**
//! E⊥ (lux), so a surface with BRDF f receives radiance f·E⊥·cos θ. Range falloff and spot
//! cone falloff follow the spec's recommended formulas.
//!
//! Colour: a light with an `iris_spectrum` ([`crate::spectrum::EmissionSpectrum`]) emits
//! `intensity × color × linear_srgb(spectrum)`, the spectrum's sRGB colour normalised to
//! luminance 1, so its luminous intensity is unchanged; spectral transport emits the
//! spectrum's exact shape ([`PunctualLight::shape`]).

use crate::spectrum::EmitterShape;
use glam::Vec3;

/// A punctual light of the render scene with its spectral shape.
#[derive(Debug, Clone, PartialEq)]
pub struct PunctualLight {
    /// The light in RGB terms.
    pub light: Light,
    /// The exact spectral shape of a light that names one (`iris_spectrum`), for spectral
    /// transport; `None` upsamples the RGB intensity.
    pub shape: Option<EmitterShape>,
}

/// A punctual light in RGB terms.
#[derive(Debug, Clone, PartialEq)]
pub enum Light {
    /// Isotropic point light.
    Point {
        /// World position.
        position: Vec3,
        /// Intensity × colour, candela.
        intensity: Vec3,
        /// Optional range.
        range: Option<f32>,
    },
    /// Spot light.
    Spot {
        /// World position.
        position: Vec3,
        /// Unit direction the spot points to.
        direction: Vec3,
        /// Intensity × colour, candela.
        intensity: Vec3,
        /// cos(inner cone angle).
        cos_inner: f32,
        /// cos(outer cone angle).
        cos_outer: f32,
        /// Optional range.
        range: Option<f32>,
    },
    /// Distant light.
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
        /// Illuminance × colour, lux.
        illuminance: Vec3,
    },
}

/// Illumination arriving at a point from one punctual light ([`PunctualLight`]'s
/// [`Light::sample_li`]).
#[derive(Debug, Clone, Copy)]
pub struct Incidence {
    /// Unit direction from the point toward the light.
    pub wi: Vec3,
    /// The light's position, or `None` for a directional light (at infinity).
    pub position: Option<Vec3>,
    /// Irradiance on a surface facing the light, lux.
    pub irradiance: Vec3,
}

/// KHR_lights_punctual recommended range window: clamp(1 − (d/range)⁴, 0, 1).
#[inline]
pub(crate) fn range_window(d: f32, range: Option<f32>) -> f32 {
    match range {
        Some(r) if r > 0.0 => (1.0 - (d / r).powi(4)).clamp(0.0, 1.0),
        _ => 1.0,
    }
}

/// A spot light's attenuation at `cd`, the cosine between its axis and the direction to
/// the point (KHR_lights_punctual's recommendation): the linear ramp between the cone
/// cosines, squared; a hard edge when the cones coincide.
#[inline]
pub(crate) fn cone_falloff(cd: f32, cos_inner: f32, cos_outer: f32) -> f32 {
    let t = if cos_inner > cos_outer {
        ((cd - cos_outer) / (cos_inner - cos_outer)).clamp(0.0, 1.0)
    } else if cd >= cos_outer {
        1.0
    } else {
        0.0
    };
    t * t
}

/// Unit direction, distance and squared distance from `p` to a light at `position`;
/// `None` at the light itself.
fn toward(position: Vec3, p: Vec3) -> Option<(Vec3, f32, f32)> {
    let v = position - p;
    let d2 = v.length_squared();
    if d2.is_nan() || d2 <= 0.0 {
        return None;
    }
    let d = d2.sqrt();
    Some((v / d, d, d2))
}

impl Light {
    /// Illumination at `p`, or `None` if the light cannot reach it (outside the cone or
    /// range, or at the light's own position).
    pub fn sample_li(&self, p: Vec3) -> Option<Incidence> {
        match *self {
            Light::Point {
                position,
                intensity,
                range,
            } => {
                let (wi, d, d2) = toward(position, p)?;
                let e = intensity * (range_window(d, range) / d2);
                Some(Incidence {
                    wi,
                    position: Some(position),
                    irradiance: e,
                })
            }
            Light::Spot {
                position,
                direction,
                intensity,
                cos_inner,
                cos_outer,
                range,
            } => {
                let (wi, d, d2) = toward(position, p)?;
                let cd = (-wi).dot(direction);
                let w = cone_falloff(cd, cos_inner, cos_outer) * range_window(d, range);
                if w <= 0.0 {
                    return None;
                }
                Some(Incidence {
                    wi,
                    position: Some(position),
                    irradiance: intensity * (w / d2),
                })
            }
            Light::Directional {
                direction,
                illuminance,
            } => Some(Incidence {
                wi: -direction,
                position: None,
                irradiance: illuminance,
            }),
        }
    }
}

/// The key and fill lights used when a file has no light: a directional key from the
/// front-right-above (3 lux) and a weaker fill from the left (1 lux), both white.
pub fn default_lights() -> Vec<Light> {
    vec![
        Light::Directional {
            direction: -Vec3::new(1.0, 2.0, 1.5).normalize(),
            illuminance: Vec3::splat(3.0),
        },
        Light::Directional {
            direction: -Vec3::new(-1.5, 0.5, 1.0).normalize(),
            illuminance: Vec3::splat(1.0),
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_square_and_cone() {
        let l = Light::Point {
            position: Vec3::new(0.0, 2.0, 0.0),
            intensity: Vec3::splat(100.0),
            range: None,
        };
        let s = l.sample_li(Vec3::ZERO).unwrap();
        assert!((s.irradiance.x - 25.0).abs() < 1e-4);
        assert!((s.wi - Vec3::Y).length() < 1e-6);
        let spot = Light::Spot {
            position: Vec3::new(0.0, 2.0, 0.0),
            direction: -Vec3::Y,
            intensity: Vec3::splat(100.0),
            cos_inner: 0.2f32.cos(),
            cos_outer: 0.4f32.cos(),
            range: None,
        };
        assert!((spot.sample_li(Vec3::ZERO).unwrap().irradiance.x - 25.0).abs() < 1e-4);
        // 45° off axis is outside the 0.4 rad cone.
        assert!(spot.sample_li(Vec3::new(2.0, 0.0, 0.0)).is_none());
    }
}
