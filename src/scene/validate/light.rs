//! Light and camera checks (part of [`validate`](super::validate)). World units, radians.
//!
//! Lights: positions and directions finite, directions non-zero (normalised here), colour
//! finite and ≥ 0, intensity finite and ≥ 0, `range > 0` when given, spot cones
//! `0 ≤ inner < outer ≤ π/2` — `inner ≥ outer` is repaired to a hard-edged cone
//! (`inner = 0.999·outer`) with a warning. Cameras: perspective `0 < yfov < π` and
//! `aspect > 0` when given, orthographic `xmag`, `ymag` finite and non-zero, a finite
//! world-from-camera matrix. An `iris_spectrum` blackbody must lie in
//! [`BLACKBODY_KELVIN`](crate::spectrum::BLACKBODY_KELVIN). Violations are
//! `InvalidValue` naming the light or camera.

use super::{element, fail};
use crate::error::{LoadError, LoadErrorKind};
use crate::scene::desc::{CameraDesc, LightDesc, Projection};
use std::f32::consts::{FRAC_PI_2, PI};
use std::path::Path;

pub(super) fn check_light(
    src: &Path,
    index: usize,
    light: &mut LightDesc,
    warnings: &mut Vec<String>,
) -> Result<(), LoadError> {
    let spectrum = light.spectrum();
    let (name, position, direction, color, intensity, range) = match light {
        LightDesc::Point {
            name,
            position,
            color,
            intensity,
            range,
            ..
        } => (name, Some(*position), None, *color, *intensity, *range),
        LightDesc::Spot {
            name,
            position,
            direction,
            color,
            intensity,
            range,
            ..
        } => (
            name,
            Some(*position),
            Some(direction),
            *color,
            *intensity,
            *range,
        ),
        LightDesc::Directional {
            name,
            direction,
            color,
            intensity,
            ..
        } => (name, None, Some(direction), *color, *intensity, None),
    };
    let name = element(name, "light", index);
    let invalid = |detail: String| fail(src, &name, LoadErrorKind::InvalidValue, detail);
    if let Some(p) = position.filter(|p| !p.is_finite()) {
        return Err(invalid(format!("position {p} is not finite")));
    }
    if let Some(d) = direction {
        let v = *d;
        *d = crate::math::unit_direction(v.as_dvec3())
            .map_err(|why| invalid(format!("direction {why}: {v}")))?;
    }
    if !color.is_finite() || color.min_element() < 0.0 {
        return Err(invalid(format!("colour {color} must be finite and ≥ 0")));
    }
    if !intensity.is_finite() || intensity < 0.0 {
        return Err(invalid(format!(
            "intensity {intensity} must be finite and ≥ 0"
        )));
    }
    if let Some(r) = range.filter(|r| r.is_nan() || *r <= 0.0) {
        return Err(invalid(format!("range {r} must be > 0")));
    }
    if let Some(Err(e)) = spectrum.map(|s| s.check()) {
        return Err(invalid(format!("iris_spectrum: {e}")));
    }
    if let LightDesc::Spot {
        inner_cone,
        outer_cone,
        ..
    } = light
    {
        let (inner, outer) = (*inner_cone, *outer_cone);
        if !(outer.is_finite() && outer > 0.0 && outer <= FRAC_PI_2) {
            return Err(invalid(format!(
                "outer cone angle {outer} must be in (0, π/2]"
            )));
        }
        if !(inner.is_finite() && inner >= 0.0) {
            return Err(invalid(format!("inner cone angle {inner} must be ≥ 0")));
        }
        if inner >= outer {
            *inner_cone = 0.999 * outer;
            warnings.push(format!(
                "{name}: inner cone angle {inner} ≥ outer {outer}; set to {} (hard edge)",
                *inner_cone
            ));
        }
    }
    Ok(())
}

pub(super) fn check_camera(src: &Path, index: usize, camera: &CameraDesc) -> Result<(), LoadError> {
    let name = element(&camera.name, "camera", index);
    let invalid = |detail: String| fail(src, &name, LoadErrorKind::InvalidValue, detail);
    match camera.projection {
        Projection::Perspective { yfov, aspect } => {
            if !(yfov.is_finite() && yfov > 0.0 && yfov < PI) {
                return Err(invalid(format!("yfov {yfov} must be in (0, π)")));
            }
            if let Some(a) = aspect.filter(|a| !(a.is_finite() && *a > 0.0)) {
                return Err(invalid(format!("aspect ratio {a} must be finite and > 0")));
            }
        }
        Projection::Orthographic { xmag, ymag } => {
            if !(xmag.is_finite() && ymag.is_finite() && xmag != 0.0 && ymag != 0.0) {
                return Err(invalid(format!(
                    "xmag {xmag}, ymag {ymag} must be finite and non-zero"
                )));
            }
        }
    }
    if !camera.world_from_camera.is_finite() {
        return Err(invalid("world-from-camera transform is not finite".into()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::tests::{err_kind, scene, warnings};
    use super::super::validate;
    use crate::error::LoadErrorKind;
    use crate::scene::desc::*;
    use crate::spectrum::EmissionSpectrum;
    use glam::{Mat4, Vec3};
    use std::f32::consts::FRAC_PI_4;

    fn spot(inner: f32, outer: f32) -> LightDesc {
        LightDesc::Spot {
            name: "light 0 \"spot\"".into(),
            position: Vec3::ONE,
            direction: Vec3::new(0.0, -2.0, 0.0),
            color: Vec3::ONE,
            intensity: 10.0,
            range: None,
            inner_cone: inner,
            outer_cone: outer,
            spectrum: None,
        }
    }

    /// A white point light "bulb" at `position`.
    fn bulb(position: Vec3, intensity: f32, range: Option<f32>) -> LightDesc {
        LightDesc::Point {
            name: "light 0 \"bulb\"".into(),
            position,
            color: Vec3::ONE,
            intensity,
            range,
            spectrum: None,
        }
    }

    #[test]
    fn lights_are_checked_and_normalised() {
        let mut d = scene();
        d.lights.push(spot(0.0, FRAC_PI_4));
        let (d, _) = warnings(d);
        match &d.lights[0] {
            LightDesc::Spot { direction, .. } => assert_eq!(*direction, Vec3::NEG_Y),
            other => panic!("{other:?}"),
        }
        let bad: [LightDesc; 6] = [
            spot(0.0, 2.0),
            spot(-0.1, 0.5),
            LightDesc::Directional {
                name: "light 0 \"sun\"".into(),
                direction: Vec3::ZERO,
                color: Vec3::ONE,
                intensity: 1.0,
                spectrum: None,
            },
            bulb(Vec3::new(f32::NAN, 0.0, 0.0), 1.0, None),
            bulb(Vec3::ZERO, -1.0, None),
            bulb(Vec3::ZERO, 1.0, Some(0.0)),
        ];
        for light in bad {
            let mut d = scene();
            d.lights.push(light);
            let (k, msg) = err_kind(d);
            assert_eq!(k, LoadErrorKind::InvalidValue);
            assert!(msg.contains("light 0"), "{msg}");
        }
    }

    #[test]
    fn light_spectrum_is_checked() {
        let with = |spectrum| LightDesc::Directional {
            name: "light 0 \"sun\"".into(),
            direction: Vec3::NEG_Y,
            color: Vec3::ONE,
            intensity: 1.0,
            spectrum: Some(spectrum),
        };
        for ok in [
            EmissionSpectrum::D65,
            EmissionSpectrum::Sun,
            EmissionSpectrum::Blackbody { kelvin: 1000.0 },
            EmissionSpectrum::Blackbody { kelvin: 40000.0 },
        ] {
            let mut d = scene();
            d.lights.push(with(ok));
            assert!(validate(d).is_ok(), "{ok:?}");
        }
        for kelvin in [999.0, 40001.0, f32::NAN, f32::INFINITY, -3000.0] {
            let mut d = scene();
            d.lights.push(with(EmissionSpectrum::Blackbody { kelvin }));
            let (k, msg) = err_kind(d);
            assert_eq!(k, LoadErrorKind::InvalidValue);
            assert!(
                msg.contains("\"sun\"") && msg.contains("iris_spectrum"),
                "{msg}"
            );
        }
    }

    #[test]
    fn spot_inner_not_below_outer_is_fixed() {
        let mut d = scene();
        d.lights.push(spot(0.6, 0.5));
        let (d, w) = warnings(d);
        match &d.lights[0] {
            LightDesc::Spot {
                inner_cone,
                outer_cone,
                ..
            } => assert!(inner_cone < outer_cone),
            other => panic!("{other:?}"),
        }
        assert!(w.contains("\"spot\""), "{w}");
    }

    #[test]
    fn cameras() {
        let cam = |projection, m: Mat4| CameraDesc {
            name: "camera 0 \"cam\"".into(),
            projection,
            world_from_camera: m,
        };
        let mut d = scene();
        d.cameras.push(cam(
            Projection::Perspective {
                yfov: 0.8,
                aspect: Some(1.5),
            },
            Mat4::IDENTITY,
        ));
        assert!(validate(d).is_ok());
        let bad = [
            cam(
                Projection::Perspective {
                    yfov: 0.0,
                    aspect: None,
                },
                Mat4::IDENTITY,
            ),
            cam(
                Projection::Perspective {
                    yfov: 3.2,
                    aspect: None,
                },
                Mat4::IDENTITY,
            ),
            cam(
                Projection::Perspective {
                    yfov: 1.0,
                    aspect: Some(0.0),
                },
                Mat4::IDENTITY,
            ),
            cam(
                Projection::Orthographic {
                    xmag: 0.0,
                    ymag: 1.0,
                },
                Mat4::IDENTITY,
            ),
            cam(
                Projection::Orthographic {
                    xmag: 1.0,
                    ymag: f32::INFINITY,
                },
                Mat4::IDENTITY,
            ),
            cam(
                Projection::Perspective {
                    yfov: 1.0,
                    aspect: None,
                },
                Mat4::from_translation(Vec3::new(f32::NAN, 0.0, 0.0)),
            ),
        ];
        for c in bad {
            let mut d = scene();
            d.cameras.push(c);
            let (k, msg) = err_kind(d);
            assert_eq!(k, LoadErrorKind::InvalidValue);
            assert!(msg.contains("\"cam\""), "{msg}");
        }
    }
}
